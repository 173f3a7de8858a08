// Drained triaxial element test of one periodic cell (see element_test.hpp).
#include "dem/element_test.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

double inertial_time(double d50, double rho, double p) { return std::sqrt(rho * d50 * d50 / p); }

double strain_rate(double inertial_number, double d50, double rho, double p) {
  return inertial_number / inertial_time(d50, rho, p);
}

MixedControl triaxial_servo(const DrainedTriaxial& test) {
  MixedControl mc =
      triaxial_control(test.axial_rate, test.confining, test.servo_rate_factor * test.axial_rate);
  mc.tau_steps = test.servo_tau_steps;
  if (test.plane_strain) {
    mc.stress_axis[1] = false;  // y follows l_imposed(1, 1) = 0: zero strain
    mc.target[1] = 0.0;
  }
  return mc;
}

std::int64_t run_drained_triaxial(Simulation& sim, const DrainedTriaxial& test,
                                  const TriaxialObserver& observe) {
  MixedController servo(triaxial_servo(test));
  const double lz0 = sim.cell().h(2, 2);
  const double v0 = sim.cell().volume();
  TriaxialProgress now;
  while (now.eps_a < test.eps_end && now.steps < test.max_steps) {
    const std::int64_t n = std::min(test.check_every, test.max_steps - now.steps);
    advance(sim, &servo, n);
    now.steps += n;
    now.eps_a = -std::log(sim.cell().h(2, 2) / lz0);
    now.eps_v = -std::log(sim.cell().volume() / v0);
    now.last = now.eps_a >= test.eps_end || now.steps >= test.max_steps;
    if (observe) observe(sim, now);
  }
  return now.steps;
}

}  // namespace dem
