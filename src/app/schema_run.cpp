// Job-file sections that steer a run: top-level keys, [output], [farm].
#include "app/schema.hpp"

namespace app {

void add_run_sections(Schema& s) {
  using Q = Quantity;
  s.add("title", Type::String, "Free text shown in logs and written with the results.")
      .or_default(std::string());

  s.add("output", Type::Table, "What is written and how often.");
  s.add("output.every", Type::Int,
        "Write the time series every this many MPM steps (DEM jobs: DEM steps).")
      .in(1, std::nullopt)
      .or_default(std::int64_t{10});
  s.add("output.checkpoint_every", Type::Int,
        "Write a checkpoint every this many MPM steps; 0: never.")
      .in(0, std::nullopt)
      .or_default(std::int64_t{0});
  s.add("output.checkpoint_interval", Type::Float,
        "Write a checkpoint every this much wall time (\"30 min\"); 0: never.")
      .unit(Q::Time)
      .in(0, std::nullopt)
      .or_default(0.0);
  s.add("output.progress_interval", Type::Float,
        "Progress line (step, strain, ETA) at most this often (wall time).")
      .unit(Q::Time)
      .in(0, std::nullopt, true)
      .or_default(10.0);
  s.add("output.checkpoint_keep", Type::Int,
        "Newest checkpoints kept in the output directory (older ones are deleted).")
      .in(1, std::nullopt)
      .or_default(std::int64_t{2});

  s.add("farm", Type::Table, "Distribution of the RVEs over MPI ranks.");
  s.add("farm.rebalance_threshold", Type::Float,
        "Repartition the RVEs when max over mean worker busy time exceeds this.")
      .in(1, std::nullopt)
      .or_default(1.2);
  s.add("farm.rebalance_check_every", Type::Int,
        "MPM steps between two checks of the load balance.")
      .in(1, std::nullopt)
      .or_default(std::int64_t{20});
  s.add("farm.wait", Type::String,
        "How a rank waits for the others: auto (spin where every thread of the node's ranks has a "
        "core, sleep where they share cores; the log says which), spin, or sleep.")
      .one_of({"auto", "spin", "sleep"})
      .or_default(std::string("auto"));
}

}  // namespace app
