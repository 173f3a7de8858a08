// MPM time stepping: USF / MUSL step, time step (see header, docs/design/mpm.md); the state
// save/load is in solver_state.cpp, the configuration's rules in solver_config.cpp.
#include "mpm/solver.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "mpm/messages.hpp"
#include "mpm/parallel.hpp"
#include "mpm/subcell_relaxation.hpp"
#include "mpm/transfers.hpp"

namespace mpm {

using messages::num_str;
using messages::short_str;
using messages::vec_str;

Solver::Solver(SolverConfig config, MaterialPoints points, std::vector<MaterialModel*> materials)
    : config_(std::move(config)), points_(std::move(points)), materials_(std::move(materials)) {
  config_.validate();
  points_.validate();
  guard_ = EnergyGuard(config_.energy_guard);
  if (materials_.empty()) throw common::InputError("mpm solver: no material model given");
  for (std::size_t k = 0; k < materials_.size(); ++k) {
    if (materials_[k] == nullptr) {
      throw common::InputError("mpm solver: material " + std::to_string(k) + " is null");
    }
  }
  for (std::size_t p = 0; p < points_.size(); ++p) {
    if (static_cast<std::size_t>(points_.material[p]) >= materials_.size()) {
      throw common::InputError("mpm solver: point id " + std::to_string(points_.id[p]) +
                               " has material " + std::to_string(points_.material[p]) +
                               " but only " + std::to_string(materials_.size()) +
                               " material model(s) were given");
    }
  }
  check_shape_domains(config_.shape, config_.grid, points_, config_.plane_strain_axis);
  fields_.resize(config_.grid);
  if (config_.regularisation_length > 0.0) {
    regularisation_.emplace(config_.regularisation_length, config_.regularisation_modulus,
                            config_.regularisation_average);
  }
}

void Solver::add_constraint(const VelocityConstraint& constraint) {
  ResolvedConstraint r = resolve(config_.grid, constraint);
  if (r.spec.name.empty()) r.spec.name = "constraint_" + std::to_string(constraints_.size());
  for (const ResolvedConstraint& c : constraints_) {
    if (c.spec.name == r.spec.name) {
      throw common::InputError("mpm constraint: name '" + r.spec.name + "' is used twice");
    }
  }
  constraints_.push_back(std::move(r));
  reactions_.push_back(common::Vec3::Zero());
  displacements_.push_back(common::Vec3::Zero());
}

std::vector<std::string> Solver::constraint_names() const {
  std::vector<std::string> out;
  for (const ResolvedConstraint& c : constraints_) out.push_back(c.spec.name);
  return out;
}

void Solver::advance_displacements(double t, double dt) {
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    const VelocityConstraint& c = constraints_[k].spec;
    if (!c.has_window() && !c.field) {
      // Always active at a constant velocity: exactly v t, no state to checkpoint.
      displacements_[k] = prescribed_velocity(c, t + dt) * (t + dt);
    } else if (c.active_at(t)) {
      displacements_[k] += 0.5 * dt * (prescribed_velocity(c, t) + prescribed_velocity(c, t + dt));
    }
  }
}

void Solver::add_traction(const TractionLoad& load) {
  if (load.axis < 0 || load.axis > 2 || (load.side != -1 && load.side != 1)) {
    throw common::InputError("mpm traction load: axis = " + std::to_string(load.axis) +
                             ", side = " + std::to_string(load.side) +
                             ": axis must be 0..2 and side -1 or +1");
  }
  std::vector<std::int64_t> facets = face_points(points_, load.axis, load.side);
  if (facets.empty()) {
    throw common::InputError("mpm traction load on axis " + std::to_string(load.axis) + " side " +
                             std::to_string(load.side) + ": no material point lies on that face");
  }
  tractions_.push_back(load);
  traction_points_.push_back(std::move(facets));
  traction_areas_.push_back(0.0);
}

double Solver::stable_dt(double& speed) const {
  double c = 0.0;
  for (const MaterialModel* m : materials_) c = std::max(c, m->wave_speed());
  // Mass scaling: the inertia is s times the mass, the wave speed c / sqrt(s).
  if (config_.mass_scaling != 1.0) c /= std::sqrt(config_.mass_scaling);
  // |v| in parallel, the maximum in slot order (the same result on any number of threads).
  thread_local std::vector<double> speeds;
  compute_terms(static_cast<std::int64_t>(points_.size()), speeds,
                [&](std::int64_t q) { return points_.v[static_cast<std::size_t>(q)].norm(); });
  double vmax = 0.0;
  for (const double v : speeds) vmax = std::max(vmax, v);
  speed = c + vmax;
  if (!(speed > 0.0) || !std::isfinite(speed)) {
    throw common::NumericalError("mpm step " + std::to_string(step_) + " (t = " + num_str(time_) +
                                 " s): the time step needs a positive finite wave speed, got " +
                                 num_str(speed) + " m/s");
  }
  return config_.grid.spacing.minCoeff() / speed;
}

double Solver::next_dt() const {
  if (config_.dt > 0.0 && !config_.refuse_unstable_dt) return config_.dt;
  double speed = 0.0;
  const double limit = stable_dt(speed);
  // The CFL step exactly as written before the stability check existed (bit-for-bit results).
  if (config_.dt <= 0.0) return config_.cfl * config_.grid.spacing.minCoeff() / speed;
  if (config_.dt > limit) {
    throw common::NumericalError(
        "mpm step " + std::to_string(step_) + " (t = " + num_str(time_) +
        " s): the fixed dt = " + num_str(config_.dt) +
        " s is above the stability limit h / (c + |v|max) = " + num_str(limit) + " s (h = " +
        num_str(config_.grid.spacing.minCoeff()) + " m, c + |v|max = " + num_str(speed) +
        " m/s): lower dt, or leave it out to use the CFL "
        "step");
  }
  return config_.dt;
}

void Solver::prepare_grid(std::int64_t step, double t) {
  const std::int64_t bad =
      compute_stencils(config_.shape, config_.grid, points_, cache_, config_.plane_strain_axis);
  if (bad >= 0) {
    const auto p = static_cast<std::size_t>(bad);
    throw common::NumericalError(
        "mpm step " + std::to_string(step) + " (t = " + num_str(t) + " s): point id " +
        std::to_string(points_.id[p]) + " at x = " + vec_str(points_.x[p]) +
        " m has left the grid [" + vec_str(config_.grid.origin) + ", " +
        vec_str(config_.grid.upper()) + "] (its " + std::string(to_string(config_.shape)) +
        " stencil needs nodes outside it)");
  }
  bin_points(config_.grid, cache_, bins_);
  activate_nodes(config_.grid, cache_, bins_, fields_);
  p2g_mass_momentum(config_.grid, cache_, bins_, points_, config_.gravity, fields_,
                    config_.transfer == Transfer::apic);
  scale_inertia(true);  // after P2G: the gravity force above keeps the real mass
  threshold_ = config_.mass_threshold * typical_nodal_mass(fields_);
  compute_nodal_velocity(threshold_, fields_);
  // The walls' momentum stage changes the grid's kinetic energy: their work (energy guard), where
  // it is an impulse on the points (wall_impulse_on_points); otherwise it is only the step's
  // kinematics, the points keep their velocity, and the same energy would be "removed" again
  // at every step.
  const bool wall_work = guard_.enabled() && config_.wall_impulse_on_points;
  const double ke_before = wall_work ? grid_kinetic_energy() : 0.0;
  // Plane strain holds the thickness component before the constraints too: a frictional wall then
  // sees no slip through the thickness (it would resist it and report it as its reaction).
  hold_thickness_velocity();
  apply_velocity_constraints(config_.grid, constraints_, t, fields_);
  hold_thickness_velocity();
  w_ext_step_ = wall_work ? grid_kinetic_energy() - ke_before : 0.0;
}

double Solver::grid_kinetic_energy() const {
  thread_local std::vector<double> terms;
  const std::vector<std::int64_t>& active = fields_.active;
  compute_terms(static_cast<std::int64_t>(active.size()), terms, [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    return fields_.mass[u] * fields_.velocity[u].squaredNorm();
  });
  double sum = 0.0;
  for (const double x : terms) sum += x;  // slot order: the same bits on any number of threads
  return 0.5 * sum;
}

void Solver::internal_force_tracked() {
  if (!guard_.enabled()) {
    internal_force();
    return;
  }
  const std::vector<std::int64_t>& active = fields_.active;
  if (f_internal_.size() < fields_.force.size()) f_internal_.resize(fields_.force.size());
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    f_internal_[u] = fields_.force[u];
  });
  internal_force();
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    f_internal_[u] = fields_.force[u] - f_internal_[u];
  });
}

double Solver::grid_external_work(double dt) const {
  // On the velocity the materials' L comes from, so that the forces' work and the materials'
  // stress power pair up: V(t) in USF, V(t) + a dt (what the points carry into the re-projected
  // L) in MUSL. The step's kinetic energy change then differs from the net work by
  // dt^2 / 2 sum m |a|^2 (USF; minus that in MUSL): negligible in a stable step, the growth
  // itself in an unstable one.
  const double w = config_.stress_update == StressUpdate::usf ? 0.0 : 1.0;
  thread_local std::vector<double> terms;
  const std::vector<std::int64_t>& active = fields_.active;
  compute_terms(static_cast<std::int64_t>(active.size()), terms, [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    const common::Vec3& a = fields_.acceleration[u];
    const common::Vec3 f_ext = fields_.mass[u] * a - f_internal_[u];
    return f_ext.dot(fields_.velocity[u] + w * dt * a);
  });
  double sum = 0.0;
  for (const double x : terms) sum += x;
  return dt * sum;
}

void Solver::observe_energy(double t_end) {
  const double kin = kinetic_energy(points_, config_.mass_scaling);
  kinetic_step_ = step_;  // energies() of this step reuses it
  kinetic_ = kin;
  if (!guard_.observe(kin, internal_work_, w_ext_step_)) return;
  std::size_t fast = 0;
  double e_max = -1.0;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const double e = points_.mass[p] * points_.v[p].squaredNorm();
    if (e > e_max) {
      e_max = e;
      fast = p;
    }
  }
  throw common::NumericalError(
      "mpm step " + std::to_string(step_) + " (t = " + num_str(t_end) +
      " s): the energy grows without a source: the steps created " + num_str(guard_.created()) +
      " J since the start (kinetic energy " + num_str(kin) + " J, internal work " +
      num_str(internal_work_) + " J, work of gravity, loads and walls " +
      num_str(guard_.external_work()) + " J), more than " + num_str(guard_.share()) +
      " of the scene's energy scale " + num_str(guard_.scale()) + " J for " +
      std::to_string(EnergyGuard::kPersist) + " steps in a row; the fastest point is id " +
      std::to_string(points_.id.empty() ? -1 : points_.id[fast]) +
      " at x = " + (points_.x.empty() ? std::string("-") : vec_str(points_.x[fast])) +
      " m, |v| = " + (points_.v.empty() ? std::string("-") : num_str(points_.v[fast].norm())) +
      " m/s. An unstable step (a time step above the stability limit, mpm.dt) or a material "
      "update that returns more work than it took; mpm.energy_guard = 0 turns the guard off "
      "(docs/design/mpm.md, Energy-growth guard)");
}

void Solver::project_wall_trial(double dt) {
  // The walls' momentum-stage correction reaches the points (g2p_update adds wall_dv / dt to the
  // FLIP increment), so the step's contact and friction are decided once, on the trial velocity
  // from the projected one: V(t) + a dt - wall_dv = V_projected + a dt. A wall in contact then
  // sets a = (v_corrected - V(t)) / dt, and its reaction m (a - a_before) is the whole impulse
  // of the step, m (v_corrected - V_projected) / dt - m a_free; a node the wall leaves (no
  // contact on the trial) keeps the shift: its end velocity and the points' increment are the
  // free ones, as if the momentum stage had not corrected it.
  if (!config_.wall_impulse_on_points) return;
  const std::vector<std::int64_t>& active = fields_.active;
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    fields_.acceleration[u] -= fields_.wall_dv[u] / dt;
  });
}

void Solver::scale_inertia(bool with_mass) {
  const double s = config_.mass_scaling;
  if (s == 1.0) return;
  const std::vector<std::int64_t>& active = fields_.active;
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    if (with_mass) fields_.mass[u] *= s;
    fields_.momentum[u] *= s;
  });
}

void Solver::hold_thickness_velocity() {
  const int a = config_.plane_strain_axis;
  if (a < 0) return;
  // The fixed bit also keeps the held component out of the damping (eq. 8).
  const std::vector<std::int64_t>& active = fields_.active;
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    fields_.velocity[u][a] = 0.0;
    fields_.fixed[u] = static_cast<std::uint8_t>(fields_.fixed[u] | (1u << a));
  });
}

void Solver::hold_thickness_acceleration() {
  const int a = config_.plane_strain_axis;
  if (a < 0) return;
  const std::vector<std::int64_t>& active = fields_.active;
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    fields_.acceleration[static_cast<std::size_t>(active[static_cast<std::size_t>(k)])][a] = 0.0;
  });
}

void Solver::update_stress(double dt) {
  const auto n = static_cast<std::int64_t>(points_.size());
  const common::Mat3 I = common::Mat3::Identity();
  if (config_.formulation == Formulation::total_lagrangian)
    to_spatial_gradient(points_.F, points_.L);
  if (config_.strain_smoothing == StrainSmoothing::cell) {
    average_per_cell(config_.grid, points_.x, points_.volume, points_.L, smoothing_scratch_);
  } else if (config_.strain_smoothing == StrainSmoothing::volumetric) {
    average_trace_per_cell(config_.grid, points_.x, points_.volume, config_.plane_strain_axis,
                           points_.L, smoothing_scratch_);
  }
  if (config_.subcell_relaxation > 0.0) {
    // tau in units of the time a wave takes to cross a cell (as the CFL step, mass-scaled); the
    // modulus rho c^2 with the material's own wave speed.
    double c = 0.0;
    for (const MaterialModel* m : materials_) c = std::max(c, m->wave_speed());
    if (!(c > 0.0) || !std::isfinite(c)) {
      throw common::NumericalError("mpm step " + std::to_string(step_) + " (t = " + num_str(time_) +
                                   " s): mpm.subcell_relaxation needs the materials' wave speed, "
                                   "got " +
                                   num_str(c) + " m/s");
    }
    const double c_step = c / std::sqrt(config_.mass_scaling);
    const double tau = config_.subcell_relaxation * config_.grid.spacing.minCoeff() / c_step;
    relax_subcell_stress(config_.grid, points_.x, points_.mass, points_.volume, points_.stress,
                         config_.plane_strain_axis, c, tau, points_.L, smoothing_scratch_);
  }
  if (const int a = config_.plane_strain_axis; a >= 0) {
    // Plane strain: no stretching or shearing through the thickness reaches the material, even
    // when its out-of-plane shear stress makes the in-plane velocities vary through the cell.
    for_each_index(static_cast<std::int64_t>(points_.size()), [&](std::int64_t q) {
      common::Mat3& L = points_.L[static_cast<std::size_t>(q)];
      L.row(a).setZero();
      L.col(a).setZero();
    });
  }
  if (config_.free_density == FreeDensity::grid && dt > 0.0) {
    // The volumes are those of the step's start, the stencils those of the L just computed.
    grid_density(config_.grid, cache_, points_, density_node_m_, density_node_v_, density_rho_);
    limit_free_dilation(density_rho_, config_.plane_strain_axis, dt, points_);
  }
  // Internal work: trapezoidal rule on the stress power (old and new volume and stress).
  const double power_start = stress_power(points_);
  // Kinematics: F <- (I + L dt) F, V <- det(I + L dt) V.
  for_each_index(n, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    const common::Mat3 dF = I + dt * points_.L[p];
    points_.F[p] = dF * points_.F[p];
    points_.volume[p] *= dF.determinant();
  });
  try {
    update_material_stress(dt);
  } catch (const common::NumericalError& e) {
    // A material's failure (e.g. an RVE of the farm) gains the MPM step and simulated time.
    throw common::NumericalError("mpm step " + std::to_string(step_) +
                                 " (t = " + num_str(time_ + dt) + " s, dt = " + num_str(dt) +
                                 " s): " + e.what());
  }
  internal_work_ += 0.5 * dt * (power_start + stress_power(points_));
  if (regularisation_) {
    // The regularisation's strain from the L the materials saw, at the step's positions and
    // volumes (those of the internal forces that follow, in USF).
    internal_work_ +=
        regularisation_->update(points_.x, points_.volume, points_.material, points_.L, dt);
  }
}

Energies Solver::energies() const {
  const double kin =
      kinetic_step_ == step_ ? kinetic_ : kinetic_energy(points_, config_.mass_scaling);
  return {kin, internal_work_};
}

void Solver::update_material_stress(double dt) {
  dilute_.resize(points_.size());
  if (materials_.size() == 1) {
    materials_[0]->update_stress(points_.id, points_.L, dt, points_.stress);
    materials_[0]->mark_dilute(points_.id, dilute_);
    return;
  }
  for (std::size_t k = 0; k < materials_.size(); ++k) {
    gather_ids_.clear();
    gather_L_.clear();
    for (std::size_t p = 0; p < points_.size(); ++p) {
      if (static_cast<std::size_t>(points_.material[p]) != k) continue;
      gather_ids_.push_back(points_.id[p]);
      gather_L_.push_back(points_.L[p]);
    }
    if (gather_ids_.empty()) continue;
    gather_stress_.resize(gather_ids_.size());
    materials_[k]->update_stress(gather_ids_, gather_L_, dt, gather_stress_);
    gather_dilute_.resize(gather_ids_.size());
    materials_[k]->mark_dilute(gather_ids_, gather_dilute_);
    std::size_t j = 0;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      if (static_cast<std::size_t>(points_.material[p]) != k) continue;
      points_.stress[p] = gather_stress_[j];
      dilute_[p] = gather_dilute_[j++];
    }
  }
}

void Solver::check_points(double t_end) const {
  // Which points fail, in parallel; the first of them (in slot order) is reported below.
  const double vr = config_.max_volume_ratio;
  // A stress-free point may expand without bound: a disconnected material (a spray of grains,
  // dem.coupling.contact_loss) whose volume carries no force; so may a dilute one, whose grains
  // collide now and then (its material says so); a stressed, dense one has blown up.
  const auto too_large = [&](std::size_t p, double ratio) {
    return ratio > vr && !points_.stress[p].isZero(0.0) && dilute_[p] == 0;
  };
  thread_local std::vector<std::uint8_t> bad;
  compute_terms(static_cast<std::int64_t>(points_.size()), bad, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    const double vol = points_.volume[p];
    const double ratio = vol / points_.volume0[p];
    const bool ok = vol > 0.0 && std::isfinite(vol) &&
                    !(points_.volume0[p] > 0.0 && (too_large(p, ratio) || ratio < 1.0 / vr)) &&
                    points_.stress[p].allFinite() && points_.v[p].allFinite();
    return static_cast<std::uint8_t>(ok ? 0 : 1);
  });
  const auto first = std::find(bad.begin(), bad.end(), std::uint8_t{1});
  if (first == bad.end()) return;
  const auto p = static_cast<std::size_t>(first - bad.begin());
  const double vol = points_.volume[p];
  if (!(vol > 0.0) || !std::isfinite(vol)) {
    throw common::NumericalError(
        "mpm step " + std::to_string(step_) + " (t = " + num_str(t_end) + " s): point id " +
        std::to_string(points_.id[p]) + " at x = " + vec_str(points_.x[p]) +
        " m: volume = " + num_str(vol) + " m^3 (must be positive and finite)");
  }
  const double ratio = vol / points_.volume0[p];
  if (points_.volume0[p] > 0.0 && (too_large(p, ratio) || ratio < 1.0 / vr)) {
    throw common::NumericalError(
        "mpm step " + std::to_string(step_) + " (t = " + num_str(t_end) + " s): point id " +
        std::to_string(points_.id[p]) + " at x = " + vec_str(points_.x[p]) +
        " m: volume / initial volume = " + num_str(ratio) + ", outside [1/" +
        short_str(config_.max_volume_ratio) + ", " + short_str(config_.max_volume_ratio) +
        "] (its pressure " + num_str(-points_.stress[p].trace() / 3.0) +
        " Pa, |v| = " + num_str(points_.v[p].norm()) +
        " m/s): the run has blown up (time step too large), or a material that keeps a stress "
        "without contacts (dem.coupling.contact_loss = \"strained\") was strained by its "
        "neighbours' nodes");
  }
  if (!points_.stress[p].allFinite() || !points_.v[p].allFinite()) {
    throw common::NumericalError(
        "mpm step " + std::to_string(step_) + " (t = " + num_str(t_end) + " s): point id " +
        std::to_string(points_.id[p]) +
        ": stress is not finite (trace = " + num_str(points_.stress[p].trace()) +
        " Pa, |v| = " + num_str(points_.v[p].norm()) + " m/s)");
  }
}

void Solver::add_external_loads() {
  for (std::size_t k = 0; k < tractions_.size(); ++k) {
    traction_areas_[k] =
        apply_traction(config_.grid, config_.shape, tractions_[k], points_, traction_points_[k],
                       fields_, config_.formulation == Formulation::total_lagrangian);
  }
}

void Solver::internal_force() {
  const bool total = config_.formulation == Formulation::total_lagrangian;
  const bool smooth = config_.strain_smoothing != StrainSmoothing::none;
  if (!total && !smooth && !regularisation_) {
    p2g_internal_force(config_.grid, cache_, bins_, points_, fields_);
    return;
  }
  // Total Lagrangian: the grid gradients are reference ones, V sigma grad_x S = V sigma F^-T
  // grad_X S. Smoothing: the forces of the cell's mean stress (or mean normal stress), the
  // adjoint of the smoothed L, so the forces' power equals the material's and, with "cell", the
  // hourglass modes, which the smoothed L does not see, get no force either (docs/design/mpm.md).
  const bool volumetric = config_.strain_smoothing == StrainSmoothing::volumetric;
  if (total && !volumetric) {
    stress_for_reference_gradient(points_.F, points_.stress, force_stress_);
  } else {
    force_stress_ = points_.stress;
  }
  if (regularisation_) {
    // Before the cell average: the energy's strain is taken on the smoothed L, and the cell
    // average is its own adjoint.
    regularisation_->add_force_stress(points_.x, points_.volume, points_.material, force_stress_);
  }
  if (config_.strain_smoothing == StrainSmoothing::cell) {
    average_per_cell(config_.grid, points_.x, points_.volume, force_stress_, smoothing_scratch_);
  } else if (volumetric) {
    // On the Cauchy stress, whose power the spatial L's trace average conserves; then, total
    // Lagrangian, to the reference gradients.
    average_trace_per_cell(config_.grid, points_.x, points_.volume, config_.plane_strain_axis,
                           force_stress_, smoothing_scratch_);
    if (total) stress_for_reference_gradient(points_.F, force_stress_, force_stress_);
  }
  points_.stress.swap(force_stress_);
  p2g_internal_force(config_.grid, cache_, bins_, points_, fields_);
  points_.stress.swap(force_stress_);
}

void Solver::update_points(double dt) {
  if (config_.transfer == Transfer::apic) {
    g2p_update_affine(config_.grid, cache_, fields_, threshold_, config_.move_points, dt, points_);
  } else {
    // The PIC share: 1 - flip (the expression the app computed from the job before, same bits),
    // or the relaxation of pic_time over this step.
    const double share = pic_share(config_.flip, config_.pic_time, dt);
    // XPIC(m): the PIC share's grid velocity is V* instead of V.
    const bool xpic = config_.xpic_order > 1 && share > 0.0;
    if (xpic) {
      xpic_velocity(config_.grid, cache_, bins_, points_, fields_, threshold_, config_.xpic_order,
                    xpic_scratch_, xpic_velocity_);
    }
    g2p_update(config_.grid, cache_, fields_, share, config_.move_points, dt, points_,
               config_.grid_positions, config_.wall_impulse_on_points,
               xpic ? &xpic_velocity_ : nullptr);
  }
}

void Solver::stress_stage(double t, double dt) {
  g2p_velocity_gradient(config_.grid, cache_, fields_, threshold_, points_);
  update_stress(dt);
  check_points(t + dt);
}

void Solver::momentum_stage(double t, double dt) {
  internal_force_tracked();
  add_external_loads();
  compute_nodal_acceleration(threshold_, config_.damping, config_.damping_mode, fields_);
  hold_thickness_acceleration();  // before the walls: no reaction through the thickness
  project_wall_trial(dt);
  apply_acceleration_constraints(config_.grid, constraints_, t, dt, fields_, &reactions_);
  hold_thickness_acceleration();
  if (guard_.enabled()) w_ext_step_ += grid_external_work(dt);
  update_points(dt);
}

void Solver::reproject_momentum(double t, double dt) {
  p2g_momentum(config_.grid, cache_, bins_, points_, fields_, config_.transfer == Transfer::apic);
  scale_inertia(false);
  compute_nodal_velocity(threshold_, fields_);
  hold_thickness_velocity();
  apply_velocity_constraints(config_.grid, constraints_, t + dt, fields_);
  hold_thickness_velocity();
}

void Solver::step() {
  const double dt = next_dt();
  const double t = time_;
  if (guard_.enabled() && !guard_.started())
    guard_.start(kinetic_energy(points_, config_.mass_scaling), internal_work_);
  prepare_grid(step_, t);
  if (config_.stress_update == StressUpdate::usf) {
    // USF: L from V_v(t), stress first, then forces from the new stress (eqs. 5, 6, 8-10).
    stress_stage(t, dt);
    momentum_stage(t, dt);
  } else {
    // MUSL: forces from the old stress, move the points, re-project their new momentum with the
    // start-of-step weights, then L and the stress from it.
    momentum_stage(t, dt);
    reproject_momentum(t, dt);
    stress_stage(t, dt);
  }
  advance_displacements(t, dt);
  time_ = t + dt;
  ++step_;
  if (guard_.enabled()) observe_energy(time_);
}

void Solver::run(std::int64_t n) {
  for (std::int64_t k = 0; k < n; ++k) step();
}

}  // namespace mpm
