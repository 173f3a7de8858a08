// farm::MicroModel: one RVE behind the macro-micro contract of the preCICE micro-manager
// (solve(macro_data, dt), get_state(), set_state()): step under the macro velocity gradient,
// report the Cauchy stress, save/restore as named fields (checkpoints and migration alike).
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/state_io.hpp"
#include "common/types.hpp"

namespace farm {

/// What one micro step did: the only report type of the farm (it travels inside RveRecord,
/// farm/exchange.hpp). Soil-mechanics quantities are compression positive.
struct MicroReport {
  double p = 0.0;              ///< mean pressure -tr(sigma)/3 [Pa]
  double q = 0.0;              ///< deviatoric stress sqrt(3/2 s:s) [Pa]
  double void_ratio = 0.0;     ///< e [-]
  double z = 0.0;              ///< coordination number 2 Nc / N [-] (0 for continuum models)
  std::int64_t dem_steps = 0;  ///< DEM steps (or sub-steps) done [-]
  double t_p = 0.0;            ///< quasi-static time of the step, eq. (11) [s]
  std::uint32_t guards = 0;    ///< guard bits (dem::RveGuard for DemMicro) [-]
  /// Neighbour-list builds in the step [-]: a cost (a build costs ~20 DEM steps of a 300-sphere
  /// RVE), for cost traces (farm/cost_trace.hpp); never output.
  std::uint32_t rebuilds = 0;
  double wall_s = 0.0;  ///< wall-clock seconds of the step [s] (timing only, never state)
};

/// How a member of MicroReport is stored (a count and the guard bits are written as int64).
enum class ReportType : std::uint8_t { real, int64, uint32 };

/// One member of MicroReport as the outputs know it: results.h5's /rve/<name> [row, rve] on every
/// row; with a point_description, also /points/<name> [row, point] (the value of the point's RVE)
/// and the points' Xdmf Scalar <name>. `state`: a property of the RVE's state, known before any
/// step (every rank gathers it at the start, farm/exchange.hpp InitRecord); otherwise a property
/// of the last step (0 before the first). wall_s is timing, never output.
struct ReportField {
  const char* name;               ///< dataset name under /rve (and /points)
  std::size_t offset;             ///< offsetof(MicroReport, member)
  ReportType type;                ///< the member's type
  bool state;                     ///< known from the state (true) or from a step (false)
  const char* unit;               ///< attribute "unit" ("-": dimensionless, "": a count or bits)
  const char* description;        ///< attribute "description" of /rve/<name>
  const char* point_description;  ///< of /points/<name>; nullptr: the RVEs' series only
};

/// The per-step fields in the order results.h5 creates them: a new one is a member of MicroReport,
/// its row here, and where the models set it.
inline constexpr ReportField kReportFields[] = {
    {"p", offsetof(MicroReport, p), ReportType::real, true, "Pa",
     "mean stress p = -tr(sigma)/3, compression positive",
     "p of the point's RVE (/rve/p), compression positive"},
    {"q", offsetof(MicroReport, q), ReportType::real, true, "Pa",
     "von Mises deviatoric stress q = sqrt(3/2 s:s), s = sigma + p I (always >= 0)",
     "q of the point's RVE (/rve/q), von Mises"},
    {"void_ratio", offsetof(MicroReport, void_ratio), ReportType::real, true, "-",
     "void ratio e = V_voids / V_solids", "void ratio of the point's RVE"},
    {"z", offsetof(MicroReport, z), ReportType::real, true, "-",
     "coordination number 2 Nc / N (0 for continuum models)",
     "coordination number of the point's RVE"},
    {"t_p", offsetof(MicroReport, t_p), ReportType::real, false, "s",
     "quasi-static time of the step, eq. (11)", nullptr},
    {"dem_steps", offsetof(MicroReport, dem_steps), ReportType::int64, false, "",
     "DEM steps run for the MPM step", nullptr},
    {"guards", offsetof(MicroReport, guards), ReportType::uint32, false, "",
     "guard bits (dem::RveGuard, docs/design/dem.md; bit 16 farm::kGuardSpared: the DEM was not "
     "stepped, docs/design/sparing.md)",
     nullptr},
};

/// The rows of kReportFields with `state` (they must be reals: InitRecord is doubles only).
constexpr std::size_t report_state_fields() {
  std::size_t n = 0;
  for (const ReportField& f : kReportFields) n += f.state ? 1 : 0;
  return n;
}

constexpr bool report_states_are_real() {
  for (const ReportField& f : kReportFields) {
    if (f.state && f.type != ReportType::real) return false;
  }
  return true;
}
static_assert(report_states_are_real(), "InitRecord carries the state fields as doubles");

/// The value of a real field of `r`; of an integer one, as an int64.
inline double report_real(const MicroReport& r, const ReportField& f) {
  double v = 0.0;
  std::memcpy(&v, reinterpret_cast<const char*>(&r) + f.offset, sizeof v);
  return v;
}
inline std::int64_t report_int(const MicroReport& r, const ReportField& f) {
  const char* at = reinterpret_cast<const char*>(&r) + f.offset;
  if (f.type == ReportType::uint32) {
    std::uint32_t v = 0;
    std::memcpy(&v, at, sizeof v);
    return v;
  }
  std::int64_t v = 0;
  std::memcpy(&v, at, sizeof v);
  return v;
}
/// Sets a real field of `r`.
inline void set_report_real(MicroReport& r, const ReportField& f, double v) {
  std::memcpy(reinterpret_cast<char*>(&r) + f.offset, &v, sizeof v);
}

/// Grain-scale measures of an RVE's current state (dem::Measures): computed only when an output
/// row is written (RveFarm::measure, one command of its own), never on the other MPM steps.
/// Continuum models have none: every entry NaN (MicroMeasures::none()). Every member has its row
/// in kMeasureFields, from which the exchange's size check, results.h5 and the points' Xdmf view
/// are made: a new measure is a member here, its row there, and where the model computes it.
struct MicroMeasures {
  double fabric[9] = {};    ///< fabric tensor <n (x) n> over the contacts, row-major [-]
  double z_mech = 0.0;      ///< coordination without rattlers 2 Nc' / N' [-]
  double unbalanced = 0.0;  ///< mean |f_sphere| / mean |f_contact| [-]
  double kinetic = 0.0;     ///< kinetic energy of the spheres' fluctuating motion [J]
  /// Every entry NaN: what a model without grains reports.
  [[nodiscard]] static MicroMeasures none();
};

/// One member of MicroMeasures as the outputs know it: results.h5's dataset /rve/<name> [row, rve,
/// components] with its unit and description attributes, and the points' Xdmf attribute <name>
/// (a Scalar for 1 component, a Vector for 3, a Tensor for 9).
struct MeasureField {
  const char* name;         ///< dataset name under /rve and Xdmf attribute name
  std::size_t offset;       ///< offsetof(MicroMeasures, member)
  int components;           ///< doubles of the member: 1, 3 or 9 (a row-major 3x3)
  const char* unit;         ///< attribute "unit" ("-": dimensionless)
  const char* description;  ///< attribute "description"
};

/// The measures in the order results.h5 creates them and the Xdmf view lists them.
inline constexpr MeasureField kMeasureFields[] = {
    {"fabric", offsetof(MicroMeasures, fabric), 9, "-",
     "fabric tensor <n (x) n> over the RVE's contacts (n: unit contact normal), row-major 3x3 "
     "[row, rve, 9], trace 1; NaN for continuum models. Written for output rows only"},
    {"z_mech", offsetof(MicroMeasures, z_mech), 1, "-",
     "mechanical coordination number 2 Nc' / N' without rattlers (spheres with < 2 contacts, "
     "removed repeatedly); NaN for continuum models"},
    {"unbalanced", offsetof(MicroMeasures, unbalanced), 1, "-",
     "unbalanced force ratio: mean over spheres of |resultant force| / mean over contacts of "
     "|contact force|; NaN for continuum models"},
    {"kinetic_energy", offsetof(MicroMeasures, kinetic), 1, "J",
     "kinetic energy of the spheres' fluctuating motion 1/2 sum (m |u|^2 + I |w|^2) (u: velocity "
     "relative to the cell's affine field); NaN for continuum models"},
};

/// Doubles in all the rows of kMeasureFields.
constexpr std::size_t measure_doubles() {
  std::size_t n = 0;
  for (const MeasureField& f : kMeasureFields) n += static_cast<std::size_t>(f.components);
  return n;
}
static_assert(sizeof(MicroMeasures) == measure_doubles() * sizeof(double),
              "every member of MicroMeasures needs its row in kMeasureFields");

/// The doubles of `m` that `f` names.
inline std::span<const double> values(const MicroMeasures& m, const MeasureField& f) {
  return {reinterpret_cast<const double*>(reinterpret_cast<const char*>(&m) + f.offset),
          static_cast<std::size_t>(f.components)};
}
inline std::span<double> values(MicroMeasures& m, const MeasureField& f) {
  const std::span<const double> v = values(std::as_const(m), f);
  return {const_cast<double*>(v.data()), v.size()};
}

/// One file of a grain-scale view: its name inside the view directory and its whole content.
struct ViewFile {
  std::string name;
  std::string text;
};

/// One RVE. Implementations are deterministic: the same calls on the same state give the same
/// bits on any rank and thread.
class MicroModel {
 public:
  virtual ~MicroModel() = default;
  /// Advance by dt under the macro velocity gradient L (v = L x, spin included).
  /// @param L [1/s] @param dt MPM step [s], > 0
  /// @post stress() is the new Cauchy stress. Throws common::NumericalError on a failure
  /// (non-finite stress, guard exhausted); the farm adds the RVE id and the step.
  virtual MicroReport step(const common::Mat3& L, double dt) = 0;
  /// Cauchy stress, TENSION POSITIVE (the seam convention of mpm::MaterialModel) [Pa].
  [[nodiscard]] virtual common::Mat3 stress() const = 0;
  /// Measures of the current state without stepping: p, q, void_ratio, z (and guards that
  /// describe the state); dem_steps, t_p and wall_s are zero. Outputs at step 0 use it.
  [[nodiscard]] virtual MicroReport report() const = 0;
  /// Grain-scale measures of the current state (an extra pass over the contacts for DEM: called
  /// only for output rows). MicroMeasures::none() for continuum models.
  [[nodiscard]] virtual MicroMeasures measures() const = 0;
  /// The grain-scale view of the current state as files for ParaView, named from `stem` (a plain
  /// file name): for DEM the spheres, the contact network and the periodic cell
  /// (dem/vtk_export.hpp, docs/design/dem.md "Grain-scale views"). Continuum models have none
  /// (empty).
  [[nodiscard]] virtual std::vector<ViewFile> grain_view(const std::string& stem) const {
    (void)stem;
    return {};
  }
  /// Whole state as named fields; the loader of the same kind rebuilds an equal model.
  virtual void save(common::StateWriter& writer) const = 0;
  /// Cost estimate before any timing exists (particle count for DEM) [arbitrary units, > 0].
  [[nodiscard]] virtual double cost_estimate() const = 0;
  /// Largest elastic wave speed of the RVE's continuum response (CFL bound) [m/s].
  [[nodiscard]] virtual double wave_speed() const = 0;
  /// Whether the current state is a dilute material whose volume carries no lasting force (for
  /// DEM, a spray of grains: dem::Rve::dilute). The MPM's blow-up bound on a point's volume does
  /// not apply to it (mpm::MaterialModel::mark_dilute). Continuum models: never.
  [[nodiscard]] virtual bool dilute() const { return false; }
};

inline MicroMeasures MicroMeasures::none() {
  MicroMeasures m;
  for (const MeasureField& f : kMeasureFields) {
    for (double& v : values(m, f)) v = std::numeric_limits<double>::quiet_NaN();
  }
  return m;
}

/// How the farm creates and restores micro models; every rank holds an identical copy.
struct MicroKind {
  /// Creates the RVE of material point `id` (called only on the rank that owns it).
  std::function<std::unique_ptr<MicroModel>(std::int64_t id)> create;
  /// Rebuilds an RVE from what MicroModel::save wrote (restart, migration).
  std::function<std::unique_ptr<MicroModel>(const common::StateReader& reader)> load;
  /// Optional, collective over the farm's communicator: called once on every rank of a fresh
  /// start, with the ids the rank will create, before the first create(); makes ahead, spread
  /// over the ranks and their threads, what several RVEs share (the DEM preparations of
  /// app::DemPool). create() must give the same RVEs with or without it. An error must be
  /// thrown on every rank alike (farm::agree_on_errors), never on some ranks only.
  std::function<void(const std::vector<std::int64_t>& ids, MPI_Comm comm)> prepare;
};

}  // namespace farm
