// farm::RveFarm: mpm::MaterialModel whose points are RVEs spread over MPI ranks. Rank 0 runs the
// MPM solver and hosts RVEs too; ranks > 0 serve commands (step, checkpoint, migrate, stop).
// Its collaborators: Placement (who owns what), StepExchange (the wire), CostLedger (costs and
// times). Protocol, ordering rules and measurements: docs/design/farm.md.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/choice_table.hpp"
#include "common/state_store.hpp"
#include "farm/checkpoint.hpp"
#include "farm/cost_ledger.hpp"
#include "farm/cost_trace.hpp"
#include "farm/exchange.hpp"
#include "farm/micro_model.hpp"
#include "farm/mpi_util.hpp"
#include "farm/placement.hpp"
#include "farm/rebalance.hpp"
#include "mpm/grid.hpp"
#include "mpm/material_model.hpp"

namespace farm {

struct FarmOptions {
  WaitMode wait = WaitMode::automatic;  ///< how idle ranks wait (docs/design/farm.md, "Waiting")
  /// OpenMP over the RVEs of a rank (schedule dynamic, 1); false: one RVE at a time, OpenMP
  /// left to the inside of each RVE.
  bool omp_over_rves = true;
  int metis_seed = 1;  ///< METIS_OPTION_SEED
  /// Rank 0 owns RVEs too; false: with more than one rank, rank 0 runs only the MPM and the
  /// exchange, the RVEs go to ranks 1.. (`farm.rank0_rves`; docs/design/farm.md,
  /// docs/validation/scaling.md).
  bool rank0_rves = true;
  /// How the RVEs are grouped on ranks (`farm.partition`; partition.hpp, PartitionStyle).
  PartitionStyle partition = PartitionStyle::spread;
};

/// [farm]: the settings of FarmOptions that are a name out of a list or a switch
/// (common/choice_table.hpp).
inline constexpr common::ChoiceTable<FarmOptions, 3> kFarmChoices{
    "farm",
    {common::choice<&FarmOptions::wait, kWaitModeNames>(
         "wait",
         "How a rank waits for the others: auto (spin where every thread of the node's ranks has a "
         "core, sleep where they share cores; the log says which), spin, or sleep."),
     common::choice<&FarmOptions::partition, kPartitionStyleNames>(
         "partition",
         "How the RVEs are grouped on ranks: spread (neighbouring points on different ranks: their "
         "step costs rise and fall together, so a rank of neighbours swings; balance 0.85-0.99 "
         "where cells gives 0.68-0.93 on 2-16 ranks, docs/design/farm.md) or cells (METIS's "
         "contiguous parts of the grid's cell graph). Results are the same bits either way."),
     common::flag<&FarmOptions::rank0_rves>(
         "rank0_rves",
         "Rank 0 steps RVEs besides the MPM (true), or, with more than one rank, runs only the MPM "
         "and the exchange while ranks 1.. step the RVEs (false: for many ranks, where rank 0's "
         "MPM is on every step's critical path; give rank 0 the node's threads, "
         "docs/design/farm.md). Results are the same bits either way.")}};

class RveFarm final : public mpm::MaterialModel {
 public:
  /// Collective. Creates the RVEs of `ids` (ascending, identical on every rank), first split in
  /// blocks, then partitioned with METIS on the RVE graph (`x`, positions on rank 0; the grid)
  /// weighted by the models' cost estimates, migrating RVEs to their owners.
  RveFarm(MPI_Comm comm, MicroKind kind, std::vector<std::int64_t> ids,
          const std::vector<common::Vec3>& x, const mpm::Grid& grid, FarmOptions options);
  /// Collective restore from a checkpoint on any number of ranks: METIS partition weighted by
  /// the costs stored in it; every rank reads its RVEs. `x`: point positions on rank 0.
  RveFarm(MPI_Comm comm, MicroKind kind, const CheckpointInfo& info,
          const std::vector<common::Vec3>& x, const mpm::Grid& grid, FarmOptions options);
  ~RveFarm() override;
  RveFarm(const RveFarm&) = delete;
  RveFarm& operator=(const RveFarm&) = delete;

  // ---- rank 0 (the master) ----
  /// Rank 0 only. Every RVE whose id is in `ids` (a permutation of ids()) steps under L[p];
  /// stress[p] gets its new stress. Results are stored by RVE id. A failed RVE (on any rank)
  /// throws common::NumericalError naming the RVE id, the rank, the MPM step and the cause,
  /// after the exchange completed (no rank is left in a collective).
  void update_stress(std::span<const std::int64_t> ids, std::span<const common::Mat3> L, double dt,
                     std::span<common::Mat3> stress) override;
  /// Largest wave speed over all RVEs as of their last step (or creation) [m/s].
  double wave_speed() const override { return wave_speed_; }
  /// Rank 0 only, for the ids of the last update_stress: MicroModel::dilute of each point's RVE
  /// after that step (0 before the first step).
  void mark_dilute(std::span<const std::int64_t> ids,
                   std::span<std::uint8_t> dilute) const override;
  /// Rank 0 only. Collective checkpoint (all ranks write one HDF5 file; see checkpoint.hpp).
  void checkpoint(const std::string& path, std::int64_t step, double time,
                  const std::string& job_text, const common::StateStore& mpm_state,
                  bool abort_mid_write);
  /// Rank 0 only. Closes a cost window (the RVE step times since the last call) into the per-RVE
  /// cost average (rebalance.hpp); once the average is settled (3 windows), if the imbalance of
  /// that average exceeds `threshold` and the proposal plan_rebalance chooses (the incremental
  /// repartition from the current owners or a METIS partition; graph from `x`, current positions
  /// by RVE index) lowers it by more than the noise margin and pays back its move
  /// (Payback: the critical rank's step time of the last window, a horizon of the steps the
  /// current partition has lasted, the measured time per RVE moved), migrates the RVEs. Returns
  /// true if RVEs moved; last_plan() tells the decision.
  bool rebalance_if_needed(double threshold, const std::vector<common::Vec3>& x);
  /// Rank 0 only. Collective (Command::measure): every RVE's grain-scale measures of its current
  /// state (MicroModel::measures, OpenMP over a rank's RVEs), by RVE index. Called for output
  /// rows only: the MPM steps in between neither compute nor send them.
  [[nodiscard]] std::vector<MicroMeasures> measure();
  /// Rank 0 only. Collective (Command::grains): the owner of every RVE index in `indices`
  /// (ascending) writes its MicroModel::grain_view, stem "rve_<id>_step_<step>" (the farm's MPM
  /// step), into the existing directory `dir` that every rank sees (a rank's files all or none:
  /// dem::write_vtk_files). Returns, on rank 0, the indices whose RVE has a view (continuum
  /// RVEs have none). A rank that cannot write makes rank 0 throw common::IoError naming the RVE
  /// and the reason, with every worker back in serve(). Implemented in rve_farm_grains.cpp.
  std::vector<std::size_t> write_grain_views(const std::vector<std::size_t>& indices,
                                             const std::string& dir);
  /// Rank 0 only: moves the RVEs to `owner` (one rank per RVE index), whatever the costs.
  /// For tests and benchmarks (e.g. round-robin against METIS).
  void migrate_to(std::vector<int> owner);
  /// Rank 0 only: releases the workers (serve() returns).
  void stop();
  /// Rank 0 only: makes the workers' serve() throw an error of `kind` with `message`.
  void stop_with_error(ErrorKind kind, const std::string& message);

  // ---- ranks > 0 ----
  /// Command loop until rank 0 calls stop() (returns) or stop_with_error() (throws that error).
  void serve();

  // ---- queries ----
  [[nodiscard]] const std::vector<std::int64_t>& ids() const { return placement_.ids(); }
  [[nodiscard]] const std::vector<int>& owner() const { return placement_.owner(); }
  [[nodiscard]] const Placement& placement() const { return placement_; }
  /// Rank 0: the last report of every RVE, by index (ids() order).
  [[nodiscard]] const std::vector<MicroReport>& reports() const { return reports_; }
  /// Rank 0: the stress of every RVE, by index [Pa, tension positive].
  [[nodiscard]] const std::vector<common::Mat3>& stresses() const { return stresses_; }
  /// Rank 0: measured cost of every RVE (sum of the CPU times of its steps, on the thread that
  /// ran each) [s]; zero before steps (a checkpoint's costs after a restart).
  [[nodiscard]] const std::vector<double>& cost() const { return ledger_.total(); }
  /// Rank 0: imbalance max/mean over the worker ranks of the averaged RVE costs [-] (>= 1).
  [[nodiscard]] double imbalance() const {
    return ledger_.imbalance(placement_.parts(), placement_.workers());
  }
  [[nodiscard]] const FarmTimes& times() const { return ledger_.times(); }
  [[nodiscard]] int rank() const { return rank_; }
  /// The wait mode in use (options' `automatic` resolved at construction).
  [[nodiscard]] WaitMode wait_mode() const { return options_.wait; }
  [[nodiscard]] int size() const { return size_; }
  /// The MPM step counter carried in messages (set by the driver after a restart).
  void set_step(std::int64_t step) {
    step_ = step;
    ledger_.set_step(step);
  }
  /// Number of migrations done (including the start-up one) and RVEs moved in total.
  [[nodiscard]] std::int64_t migrations() const { return ledger_.migrations(); }
  [[nodiscard]] std::int64_t rves_moved() const { return ledger_.moved(); }
  /// Rank 0: the decision of the last rebalance_if_needed check.
  [[nodiscard]] const RebalancePlan& last_plan() const { return last_plan_; }

 private:
  struct Setup {};
  /// The members every constructor sets up; the object counts as stopped until a public
  /// constructor completes (a failing one must not make rank 0's destructor send a command).
  RveFarm(Setup tag, MPI_Comm comm, MicroKind kind, std::vector<std::int64_t> ids,
          const mpm::Grid& grid, FarmOptions options);
  /// Every rank: advance my RVEs under the L of the command; rank 0 stores the gathered records
  /// and writes `stress` (by point slot).
  void exec_step(const CommandHeader& h, std::span<common::Mat3> stress);
  /// Rank 0: stores the gathered records by RVE index; throws the first failure (by RVE id).
  void collect_records(std::span<common::Mat3> stress);
  /// Every rank: the texts of the RVE failures of the last step, gathered to rank 0.
  std::vector<std::pair<std::size_t, std::string>> exec_error_texts();
  /// Every rank: the measures of my RVEs, gathered to rank 0 (by RVE index there).
  std::vector<MicroMeasures> exec_measure();
  /// Every rank: writes the views of my RVEs among `indices` into `dir` (broadcast by rank 0);
  /// rank 0 gets back which indices have a view and the write failures.
  std::vector<std::size_t> exec_grains(const CommandHeader& h, std::vector<std::size_t> indices,
                                       std::string dir);
  void exec_checkpoint(const CommandHeader& h, std::string path, std::string job_text,
                       const common::StateStore* mpm_state);
  void exec_migrate(std::vector<int> new_owner);
  /// Every rank, after the models exist: start-up measures, costs, the METIS partition.
  void initial_costs_and_partition(const std::vector<common::Vec3>& x,
                                   const std::vector<double>* costs);
  /// Every rank: the model of RVE index k.
  MicroModel& model(std::size_t k) { return *models_[k]; }

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  int size_ = 1;
  MicroKind kind_;
  FarmOptions options_;
  mpm::Grid grid_;
  Placement placement_;
  std::vector<std::unique_ptr<MicroModel>> models_;  ///< by index; null if not mine
  StepExchange exchange_;
  std::vector<std::string> errors_;     ///< my failures of the last step, by local position
  std::vector<RveRecord> records_;      ///< my records of the last step, by local position
  std::vector<int> stepped_by_;         ///< the OpenMP thread that stepped each of them
  PointIndex points_;                   ///< rank 0: solver slot <-> RVE index
  std::vector<MicroReport> reports_;    ///< rank 0, by index
  std::vector<common::Mat3> stresses_;  ///< rank 0, by index
  std::vector<double> wave_;            ///< rank 0, by index [m/s]
  std::vector<std::uint8_t> dilute_;    ///< rank 0, by index: MicroModel::dilute after the step
  double wave_speed_ = 0.0;
  CostLedger ledger_;
  std::int64_t step_ = 0;
  RebalancePlan last_plan_;  ///< rank 0
  /// Rank 0, with MPMXDEM_COST_TRACE set: the per-step cost trace (cost_trace.hpp) and the
  /// step's RVE costs, DEM steps and neighbour-list builds by index.
  std::unique_ptr<CostTrace> trace_;
  std::vector<double> step_cpu_;
  std::vector<std::int64_t> step_dem_steps_;
  std::vector<std::int64_t> step_rebuilds_;
  bool stopped_ = true;  ///< the workers left serve() (or never entered it)
};

}  // namespace farm
