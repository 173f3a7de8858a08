// `mpmxdem dem JOB`: a pure DEM job on one rank (OpenMP inside): prepare the sample, then the
// loading programme of [dem.loading]; time series to dem_series.csv/.h5, packings to text files.
// This is the pure-DEM reference of the paper (its 30,000-sphere sample).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "app/commands/commands.hpp"
#include "app/run/progress.hpp"
#include "app/run/series_output.hpp"
#include "app/run/stop_signals.hpp"
#include "app/setup/dem_setup.hpp"
#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "dem/element_test.hpp"
#include "dem/measures.hpp"
#include "dem/packing_io.hpp"

namespace app {

namespace {

std::vector<Column> series_columns() {
  return {{"iter", ""},   {"time", "s"}, {"dt", "s"},     {"eps_a", ""},     {"eps_v", ""},
          {"p", "Pa"},    {"q", "Pa"},   {"sig_a", "Pa"}, {"sig_r", "Pa"},   {"sxx", "Pa"},
          {"syy", "Pa"},  {"szz", "Pa"}, {"sxy", "Pa"},   {"sxz", "Pa"},     {"syz", "Pa"},
          {"e", ""},      {"Z", ""},     {"Zm", ""},      {"nContacts", ""}, {"unbalanced", ""},
          {"wall_s", "s"}};
}

struct Reference {
  double lz0 = 0.0;
  double v0 = 0.0;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
};

// One row, in the column order above: p, q, sig_a, sig_r compression positive (the paper's
// plots); components in the seam's convention (tension positive, as YADE writes them). sig_r is
// the mean of sigma_xx and sigma_yy, or sigma_xx alone in a plane-strain (biaxial) test.
std::vector<double> row(const dem::Simulation& sim, const dem::Measures& m, const Reference& ref,
                        bool plane_strain = false) {
  const auto& s = m.stress;
  const double eps_a = -std::log(sim.cell().h(2, 2) / ref.lz0);
  const double eps_v = -std::log(sim.cell().volume() / ref.v0);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - ref.start).count();
  const double sig_a = -s(2, 2);
  const double sig_r = plane_strain ? -s(0, 0) : -0.5 * (s(0, 0) + s(1, 1));
  return {static_cast<double>(sim.steps()),
          sim.time(),
          sim.dt(),
          eps_a,
          eps_v,
          m.p,
          sig_a - sig_r,
          sig_a,
          sig_r,
          s(0, 0),
          s(1, 1),
          s(2, 2),
          s(0, 1),
          s(0, 2),
          s(1, 2),
          m.void_ratio,
          m.z,
          m.z_mech,
          static_cast<double>(m.n_contacts),
          m.unbalanced,
          wall};
}

void check_finite(const dem::Measures& m, const dem::Simulation& sim) {
  if (!std::isfinite(m.p) || !std::isfinite(m.q)) {
    throw common::NumericalError(
        fmt::format("DEM step {} (t = {:.6g} s): stress is not finite (p = {}, q = {})",
                    sim.steps(), sim.time(), m.p, m.q));
  }
}

/// A drained triaxial test whose servo no longer holds the lateral stresses is stopped: its curve
/// would be another test's (dem.loading.lateral_tolerance).
void check_lateral_control(const common::Mat3& stress, double confining, double tol, double eps_a,
                           const dem::Simulation& sim, int axes) {
  if (eps_a <= 1e-3) return;  // the servo picks up the lateral rate first
  for (int a = 0; a < axes; ++a) {
    const double sig = -stress(a, a);
    const double err = std::abs(sig - confining) / confining;
    if (err > tol) {
      throw common::NumericalError(fmt::format(
          "DEM step {} (t = {:.6g} s, eps_a = {:.4g}): the lateral stress control failed: "
          "sigma_{} = {:.4g} Pa against the confining pressure {:.4g} Pa ({:.1f} % off, "
          "dem.loading.lateral_tolerance = {}): the servo cannot follow this loading rate; lower "
          "dem.loading.inertial_number",
          sim.steps(), sim.time(), eps_a, a == 0 ? "xx" : "yy", sig, confining, 100.0 * err, tol));
    }
  }
}

// What the loadings share: the job, the command line, the series and its reference state.
struct Loading {
  const Job& job;
  const Options& o;
  dem::LoadingType type;  ///< dem.loading.type
  SeriesWriter& series;
  Reference ref;
  std::int64_t every = 0;
  std::int64_t max_steps = 0;
};

// A loading's end: DEM steps done, and whether a signal stopped it before its end.
struct LoadingEnd {
  std::int64_t done = 0;
  bool cut = false;
};

// A drained triaxial or biaxial test; a signal stops it at its next series row.
LoadingEnd triaxial(dem::Simulation& sim, const Loading& ld) {
  const Job& job = ld.job;
  const Options& o = ld.o;
  SeriesWriter& series = ld.series;
  const Reference& ref = ld.ref;
  struct Stopped {};  // thrown by the observer, caught below
  LoadingEnd end;
  const std::string type(dem::loading_type_name(ld.type));
  const bool plane = ld.type == dem::LoadingType::biaxial;
  bool generated = false;
  const double rho = job.number("dem.material.density");
  dem::DrainedTriaxial test;
  test.confining = job.number("dem.loading.confining_pressure");
  const double d50 = dem_d50(job, dem_packing(job, generated));
  test.axial_rate =
      dem::strain_rate(job.number("dem.loading.inertial_number"), d50, rho, test.confining);
  test.eps_end = job.number("dem.loading.axial_strain");
  test.plane_strain = plane;
  test.check_every = ld.every;
  test.max_steps = ld.max_steps;
  const double lateral_tol = job.number("dem.loading.lateral_tolerance");
  spdlog::info(
      "{}: d50 = {:.4g} m, t_ref = d50 sqrt(rho/p) = {:.4g} s, axial strain rate {:.4g} "
      "1/s, to eps_a = {}, lateral stress {:.4g} Pa{}; about {:.3g} DEM steps",
      type, d50, dem::inertial_time(d50, rho, test.confining), test.axial_rate, test.eps_end,
      test.confining, plane ? " on x, zero strain on y (plane strain)" : "",
      test.eps_end / test.axial_rate / sim.dt());
  check_step_count(job, o, test.eps_end / test.axial_rate / sim.dt(), "DEM",
                   "dem.loading.inertial_number");
  Progress progress(type, test.eps_end);
  try {
    end.done = dem::run_drained_triaxial(
        sim, test, [&](const dem::Simulation& s, const dem::TriaxialProgress& now) {
          const dem::Measures m = dem::measure(s);
          check_finite(m, s);
          series.add(row(s, m, ref, plane));
          check_lateral_control(m.stress, test.confining, lateral_tol, now.eps_a, s, plane ? 1 : 2);
          progress.update(
              now.eps_a, s.steps(),
              fmt::format("q/p {:.3f}, eps_v {:.4f}, e {:.4f}", m.q / m.p, now.eps_v, m.void_ratio),
              now.eps_a >= test.eps_end);
          if (!now.last && StopSignals::received() != 0) {
            end.done = now.steps;
            throw Stopped{};
          }
        });
  } catch (const Stopped&) {
    end.cut = true;  // done: the steps up to the last row
  }
  return end;
}

// An isotropic equilibration (no rows to stop at: no signal ends it).
LoadingEnd isotropic(dem::Simulation& sim, const Loading& ld) {
  const Job& job = ld.job;
  dem::EquilibriumTarget t;
  t.pressure = job.number("dem.loading.confining_pressure");
  t.stress_tol = job.number("dem.preparation.stress_tolerance");
  t.unbalanced_tol = job.number("dem.preparation.unbalanced_force");
  const std::int64_t done = dem::equilibrate(sim, t);
  ld.series.add(row(sim, dem::measure(sim), ld.ref));
  return {done, false};
}

// A prescribed velocity gradient for a duration; a signal stops it at its next series row.
LoadingEnd strain_path(dem::Simulation& sim, const Loading& ld) {
  const Job& job = ld.job;
  const Options& o = ld.o;
  SeriesWriter& series = ld.series;
  const Reference& ref = ld.ref;
  std::int64_t done = 0;
  const auto& l = job.numbers("dem.loading.velocity_gradient");
  const common::Mat3 L = common::row_major(l.data());
  const double duration = job.number("dem.loading.duration");
  check_step_count(job, o, duration / sim.dt(), "DEM", "dem.loading.duration");
  const double t_end = sim.time() + duration;
  Progress progress("strain path", duration);
  const double t0 = sim.time();
  while (sim.time() < t_end && done < ld.max_steps && StopSignals::received() == 0) {
    sim.cell().l = L;
    // The steps left, compared in double precision before the conversion.
    const double left = std::max(1.0, std::floor((t_end - sim.time()) / sim.dt()));
    const std::int64_t n =
        std::min(ld.max_steps - done,
                 left < static_cast<double>(ld.every) ? static_cast<std::int64_t>(left) : ld.every);
    dem::advance(sim, nullptr, n);
    done += n;
    const dem::Measures m = dem::measure(sim);
    check_finite(m, sim);
    series.add(row(sim, m, ref));
    progress.update(sim.time() - t0, sim.steps(), fmt::format("p {:.4g} Pa, q {:.4g} Pa", m.p, m.q),
                    sim.time() >= t_end);
  }
  // Only a signal ends the loop early.
  return {done, sim.time() < t_end && done < ld.max_steps};
}

}  // namespace

int command_dem(const Options& o, const Comm& comm) {
  const Job job = load_job_collective(o.job, comm);
  check_omp_environment(comm);
  if (!job.has_section("dem.loading")) {
    throw common::InputError(fmt::format(
        "{}: `dem` needs a [dem.loading] section (what to do after preparation)", job.file()));
  }
  // Nothing is written before the sample is prepared (rank 0; its error reaches every rank).
  check_output(o, comm);
  check_job_packing(job, comm);
  std::optional<dem::Simulation> sample;
  on_root(comm, [&] { sample.emplace(prepared_sample(job)); });
  const std::filesystem::path out = open_output(o, job, comm);
  if (comm.size > 1) {
    spdlog::warn("`dem` runs one sample on rank 0 with OpenMP; ranks 1..{} have nothing to do",
                 comm.size - 1);
  }
  if (comm.rank != 0) return 0;

  dem::Simulation sim = std::move(*sample);
  dem::Packing prepared{sim.cell(), sim.spheres().x, sim.spheres().r};
  prepared.cell.l.setZero();
  dem::write_packing((out / "prepared_packing.txt").string(), prepared,
                     "prepared by mpmxdem dem " + o.job);

  const dem::LoadingType type = dem_loading(job).type;
  const std::int64_t every = job.integer("output.every");
  const std::int64_t max_steps =
      o.max_steps >= 0 ? o.max_steps : std::numeric_limits<std::int64_t>::max();
  SeriesWriter series(out, "dem_series", series_columns());
  Reference ref;
  ref.lz0 = sim.cell().h(2, 2);
  ref.v0 = sim.cell().volume();
  series.add(row(sim, dem::measure(sim), ref));

  // From here a signal ends the loading at its next series row, with the series and the final
  // packing written (docs/reference/errors.md, "Stopping a run"); a pure DEM test has no
  // checkpoint. (Not during an isotropic equilibration: it has no rows to stop at.)
  std::optional<StopSignals> signals;
  if (type != dem::LoadingType::isotropic) signals.emplace();
  const Loading ld{job, o, type, series, ref, every, max_steps};
  LoadingEnd end;
  switch (type) {
    case dem::LoadingType::triaxial:
    case dem::LoadingType::biaxial:
      end = triaxial(sim, ld);
      break;
    case dem::LoadingType::isotropic:
      end = isotropic(sim, ld);
      break;
    case dem::LoadingType::strain_path:
      end = strain_path(sim, ld);
      break;
  }
  const std::int64_t done = end.done;
  const bool cut = end.cut;
  if (done >= max_steps) spdlog::warn("stopped after --max-steps {} DEM steps", max_steps);
  series.finish(job.has("title") ? job.text("title") : o.job);
  dem::Packing final_pk{sim.cell(), sim.spheres().x, sim.spheres().r};
  final_pk.cell.l.setZero();
  dem::write_packing((out / "final_packing.txt").string(), final_pk,
                     "final state of mpmxdem dem " + o.job);
  spdlog::info("done: {} loading steps; series in {} ({} rows)", done,
               (out / "dem_series.csv").string(), series.rows());
  if (cut) {
    const int stopped = StopSignals::received();
    spdlog::warn(
        "stopped by {} after {} loading steps, before the end of the loading: the series and {} "
        "hold the state there (a pure DEM test has no checkpoint; exit {} = 128 + {})",
        signal_name(stopped), done, (out / "final_packing.txt").string(), 128 + stopped, stopped);
    return 128 + stopped;
  }
  return 0;
}

}  // namespace app
