// Mixed-control servo, step driver, equilibration, random cloud and compaction.
#include "dem/loading.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "common/errors.hpp"
#include "dem/measures.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

Vec3 MixedController::feed_forward(double p_ref) const {
  // The imposed diagonal rates (the other axes) and the stress-controlled axes with stiffness.
  Vec3 ahead = Vec3::Zero();
  std::array<int, 3> s{};
  int ns = 0;
  bool imposed = false;
  for (int a = 0; a < 3; ++a) {
    if (ctl_.stress_axis[a]) {
      if (modulus_[a] > 1e-3 * p_ref) s[ns++] = a;
    } else if (ctl_.l_imposed(a, a) != 0.0) {
      imposed = true;
    }
  }
  if (!imposed || ns == 0) return ahead;
  // K_SS r_S = -K_SI L_I: the stress-controlled axes' rates that hold their stress.
  Eigen::MatrixXd kss(ns, ns);
  Eigen::VectorXd rhs(ns);
  for (int i = 0; i < ns; ++i) {
    rhs[i] = 0.0;
    for (int b = 0; b < 3; ++b) {
      if (!ctl_.stress_axis[b]) rhs[i] -= stiffness_(s[i], b) * ctl_.l_imposed(b, b);
    }
    for (int j = 0; j < ns; ++j) kss(i, j) = stiffness_(s[i], s[j]);
  }
  const Eigen::VectorXd r = kss.ldlt().solve(rhs);
  for (int i = 0; i < ns; ++i) {
    if (std::isfinite(r[i])) ahead[s[i]] = r[i];
  }
  return ahead;
}

void MixedController::update(Simulation& sim) {
  Mat3 l = ctl_.l_imposed;
  const double dt = sim.dt();
  const double tau = ctl_.tau_steps * dt;
  if (sim.steps() - last_modulus_step_ >= 50 || last_modulus_step_ < 0) {
    // Contact-stiffness modulus, fixed-order sum.
    const Contacts& c = sim.contacts();
    Vec3 m = Vec3::Zero();
    Mat3 k = Mat3::Zero();
    for (std::size_t p = 0; p < c.size(); ++p) {
      if (!c.active[p]) continue;
      const Vec3& d = c.branch[p];
      const Vec3 n = at(c.hist.normal, p);
      const double kn = sim.contact_props(p).kn;
      for (int a = 0; a < 3; ++a) m[a] += kn * (n[a] * d[a]) * (n[a] * d[a]);
      const Vec3 nd = n.cwiseProduct(d);
      k += kn * nd * nd.transpose();
    }
    modulus_ = m / sim.cell().volume();
    stiffness_ = k / sim.cell().volume();
    last_modulus_step_ = sim.steps();
  }
  const Mat3& sigma = sim.stress();
  // Scale for an empty cell: no modulus, the rate bound governs.
  const double p_ref = std::max(std::abs(ctl_.target.maxCoeff()), std::abs(ctl_.target.minCoeff()));
  const Vec3 ahead = feed_forward(p_ref);
  for (int a = 0; a < 3; ++a) {
    if (!ctl_.stress_axis[a]) continue;
    const double err = ctl_.target[a] - sigma(a, a);
    double rate = 0.0;
    if (modulus_[a] > 1e-3 * p_ref) {
      const double e = err / modulus_[a];  // strain error [-]
      integral_[a] += e * dt / (4.0 * tau * tau);
      integral_[a] = std::clamp(integral_[a], -ctl_.max_rate, ctl_.max_rate);
      rate = ahead[a] + e / tau + integral_[a];
    } else {
      // No stiffness: move toward the target at the bound.
      rate = err > 0.0 ? ctl_.max_rate : -ctl_.max_rate;
      integral_[a] = 0.0;
    }
    l(a, a) = std::clamp(rate, -ctl_.max_rate, ctl_.max_rate);
  }
  sim.cell().l = l;
}

void advance(Simulation& sim, MixedController* ctl, std::int64_t n,
             const std::function<void(const Simulation&)>& observer) {
  const std::int64_t refresh = sim.numerics().timestep_update_interval;
  const Simulation::StepHook between = [refresh, ctl](Simulation& s) {
    if (s.steps() % refresh == 0) s.refresh_dt();
    if (ctl != nullptr) ctl->update(s);
  };
  for (std::int64_t s = 0; s < n; ++s) {
    sim.step(between);
    if (observer) observer(sim);
  }
}

Simulation make_simulation(const Packing& pk, const Material& mat, const Numerics& num) {
  // Spatial order (bins of about two diameters in reduced coordinates, z-y-x): neighbours are
  // close in memory, which keeps the force loop in cache for large packings.
  const std::size_t n = pk.r.size();
  const Mat3 hinv = pk.cell.h.inverse();
  const int nb = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(n) / 4.0)));
  std::vector<std::int64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 xi = hinv * pk.x[i];
    std::int64_t kk = 0;
    for (int a = 2; a >= 0; --a) {
      const double f = xi[a] - std::floor(xi[a]);
      kk = kk * nb + std::clamp(static_cast<int>(f * nb), 0, nb - 1);
    }
    key[i] = kk;
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  Spheres s;
  for (std::size_t i : order) s.add(pk.x[i], pk.r[i], mat.density);
  PeriodicCell cell = pk.cell;
  cell.l.setZero();
  Simulation sim(std::move(s), cell, mat, num);
  // Detect the initial contacts with a zero step, then size dt on them.
  sim.set_dt(0.0);
  sim.compute_forces();
  sim.refresh_dt();
  return sim;
}

std::int64_t equilibrate(Simulation& sim, const EquilibriumTarget& t,
                         const CheckObserver& observe) {
  const FixedSkinScope fixed(sim);
  MixedControl mc;
  mc.stress_axis = {true, true, true};
  mc.target = Vec3::Constant(-t.pressure);
  mc.max_rate = t.max_rate;
  MixedController ctl(mc);
  std::int64_t done = 0;
  Measures m;
  double worst = 0.0;
  while (done < t.max_steps) {
    advance(sim, &ctl, t.check_every);
    done += t.check_every;
    m = measure(sim);
    if (observe) observe(sim, m);
    worst = 0.0;
    for (int a = 0; a < 3; ++a) worst = std::max(worst, std::abs(m.stress(a, a) + t.pressure));
    if (worst <= t.stress_tol * t.pressure && m.unbalanced <= t.unbalanced_tol &&
        m.n_contacts > 0) {
      sim.cell().l.setZero();
      return done;
    }
  }
  // Which criterion failed, each against its tolerance (a tolerance no packing reaches reads as
  // such: 1e-300 against 1e-9).
  char msg[320];
  std::snprintf(msg, sizeof msg,
                "dem: equilibrate: target p = %.6g Pa not reached in %lld steps: p = %.6g Pa, "
                "largest diagonal stress error %.3g of p (tolerance %.3g), unbalanced force %.3g "
                "(tolerance %.3g), %lld contacts",
                t.pressure, static_cast<long long>(t.max_steps), m.p, worst / t.pressure,
                t.stress_tol, m.unbalanced, t.unbalanced_tol, static_cast<long long>(m.n_contacts));
  throw common::NumericalError(msg);
}

namespace {
double uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

void check_cloud(const Psd& psd, std::int64_t n, double solid) {
  const std::size_t m = psd.diameter.size();
  if (m < 2 || psd.passing.size() != m) {
    throw common::InputError("dem: PSD needs >= 2 (diameter, passing) rows of equal length");
  }
  for (std::size_t a = 1; a < m; ++a) {
    if (!(psd.diameter[a] > psd.diameter[a - 1]) || psd.passing[a] < psd.passing[a - 1]) {
      throw common::InputError("dem: PSD diameters must increase and passing must not decrease");
    }
  }
  if (!(solid > 0.0 && solid < 0.5))
    throw common::InputError("dem: cloud solid fraction in (0, 0.5)");
  // A count no machine holds fails here, not in std::bad_alloc (the app bounds it by memory).
  constexpr std::int64_t kMaxCloud = 1'000'000'000;
  if (n < 2 || n > kMaxCloud) {
    throw common::InputError("dem: make_cloud: " + std::to_string(n) + " spheres: must be in [2, " +
                             std::to_string(kMaxCloud) + "]");
  }
}

// n radii drawn from the grading (by number: mass fraction / d^3 over fine sub-intervals),
// largest first; vs: their total volume.
std::vector<double> draw_radii(const Psd& psd, std::int64_t n, std::mt19937_64& gen, double& vs) {
  const std::size_t m = psd.diameter.size();
  // Number weights of fine sub-intervals: mass fraction / d^3.
  constexpr int kSub = 64;
  std::vector<double> d_lo;
  std::vector<double> d_hi;
  std::vector<double> cum;
  double total = 0.0;
  for (std::size_t a = 1; a < m; ++a) {
    const double dm = psd.passing[a] - psd.passing[a - 1];
    for (int s = 0; s < kSub; ++s) {
      const double lo = psd.diameter[a - 1] + (psd.diameter[a] - psd.diameter[a - 1]) * s / kSub;
      const double hi =
          psd.diameter[a - 1] + (psd.diameter[a] - psd.diameter[a - 1]) * (s + 1) / kSub;
      const double dmid = 0.5 * (lo + hi);
      total += dm / kSub / (dmid * dmid * dmid);
      d_lo.push_back(lo);
      d_hi.push_back(hi);
      cum.push_back(total);
    }
  }
  std::vector<double> r(static_cast<std::size_t>(n));
  vs = 0.0;
  for (auto& ri : r) {
    const double u = uniform01(gen) * total;
    const std::size_t b =
        static_cast<std::size_t>(std::lower_bound(cum.begin(), cum.end(), u) - cum.begin());
    const std::size_t bb = std::min(b, cum.size() - 1);
    ri = 0.5 * (d_lo[bb] + (d_hi[bb] - d_lo[bb]) * uniform01(gen));
    vs += 4.0 / 3.0 * std::numbers::pi * ri * ri * ri;
  }
  std::sort(r.begin(), r.end(), std::greater<>());  // big first: random addition succeeds
  return r;
}

// The spheres of radii r (largest first) placed at random without overlap in a periodic cube of
// this side.
Packing place_spheres(const std::vector<double>& r, double side, std::mt19937_64& gen) {
  Packing pk;
  pk.cell.h = Mat3::Identity() * side;
  // Overlap test against the placed spheres of the 27 periodic bins around the candidate only
  // (bins at least one largest diameter wide): the same accepted positions as testing all
  // spheres, in O(n) instead of O(n^2) (30,000 spheres: 43 s before).
  const int nb = std::max(1, static_cast<int>(side / (2.0 * r.front())));
  const double bw = side / nb;
  std::vector<std::vector<std::int32_t>> bins(static_cast<std::size_t>(nb) * nb * nb);
  auto bin_of = [&](double c) { return std::clamp(static_cast<int>(c / bw), 0, nb - 1); };
  auto bin_index = [&](int i, int j, int k) {
    auto wrap = [&](int v) { return (v % nb + nb) % nb; };
    return static_cast<std::size_t>((wrap(k) * nb + wrap(j)) * nb + wrap(i));
  };
  for (double ri : r) {
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      const Vec3 x(uniform01(gen) * side, uniform01(gen) * side, uniform01(gen) * side);
      const int bi = bin_of(x[0]);
      const int bj = bin_of(x[1]);
      const int bk = bin_of(x[2]);
      const int reach = nb >= 3 ? 1 : 0;  // fewer than 3 bins: one bin holds everything
      bool ok = true;
      for (int dk = -reach; dk <= reach && ok; ++dk) {
        for (int dj = -reach; dj <= reach && ok; ++dj) {
          for (int di = -reach; di <= reach && ok; ++di) {
            for (const std::int32_t q : bins[nb >= 3 ? bin_index(bi + di, bj + dj, bk + dk) : 0]) {
              Vec3 d = pk.x[static_cast<std::size_t>(q)] - x;
              for (int a = 0; a < 3; ++a) d[a] -= side * std::round(d[a] / side);
              if (!(d.norm() > pk.r[static_cast<std::size_t>(q)] + ri)) {
                ok = false;
                break;
              }
            }
          }
        }
      }
      if (ok) {
        bins[nb >= 3 ? bin_index(bi, bj, bk) : 0].push_back(static_cast<std::int32_t>(pk.x.size()));
        pk.x.push_back(x);
        pk.r.push_back(ri);
        placed = true;
      }
    }
    if (!placed) throw common::NumericalError("dem: make_cloud: could not place a sphere");
  }
  return pk;
}

}  // namespace

Packing make_cloud(const Psd& psd, std::int64_t n, double solid, std::uint64_t seed) {
  check_cloud(psd, n, solid);
  std::mt19937_64 gen(seed);
  double vs = 0.0;
  const std::vector<double> r = draw_radii(psd, n, gen, vs);
  return place_spheres(r, std::cbrt(vs / solid), gen);
}

namespace {

// One compaction of `sim` at `friction_deg`; returns the DEM steps.
std::int64_t compact(Simulation& sim, double friction_deg, const EquilibriumTarget& comp,
                     const CheckObserver& observe) {
  sim.set_friction_deg(friction_deg, true);
  return equilibrate(sim, comp, observe);
}

// Towards prep.void_ratio: bisection on the compaction friction in [0, friction_comp_deg] (a
// lower friction gives a denser packing), each trial a compaction of the cloud `sim` holds; `sim`
// ends as the trial within the tolerance, or the closest one.
Prepared compact_to_void_ratio(Simulation& sim, const Preparation& prep,
                               const EquilibriumTarget& comp, const CheckObserver& observe) {
  const Simulation cloud = sim;
  Prepared out;
  out.reached = false;
  double lo = 0.0;
  double hi = prep.friction_comp_deg;
  double f = hi;
  double best = std::numeric_limits<double>::infinity();
  while (out.compactions < prep.max_compactions) {
    Simulation trial = cloud;
    out.steps += compact(trial, f, comp, observe);
    ++out.compactions;
    const double e = void_ratio(trial);
    const double miss = std::abs(e - prep.void_ratio);
    if (miss < best) {
      best = miss;
      out.friction_deg = f;
      out.compacted_void_ratio = e;
      sim = std::move(trial);
    }
    if (miss <= prep.void_ratio_tol) {
      out.reached = true;
      break;
    }
    if (out.compactions == 1 && e < prep.void_ratio) break;  // denser at friction_comp_deg
    (e > prep.void_ratio ? hi : lo) = f;
    f = 0.5 * (lo + hi);
  }
  return out;
}

}  // namespace

Prepared prepare(Simulation& sim, const Preparation& prep, const CheckObserver& observe) {
  const double phi = sim.law().material().friction_deg;
  EquilibriumTarget comp = prep.target;
  comp.max_rate = prep.compaction_rate;
  Prepared out;
  if (prep.void_ratio > 0.0) {
    out = compact_to_void_ratio(sim, prep, comp, observe);
  } else {
    out.friction_deg = prep.friction_comp_deg;
    out.steps = compact(sim, out.friction_deg, comp, observe);
    out.compacted_void_ratio = void_ratio(sim);
    out.compactions = 1;
  }
  sim.set_friction_deg(phi, true);
  out.steps += equilibrate(sim, prep.target, observe);
  return out;
}

}  // namespace dem

namespace dem {
MixedControl triaxial_control(double axial_rate, double confining, double max_rate) {
  MixedControl mc;
  mc.l_imposed(2, 2) = -axial_rate;
  mc.stress_axis = {true, true, false};
  mc.target = Vec3(-confining, -confining, 0.0);
  mc.max_rate = max_rate;
  return mc;
}
}  // namespace dem
