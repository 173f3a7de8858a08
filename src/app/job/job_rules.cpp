// Cross-key rules of a job file: what one key requires of others (sample source, loading type,
// materials of the bodies, geometry). Single-key rules live in the schema.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/job/job.hpp"
#include "app/job/memory_check.hpp"
#include "app/job/schema_params.hpp"
#include "app/setup/dem_setup.hpp"
#include "app/setup/insitu.hpp"
#include "app/setup/mpm_setup.hpp"
#include "common/choice_table.hpp"
#include "common/errors.hpp"
#include "dem/params.hpp"
#include "mpm/formulation.hpp"
#include "mpm/shape_function.hpp"
#include "mpm/solver.hpp"

namespace app {

namespace {

// A path short enough to print (a 100 kB path is not echoed whole).
std::string short_path(const std::string& p) {
  return p.size() > 120 ? p.substr(0, 50) + "..." + p.substr(p.size() - 50) : p;
}

class Rules {
 public:
  explicit Rules(const Job& job) : job_(job) {}

  void require(const std::string& path, const std::string& why) {
    if (!job_.has(path)) errors_.push_back(job_.missing_message(path, "required " + why));
  }
  void fail(const std::string& path, const std::string& rule) {
    errors_.push_back(job_.message(path, rule));
  }
  void fail_missing(const std::string& path, const std::string& rule) {
    errors_.push_back(job_.missing_message(path, rule));
  }
  void fail_section(const std::string& path, const std::string& rule) {
    errors_.push_back(job_.section_message(path, rule));
  }
  void add(const std::string& message) { errors_.push_back(message); }
  [[nodiscard]] const std::vector<std::string>& errors() const { return errors_; }

 private:
  const Job& job_;
  std::vector<std::string> errors_;
};

void sample_rules(const Job& job, Rules& r) {
  if (!job.has_section("dem.sample")) return;
  if (job.has("dem.sample.cell") && !job.has("dem.sample.packing")) {
    r.fail("dem.sample.cell",
           "only for a packing file (dem.sample.packing): a generated "
           "sample makes its own cell");
  }
  if (job.has("dem.sample.packing")) {
    for (const char* k :
         {"dem.sample.spheres", "dem.sample.psd_diameters", "dem.sample.psd_passing"}) {
      if (job.has(k)) r.fail(k, "not used when dem.sample.packing is given: remove one of them");
    }
    // Not its tolerance: a resolved job (job.resolved.toml) writes every default.
    if (written(job, "dem.preparation.void_ratio")) {
      r.fail("dem.preparation.void_ratio",
             "only for a generated sample: a packing file (dem.sample.packing) is re-equilibrated "
             "as it is, not compacted");
    }
    std::filesystem::path p(job.text("dem.sample.packing"));
    if (p.is_relative()) p = std::filesystem::path(job.directory()) / p;
    std::error_code ec;
    if (!std::filesystem::exists(p, ec)) {
      r.fail("dem.sample.packing",
             fmt::format("no such file '{}' (paths are relative to the job file)",
                         short_path(p.string())));
    } else if (!std::filesystem::is_regular_file(p, ec)) {
      r.fail("dem.sample.packing",
             fmt::format("'{}' is not a regular file (a directory, a device or a pipe): a "
                         "packing is a text file",
                         short_path(p.string())));
    }
    return;
  }
  const std::string why = "when no packing file is given (dem.sample.packing)";
  r.require("dem.sample.spheres", why);
  r.require("dem.sample.psd_diameters", why);
  r.require("dem.sample.psd_passing", why);
  if (job.has("dem.sample.spheres")) {
    // An upper bound from the memory a sample needs (spheres, contacts, neighbour lists: about
    // kBytesPerSphere each, measured order of magnitude) against this machine's memory.
    constexpr double kBytesPerSphere = 2048.0;
    const double mem = usable_memory_bytes();
    const auto n = static_cast<double>(job.integer("dem.sample.spheres"));
    if (mem > 0.0 && n * kBytesPerSphere > mem) {
      r.fail("dem.sample.spheres",
             fmt::format("a sample of {:.3g} spheres needs about {:.3g} GB of memory ({} bytes per "
                         "sphere), more than the {:.3g} GB this machine lets the job use: at most "
                         "{:.0f} spheres",
                         n, n * kBytesPerSphere / 1e9, kBytesPerSphere, mem / 1e9,
                         std::floor(mem / kBytesPerSphere)));
    }
  }
  if (!job.has("dem.sample.psd_diameters") || !job.has("dem.sample.psd_passing")) return;
  const auto& d = job.numbers("dem.sample.psd_diameters");
  const auto& f = job.numbers("dem.sample.psd_passing");
  if (d.size() != f.size()) {
    r.fail("dem.sample.psd_passing",
           fmt::format("must have as many entries as dem.sample.psd_diameters ({}), not {}",
                       d.size(), f.size()));
    return;
  }
  for (std::size_t i = 1; i < d.size(); ++i) {
    if (!(d[i] > d[i - 1]))
      return r.fail("dem.sample.psd_diameters", "must be strictly increasing");
    if (f[i] < f[i - 1]) return r.fail("dem.sample.psd_passing", "must be non-decreasing");
  }
  if (f.front() != 0.0 || f.back() != 1.0)
    r.fail("dem.sample.psd_passing", "must start at 0 and end at 1");
}

// The keys of one contact law are required with it and refused with another: CohFrict's in
// [dem.material] (and [dem.material.twisting]), every other law's in its own table
// (dem::for_each_table_law).
void material_rules(const Job& job, Rules& r) {
  if (!job.has_section("dem.material")) return;
  const std::string law = job.has("dem.material.contact_law")
                              ? job.text("dem.material.contact_law")
                              : std::string(dem::contact_law_name(dem::Material{}.law));
  const std::string why = fmt::format("with dem.material.contact_law = \"{}\"", law);
  const std::string refuse = fmt::format("not used {}: remove it or change the law", why);
  if (law == dem::contact_law_name(dem::ContactLawKind::cohfrict)) {
    for (const auto& p : dem::kCohFrict) {
      // The rows of the optional [dem.material.twisting] table are required by the schema.
      if (p.key.find('.') == std::string_view::npos) r.require(dem::kCohFrict.name(p), why);
    }
  }
  dem::for_each_table_law([&](const auto& d) {
    const std::string section(d.section());
    if (law != d.name()) {
      if (job.has_section(section)) r.fail_section(section, refuse);
      return;
    }
    if (!job.has_section(section)) {
      std::string keys;
      for (const auto& p : d.table) keys += (keys.empty() ? "" : ", ") + std::string(p.key);
      r.fail("dem.material.contact_law", fmt::format("needs the table [{}] ({})", section, keys));
    }  // present: the schema requires its keys
  });
  if (law == dem::contact_law_name(dem::ContactLawKind::cohfrict)) return;
  for (const auto& p : dem::kCohFrict) {
    if (job.has(dem::kCohFrict.name(p))) r.fail(dem::kCohFrict.name(p), refuse);
  }
  if (job.has_section("dem.material.twisting")) r.fail_section("dem.material.twisting", refuse);
}

void loading_rules(const Job& job, Rules& r) {
  if (!job.has_section("dem.loading")) return;
  const dem::LoadingType type = dem_loading(job).type;
  const std::string why =
      fmt::format("for dem.loading.type = \"{}\"", dem::loading_type_name(type));
  if (type == dem::LoadingType::triaxial || type == dem::LoadingType::biaxial) {
    for (const char* k : {"dem.loading.inertial_number", "dem.loading.axial_strain",
                          "dem.loading.confining_pressure"})
      r.require(k, why);
  } else if (type == dem::LoadingType::isotropic) {
    for (const char* k : {"dem.loading.inertial_number", "dem.loading.confining_pressure"})
      r.require(k, why);
  } else {
    for (const char* k : {"dem.loading.velocity_gradient", "dem.loading.duration"})
      r.require(k, why);
  }
}

void numerics_rules(const Job& job, Rules& r) {
  // The adaptive skin's range [verlet_skin_min, verlet_skin] (each key's own range: the schema).
  const std::string lo = "dem.numerics.verlet_skin_min";
  if (!job.has(lo)) return;
  const double hi = job.has("dem.numerics.verlet_skin") ? job.number("dem.numerics.verlet_skin")
                                                        : dem::Numerics{}.skin_factor;
  if (job.number(lo) > hi) {
    r.fail(lo, fmt::format("must be <= dem.numerics.verlet_skin ({:g}): the thinnest skin of "
                           "the adaptive range, whose widest is verlet_skin",
                           hi));
  }
}

void regularisation_rules(const Job& job, Rules& r) {
  if (!job.has_section("mpm.regularisation")) return;
  // Both written as 0: off, as a run's job.resolved.toml writes the defaults of a job without it.
  const auto off = [&](const char* key) { return written(job, key) && job.number(key) == 0.0; };
  if (off("mpm.regularisation.length") && off("mpm.regularisation.modulus")) return;
  // The strain-gradient regularisation needs its length and its modulus (no silent default).
  for (const char* key : {"mpm.regularisation.length", "mpm.regularisation.modulus"}) {
    if (!written(job, key)) {
      r.fail_missing(key,
                     "required in [mpm.regularisation]: the regularisation needs its length "
                     "l and its modulus H (docs/design/mpm.md, Regularisation)");
    } else if (!(job.number(key) > 0.0)) {
      r.fail(key, "must be > 0 in [mpm.regularisation] (remove the table for no regularisation)");
    }
  }
}

// The friction softening: both keys or neither, with a friction angle above the residual one and
// a deviatoric flow.
void softening_rules(const Job& job, Rules& r) {
  const std::string phi_r = "mpm.elastic.residual_friction_angle";
  const std::string gamma = "mpm.elastic.softening_strain";
  if (!job.has(phi_r) && !job.has(gamma)) return;
  if (!job.has(gamma)) {
    r.fail(phi_r, "needs mpm.elastic.softening_strain: the strain at which it is reached");
    return;
  }
  if (!job.has(phi_r)) {
    r.fail(gamma, "needs mpm.elastic.residual_friction_angle: the friction it softens to");
    return;
  }
  // The table's range takes 0 (farm::ElasticMaterial: no softening); a job writing 0 would mean
  // a sudden drop, which the model does not do.
  if (!(job.number(gamma) > 0.0)) {
    r.fail(gamma,
           "must be > 0 (remove it and mpm.elastic.residual_friction_angle for no "
           "softening)");
  }
  const std::string phi = "mpm.elastic.friction_angle";
  if (!job.has(phi)) {
    r.fail(phi_r, "needs mpm.elastic.friction_angle: the peak it softens from");
  } else if (job.number(phi_r) > job.number(phi)) {
    r.fail(phi_r, fmt::format("must be <= mpm.elastic.friction_angle ({:g} deg): friction "
                              "softens, it does not harden",
                              job.number(phi)));
  }
  const std::string psi = "mpm.elastic.dilatancy_angle";
  if (job.has(psi) && job.number(psi) != 0.0) {
    r.fail(psi,
           "must be 0 with mpm.elastic.softening_strain: the softening cone has a "
           "deviatoric flow");
  }
}

// The dilatancy of the Drucker-Prager continuum: with its friction angle, and not above it; its
// cut-off with a dilatancy; then its softening.
void continuum_rules(const Job& job, Rules& r) {
  softening_rules(job, r);
  const std::string psi = "mpm.elastic.dilatancy_angle";
  const std::string cutoff = "mpm.elastic.dilatancy_cutoff";
  if (job.has(cutoff)) {
    // The table's range takes 0 (farm::ElasticMaterial: no cut-off); a job writing 0 would mean
    // no dilatancy at all, which is dilatancy_angle = 0.
    if (!(job.number(cutoff) > 0.0)) {
      r.fail(cutoff, "must be > 0 (remove it for a material that dilates for ever)");
    } else if (!job.has(psi) || !(job.number(psi) > 0.0)) {
      r.fail(cutoff, "needs mpm.elastic.dilatancy_angle > 0: it stops the dilatancy");
    }
  }
  if (!job.has(psi)) return;
  const std::string phi = "mpm.elastic.friction_angle";
  if (!job.has(phi)) {
    r.fail(psi, "needs mpm.elastic.friction_angle: a linear elastic material has no plastic flow");
  } else if (job.number(psi) > job.number(phi)) {
    r.fail(psi, fmt::format("must be <= mpm.elastic.friction_angle ({:g} deg): a flow more "
                            "dilatant than associated is not a granular material",
                            job.number(phi)));
  }
}

// The thickness axis of plane strain (mpm.plane_strain; its names are kPlaneStrainAxisNames'),
// -1 in 3D.
int plane_strain_axis(const Job& job) {
  if (!job.has("mpm.plane_strain")) return -1;
  return common::value_of(mpm::kPlaneStrainAxisNames, job.text("mpm.plane_strain")).value_or(-1);
}

struct BodyMaterials {
  bool dem = false;
  bool elastic = false;
};

// Each body's box inside the grid (and clear of its boundary with uGIMP); the materials used.
BodyMaterials body_rules(const Job& job, Rules& r) {
  const auto& origin = job.numbers("mpm.grid.origin");
  const auto& h = job.numbers("mpm.grid.spacing");
  const auto& n = job.integers("mpm.grid.cells");
  BodyMaterials used;
  for (std::size_t b = 0; b < job.count("mpm.body"); ++b) {
    const std::string base = fmt::format("mpm.body[{}].", b);
    const auto& lo = job.numbers(base + "min");
    const auto& hi = job.numbers(base + "max");
    for (int a = 0; a < 3; ++a) {
      if (!(hi[a] > lo[a])) {
        r.fail(base + "max",
               fmt::format("must be greater than min on every axis (axis {})", "xyz"[a]));
        break;
      }
      const double top = origin[a] + h[a] * static_cast<double>(n[a]);
      if (lo[a] < origin[a] || hi[a] > top) {
        r.fail(base + "max", fmt::format("the box must lie inside the grid [{}, {}] on axis {}",
                                         origin[a], top, "xyz"[a]));
        break;
      }
      // uGIMP (in the plane of plane strain): the points' domains fill the box, and a domain on
      // the grid's boundary has a stencil node beyond it as soon as its point moves outward.
      const bool thickness = plane_strain_axis(job) == a;
      const double tol = 1e-9 * h[a];
      if (job.text("mpm.shape_function") == mpm::to_string(mpm::ShapeKind::ugimp) && !thickness &&
          (lo[a] <= origin[a] + tol || hi[a] >= top - tol)) {
        r.fail(
            lo[a] <= origin[a] + tol ? base + "min" : base + "max",
            fmt::format("with mpm.shape_function = \"ugimp\" the box must not reach the "
                        "boundary of the grid [{}, {}] on axis {} (uGIMP's 3-node stencil reaches "
                        "past the points' own cells: pad mpm.grid by a cell and hold that node "
                        "plane with the wall)",
                        origin[a], top, "xyz"[a]));
        break;
      }
    }
    // A dem body's initial_stress: the insitu rules (check_insitu_rules).
    const std::int32_t m = choice_of(job, base + "material", kBodyMaterialNames);
    used.dem = used.dem || m == kDemMaterial;
    used.elastic = used.elastic || m == kElasticMaterial;
  }
  return used;
}

// An upper bound from the memory rank 0 needs for the grid and the points (about kBytesPerNode
// and kBytesPerPoint, order of magnitude of mpm::GridFields and MaterialPoints with stencils):
// a count no machine holds is an input error here, not std::bad_alloc in the run.
void grid_memory_rules(const Job& job, Rules& r) {
  const auto& h = job.numbers("mpm.grid.spacing");
  const auto& n = job.integers("mpm.grid.cells");
  constexpr double kBytesPerNode = 160.0;
  constexpr double kBytesPerPoint = 1024.0;
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) nodes *= static_cast<double>(n[a]) + 1.0;
  double points = 0.0;
  for (std::size_t b = 0; b < job.count("mpm.body"); ++b) {
    const std::string base = fmt::format("mpm.body[{}].", b);
    const auto& lo = job.numbers(base + "min");
    const auto& hi = job.numbers(base + "max");
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) cells *= std::max(0.0, std::ceil((hi[a] - lo[a]) / h[a]));
    const auto ppc = job.per_axis(base + "points_per_cell");
    points += cells * static_cast<double>(ppc[0]) * static_cast<double>(ppc[1]) *
              static_cast<double>(ppc[2]);
  }
  const double need = nodes * kBytesPerNode + points * kBytesPerPoint;
  const double mem = usable_memory_bytes();
  if (mem > 0.0 && need > mem) {
    r.fail("mpm.grid.cells",
           fmt::format("{:.3g} grid nodes and {:.3g} material points need about {:.3g} GB of "
                       "memory on rank 0, more than the {:.3g} GB this machine lets the job use",
                       nodes, points, need / 1e9, mem / 1e9));
  }
}

// The formulation and plane strain against the grid and the shape functions.
void scheme_rules(const Job& job, Rules& r) {
  const auto& n = job.integers("mpm.grid.cells");
  if (job.text("mpm.formulation") == mpm::to_string(mpm::Formulation::total_lagrangian) &&
      job.flag("mpm.move_points")) {
    r.fail("mpm.formulation",
           "needs mpm.move_points = false (the grid is the reference configuration only while "
           "the points keep their initial positions: an element test whose cell is the sample)");
  }
  if (const int a = plane_strain_axis(job); a >= 0) {
    // Plane strain holds the velocity along the thickness on every node: one cell through it.
    if (n[static_cast<std::size_t>(a)] != 1) {
      r.fail("mpm.plane_strain",
             fmt::format("the grid must have exactly 1 cell along the thickness axis {} "
                         "(mpm.grid.cells = [{}, {}, {}])",
                         "xyz"[a], n[0], n[1], n[2]));
    }
    if (common::value_of(mpm::kShapeKindNames, job.text("mpm.shape_function")) ==
        mpm::ShapeKind::bspline2) {
      r.fail("mpm.plane_strain",
             fmt::format("needs mpm.shape_function = \"linear\" or \"ugimp\", not \"{}\" "
                         "(the B-spline spans 3 node planes, the one-cell-thick grid has 2; "
                         "uGIMP runs linear through the thickness)",
                         job.text("mpm.shape_function")));
    }
  }
}

// A constraint's box (min and max): both given, ordered, holding a grid node. False: the
// constraint is not checked further.
bool velocity_box_rules(const Job& job, Rules& r, const std::string& base) {
  const auto& origin = job.numbers("mpm.grid.origin");
  const auto& h = job.numbers("mpm.grid.spacing");
  const auto& n = job.integers("mpm.grid.cells");
  if (!job.has(base + "min") || !job.has(base + "max")) {
    r.fail_missing(base + (job.has(base + "min") ? "max" : "min"),
                   "required: a box needs both min and max");
    return false;
  }
  const auto& lo = job.numbers(base + "min");
  const auto& hi = job.numbers(base + "max");
  if (lo.size() != 3 || hi.size() != 3) {
    r.fail(base + "max", "min and max must have 3 coordinates each");
    return false;
  }
  bool ordered = true;
  for (int a = 0; a < 3 && ordered; ++a) {
    if (!(hi[a] >= lo[a])) {
      r.fail(base + "max", fmt::format("must be >= min on every axis (axis {})", "xyz"[a]));
      ordered = false;
    }
  }
  // A box must hold at least one grid node on every axis, or the constraint does nothing
  // (e.g. a platen that never moves). Nodes are origin + i spacing, i in 0..cells.
  for (int a = 0; a < 3 && ordered; ++a) {
    const double k_lo = std::ceil((lo[a] - origin[a]) / h[a] - 1e-9);
    const double k_hi = std::floor((hi[a] - origin[a]) / h[a] + 1e-9);
    if (std::max(k_lo, 0.0) > std::min(k_hi, static_cast<double>(n[a]))) {
      r.fail(base + "max",
             fmt::format("the box [{}, {}] x [{}, {}] x [{}, {}] holds no grid node (none on "
                         "axis {}; nodes are origin + i spacing, i in 0..cells): the "
                         "constraint would act on nothing",
                         lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], "xyz"[a]));
      break;
    }
  }
  return true;
}

// Each velocity constraint: where it acts (one of face, node or box) and on what.
void velocity_rules(const Job& job, Rules& r) {
  const auto& origin = job.numbers("mpm.grid.origin");
  const auto& h = job.numbers("mpm.grid.spacing");
  const auto& n = job.integers("mpm.grid.cells");
  for (std::size_t i = 0; i < job.count("mpm.velocity"); ++i) {
    const std::string base = fmt::format("mpm.velocity[{}].", i);
    const bool face = job.has(base + "face");
    const bool node = job.has(base + "node");
    const bool box = job.has(base + "min") || job.has(base + "max");
    const int given = static_cast<int>(face) + static_cast<int>(node) + static_cast<int>(box);
    if (given != 1) {
      if (given > 1) {
        r.fail(base + (node ? "node" : "max"),
               "give one of face, node or a box (min and max), not several");
      } else {
        r.fail_missing(base + "face",
                       "required: give face (a grid face), node (a grid node position) or a box "
                       "(min and max)");
      }
      continue;
    }
    const std::string where = base + (face ? "face" : node ? "node" : "max");
    if (box && !velocity_box_rules(job, r, base)) continue;
    if (!job.has(base + "x") && !job.has(base + "y") && !job.has(base + "z")) {
      r.fail(where, "a velocity constraint needs at least one of x, y, z");
    }
    if (!node) continue;
    const auto& x = job.numbers(base + "node");
    if (x.size() != 3) {
      r.fail(base + "node", fmt::format("must have 3 coordinates, not {}", x.size()));
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      const double k = (x[a] - origin[a]) / h[a];
      if (std::abs(k - std::round(k)) > 1e-9 || k < -1e-9 || k > static_cast<double>(n[a]) + 1e-9) {
        r.fail(base + "node", fmt::format("({}, {}, {}) is not a node of the grid (origin + i "
                                          "spacing, i in 0..cells) on axis {}",
                                          x[0], x[1], x[2], "xyz"[a]));
        break;
      }
    }
  }
}

void mpm_rules(const Job& job, Rules& r) {
  if (!job.has_section("mpm")) return;
  regularisation_rules(job, r);
  const BodyMaterials used = body_rules(job, r);
  grid_memory_rules(job, r);
  scheme_rules(job, r);
  if (used.elastic && !job.has_section("mpm.elastic")) {
    r.fail_missing("mpm.elastic", "required section when a body has material = \"elastic\"");
  }
  if (used.dem && !job.has_section("dem.coupling")) {
    r.fail_missing("dem.coupling", "required section when a body has material = \"dem\"");
  }
  if (used.dem && !job.has_section("dem"))
    r.fail_missing("dem", "required section when a body has material = \"dem\"");
  velocity_rules(job, r);
}

}  // namespace

// Stresses the grains are asked to carry, against their Young modulus E: a linear contact overlaps
// by about 4 p / E of the radii, so a mean stress above E / 10 means overlaps of tens of % of the
// radii, where a DEM of rigid-ish grains means nothing (and the preparation fails with "contact
// lost" instead of an input error). Typical geomechanics: p / E of 1e-4 to 1e-2.
void stress_level_rules(const Job& job, Rules& r) {
  const double e =
      job.has("dem.material.young_modulus") ? job.number("dem.material.young_modulus") : 0.0;
  const double limit = 0.1 * e;
  const auto check = [&](const std::string& key, double stress, const std::string& what) {
    if (e > 0.0 && std::abs(stress) > limit) {
      r.fail(key, fmt::format("{} {:.4g} Pa is above a tenth of the grains' Young modulus "
                              "(dem.material.young_modulus = {:.4g} Pa): contacts would overlap "
                              "by about 4 p / E = {:.2g} of the radii (stress and modulus in "
                              "the same unit?)",
                              what, std::abs(stress), e, 4.0 * std::abs(stress) / e));
    }
  };
  for (const char* k : {"dem.preparation.pressure", "dem.loading.confining_pressure",
                        "dem.coupling.pressure_floor", "dem.initial_state.pressure_floor"}) {
    if (job.has(k)) check(k, job.number(k), "a stress of");
  }
  // A traction above the stiffness of every material of the job: elastic bodies against their
  // Young modulus (a strain above 100 %), DEM bodies against a tenth of the grains' as above.
  double stiffest = 0.0;
  for (std::size_t b = 0; b < job.count("mpm.body"); ++b) {
    const std::int32_t m =
        choice_of(job, fmt::format("mpm.body[{}].material", b), kBodyMaterialNames);
    if (m == kElasticMaterial && job.has("mpm.elastic.young_modulus")) {
      stiffest = std::max(stiffest, job.number("mpm.elastic.young_modulus"));
    } else if (m == kDemMaterial) {
      stiffest = std::max(stiffest, limit);
    }
  }
  for (std::size_t k = 0; k < job.count("mpm.traction"); ++k) {
    const std::string key = fmt::format("mpm.traction[{}].pressure", k);
    if (stiffest > 0.0 && job.has(key) && job.number(key) > stiffest) {
      r.fail(key, fmt::format("{:.4g} Pa is above the stiffness of every material of the job "
                              "({:.4g} Pa: the elastic Young modulus, or a tenth of the grains'): "
                              "it would crush them (pressure in Pa?)",
                              job.number(key), stiffest));
    }
  }
  for (std::size_t b = 0; b < job.count("mpm.body"); ++b) {
    const std::string key = fmt::format("mpm.body[{}].initial_stress", b);
    if (!job.has(key)) continue;
    const auto& v = job.numbers(key);
    if (v.size() < 3) continue;  // the schema reports the length
    check(key, (v[0] + v[1] + v[2]) / 3.0, "a mean stress of");
  }
}

void check_job_rules(const Job& job) {
  Rules r(job);
  sample_rules(job, r);
  material_rules(job, r);
  loading_rules(job, r);
  numerics_rules(job, r);
  mpm_rules(job, r);
  continuum_rules(job, r);
  stress_level_rules(job, r);
  for (const std::string& e : check_insitu_rules(job)) r.add(e);
  if (!r.errors().empty()) throw common::InputError(fmt::format("{}", fmt::join(r.errors(), "\n")));
}

}  // namespace app
