// Energy-growth guard: stops a run whose kinetic energy grows beyond what the loads, gravity,
// walls and the release of stored stress have put in (docs/design/mpm.md, "Energy-growth guard").
//
// The balance since the guard's start (the first step of this process: a restart starts it
// again):   created = (E_kin - E_kin,0) + (W_int - W_int,0) - W_ext
// E_kin: the points' kinetic energy (scaled inertia); W_int: the materials' internal work (stress
// power, the regularisation's energy); W_ext: the work of every force but the internal ones on
// the grid (gravity, tractions, walls, damping, friction), summed per step. A consistent step
// keeps `created` at the level of its discretisation error (zero or negative: the transfers and
// the damping dissipate); an unstable one makes it grow with E_kin.
#pragma once

#include <array>
#include <cstdint>

namespace mpm {

class EnergyGuard {
 public:
  /// Steps in a row that must show created > share x scale, with at least half of `created` in
  /// the kinetic energy (an unstable step's energy is motion; a balance that drifts while the
  /// points hardly move is the materials' work, e.g. one point per cell with FLIP, whose
  /// lateral stress climbs without motion) and a growing kinetic energy: a
  /// consistent step errs by about one step's work at a time (the stress update's half-step lag
  /// behind the forces, the release of a pre-stress one step before its internal work).
  static constexpr int kPersist = 10;
  /// share: mpm.energy_guard (0 = off).
  explicit EnergyGuard(double share) : share_(share) {}
  [[nodiscard]] bool enabled() const { return share_ > 0.0; }
  /// The baseline: the kinetic energy and the internal work before the first step observed.
  void start(double kinetic, double internal_work);
  [[nodiscard]] bool started() const { return started_; }
  /// After a step (start() called before the first): the kinetic energy now [J], the internal work
  /// since the solver's start [J], the external work of this step [J]. Returns true when the guard
  /// trips.
  bool observe(double kinetic, double internal_work, double external_work_step);
  /// created, and the scale it is measured against: the largest of the kinetic energy (now and
  /// at the start), |W_int - W_int,0| and the sum of |W_ext| over the steps [J].
  [[nodiscard]] double created() const { return created_; }
  [[nodiscard]] double scale() const { return scale_; }
  [[nodiscard]] double external_work() const { return w_ext_; }
  /// Largest share the rule compares with mpm.energy_guard: created / scale held for kPersist
  /// steps in a row (the smallest of the last kPersist steps' shares, a share counting only
  /// where the kinetic energy holds half of `created`), over the steps observed (0 before) [-]:
  /// logged at the end, so that a scene's margin can be read.
  [[nodiscard]] double max_share() const { return max_share_; }
  /// Share of the balance's scale that `created` has held for the last kPersist steps, wherever
  /// the energy sits (motion or the materials' work; 0 before kPersist steps, and a step counts
  /// only where `created` exceeds kDriftSteps mean steps' work, scale / steps observed) [-]. The
  /// rule above leaves a drift into the materials' work alone; the run's log warns of it beyond
  /// kDriftWarn (a point crossing cells under a held plane absorbed work that no load gave:
  /// docs/design/mpm.md, "Energy-growth guard").
  [[nodiscard]] double drift() const { return drift_; }
  /// Largest drift() over the steps observed [-].
  [[nodiscard]] double max_drift() const { return max_drift_; }
  static constexpr double kDriftWarn = 0.1;
  /// A drift must exceed this many mean steps' work: it leaves a run's first few hundred steps
  /// alone (a start-up whose scale is a few steps' work), and from step 1000 on kDriftWarn decides.
  static constexpr double kDriftSteps = 100.0;
  [[nodiscard]] double share() const { return share_; }

 private:
  double share_;
  bool started_ = false;
  double kin0_ = 0.0;
  double wint0_ = 0.0;
  double w_ext_ = 0.0;
  double w_ext_abs_ = 0.0;
  double created_ = 0.0;
  double scale_ = 0.0;
  double max_share_ = 0.0;
  double drift_ = 0.0;
  double max_drift_ = 0.0;
  std::array<double, kPersist> last_share_{};  ///< ring of the last kPersist shares
  std::array<double, kPersist> last_drift_{};  ///< and of created / scale
  std::array<double, kPersist> last_kin_{};    ///< and kinetic energies
  std::int64_t observed_ = 0;
};

}  // namespace mpm
