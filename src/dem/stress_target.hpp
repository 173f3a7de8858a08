// Full-tensor stress control of the periodic cell: a PI servo on the six components of a symmetric
// velocity gradient (no spin) brings a prepared sample to a target Cauchy stress tensor (in-situ
// initial states, issue 15); the gain uses the affine contact-stiffness modulus of each component.
#pragma once

#include <cstdint>

#include "common/types.hpp"
#include "dem/loading.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// A target stress tensor and the tolerances of "reached".
struct StressTarget {
  common::Mat3 stress = common::Mat3::Zero();  ///< target Cauchy stress, symmetric, tension
                                               ///< positive; p = -tr / 3 must be > 0 [Pa]
  double stress_tol = 0.01;                    ///< see stress_reached() [-]
  double unbalanced_tol = 0.01;                ///< unbalanced force ratio below this [-]
  double max_rate = 1.0;                       ///< bound on every |L_ab| [1/s]
  double tau_steps = 200.0;                    ///< servo time constant, in DEM steps [-]
  std::int64_t check_every = 200;
  std::int64_t max_steps = 2000000;
};

/// Affine contact-stiffness moduli [Pa] of the six strain-rate components: M(a, a) is
/// d sigma_aa / d eps_aa and M(a, b) = M(b, a) is d sigma_ab / d eps_ab (eps_ab = eps_ba) when the
/// spheres follow the cell's affine motion: (1/V) sum_c |d|^2 [k_n n_a^2 n_b^2 (2 - delta_ab) +
/// k_s ((n_a^2 + n_b^2) / 2 - n_a^2 n_b^2 (2 - delta_ab))]. An upper bound of the tangent
/// modulus (no rearrangement): a servo using it errs on the slow, stable side. Fixed-order sum.
[[nodiscard]] common::Mat3 affine_modulus(const Simulation& sim);

/// True when every component of `sigma` is within tolerance of `target`: diagonal components
/// |sigma_aa - S_aa| <= tol max(|S_aa|, p / 10), off-diagonal |sigma_ab - S_ab| <= tol p, with
/// p = -tr(S) / 3. @param tol relative tolerance [-]
[[nodiscard]] bool stress_reached(const common::Mat3& sigma, const common::Mat3& target,
                                  double tol);

/// PI servo on the symmetric strain rate D = L (no spin): component ab moves by
/// (S_ab - sigma_ab) / M_ab per time constant, with an integral term (the diagonal law of
/// MixedController applied to all six components).
class TensorController {
 public:
  /// @param target symmetric [Pa] @param max_rate [1/s] @param tau_steps [-]
  TensorController(const common::Mat3& target, double max_rate, double tau_steps);
  /// Sets sim.cell().l from the stress of the last compute_forces(). Deterministic.
  void update(Simulation& sim);

 private:
  common::Mat3 target_;
  double max_rate_;
  double tau_steps_;
  common::Mat3 integral_ = common::Mat3::Zero();  ///< integral term [1/s]
  common::Mat3 modulus_ = common::Mat3::Zero();   ///< M_ab [Pa]
  std::int64_t last_modulus_step_ = -1;
};

/// Runs the tensor servo until the stress is reached (stress_reached with t.stress_tol) and the
/// unbalanced force ratio is below t.unbalanced_tol, checked every t.check_every steps; leaves
/// the cell at rest (L = 0). Returns the DEM steps done. Throws common::InputError for a target
/// that is not symmetric or has p <= 0, common::NumericalError when max_steps pass (a target
/// outside the material's strength, e.g. q / p too large, cannot be reached).
std::int64_t reach_stress(Simulation& sim, const StressTarget& t,
                          const CheckObserver& observe = {});

}  // namespace dem
