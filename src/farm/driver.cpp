// Coupled driver: builds the MPM solver on rank 0 around the RVE farm, steps, writes outputs and
// checkpoints, balances, and turns any rank's failure into the same error on every rank.
#include "farm/driver.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "common/errors.hpp"
#include "farm/results.hpp"

namespace farm {

namespace {

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void bad(const std::string& key, const std::string& value, const std::string& rule) {
  throw common::InputError("farm config: " + key + " = " + value + ": " + rule);
}

std::int64_t fault_from_env(std::int64_t configured) {
  const char* env = std::getenv("MPMXDEM_FARM_FAULT");
  if (env == nullptr || *env == '\0') return configured;
  const std::string s(env);
  const std::string prefix = "abort_checkpoint:";
  if (s.rfind(prefix, 0) != 0) {
    bad("MPMXDEM_FARM_FAULT (environment)", s, "must be abort_checkpoint:<n> with n >= 1");
  }
  try {
    const std::int64_t n = std::stoll(s.substr(prefix.size()));
    if (n >= 1) return n;
  } catch (const std::exception&) {
  }
  bad("MPMXDEM_FARM_FAULT (environment)", s, "must be abort_checkpoint:<n> with n >= 1");
  return 0;
}

/// Positions by RVE index (ids ascending) from points in slot order.
std::vector<common::Vec3> positions_by_index(const std::vector<std::int64_t>& ids,
                                             const mpm::MaterialPoints& pts) {
  std::vector<common::Vec3> x(ids.size(), common::Vec3::Zero());
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), pts.id[p]);
    MPMXDEM_CHECK(it != ids.end() && *it == pts.id[p], "point without an RVE");
    x[static_cast<std::size_t>(it - ids.begin())] = pts.x[p];
  }
  return x;
}

std::string error_text() {
  try {
    throw;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
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
    msg = error_text();
  }
  agree_on_errors(comm, kind, msg);
  return std::move(*out);
}

std::string fmt_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const auto t = static_cast<long long>(s);
  return std::to_string(t / 3600) + "h" + std::to_string((t / 60) % 60) + "m" +
         std::to_string(t % 60) + "s";
}

RunSummary run_impl(const CoupledConfig& cfg, MPI_Comm comm, const std::string* restart) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  collective(comm, [&] {
    cfg.validate();
    return 0;
  });
  const std::int64_t fault_at =
      collective(comm, [&] { return fault_from_env(cfg.checkpoint.fault_abort_at); });

  // State to start from: the config, or a checkpoint (read and verified on every rank / rank 0).
  std::optional<CheckpointInfo> info;
  common::StateStore mpm_state;
  if (restart != nullptr) {
    info = collective(comm, [&] { return read_checkpoint_info(*restart); });
    collective(comm, [&] {
      if (rank == 0) mpm_state = read_checkpoint_mpm(*restart);
      return 0;
    });
  }
  std::vector<std::int64_t> ids;
  std::vector<common::Vec3> x;
  if (info) {
    ids = info->ids;
    if (rank == 0) {
      mpm::MaterialPoints pts;
      const auto pid = mpm_state.read_i64("points/id");
      const auto px = mpm_state.read_f64("points/x");
      pts.id = pid;
      for (std::size_t p = 0; p < pid.size(); ++p)
        pts.x.emplace_back(px[3 * p], px[3 * p + 1], px[3 * p + 2]);
      x = positions_by_index(ids, pts);
    }
  } else {
    ids = cfg.points.id;
    std::sort(ids.begin(), ids.end());
    x = positions_by_index(ids, cfg.points);
  }
  std::unique_ptr<RveFarm> farm =
      info ? std::make_unique<RveFarm>(comm, cfg.micro, *info, x, cfg.solver.grid, cfg.farm)
           : std::make_unique<RveFarm>(comm, cfg.micro, ids, x, cfg.solver.grid, cfg.farm);

  RunSummary sum;
  sum.wait = farm->wait_mode();
  if (rank == 0) {
    spdlog::info("farm: {} RVEs on {} rank(s), waits {} ({})", ids.size(), size,
                 to_string(sum.wait),
                 cfg.farm.wait == WaitMode::automatic
                     ? (sum.wait == WaitMode::spin ? "auto: every thread of the node has a core"
                                                   : "auto: the node's threads share cores")
                     : "as configured");
  }
  if (rank != 0) {
    farm->serve();  // throws the error rank 0 reports
  } else {
    try {
      mpm::Solver solver(cfg.solver, cfg.points, {farm.get()});
      for (const auto& c : cfg.constraints) solver.add_constraint(c);
      for (const auto& t : cfg.tractions) solver.add_traction(t);
      if (info) {
        solver.load(mpm_state);
      } else {
        // A fresh run: every point starts with its RVE's stress (the prepared sample's), not
        // the config's (zero for DEM points): row 0 of the outputs, and MUSL's first step.
        mpm::MaterialPoints& pts = solver.points();
        for (std::size_t p = 0; p < pts.size(); ++p) {
          const auto k = std::lower_bound(ids.begin(), ids.end(), pts.id[p]) - ids.begin();
          pts.stress[p] = farm->stresses()[static_cast<std::size_t>(k)];
        }
      }
      farm->set_step(solver.step_count());
      const std::int64_t start_step = solver.step_count();
      ResultsWriter results(cfg.output.dir, ids, solver.points(), info ? info->step : -1);
      auto output = [&] {
        results.append(solver.step_count(), solver.time(), farm->stresses(), farm->reports(),
                       solver.points(),
                       sample_means(solver.points(), farm->reports(), cfg.output.axial_axis));
      };
      if (results.rows() == 0) output();
      std::int64_t n_ckpt = 0;
      std::int64_t last_ckpt_step = info ? info->step : -1;
      auto write_ckpt = [&] {
        results.flush();
        common::StateStore st;
        solver.save(st);
        ++n_ckpt;
        const std::string path = checkpoint_path(cfg.output.dir, solver.step_count());
        farm->checkpoint(path, solver.step_count(), solver.time(), cfg.job_text, st,
                         n_ckpt == fault_at);
        sum.checkpoints.push_back(path);
        last_ckpt_step = solver.step_count();
        const std::vector<std::string> all = list_checkpoints(cfg.output.dir);
        for (std::size_t i = 0; i + static_cast<std::size_t>(cfg.checkpoint.keep) < all.size();
             ++i) {
          std::filesystem::remove(all[i]);
        }
      };
      auto more = [&] {
        const bool by_steps = cfg.max_steps <= 0 || solver.step_count() < cfg.max_steps;
        const bool by_time = cfg.end_time <= 0.0 || solver.time() < cfg.end_time * (1.0 - 1e-12);
        return by_steps && by_time;
      };
      const double t0 = wall_now();
      double last_log = t0;
      double last_ckpt_wall = t0;
      while (more()) {
        solver.step();
        const std::int64_t s = solver.step_count();
        if (s % cfg.output.every == 0) output();
        if (cfg.balance.enabled && size > 1 && s % cfg.balance.check_every == 0) {
          if (farm->rebalance_if_needed(cfg.balance.threshold,
                                        positions_by_index(ids, solver.points()))) {
            const RebalancePlan& plan = farm->last_plan();
            spdlog::info(
                "farm: step {}: rebalanced with METIS: imbalance {:.3f} -> {:.3f}, {} RVE(s) "
                "moved (predicted saving {:.3g} s, move {:.3g} s); {} moved in total",
                s, plan.imbalance_now, plan.imbalance_new, plan.moves, plan.saving_s, plan.move_s,
                farm->rves_moved());
          }
        }
        const double now = wall_now();
        const bool due = (cfg.checkpoint.every_steps > 0 && s % cfg.checkpoint.every_steps == 0) ||
                         (cfg.checkpoint.every_wall_s > 0.0 &&
                          now - last_ckpt_wall >= cfg.checkpoint.every_wall_s);
        if (due) {
          write_ckpt();
          last_ckpt_wall = wall_now();
        }
        if (now - last_log >= cfg.output.log_every_s) {
          last_log = now;
          results.flush(false);  // the ParaView / CSV indexes within their time share
          const double per_step = (now - t0) / static_cast<double>(s - start_step);
          double left = cfg.max_steps > 0 ? static_cast<double>(cfg.max_steps - s) : 1e300;
          if (cfg.end_time > 0.0 && solver.time() > 0.0) {
            left = std::min(
                left, (cfg.end_time - solver.time()) / (solver.time() / static_cast<double>(s)));
          }
          const SampleMeans m =
              sample_means(solver.points(), farm->reports(), cfg.output.axial_axis);
          spdlog::info("step {} t = {:.6g} s eps_ax = {:.4g} q = {:.4g} Pa ETA {} imbalance {:.3f}",
                       s, solver.time(), m.eps_ax, m.q, fmt_duration(left * per_step),
                       farm->imbalance());
        }
        if (cfg.on_step) cfg.on_step(s, farm->times());
      }
      sum.wall_s = wall_now() - t0;
      if (results.rows() == 0 || solver.step_count() % cfg.output.every != 0) output();
      results.flush();
      if (cfg.checkpoint.at_end && last_ckpt_step != solver.step_count()) write_ckpt();
      sum.steps = solver.step_count();
      sum.time = solver.time();
      sum.times = farm->times();
      sum.migrations = farm->migrations();
      sum.rves_moved = farm->rves_moved();
    } catch (...) {
      const ErrorKind kind = current_error_kind();
      farm->stop_with_error(kind, error_text());
      throw;
    }
    farm->stop();
  }
  MPI_Bcast(&sum.steps, 1, MPI_INT64_T, 0, comm);
  MPI_Bcast(&sum.time, 1, MPI_DOUBLE, 0, comm);
  return sum;
}

}  // namespace

void CoupledConfig::validate() const {
  solver.validate();
  points.validate();
  if (points.size() == 0) bad("points", "0", "a coupled run needs at least one material point");
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points.material[p] != 0) {
      bad("points.material of point id " + std::to_string(points.id[p]),
          std::to_string(points.material[p]), "must be 0 (every point is an RVE of the farm)");
    }
  }
  if (!(end_time > 0.0) && max_steps <= 0) {
    bad("end_time / max_steps", std::to_string(end_time) + " / " + std::to_string(max_steps),
        "at least one must be > 0 (when to stop)");
  }
  if (!micro.create || !micro.load)
    bad("micro", "(empty)", "a MicroKind with create and load is required");
  if (output.dir.empty()) bad("output.dir", "\"\"", "an output directory is required");
  if (output.every < 1) bad("output.every", std::to_string(output.every), "must be >= 1 step");
  if (output.axial_axis < 0 || output.axial_axis > 2) {
    bad("output.axial_axis", std::to_string(output.axial_axis), "must be 0, 1 or 2");
  }
  if (checkpoint.every_steps < 0)
    bad("checkpoint.every_steps", std::to_string(checkpoint.every_steps), "must be >= 0");
  if (!(checkpoint.every_wall_s >= 0.0))
    bad("checkpoint.every_wall_s", std::to_string(checkpoint.every_wall_s), "must be >= 0 s");
  if (checkpoint.keep < 1) bad("checkpoint.keep", std::to_string(checkpoint.keep), "must be >= 1");
  if (!(balance.threshold >= 1.0))
    bad("balance.threshold", std::to_string(balance.threshold), "must be >= 1 (max/mean)");
  if (balance.check_every < 1)
    bad("balance.check_every", std::to_string(balance.check_every), "must be >= 1");
}

RunSummary run_coupled(const CoupledConfig& config, MPI_Comm comm) {
  return run_impl(config, comm, nullptr);
}

RunSummary restart_coupled(const CoupledConfig& config, const std::string& checkpoint_path,
                           MPI_Comm comm) {
  return run_impl(config, comm, &checkpoint_path);
}

CheckpointInfo inspect_checkpoint(const std::string& path, bool verify) {
  CheckpointInfo info = read_checkpoint_info(path);
  if (verify) verify_checkpoint(path);
  return info;
}

}  // namespace farm
