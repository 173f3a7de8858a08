// ElasticMicro: hypoelastic verification micro model (see header).
#include "farm/elastic_micro.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.hpp"
#include "common/state_params.hpp"
#include "common/tensor.hpp"
#include "mpm/drucker_prager.hpp"
#include "mpm/friction_softening.hpp"

namespace farm {

namespace {

void bad(const char* key, double value, const char* rule) {
  throw common::InputError(std::string("farm elastic micro model: ") + key + " = " +
                           std::to_string(value) + ": " + rule);
}

// The material's rows under their job keys (common/state_params.hpp), from version 6.
constexpr std::string_view kParamsDir = "elastic/params/";
constexpr std::string_view kWhat = "elastic micro state";

// The material of a state of versions 2 to 5: under the C++ members' names then
// (elastic/params/young, poisson), the angles in radians; a field the version lacks as the model
// of that version had it (no friction, no dilatancy, no softening). The degrees are for the
// parameters' report and later states (degrees_of_radians); the model keeps the radians.
struct FormerMaterial {
  ElasticMaterial material;
  ElasticAngles radians;
};

FormerMaterial read_former_material(const common::StateReader& r, std::int64_t version) {
  auto f64 = [&r](std::string_view name) {
    return common::read_scalar_f64(r, std::string(kParamsDir) + std::string(name));
  };
  FormerMaterial f;
  ElasticMaterial& m = f.material;
  ElasticAngles& a = f.radians;
  m.young_modulus = f64("young");
  m.poisson_ratio = f64("poisson");
  a.friction = version >= 3 ? f64("friction_angle") : 0.0;
  a.dilatancy = version >= 4 ? f64("dilatancy_angle") : 0.0;
  if (version >= 5) {
    m.softening_strain = f64("softening_strain");
    a.residual_friction = f64("residual_friction_angle");
  } else {
    a.residual_friction = a.friction;
  }
  m.friction_deg = degrees_of_radians(a.friction);
  m.dilatancy_deg = degrees_of_radians(a.dilatancy);
  m.residual_friction_deg = degrees_of_radians(a.residual_friction);
  return f;
}

/// A 3x3 as the 9 doubles of a state field (row-major).
std::vector<double> nine(const common::Mat3& m) {
  std::vector<double> v(9);
  common::to_row_major(m, std::span<double, 9>(v.data(), 9));
  return v;
}

}  // namespace

void ElasticMicroParams::validate() const {
  material.validate();
  if (!(density > 0.0)) bad("density", density, "must be > 0 kg/m^3");
  if (!(void_ratio0 >= 0.0)) bad("void_ratio0", void_ratio0, "must be >= 0");
  if (substeps < 1) bad("substeps", static_cast<double>(substeps), "must be >= 1");
  if (!initial_stress.allFinite()) bad("initial_stress", initial_stress.trace(), "must be finite");
}

ElasticMicro::ElasticMicro(std::int64_t id, const ElasticMicroParams& params)
    : id_(id),
      params_(params),
      angles_(to_radians(params.material)),
      stress_(params.initial_stress) {
  params_.validate();
}

ElasticMicro::ElasticMicro(std::int64_t id, const ElasticMicroParams& params,
                           const common::Mat3& initial_stress)
    : ElasticMicro(id, params) {
  if (!initial_stress.allFinite()) bad("initial_stress", initial_stress.trace(), "must be finite");
  stress_ = initial_stress;
}

MicroReport ElasticMicro::step(const common::Mat3& L, double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  ++steps_;
  if (id_ == params_.fail_id && steps_ == params_.fail_step) {
    throw common::NumericalError(
        "elastic micro model: injected failure (fail_id = " + std::to_string(params_.fail_id) +
        ", fail_step = " + std::to_string(params_.fail_step) + ")");
  }
  const double h = dt / static_cast<double>(params_.substeps);
  const common::Lame c =
      common::lame(params_.material.young_modulus, params_.material.poisson_ratio);
  const common::HughesWinget update(L, h, c);
  const double dj = (common::Mat3::Identity() + h * L).determinant();
  for (std::int64_t k = 0; k < params_.substeps; ++k) {
    if (angles_.friction > 0.0) {
      frictional_substep(update, L, h, std::log(dj));
    } else {
      stress_ = update.apply(stress_);
    }
    j_ *= dj;
  }
  if (!stress_.allFinite()) {
    throw common::NumericalError("elastic micro model: non-finite stress (trace = " +
                                 std::to_string(stress_.trace()) + " Pa)");
  }
  MicroReport r = report();
  r.dem_steps = params_.substeps;
  r.t_p = dt;
  r.guards = 0;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void ElasticMicro::frictional_substep(const common::HughesWinget& update, const common::Mat3& L,
                                      double h, double volumetric) {
  const ElasticMaterial& m = params_.material;
  const common::Lame c = common::lame(m.young_modulus, m.poisson_ratio);
  const double bulk = c.lambda + 2.0 * c.mu / 3.0;
  // Past the cut-off the flow is deviatoric, on the cone of the same plane-strain friction angle.
  const bool dilates = angles_.dilatancy > 0.0 &&
                       !(m.dilatancy_cutoff > 0.0 && plastic_dilation_ >= m.dilatancy_cutoff);
  const mpm::DruckerPragerCone cone =
      mpm::plane_strain_cone(angles_.friction, dilates ? angles_.dilatancy : 0.0);
  auto ret = [&](const common::Mat3& trial) {
    if (m.softening_strain > 0.0) {
      const mpm::FrictionSoftening softening{
          std::sin(angles_.friction), std::sin(angles_.residual_friction), m.softening_strain};
      const mpm::SofteningResult r = mpm::softening_return(trial, softening, plastic_shear_, c.mu);
      plastic_shear_ = r.gamma;
      return r.result;
    }
    const mpm::DruckerPragerResult r = mpm::drucker_prager_return(trial, cone, bulk, c.mu);
    if (dilates && r.plastic && !r.apex) {
      // The return raises p by K tr(d eps_p) >= 0 (mpm::drucker_prager_return); read back from
      // the traces, a tiny return can round below zero, which a state may not hold.
      plastic_dilation_ += std::max(0.0, (trial.trace() - r.stress.trace()) / (3.0 * bulk));
    }
    return r;
  };
  if (free_volume_ > 0.0) {  // disconnected: a dilation adds to the free volume, stress-free
    free_volume_ += volumetric;
    if (free_volume_ > 0.0) {
      stress_ = common::Mat3::Zero();
      return;
    }
    // This compression closed the free volume: the remainder strains the material.
    const double remainder = free_volume_ / volumetric;  // in (0, 1]: both negative
    free_volume_ = 0.0;
    stress_ = ret(common::HughesWinget(L, remainder * h, c).apply(common::Mat3::Zero())).stress;
    return;
  }
  const double p = -stress_.trace() / 3.0;
  const mpm::DruckerPragerResult r = ret(update.apply(stress_));
  stress_ = r.stress;
  if (r.apex) {  // the dilation beyond the elastic unloading of p becomes free volume
    free_volume_ = std::max(0.0, volumetric - p / bulk);
  }
}

MicroReport ElasticMicro::report() const {
  MicroReport r;
  r.p = common::pressure(stress_);
  r.q = common::deviatoric(stress_);
  r.void_ratio = (1.0 + params_.void_ratio0) * j_ - 1.0;
  return r;
}

double ElasticMicro::wave_speed() const {
  const common::Lame c =
      common::lame(params_.material.young_modulus, params_.material.poisson_ratio);
  return std::sqrt((c.lambda + 2.0 * c.mu) / params_.density);
}

void ElasticMicro::save(common::StateWriter& w) const {
  common::write_scalar(w, "elastic/version", kElasticStateVersion);
  common::write_scalar(w, "elastic/id", id_);
  common::write_params(w, kParamsDir, kElasticMaterial, params_.material);
  common::write_scalar(w, "elastic/params/density", params_.density);
  common::write_scalar(w, "elastic/params/void_ratio0", params_.void_ratio0);
  w.write("elastic/params/initial_stress", nine(params_.initial_stress));
  common::write_scalar(w, "elastic/params/substeps", params_.substeps);
  common::write_scalar(w, "elastic/params/fail_id", params_.fail_id);
  common::write_scalar(w, "elastic/params/fail_step", params_.fail_step);
  w.write("elastic/stress", nine(stress_));
  common::write_scalar(w, "elastic/j", j_);
  common::write_scalar(w, "elastic/free_volume", free_volume_);
  common::write_scalar(w, "elastic/plastic_shear_strain", plastic_shear_);
  common::write_scalar(w, "elastic/plastic_volumetric_strain", plastic_dilation_);
  common::write_scalar(w, "elastic/steps", steps_);
}

std::unique_ptr<MicroModel> ElasticMicro::load(const common::StateReader& r) {
  // Version 1 had no elastic/version field and positional arrays elastic/params (13 values) and
  // elastic/int_params (3).
  const std::int64_t version =
      r.has("elastic/version") ? common::read_scalar_i64(r, "elastic/version") : 1;
  if (version < 2 || version > kElasticStateVersion) {
    throw common::InputError(
        "elastic micro state: field 'elastic/version' = " + std::to_string(version) +
        (r.has("elastic/version") ? "" : " (absent)") + ": this build reads versions 2 to " +
        std::to_string(kElasticStateVersion) +
        " only (version 1 stored the parameters as the positional array "
        "'elastic/params'; versions 2 to 5 named fields such as 'elastic/params/young', 6 the "
        "job keys such as 'elastic/params/young_modulus', 7 added the dilatancy cut-off); restart "
        "from a state written by this "
        "version");
  }
  auto matrix = [&r](const char* name) {
    const std::vector<double> v = r.read_f64(name);
    if (v.size() != 9) {
      throw common::InputError(std::string("elastic micro state: field '") + name + "' has " +
                               std::to_string(v.size()) + " values, expected 9");
    }
    common::require_finite(v, std::string("elastic micro state: field '") + name + "'");
    return common::Mat3(common::row_major(v.data()));
  };
  ElasticMicroParams params;
  std::optional<ElasticAngles> stored_radians;
  if (version >= 6) {
    // A version-6 state has no cut-off: the material keeps its default, none.
    constexpr std::array<common::FormerField, 1> kBeforeCutoff{
        {{"dilatancy_cutoff", "dilatancy_cutoff", true}}};
    common::read_params(r, kParamsDir, kElasticMaterial, params.material, kWhat,
                        version == 6 ? std::span<const common::FormerField>(kBeforeCutoff)
                                     : std::span<const common::FormerField>());
  } else {
    const FormerMaterial former = read_former_material(r, version);
    params.material = former.material;
    stored_radians = former.radians;
  }
  params.density = common::read_scalar_f64(r, "elastic/params/density");
  params.void_ratio0 = common::read_scalar_f64(r, "elastic/params/void_ratio0");
  params.initial_stress = matrix("elastic/params/initial_stress");
  params.substeps = common::read_scalar_i64(r, "elastic/params/substeps");
  params.fail_id = common::read_scalar_i64(r, "elastic/params/fail_id");
  params.fail_step = common::read_scalar_i64(r, "elastic/params/fail_step");
  auto m = std::make_unique<ElasticMicro>(common::read_scalar_i64(r, "elastic/id"), params);
  // An older state's radians are the model's as they were, not its degrees converted back: the
  // run continues bit for bit.
  if (stored_radians) m->angles_ = *stored_radians;
  m->stress_ = matrix("elastic/stress");
  m->j_ = common::read_scalar_f64(r, "elastic/j");
  if (!std::isfinite(m->j_)) {
    throw common::InputError("elastic micro state: field 'elastic/j' = " + std::to_string(m->j_) +
                             ": a state holds finite numbers only");
  }
  m->steps_ = common::read_scalar_i64(r, "elastic/steps");
  if (version >= 3) {
    m->free_volume_ = common::read_scalar_f64(r, "elastic/free_volume");
    if (!(m->free_volume_ >= 0.0 && std::isfinite(m->free_volume_))) {
      throw common::InputError("elastic micro state: field 'elastic/free_volume' = " +
                               std::to_string(m->free_volume_) + ": must be finite and >= 0");
    }
  }
  if (version >= 5) {
    m->plastic_shear_ = common::read_scalar_f64(r, "elastic/plastic_shear_strain");
    if (!(m->plastic_shear_ >= 0.0 && std::isfinite(m->plastic_shear_))) {
      throw common::InputError("elastic micro state: field 'elastic/plastic_shear_strain' = " +
                               std::to_string(m->plastic_shear_) + ": must be finite and >= 0");
    }
  }
  if (version >= 7) {
    m->plastic_dilation_ = common::read_scalar_f64(r, "elastic/plastic_volumetric_strain");
    if (!(m->plastic_dilation_ >= 0.0 && std::isfinite(m->plastic_dilation_))) {
      throw common::InputError("elastic micro state: field 'elastic/plastic_volumetric_strain' = " +
                               std::to_string(m->plastic_dilation_) + ": must be finite and >= 0");
    }
  }
  return m;
}

MicroKind ElasticMicro::kind(const ElasticMicroParams& params) {
  params.validate();
  MicroKind k;
  k.create = [params](std::int64_t id) { return std::make_unique<ElasticMicro>(id, params); };
  k.load = [](const common::StateReader& r) { return ElasticMicro::load(r); };
  return k;
}

}  // namespace farm
