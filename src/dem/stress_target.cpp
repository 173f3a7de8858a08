// Full-tensor stress servo: see stress_target.hpp.
#include "dem/stress_target.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "dem/measures.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

Mat3 affine_modulus(const Simulation& sim) {
  const Contacts& c = sim.contacts();
  Mat3 m = Mat3::Zero();
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (!c.active[p]) continue;
    const double d2 = c.branch[p].squaredNorm();
    const Vec3 n = at(c.hist.normal, p);
    const ContactProps pr = sim.contact_props(p);
    const double kn = pr.kn;
    const double ks = pr.ks;
    for (int a = 0; a < 3; ++a) {
      for (int b = a; b < 3; ++b) {
        const double w = a == b ? 1.0 : 2.0;  // eps_ab and eps_ba both act on sigma_ab
        const double nn = n[a] * n[a] * n[b] * n[b];
        m(a, b) += d2 * (kn * w * nn + ks * (0.5 * (n[a] * n[a] + n[b] * n[b]) - w * nn));
      }
    }
  }
  m /= sim.cell().volume();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < a; ++b) m(a, b) = m(b, a);
  }
  return m;
}

bool stress_reached(const Mat3& sigma, const Mat3& target, double tol) {
  const double p = -target.trace() / 3.0;
  for (int a = 0; a < 3; ++a) {
    for (int b = a; b < 3; ++b) {
      const double scale = a == b ? std::max(std::abs(target(a, a)), 0.1 * p) : p;
      if (!(std::abs(sigma(a, b) - target(a, b)) <= tol * scale)) return false;
    }
  }
  return true;
}

TensorController::TensorController(const Mat3& target, double max_rate, double tau_steps)
    : target_(0.5 * (target + target.transpose())), max_rate_(max_rate), tau_steps_(tau_steps) {}

void TensorController::update(Simulation& sim) {
  const double dt = sim.dt();
  const double tau = tau_steps_ * dt;
  if (sim.steps() - last_modulus_step_ >= 50 || last_modulus_step_ < 0) {
    modulus_ = affine_modulus(sim);
    last_modulus_step_ = sim.steps();
  }
  const Mat3& sigma = sim.stress();
  const double p_ref = std::max(target_.cwiseAbs().maxCoeff(), 1e-300);
  Mat3 l = Mat3::Zero();
  for (int a = 0; a < 3; ++a) {
    for (int b = a; b < 3; ++b) {
      // The symmetric part of the measured stress: Love-Weber is symmetric up to round-off.
      const double err = target_(a, b) - 0.5 * (sigma(a, b) + sigma(b, a));
      double rate = 0.0;
      if (modulus_(a, b) > 1e-3 * p_ref) {
        const double e = err / modulus_(a, b);  // strain error [-]
        integral_(a, b) += e * dt / (4.0 * tau * tau);
        integral_(a, b) = std::clamp(integral_(a, b), -max_rate_, max_rate_);
        rate = e / tau + integral_(a, b);
      } else {
        // No stiffness (no contacts yet): move toward the target at the bound.
        rate = err > 0.0 ? max_rate_ : -max_rate_;
        integral_(a, b) = 0.0;
      }
      l(a, b) = std::clamp(rate, -max_rate_, max_rate_);
      l(b, a) = l(a, b);  // symmetric: no spin
    }
  }
  sim.cell().l = l;
}

std::int64_t reach_stress(Simulation& sim, const StressTarget& t, const CheckObserver& observe) {
  const FixedSkinScope fixed(sim);
  const Mat3& s = t.stress;
  if (!s.allFinite() || (s - s.transpose()).cwiseAbs().maxCoeff() > 1e-12 * s.cwiseAbs().maxCoeff())
    throw common::InputError("dem: reach_stress: the target stress must be finite and symmetric");
  const double p = -s.trace() / 3.0;
  if (!(p > 0.0)) {
    throw common::InputError("dem: reach_stress: target p = " + std::to_string(p) +
                             " Pa: must be > 0 (a packing holds no tension)");
  }
  TensorController ctl(s, t.max_rate, t.tau_steps);
  std::int64_t done = 0;
  while (done < t.max_steps) {
    const std::int64_t refresh = sim.numerics().timestep_update_interval;
    const Simulation::StepHook between = [refresh, &ctl](Simulation& sm) {
      if (sm.steps() % refresh == 0) sm.refresh_dt();
      ctl.update(sm);
    };
    for (std::int64_t k = 0; k < t.check_every; ++k) sim.step(between);
    done += t.check_every;
    const Measures m = measure(sim);
    if (observe) observe(sim, m);
    if (stress_reached(m.stress, s, t.stress_tol) && m.unbalanced <= t.unbalanced_tol &&
        m.n_contacts > 0) {
      sim.cell().l.setZero();
      return done;
    }
  }
  const Mat3& sg = sim.stress();
  throw common::NumericalError(
      "dem: reach_stress: target (xx, yy, zz, yz, xz, xy) = (" + std::to_string(s(0, 0)) + ", " +
      std::to_string(s(1, 1)) + ", " + std::to_string(s(2, 2)) + ", " + std::to_string(s(1, 2)) +
      ", " + std::to_string(s(0, 2)) + ", " + std::to_string(s(0, 1)) + ") Pa not reached in " +
      std::to_string(t.max_steps) + " DEM steps (now " + std::to_string(sg(0, 0)) + ", " +
      std::to_string(sg(1, 1)) + ", " + std::to_string(sg(2, 2)) + ", " + std::to_string(sg(1, 2)) +
      ", " + std::to_string(sg(0, 2)) + ", " + std::to_string(sg(0, 1)) +
      "): a target outside the material's strength (q / p too large) cannot be held");
}

}  // namespace dem
