// One periodic DEM cell: spheres, cell, contacts, contact law and the leap-frog integrator with
// Cundall non-viscous damping on fluctuating velocities and spins (YADE's NewtonIntegrator).
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <vector>

#include "common/types.hpp"
#include "dem/adaptive_skin.hpp"
#include "dem/contact_law.hpp"
#include "dem/contacts.hpp"
#include "dem/neighbor_search.hpp"
#include "dem/params.hpp"
#include "dem/periodic_cell.hpp"
#include "dem/spheres.hpp"
#include "dem/work_split.hpp"

namespace dem {

/// The DEM system of one RVE. Results are bit-for-bit independent of the OpenMP thread count.
class Simulation {
 public:
  /// @pre spheres inside or near the cell, material and numerics valid (checked).
  Simulation(Spheres spheres, const PeriodicCell& cell, const Material& mat, const Numerics& num);

  /// Runs between the forces and the integration of a step (a stress servo): sees the new
  /// stress() and the contacts' forces, may set cell().l and dt. Called by one thread while the
  /// others form the spheres' force sums: it must not read or write spheres().
  using StepHook = std::function<void(Simulation&)>;
  /// One step: neighbour update if needed, contact forces, integration, cell deformation with
  /// cell().l. Same results as compute_forces(); integrate(), in ONE OpenMP parallel region.
  /// The integration also measures the drift of the new positions for the next step's
  /// neighbour check (kept with the cell matrix it assumed; a change through spheres(),
  /// verlet() or set_counters() discards it, and the check then measures again: the same bits).
  void step();
  /// The same with `between` run after the forces (compute_forces(); between(*this);
  /// integrate()). An exception from `between` propagates after the region; the step is then
  /// not integrated.
  void step(const StepHook& between);
  /// Neighbour update if needed, contact forces and torques, Love-Weber stress.
  void compute_forces();
  /// Leap-frog update of velocities, positions and the cell with the forces of compute_forces().
  void integrate();

  /// Critical time step from summed per-body stiffnesses (YADE GlobalStiffnessTimeStepper),
  /// without the safety factor [s]. Without contacts: 0.44 min r sqrt(rho / E) (P-wave based).
  [[nodiscard]] double critical_dt() const;
  /// dt <- safety * critical_dt().
  void refresh_dt();
  void set_dt(double dt) { dt_ = dt; }
  [[nodiscard]] double dt() const { return dt_; }  ///< [s]

  /// Love-Weber stress of the last force computation, tension positive [Pa].
  [[nodiscard]] const common::Mat3& stress() const { return stress_; }
  /// Friction angle for new contacts and, if `existing`, for current contacts too [deg].
  void set_friction_deg(double phi_deg, bool existing);

  Spheres& spheres() {
    drift_.valid = false;  // the caller may move spheres
    return spheres_;
  }
  [[nodiscard]] const Spheres& spheres() const { return spheres_; }
  PeriodicCell& cell() { return cell_; }
  [[nodiscard]] const PeriodicCell& cell() const { return cell_; }
  Contacts& contacts() { return contacts_; }
  [[nodiscard]] const Contacts& contacts() const { return contacts_; }
  VerletState& verlet() {
    drift_.valid = false;
    return verlet_;
  }
  [[nodiscard]] const VerletState& verlet() const { return verlet_; }
  [[nodiscard]] const ContactLaw& law() const { return law_; }
  /// Normal force magnitude of pair p in the last force computation [N]: the law's normal force
  /// at the overlap of its branch, its operations (the same bits); 0 for a pair out of contact.
  [[nodiscard]] double normal_force(std::size_t p) const {
    if (contacts_.active[p] == 0) return 0.0;
    const double ri = spheres_.r[static_cast<std::size_t>(contacts_.i[p])];
    const double rj = spheres_.r[static_cast<std::size_t>(contacts_.j[p])];
    return law_.normal_force(ri, rj,
                             (ri + rj) - std::sqrt(contacts_.branch[p].squaredNorm()));
  }
  /// Properties of pair p: its stiffnesses (from the radii; for Hertz-Mindlin the tangent ones at
  /// the overlap of its last branch), its stored friction coefficient.
  [[nodiscard]] ContactProps contact_props(std::size_t p) const {
    const double ri = spheres_.r[static_cast<std::size_t>(contacts_.i[p])];
    const double rj = spheres_.r[static_cast<std::size_t>(contacts_.j[p])];
    const double delta = law_.stiffness_uses_overlap()
                             ? (ri + rj) - std::sqrt(contacts_.branch[p].squaredNorm())
                             : 0.0;
    return law_.props(ri, rj, delta, contacts_.tan_phi[p]);
  }
  [[nodiscard]] const Numerics& numerics() const { return num_; }

  [[nodiscard]] double time() const { return time_; }          ///< [s]
  [[nodiscard]] std::int64_t steps() const { return steps_; }  ///< steps done
  void set_counters(double time, std::int64_t steps) {
    time_ = time;
    steps_ = steps;
    drift_.valid = false;
  }
  /// Force a neighbour rebuild at the next compute_forces().
  void invalidate_neighbors() { force_rebuild_ = true; }
  /// Whether a rebuild is pending (state restore needs it).
  [[nodiscard]] bool neighbors_pending() const { return force_rebuild_; }
  void set_neighbors_pending(bool pending) { force_rebuild_ = pending; }
  /// Switch the adaptive skin (Numerics::skin_min_factor; 0: the fixed skin) from the next
  /// neighbour check on. Throws common::InputError if outside [0, skin_factor].
  void set_skin_min_factor(double f);
  /// Sets skin_min_factor without validation and returns the previous value (FixedSkinScope).
  double exchange_skin_min_factor(double f) noexcept {
    const double old = num_.skin_min_factor;
    num_.skin_min_factor = f;
    return old;
  }
  /// Restore the stress of the last force computation (state restore) [Pa].
  void set_stress(const common::Mat3& s) { stress_ = s; }

 private:
  /// Rebuild the pair list if `due`.
  void update_neighbors(bool due);
  /// One stress block per kStressBlock pairs (each written by the pair loop).
  void size_stress_blocks();
  /// The part of step() after the neighbour update, run by every thread of its region: pair
  /// loop, sums, (hook), integration and the drift of the new positions (their largest
  /// rebuild_drift2 into amax2); an exception of the hook is stored in `error`.
  /// kTeam: called by every thread of a parallel region (each on its ranges of pair_split_ and
  /// sphere_split_); otherwise by the calling thread alone, without OpenMP constructs
  /// (dem::one_thread).
  template <bool kTeam>
  void step_shared(const StepHook& between, std::int64_t ns, double& amax2, common::Mat3& h_next,
                   std::exception_ptr& error);
  /// The neighbour check of step() and compute_forces() (from the drift the last step()
  /// measured, or measured now) and the rebuild it asks for.
  void step_neighbors();
  /// The current list's inputs to the skin choice (measure 0: the caller's).
  [[nodiscard]] SkinInputs skin_inputs() const;
  /// Whether to rebuild the list with the drift `measure`, and with which skin: the fixed skin
  /// when measure >= skin (as needs_rebuild), or decide_skin with dem.numerics.verlet_skin_min > 0.
  [[nodiscard]] SkinDecision neighbor_check(double measure, const SkinInputs& list) const;
  /// The pair loop over the stress blocks: forces, torques, block stresses.
  template <bool kTeam>
  void pair_forces();
  /// Stress block b of the pair loop, its runs of CohFrictBatch::kLanes pairs through `batch`.
  void pair_block(std::int64_t b, CohFrictBatch& batch);
  /// Stress from the block sums, in block order (thread-count independent).
  void finish_stress();
  void sum_sphere(std::int64_t q);
  void integrate_sphere(std::int64_t q, double dt, const common::Mat3& l);
  void advance_cell_and_clock();

  Spheres spheres_;
  PeriodicCell cell_;
  ContactLaw law_;
  Numerics num_;
  Contacts contacts_;
  VerletState verlet_;
  common::Mat3 stress_ = common::Mat3::Zero();
  double dt_ = 0.0;
  double time_ = 0.0;
  std::int64_t steps_ = 0;
  bool force_rebuild_ = true;
  /// The largest rebuild_drift2 of the positions a step() ended with, for the next step's check,
  /// while the cell matrix is the one it assumed (h, bit for bit: cell() may change it). Discarded
  /// by whatever else moves the spheres or changes the list: integrate(), a rebuild, a failed
  /// step, the mutable spheres() and verlet(), set_counters().
  struct Drift {
    bool valid = false;
    common::Mat3 h = common::Mat3::Zero();
    double amax2 = 0.0;
  };
  Drift drift_;
  std::vector<common::Mat3> block_stress_;  ///< scratch of the pair pass (no state)
  /// How the pair loop (in stress blocks) and the sphere loops are cut between a team's threads,
  /// moved by their measured times (no state: results do not depend on it).
  WorkSplit pair_split_;
  WorkSplit sphere_split_;
};

/// For its lifetime `sim` runs with the fixed skin: the preparations (equilibrate, prepare,
/// reach_stress) use it, so that a prepared sample does not depend on the adaptive skin, a speed
/// knob (a compaction is chaotic: another history of the lists' round-off gives another sample).
class FixedSkinScope {
 public:
  explicit FixedSkinScope(Simulation& sim) : sim_(sim), saved_(sim.exchange_skin_min_factor(0.0)) {}
  ~FixedSkinScope() { sim_.exchange_skin_min_factor(saved_); }
  FixedSkinScope(const FixedSkinScope&) = delete;
  FixedSkinScope& operator=(const FixedSkinScope&) = delete;

 private:
  Simulation& sim_;
  double saved_;
};

}  // namespace dem
