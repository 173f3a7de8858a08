// Rve: the quasi-static RVE step of Duverger et al. 2022, eqs. (11)-(12), at the material's own
// rate where it flows faster (RveRate), disconnected without contacts (ContactLoss), with guards.
#include "dem/rve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include "common/errors.hpp"
#include "common/state_params.hpp"
#include "dem/element_test.hpp"
#include "dem/free_flight.hpp"
#include "dem/loading.hpp"
#include "dem/measures.hpp"
#include "dem/state.hpp"

namespace dem {

using common::Mat3;

void RveParams::validate() const {
  material.validate();
  numerics.validate();
  common::check_ranges(kRveParams, *this);
}

double mass_median_diameter(const std::vector<double>& radii) {
  std::vector<double> r = radii;
  std::sort(r.begin(), r.end());
  double total = 0.0;
  for (double x : r) total += x * x * x;
  double acc = 0.0;
  for (double x : r) {
    acc += x * x * x;
    if (acc >= 0.5 * total) return 2.0 * x;
  }
  return r.empty() ? 0.0 : 2.0 * r.back();
}

namespace {
Simulation build(const Packing& pk, const RveParams& params) {
  params.validate();
  Simulation sim = make_simulation(pk, params.material, params.numerics);
  if (params.initial_pressure > 0.0) {
    EquilibriumTarget t;
    t.pressure = params.initial_pressure;
    equilibrate(sim, t);  // with the fixed skin (FixedSkinScope)
  }
  return sim;
}
}  // namespace

Rve::Rve(const Packing& pk, const RveParams& params)
    : sim_(build(pk, params)),
      params_(params),
      d50_(params.d50 > 0.0 ? params.d50 : mass_median_diameter(pk.r)) {}

Rve Rve::from_simulation(Simulation sim, const RveParams& params) {
  params.validate();
  sim.set_skin_min_factor(params.numerics.skin_min_factor);
  const double d50 = params.d50 > 0.0 ? params.d50 : mass_median_diameter(sim.spheres().r);
  return Rve(std::move(sim), params, d50);
}

Rve::Rve(Simulation sim, const RveParams& params, double d50)
    : sim_(std::move(sim)), params_(params), d50_(d50) {}

namespace {
std::int64_t active_contacts(const Simulation& sim) {
  std::int64_t nc = 0;
  for (auto a : sim.contacts().active) nc += a;
  return nc;
}
}  // namespace

bool Rve::dilute() const {
  // exp(-0) = 1: with no free volume, the cell's fraction 1 / (1 + e) to the bit.
  return std::exp(-free_volume_) / (1.0 + void_ratio(sim_)) < params_.disconnect_fraction;
}

bool Rve::take_free_volume(Mat3& g) {
  if (params_.contact_loss != ContactLoss::disconnected) return false;
  // ln J of the increment: the cell's own kinematics (a product of I + L dt_DEM) give exp(g).
  const double dv = g.trace();
  // Held only below the disconnection fraction: a contact-free RVE denser than that is a dense
  // gas, in which a shear or a compression makes contacts at once (holding it loses its shear:
  // a dense column, held at phi ~ 0.63, flowed as a fluid).
  if (!(free_volume_ > 0.0) && !(dv > 0.0 && active_contacts(sim_) == 0 && dilute())) {
    return false;
  }
  const double after = free_volume_ + dv;
  if (after > 0.0) {
    free_volume_ = after;  // still disconnected: the cell is held, stress-free
    return true;
  }
  // The compression closed the free volume (dv < 0 here): its remainder strains the cell.
  g *= after / dv;
  free_volume_ = 0.0;
  return false;
}

double Rve::relaxation_time(const Mat3& g, double dt, double dt_dem, StepReport& rep) const {
  // T_p of eq. (11) uses the STRAIN increment (symmetric part): a rigid spin of the cell is not a
  // deformation and must not make the step longer (the strain-split guard bounds the whole G).
  const double emax = (0.5 * (g + g.transpose())).cwiseAbs().maxCoeff();
  double p = pressure(sim_.stress());
  if (!(p >= params_.p_floor)) {
    p = params_.p_floor;
    rep.guards |= kGuardPressureFloor;
  }
  const double rho = params_.material.density;
  double t_p = std::max(emax / params_.inertial_number * inertial_time(d50_, rho, p), dt_dem);
  if (params_.rate == RveRate::material && t_p > dt && dt > 0.0) {
    // The material is faster than I_n (or the step shorter than one DEM step): the RVE runs in
    // physical time, at the material's own inertial number.
    t_p = dt;
    rep.guards |= kGuardMaterialRate;
  }
  if (params_.min_dem_steps > 1) {
    // A slow or static RVE relaxes over at least min_dem_steps DEM steps (within the MPM step
    // when the RVE runs at the material's rate).
    double t_min = static_cast<double>(params_.min_dem_steps) * dt_dem;
    if (params_.rate == RveRate::material && dt > 0.0)
      t_min = std::min(t_min, std::max(dt, dt_dem));
    if (t_p < t_min) {
      t_p = t_min;
      rep.guards |= kGuardMinSteps;
    }
  }
  return t_p;
}

std::int64_t Rve::dem_step_count(const Mat3& g, double dt_dem, double& t_p, StepReport& rep) const {
  const double gmax = g.cwiseAbs().maxCoeff();
  if (gmax == 0.0) rep.guards |= kGuardZeroIncrement;
  // Step counts in double precision until they are capped: a tiny inertial number or a huge
  // increment gives counts beyond int64 (or an infinite t_p), whose conversion is undefined.
  double n_wanted = std::ceil(t_p / dt_dem);
  const double n_split = std::ceil(gmax / params_.max_strain_per_step);
  if (n_split > n_wanted) {
    n_wanted = n_split;
    rep.guards |= kGuardStrainSplit;
  }
  std::int64_t n = params_.max_steps_per_call;
  if (!(n_wanted <= static_cast<double>(params_.max_steps_per_call))) {
    t_p = std::min(static_cast<double>(n) * dt_dem, t_p);  // t_p may be infinite
    rep.guards |= kGuardStepCap;
  } else {
    n = std::max<std::int64_t>(static_cast<std::int64_t>(n_wanted), 1);
  }
  return n;
}

bool Rve::one_free_step(const Mat3& g, double t_p) const {
  // The one step differs from the n it replaces by O(max|g|^2) relative to the branches (see
  // free_flight.hpp); up to max|g| = 1e-2 a margin of 4 max|g|^2 covers it.
  const double gmax = g.cwiseAbs().maxCoeff();
  if (!(gmax <= 1e-2) || !(t_p > 0.0) || !std::isfinite(t_p)) return false;
  return free_flight_holds(sim_, t_p, g / t_p, 4.0 * gmax * gmax + 1e-12);
}

void Rve::run_dem_steps(const Mat3& g, double t_p, std::int64_t n) {
  if (params_.carry_end_forces && !forces_carried_) {
    // The first carried step (a new RVE, or a state of "separate"): the forces of the current
    // state with no increment (no motion has happened with this step's dt and L; a DEM step
    // would count one with them), as "separate" computes its end forces; then carried on.
    sim_.cell().l.setZero();
    sim_.set_dt(0.0);
    sim_.compute_forces();
    forces_carried_ = true;
  }
  sim_.set_dt(t_p / static_cast<double>(n));
  sim_.cell().l = g / t_p;
  std::int64_t s0 = 0;
  if (forces_carried_) {
    sim_.integrate();  // the first DEM step with the forces the last step() computed
    s0 = 1;
  }
  for (std::int64_t s = s0; s < n; ++s) sim_.step();
  dt_cache_.dem_steps += n;
  if (params_.carry_end_forces) {
    // Forces of the end state with this step's dt and L: the contacts' shear, rolling and
    // twisting increments of the last DEM step's motion, which a DEM step would compute next.
    sim_.compute_forces();
    sim_.cell().l.setZero();
    forces_carried_ = true;
  } else {
    sim_.cell().l.setZero();
    // Final stress at the deformed configuration (forces of the end state, no motion).
    const double keep = sim_.dt();
    sim_.set_dt(0.0);
    sim_.compute_forces();
    sim_.set_dt(keep);
  }
}

StepReport Rve::step(const Mat3& l, double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!(dt >= 0.0) || !l.allFinite()) {
    throw common::NumericalError(
        "dem::Rve::step: non-finite L or negative dt (dt = " + std::to_string(dt) + " s)");
  }
  StepReport rep;
  Mat3 g = l * dt;  // displacement-gradient increment of this MPM step (spin included)
  if (take_free_volume(g)) {
    // Disconnected (Dunatunga & Kamrin 2015): no contact, so no stress, and no DEM step; the
    // spheres keep their state for the compression that reconnects them.
    rep = measure();
    rep.dt_dem = sim_.dt();
    rep.guards |= kGuardDisconnected;
    rep.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rep;
  }
  if (spray_too_thin_after(g)) {
    // A spray stretched by its point's neighbours: its cell follows the point's shape until the
    // increment would make it thinner than its spheres allow (the neighbour search needs 2 r_max
    // + skin across). Then it takes the increment's volume change only: a spray below the
    // disconnection fraction carries next to no stress (a few collisions), and its cell's shape
    // is nobody's (the point keeps its F).
    g = (g.trace() / 3.0) * Mat3::Identity();
    rep.guards |= kGuardSprayShape;
  }
  advance(g, dt, rep);

  const Mat3& sigma = sim_.stress();
  if (!sigma.allFinite()) {
    throw common::NumericalError("dem::Rve::step: non-finite stress after " +
                                 std::to_string(rep.dem_steps) +
                                 " DEM steps (t = " + std::to_string(sim_.time()) + " s)");
  }
  const StepReport m = measure();
  rep.dt_dem = sim_.dt();
  rep.p = m.p;
  rep.q = m.q;
  rep.void_ratio = m.void_ratio;
  rep.z = m.z;
  rep.guards |= m.guards;
  rep.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rep;
}

void Rve::advance(const Mat3& g, double dt, StepReport& rep) {
  const double dt_dem = sim_.numerics().dt_safety * critical_dt_for_step();
  double t_p = relaxation_time(g, dt, dt_dem, rep);
  std::int64_t n = dem_step_count(g, dt_dem, t_p, rep);
  if (params_.free_flight && n > 1 && one_free_step(g, t_p)) {
    n = 1;
    rep.guards |= kGuardFreeFlight;
  }
  const std::int64_t builds = sim_.verlet().builds;
  run_dem_steps(g, t_p, n);
  rep.rebuilds = static_cast<std::uint32_t>(sim_.verlet().builds - builds);
  rep.dem_steps = n;
  rep.t_p = t_p;
}

namespace {
// The neighbour search's limit on a cell width, 2 r_max + skin, with the widest skin.
double thin_cell_limit(const Simulation& sim) {
  const std::vector<double>& r = sim.spheres().r;
  const double r_max = r.empty() ? 0.0 : *std::max_element(r.begin(), r.end());
  return (2.0 + sim.numerics().skin_factor) * r_max;
}

double min_width(const PeriodicCell& cell) {
  return std::min({cell.width(0), cell.width(1), cell.width(2)});
}
}  // namespace

bool Rve::spray_too_thin_after(const Mat3& g) const {
  if (params_.contact_loss != ContactLoss::strained || !dilute()) return false;
  PeriodicCell after = sim_.cell();
  after.h = (Mat3::Identity() + g) * after.h;
  // A tenth of margin: the cell runs through the product of (I + L dt_DEM), which differs from
  // I + g at second order, and the neighbour search checks it only at its rebuilds.
  return min_width(after) < 1.1 * thin_cell_limit(sim_);
}

// With dt_refresh = 1 every step() computes it (each runs at least one DEM step): the results of
// before this cache, bit for bit. Otherwise the value is kept while fewer than dt_refresh DEM
// steps have run since (each DEM step strains the cell by at most max_strain_per_step, so the
// fabric it was computed for has moved by at most dt_refresh times that) and while the contacts
// have not grown by more than 5 %: the per-sphere stiffness sums grow with new contacts only
// (the law is linear, its stiffnesses functions of the radii), and the safety factor (0.8 by
// default) leaves room for a stiffness 1.56 times as large.
double Rve::critical_dt_for_step() {
  if (params_.dt_refresh <= 1) {
    dt_cache_ = DtCache{sim_.critical_dt(), 0, 0};
    return dt_cache_.critical_dt;
  }
  const std::int64_t nc = active_contacts(sim_);
  const bool grown = 20 * nc > 21 * dt_cache_.contacts;  // more than 5 % more contacts
  if (!(dt_cache_.critical_dt > 0.0) || dt_cache_.dem_steps >= params_.dt_refresh || grown) {
    dt_cache_ = DtCache{sim_.critical_dt(), 0, nc};
  }
  return dt_cache_.critical_dt;
}

StepReport Rve::measure() const {
  StepReport rep;
  const Mat3& sigma = sim_.stress();
  rep.p = pressure(sigma);
  rep.q = deviatoric(sigma);
  rep.void_ratio = void_ratio(sim_);
  const std::int64_t nc = active_contacts(sim_);
  rep.z =
      2.0 * static_cast<double>(nc) / static_cast<double>(std::max<std::size_t>(1, num_spheres()));
  if (nc == 0) rep.guards |= kGuardNoContacts;
  return rep;
}

namespace {

// The RVE's parameters: the rows of kRveParams and kRveChoices under rve/params/, named by their
// keys (common/state_params.hpp).
constexpr std::string_view kRveParamsDir = "rve/params/";

// DEM states of versions 2 to 4 wrote them under rve/, pressure_floor as p_floor, and older ones
// lacked the fields of later keys (absent: the member initializer, the step of then).
constexpr common::FormerField kFormerRveParams[] = {
    {"pressure_floor", "p_floor"},
    {"dt_refresh", "dt_refresh", true},
    {"disconnect_fraction", "disconnect_fraction", true},
    {"min_dem_steps", "min_dem_steps", true},
};

// A flag field (0 or 1); absent: 0 (a state of before it was written).
bool flag_field(const common::StateReader& r, const char* name) {
  if (!r.has(name)) return false;
  const std::int64_t v = common::read_scalar_i64(r, name);
  if (v != 0 && v != 1) {
    throw common::InputError("dem state: field '" + std::string(name) + "' = " + std::to_string(v) +
                             ": must be 0 or 1");
  }
  return v == 1;
}

// The choices of a state of before version 5, each a flag of its own name and encoding.
void read_former_choices(const common::StateReader& r, RveParams& params) {
  params.carry_end_forces = flag_field(r, "rve/carry_end_forces");
  // Written since dem.coupling.rate and contact_loss exist (1: material, disconnected): a state
  // without them ran with the coupling rate and a strained cell, and continues so.
  params.rate = flag_field(r, "rve/rate") ? RveRate::material : RveRate::coupling;
  params.contact_loss =
      flag_field(r, "rve/contact_loss") ? ContactLoss::disconnected : ContactLoss::strained;
  // Written since dem.coupling.free_flight exists: a state without it stepped every RVE step.
  params.free_flight = flag_field(r, "rve/free_flight");
}

}  // namespace

void Rve::save(common::StateWriter& w) const {
  save_simulation(sim_, w, "");
  common::write_params(w, kRveParamsDir, kRveParams, params_);
  common::write_choices(w, kRveParamsDir, kRveChoices, params_);
  common::write_scalar(w, "rve/d50_used", d50_);
  common::write_scalar(w, "rve/dt_cache/critical_dt", dt_cache_.critical_dt);
  common::write_scalar(w, "rve/dt_cache/dem_steps", dt_cache_.dem_steps);
  common::write_scalar(w, "rve/dt_cache/contacts", dt_cache_.contacts);
  common::write_scalar(w, "rve/forces_carried", std::int64_t{forces_carried_ ? 1 : 0});
  common::write_scalar(w, "rve/free_volume", free_volume_);
}

Rve Rve::load(const common::StateReader& r) {
  Simulation sim = load_simulation(r, "");  // checks dem/version, which covers rve/ too
  RveParams params;
  params.material = sim.law().material();
  params.numerics = sim.numerics();
  if (check_state_version(r) < kStateVersion) {
    common::read_params(r, "rve/", kRveParams, params, "dem state", kFormerRveParams);
    read_former_choices(r, params);
  } else {
    common::read_params(r, kRveParamsDir, kRveParams, params, "dem state");
    common::read_choices(r, kRveParamsDir, kRveChoices, params, "dem state");
  }
  params.validate();
  Rve rve(std::move(sim), params, common::read_scalar_f64(r, "rve/d50_used"));
  rve.forces_carried_ = flag_field(r, "rve/forces_carried");
  if (rve.forces_carried_ && !params.carry_end_forces) {
    throw common::InputError(
        "dem state: field 'rve/forces_carried' = 1 with dem.coupling.end_forces = \"separate\": "
        "carried forces belong to a state that carries them");
  }
  if (r.has("rve/free_volume")) {
    rve.free_volume_ = common::read_scalar_f64(r, "rve/free_volume");
    if (!(rve.free_volume_ >= 0.0) || !std::isfinite(rve.free_volume_) ||
        (rve.free_volume_ > 0.0 && params.contact_loss != ContactLoss::disconnected)) {
      throw common::InputError(
          "dem state: field 'rve/free_volume' = " + std::to_string(rve.free_volume_) +
          ": must be finite and >= 0, and 0 unless dem.coupling.contact_loss = \"disconnected\"");
    }
  }
  if (r.has("rve/dt_cache/critical_dt")) {
    rve.dt_cache_.critical_dt = common::read_scalar_f64(r, "rve/dt_cache/critical_dt");
    rve.dt_cache_.dem_steps = common::read_scalar_i64(r, "rve/dt_cache/dem_steps");
    rve.dt_cache_.contacts = common::read_scalar_i64(r, "rve/dt_cache/contacts");
    // contacts at most the pairs: the growth test multiplies it by 21.
    const auto pairs = static_cast<std::int64_t>(rve.sim_.contacts().size());
    if (!(rve.dt_cache_.critical_dt >= 0.0) || !std::isfinite(rve.dt_cache_.critical_dt) ||
        rve.dt_cache_.dem_steps < 0 || rve.dt_cache_.contacts < 0 ||
        rve.dt_cache_.contacts > pairs) {
      throw common::InputError(
          "dem state: fields 'rve/dt_cache/*' = (" + std::to_string(rve.dt_cache_.critical_dt) +
          ", " + std::to_string(rve.dt_cache_.dem_steps) + ", " +
          std::to_string(rve.dt_cache_.contacts) +
          "): the cached critical time step must be finite and >= 0 s, its DEM steps >= 0 and "
          "its contacts in [0, " +
          std::to_string(pairs) + "] (the state's pairs)");
    }
  }
  return rve;
}

}  // namespace dem
