// CoupledRun: the coupled run as an object (see header).
#include "farm/coupled_run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "farm/grain_views.hpp"
#include "farm/placement.hpp"
#include "farm/results.hpp"
#include "farm/run_schedules.hpp"
#include "farm/spared_micro.hpp"

namespace farm {

namespace {

/// RVEs per rank below which the RVEs' step-to-step cost swings cap the balance (docs/design/
/// farm.md, "Choosing ranks, threads and RVEs per rank"): the start-up log says so.
constexpr std::size_t kRvesPerRankForBalance = 64;

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Runs `f` on every rank; any rank's exception becomes the same exception on every rank.
template <class F>
auto collective(MPI_Comm comm, F&& f) {
  ErrorKind kind = ErrorKind::none;
  std::string msg;
  using R = decltype(f());
  std::optional<R> out;
  try {
    out.emplace(f());
  } catch (...) {
    kind = current_error_kind();
    msg = common::current_error_text();
  }
  agree_on_errors(comm, kind, msg);
  return std::move(*out);
}

/// Positions by RVE index of the points (ids, x) in slot order.
std::vector<common::Vec3> positions_by_rve(const std::vector<std::int64_t>& rve_ids,
                                           std::span<const std::int64_t> point_ids,
                                           std::span<const common::Vec3> x) {
  return PointIndex(rve_ids, point_ids).by_rve(x);
}

/// Rank 0's side of a run: the solver, results.h5 and the schedules around the farm.
class Master {
 public:
  Master(const CoupledConfig& cfg, RveFarm& farm, const std::optional<CheckpointInfo>& info,
         const common::StateStore& mpm_state, const std::vector<std::int64_t>& ids,
         std::int64_t fault_abort_at);
  void run(RunSummary& sum);

 private:
  void output() {
    results_.append(solver_.step_count(), solver_.time(), farm_.stresses(), farm_.reports(),
                    solver_.points(),
                    sample_means(solver_.points(), farm_.reports(), cfg_.output.axial_axis),
                    solver_.reactions(), solver_.constraint_displacements(), farm_.measure());
  }
  /// Adds the last MPM step's DEM steps and spared RVE steps to the run's totals.
  void count_work(RunSummary& sum) const {
    for (const MicroReport& r : farm_.reports()) {
      sum.dem_steps += r.dem_steps;
      sum.spared_steps += (r.guards & kGuardSpared) != 0 ? 1 : 0;
    }
    sum.rve_steps += static_cast<std::int64_t>(farm_.reports().size());
  }
  void checkpoint(RunSummary& sum);
  void balance(std::int64_t step);
  void progress(std::int64_t step, double per_step);
  /// Whether the app asks the run to end now (a signal): kept in the summary.
  bool stop_requested(RunSummary& sum) const {
    if (cfg_.stop_requested) sum.stopped_by = cfg_.stop_requested();
    return sum.stopped_by != 0;
  }
  [[nodiscard]] bool more() const {
    const bool by_steps = cfg_.max_steps <= 0 || solver_.step_count() < cfg_.max_steps;
    const bool by_time = cfg_.end_time <= 0.0 || solver_.time() < cfg_.end_time * (1.0 - 1e-12);
    return by_steps && by_time;
  }
  /// Current point positions by RVE index (the balance graph).
  [[nodiscard]] std::vector<common::Vec3> positions() {
    const mpm::MaterialPoints& pts = solver_.points();
    if (!index_.matches(pts.id)) index_ = PointIndex(ids_, pts.id);
    return index_.by_rve<common::Vec3>(pts.x);
  }

  const CoupledConfig& cfg_;
  RveFarm& farm_;
  const std::vector<std::int64_t>& ids_;
  mpm::Solver solver_;
  PointIndex index_;
  ResultsWriter results_;
  OutputSchedule output_;
  GrainViews grains_;
  CheckpointSchedule checkpoints_;
  BalanceSchedule balance_;
  mpm::QuasiStaticWatch quasi_static_;  ///< energy ratio of a mass-scaled run (docs/design/mpm.md)
  bool drift_warned_ = false;           ///< the energy balance's drift was warned of

  /// Warns once when the energy balance has held more than EnergyGuard::kDriftWarn of its scale
  /// for the guard's persistence, in whatever form (the guard stops only on motion), naming the
  /// point whose stress power is the largest now.
  void warn_drift(std::int64_t s) {
    const mpm::EnergyGuard& g = solver_.energy_guard();
    if (drift_warned_ || !g.enabled() || !(g.drift() > mpm::EnergyGuard::kDriftWarn)) return;
    drift_warned_ = true;
    const mpm::MaterialPoints& pts = solver_.points();
    if (pts.size() == 0) return;
    std::size_t top = 0;
    double power = -std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < pts.size(); ++p) {
      const common::Mat3 D = 0.5 * (pts.L[p] + pts.L[p].transpose());
      const double w = pts.volume[p] * pts.stress[p].cwiseProduct(D).sum();
      if (w > power) {
        power = w;
        top = p;
      }
    }
    spdlog::warn(
        "mpm step {} (t = {:.6g} s): the energy balance drifts: the steps created {:.4g} J, {:.3g} "
        "of the energy scale {:.4g} J, that no load, wall or gravity put in (kinetic energy now "
        "{:.4g} J; the rest is in the materials' work); the point taking the most work now is id "
        "{} at x = ({:.6g}, {:.6g}, {:.6g}) m ({:.4g} W). Work from nothing is not the material's: "
        "results from here on are suspect (under a footing a row of points settling on a node "
        "plane did this; a smaller mpm.cfl removed it: docs/design/mpm.md, Energy-growth guard)",
        s, solver_.time(), g.created(), g.drift(), g.scale(), solver_.energies().kinetic,
        pts.id[top], pts.x[top][0], pts.x[top][1], pts.x[top][2], power);
  }
};

/// The MPM solver around the farm, at the start state: the checkpoint's, or for a fresh run
/// every point with its RVE's stress (the prepared sample's, not the config's, which is zero
/// for DEM points): row 0 of the outputs, and MUSL's first step.
mpm::Solver start_solver(const CoupledConfig& cfg, RveFarm& farm,
                         const std::optional<CheckpointInfo>& info,
                         const common::StateStore& mpm_state) {
  mpm::Solver solver(cfg.solver, cfg.points, {&farm});
  for (const auto& c : cfg.constraints) solver.add_constraint(c);
  for (const auto& t : cfg.tractions) solver.add_traction(t);
  if (info) {
    solver.load(mpm_state);
  } else {
    mpm::MaterialPoints& pts = solver.points();
    const PointIndex index(farm.ids(), pts.id);
    for (std::size_t p = 0; p < pts.size(); ++p) pts.stress[p] = farm.stresses()[index.rve_of(p)];
  }
  farm.set_step(solver.step_count());
  return solver;
}

Master::Master(const CoupledConfig& cfg, RveFarm& farm, const std::optional<CheckpointInfo>& info,
               const common::StateStore& mpm_state, const std::vector<std::int64_t>& ids,
               std::int64_t fault_abort_at)
    : cfg_(cfg),
      farm_(farm),
      ids_(ids),
      solver_(start_solver(cfg, farm, info, mpm_state)),
      index_(ids, solver_.points().id),
      results_(cfg.output.dir, ids, solver_.points(), info ? info->step : -1,
               solver_.constraint_names(), &cfg.points),
      output_(cfg.output.every),
      grains_(cfg.grains, ids, cfg.output.dir, info ? info->step : -1, info ? info->time : 0.0),
      checkpoints_(cfg.checkpoint, fault_abort_at, info ? info->step : -1, wall_now()),
      balance_(cfg.balance, farm.size()),
      quasi_static_(cfg.solver.quasi_static_ratio, cfg.solver.mass_scaling, cfg.end_time) {}

void Master::run(RunSummary& sum) {
  const std::int64_t start_step = solver_.step_count();
  if (results_.rows() == 0) output();
  if (grains_.due(start_step)) grains_.write(farm_, start_step, solver_.time());
  const double t0 = wall_now();
  ProgressSchedule progress_(cfg_.output.log_every_s, t0);
  balance_.start(start_step, t0);
  const double scaling = cfg_.solver.mass_scaling;
  if (scaling != 1.0) {
    spdlog::warn(
        "mass scaling ON: mpm.mass_scaling = {:.6g}: the MPM inertia is {:.6g} x the real mass "
        "(the weight is not), the CFL time step {:.4g} x larger; only for quasi-static scenes: a "
        "kinetic / internal energy ratio above mpm.quasi_static_ratio = {:.3g} is warned",
        scaling, scaling, std::sqrt(scaling), cfg_.solver.quasi_static_ratio);
  }
  while (more()) {
    if (stop_requested(sum)) break;  // the app logs why
    solver_.step();
    const std::int64_t s = solver_.step_count();
    count_work(sum);
    if (scaling > 1.0) {
      const std::string w = quasi_static_.observe(s, solver_.time(), solver_.energies());
      if (!w.empty()) spdlog::warn("{}", w);
    }
    warn_drift(s);
    if (output_.due(s)) output();
    if (grains_.due(s)) grains_.write(farm_, s, solver_.time());
    if (balance_.due(s)) balance(s);
    const double now = wall_now();
    if (checkpoints_.due(s, now)) {
      checkpoint(sum);
      checkpoints_.restart_clock(wall_now());
    }
    if (progress_.due(now)) progress(s, (now - t0) / static_cast<double>(s - start_step));
    if (cfg_.on_step) cfg_.on_step(s, farm_.times());
  }
  sum.wall_s = wall_now() - t0;
  const mpm::Energies e = solver_.energies();
  spdlog::info("energies: E_kin {:.4g} J, W_int {:.4g} J, E_kin/W_int {:.3g} at the end{}",
               e.kinetic, e.internal_work, e.ratio(),
               scaling > 1.0
                   ? fmt::format(", at most {:.3g} after the first {:.0f} % of the end time",
                                 quasi_static_.max_ratio(), 100.0 * mpm::QuasiStaticWatch::kWarmUp)
                   : std::string());
  if (const mpm::EnergyGuard& g = solver_.energy_guard(); g.enabled()) {
    spdlog::info(
        "energy guard: the steps created at most {:.3g} of the energy scale (now {:.4g} J created "
        "of {:.4g} J; work of gravity, loads and walls {:.4g} J); it stops a run beyond "
        "mpm.energy_guard = {:.3g}; the balance held at most {:.3g} of the scale in any form "
        "(warned beyond {:.3g})",
        g.max_share(), g.created(), g.scale(), g.external_work(), g.share(), g.max_drift(),
        mpm::EnergyGuard::kDriftWarn);
  }
  if (output_.due_at_end(solver_.step_count(), results_.rows())) output();
  if (grains_.due_at_end(solver_.step_count())) {
    grains_.write(farm_, solver_.step_count(), solver_.time());
  }
  results_.flush();
  if (checkpoints_.due_at_end(solver_.step_count(), sum.stopped_by != 0)) checkpoint(sum);
  sum.steps = solver_.step_count();
  sum.time = solver_.time();
  sum.times = farm_.times();
  sum.migrations = farm_.migrations();
  sum.rves_moved = farm_.rves_moved();
}

void Master::checkpoint(RunSummary& sum) {
  results_.flush();
  common::StateStore st;
  solver_.save(st);
  const bool abort_mid_write = checkpoints_.begin_write();
  const std::string path = checkpoint_path(cfg_.output.dir, solver_.step_count());
  farm_.checkpoint(path, solver_.step_count(), solver_.time(), cfg_.job_text, st, abort_mid_write);
  sum.checkpoints.push_back(path);
  checkpoints_.written(solver_.step_count());
  for (const std::string& old : checkpoints_.expired(list_checkpoints(cfg_.output.dir))) {
    std::filesystem::remove(old);
  }
}

void Master::balance(std::int64_t step) {
  const bool moved = farm_.rebalance_if_needed(balance_.threshold(), positions());
  const RebalancePlan& plan = farm_.last_plan();
  const std::int64_t wait = balance_.checked(step, wall_now(), plan.proposal_s);
  if (wait > cfg_.balance.check_every) {
    spdlog::info(
        "farm: step {}: the rebalance proposals (incremental + METIS) took {:.3g} s: next balance "
        "check in {} steps (kept under {:g} % of the run)",
        step, plan.proposal_s, wait, 100.0 * BalanceSchedule::kMetisShare);
  }
  if (!moved) return;
  const bool metis = plan.method == RebalanceMethod::metis;
  const RebalanceProposal& other = metis ? plan.incremental : plan.metis;
  spdlog::info(
      "farm: step {}: rebalanced with {}: imbalance {:.3f} -> {:.3f}, {} RVE(s) moved (predicted "
      "saving {:.3g} s, move {:.3g} s; {}: {:.3f}, {} RVE(s)); {} moved in total",
      step, metis ? fresh_name(plan.style) : to_string(plan.method), plan.imbalance_now,
      plan.imbalance_new, plan.moves, plan.saving_s, plan.move_s,
      metis ? "incremental" : fresh_name(plan.style), other.imbalance, other.moves,
      farm_.rves_moved());
}

void Master::progress(std::int64_t step, double per_step) {
  results_.flush(false);  // the ParaView / CSV indexes within their time share
  const double left = eta_s(step, solver_.time(), cfg_.max_steps, cfg_.end_time, per_step);
  const SampleMeans m = sample_means(solver_.points(), farm_.reports(), cfg_.output.axial_axis);
  const mpm::Energies e = solver_.energies();
  spdlog::info(
      "step {} t = {:.6g} s eps_ax = {:.4g} q = {:.4g} Pa ETA {} imbalance {:.3f} E_kin/W_int "
      "{:.3g} (E_kin {:.4g} J, W_int {:.4g} J)",
      step, solver_.time(), m.eps_ax, m.q, format_duration(left), farm_.imbalance(), e.ratio(),
      e.kinetic, e.internal_work);
}

}  // namespace

CoupledRun::CoupledRun(const CoupledConfig& config, MPI_Comm comm, const std::string* restart)
    : cfg_(config), comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  collective(comm_, [&] {
    cfg_.validate();
    return 0;
  });
  fault_abort_at_ =
      collective(comm_, [&] { return fault_abort_from_env(cfg_.checkpoint.fault_abort_at); });
  // State to start from: the config, or a checkpoint (read and verified on every rank / rank 0).
  std::vector<common::Vec3> x;  // rank 0: point positions by RVE index (the METIS graph)
  if (restart != nullptr) {
    info_ = collective(comm_, [&] { return read_checkpoint_info(*restart); });
    collective(comm_, [&] {
      if (rank_ == 0) mpm_state_ = read_checkpoint_mpm(*restart);
      return 0;
    });
    ids_ = info_->ids;
    collective(comm_, [&] {
      if (rank_ != 0) return 0;
      const std::vector<std::int64_t> pid = mpm_state_.read_i64("points/id");
      const std::vector<double> px = mpm_state_.read_f64("points/x");
      MPMXDEM_CHECK(px.size() == 3 * pid.size(), "points/x: 3 values per point");
      std::vector<common::Vec3> pts;
      for (std::size_t p = 0; p < pid.size(); ++p)
        pts.emplace_back(px[3 * p], px[3 * p + 1], px[3 * p + 2]);
      x = positions_by_rve(ids_, pid, pts);
      return 0;
    });
    farm_ = std::make_unique<RveFarm>(comm_, cfg_.micro, *info_, x, cfg_.solver.grid, cfg_.farm);
  } else {
    ids_ = cfg_.points.id;
    std::sort(ids_.begin(), ids_.end());
    x = positions_by_rve(ids_, cfg_.points.id, cfg_.points.x);
    farm_ = std::make_unique<RveFarm>(comm_, cfg_.micro, ids_, x, cfg_.solver.grid, cfg_.farm);
  }
}

RunSummary CoupledRun::run() {
  RunSummary sum;
  sum.wait = farm_->wait_mode();
  if (rank_ == 0) {
    spdlog::info("farm: {} RVEs on {} rank(s){}, waits {} ({})", ids_.size(), size_,
                 farm_->placement().first_worker() > 0 ? " (rank 0: the MPM only)" : "",
                 to_string(sum.wait),
                 cfg_.farm.wait == WaitMode::automatic
                     ? (sum.wait == WaitMode::spin ? "auto: every thread of the node has a core"
                                                   : "auto: the node's threads share cores")
                     : "as configured");
    const auto workers = static_cast<std::size_t>(farm_->placement().workers());
    if (workers > 1 && ids_.size() < kRvesPerRankForBalance * workers) {
      spdlog::info(
          "farm: {:.0f} RVEs per rank: a rank's sum of fewer than {} RVE step costs still swings "
          "from step to step and the slowest rank sets the step (on the 8 x 16 biaxial 16 ranks "
          "of 32 balance at 0.85, 4 ranks x 4 threads at 0.97): fewer ranks with more threads "
          "each balance better (docs/design/farm.md, \"Choosing ranks, threads and RVEs per "
          "rank\")",
          static_cast<double>(ids_.size()) / static_cast<double>(workers), kRvesPerRankForBalance);
    }
  }
  if (rank_ != 0) {
    farm_->serve();  // throws the error rank 0 reports
  } else {
    try {
      Master(cfg_, *farm_, info_, mpm_state_, ids_, fault_abort_at_).run(sum);
    } catch (...) {
      farm_->stop_with_error(current_error_kind(), common::current_error_text());
      throw;
    }
    farm_->stop();
  }
  MPI_Bcast(&sum.steps, 1, MPI_INT64_T, 0, comm_);
  MPI_Bcast(&sum.time, 1, MPI_DOUBLE, 0, comm_);
  MPI_Bcast(&sum.stopped_by, 1, MPI_INT, 0, comm_);
  return sum;
}

}  // namespace farm
