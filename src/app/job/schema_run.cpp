// Job-file sections that steer a run: top-level keys, [output], [farm]. The numeric keys of
// [output] and [farm] are the rows of the farm's run option tables (farm/run_options.hpp).
#include "app/job/schema.hpp"
#include "app/job/schema_params.hpp"
#include "farm/grain_views.hpp"
#include "farm/run_options.hpp"
#include "farm/rve_farm.hpp"

namespace app {

void add_run_sections(Schema& s) {
  s.add("title", Type::String, "Free text shown in logs and written with the results.")
      .or_default(std::string());

  s.add("output", Type::Table, "What is written and how often.");
  add_params(s, farm::kOutputOptions);      // every, progress_interval
  add_params(s, farm::kCheckpointOptions);  // checkpoint_every, checkpoint_interval, _keep
  s.add("output.grains", Type::Table,
        "Grain-scale views of chosen DEM RVEs during the run (spheres, contact network, periodic "
        "cell as VTK for ParaView), in <out>/grains/: rve_<id>_step_<step>.vtm and one time "
        "series rve_<id>.pvd per RVE (docs/design/dem.md).");
  s.add("output.grains.rves", Type::IntList,
        "Point ids of the DEM RVEs to draw (the id array of points.xmf, /points/id of results.h5).")
      .in(0, std::nullopt)
      .len(1, 4096)
      .need();
  add_params(s, farm::kGrainViewOptions);  // every

  s.add("farm", Type::Table, "Distribution of the RVEs over MPI ranks.");
  add_params(s, farm::kBalanceOptions);  // rebalance_threshold, rebalance_check_every
  add_choices(s, farm::kFarmChoices);    // wait, partition, rank0_rves
}

}  // namespace app
