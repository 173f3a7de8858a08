// Simulation: force loop (per pair, parallel), fixed-order per-sphere sums, leap-frog with Cundall
// damping, cell deformation. Determinism: no floating-point sum depends on the thread count.
#include "dem/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <string>

#include <omp.h>

#include "common/errors.hpp"
#include "dem/threads.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;
using common::Vec3i;

namespace {
// Fixed reduction blocks of the stress, independent of threads; also the unit of the pair loop's
// cut between threads (WorkSplit). Smaller blocks would balance finer (8 of them at 1000 spheres)
// but change the stress's round-off, and cost 1.5-2 % on one thread (128 and 64 measured).
constexpr std::int64_t kStressBlock = 512;
// The unit of the sphere loops' cut: 8 spheres (192 bytes of a Vec3 array: fine enough to
// balance, coarse enough that two threads' ranges share at most a cache line per array).
constexpr std::int64_t kSphereUnit = 8;

// The range of the calling thread of a team under `split` (units of `unit` indices, up to n),
// or an even one if the team is not the size the split was prepared for.
struct Range {
  std::int64_t lo, hi;
};
inline Range team_range(const WorkSplit& split, std::int64_t unit, std::int64_t n) {
  const int nt = omp_get_num_threads();
  const int t = omp_get_thread_num();
  std::int64_t lo = 0, hi = 0;
  if (nt == split.threads()) {
    lo = split.begin(t) * unit;
    hi = split.end(t) * unit;
  } else {
    const std::int64_t units = (n + unit - 1) / unit;
    lo = units * t / nt * unit;
    hi = units * (t + 1) / nt * unit;
  }
  return {std::min(lo, n), std::min(hi, n)};
}

// The step's loops in two forms from one source: kTeam, a work-shared loop of the enclosing
// region's team (with its implicit barrier); otherwise a plain loop of the calling thread, with no
// OpenMP construct at all (one_thread(): also inside the farm's region over RVEs, where a
// work-shared loop would bind to the farm's team). The same iterations in the same order per
// index: the same bits.
template <bool kTeam, class F>
inline void team_for(std::int64_t n, F&& f) {
  if constexpr (kTeam) {
#pragma omp for schedule(static)
    for (std::int64_t q = 0; q < n; ++q) f(q);
  } else {
    for (std::int64_t q = 0; q < n; ++q) f(q);
  }
}

// f() on one thread of the team (the others wait at the implicit barrier), or on the caller.
template <bool kTeam, class F>
inline void team_single(F&& f) {
  if constexpr (kTeam) {
#pragma omp single
    f();
  } else {
    f();
  }
}

}  // namespace

Simulation::Simulation(Spheres spheres, const PeriodicCell& cell, const Material& mat,
                       const Numerics& num)
    : spheres_(std::move(spheres)), cell_(cell), law_(mat), num_(num) {
  mat.validate();
  num.validate();
  if (cell_.volume() <= 0.0) throw common::InputError("dem: cell matrix H has det(H) <= 0");
  spheres_.set_density(mat.density);
  double rmax = 0.0;
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    const double r = spheres_.r[i];
    if (!(r > 0.0)) throw common::InputError("dem: sphere radius must be > 0");
    // Mass and moment of inertia divide the forces: they must be ordinary positive numbers, not
    // 0 or subnormal (r^3 rho or r^5 rho underflowing) nor infinite.
    if (!std::isnormal(spheres_.m[i]) || !std::isnormal(spheres_.inertia[i])) {
      char msg[400];
      std::snprintf(msg, sizeof msg,
                    "dem: sphere %zu (radius %.6g m, density %.6g kg/m^3) has mass %.6g kg and "
                    "moment of inertia %.6g kg m^2: not ordinary positive numbers in double "
                    "precision (radii and density in SI units, m and kg/m^3?)",
                    i, r, mat.density, spheres_.m[i], spheres_.inertia[i]);
      throw common::InputError(msg);
    }
    rmax = std::max(rmax, r);
  }
  verlet_.skin = num.skin_factor * rmax;
  verlet_.skin_max = verlet_.skin;  // the adaptive skin's widest
  contacts_.resize(0);
}

void Simulation::set_friction_deg(double phi_deg, bool existing) {
  law_.set_friction_deg(phi_deg);
  if (existing) {
    const double t = law_.tan_phi();
    for (double& p : contacts_.tan_phi) p = t;
  }
}

void Simulation::update_neighbors(bool due) {
  if (due) {
    remap_and_wrap(spheres_, cell_, contacts_, num_.max_skew);
    build_pairs(spheres_, cell_, contacts_, verlet_);
    verlet_.built_at_step = steps_;
    force_rebuild_ = false;
    drift_.valid = false;
  }
}

void Simulation::set_skin_min_factor(double f) {
  Numerics num = num_;
  num.skin_min_factor = f;
  num.validate();
  num_ = num;
}

SkinInputs Simulation::skin_inputs() const {
  SkinInputs in;
  in.skin = verlet_.skin;
  in.steps = steps_ - verlet_.built_at_step;
  in.shell_pairs = verlet_.shell_pairs;
  in.spheres = static_cast<std::int64_t>(spheres_.size());
  in.lo = num_.skin_min_factor * verlet_.r_max;
  in.hi = num_.skin_factor * verlet_.r_max;
  return in;
}

SkinDecision Simulation::neighbor_check(double measure, const SkinInputs& list) const {
  if (!(num_.skin_min_factor > 0.0)) return {measure >= list.skin, list.skin};
  SkinInputs in = list;
  in.measure = measure;
  return decide_skin(in);
}

// One parallel region per step: the pair loop and the per-sphere loop are work-shared loops of
// the same team (an implicit barrier between them), not separate regions: on 2 threads each
// region's fork and join cost as much as a few hundred spheres of work (docs/design/dem.md).

// The pair loop takes the Verlet pairs of a stress block in runs of CohFrictBatch::kLanes
// consecutive pairs: it gathers their kinematics (every pair, in overlap or not: no branch on the
// overlap, which is unpredictable), creates and ends contacts, runs the law on the whole run at
// once (vectorised, bit-identical to the per-contact law, reading and writing the pairs' property
// and history arrays in place), then copies the outputs back and adds the stress in pair order.
// Pairs out of overlap get +0 force and torques, which add nothing to the sums.
template <bool kTeam>
void Simulation::pair_forces() {
  const auto np = static_cast<std::int64_t>(contacts_.size());
  const std::int64_t nblocks = (np + kStressBlock - 1) / kStressBlock;
  CohFrictBatch batch;  // per thread: each thread has its own frame
  if constexpr (kTeam) {
    // The thread's blocks under pair_split_, timed for its rebalance; then the barrier.
    const double t0 = omp_get_wtime();
    const Range r = team_range(pair_split_, 1, nblocks);
    for (std::int64_t b = r.lo; b < r.hi; ++b) pair_block(b, batch);
    pair_split_.record(omp_get_thread_num(), omp_get_wtime() - t0);
#pragma omp barrier
  } else {
    for (std::int64_t b = 0; b < nblocks; ++b) pair_block(b, batch);
  }
}

// long-function: the force loop over one block of pairs, gather, law and scatter,
// kept in one body so that the compiler sees the whole hot loop (docs/design/dem.md, "Speed").
void Simulation::pair_block(std::int64_t b, CohFrictBatch& batch) {
  const auto np = static_cast<std::int64_t>(contacts_.size());
  const Mat3 h = cell_.h;
  const Mat3 l = cell_.l;
  const double dt = dt_;
  Contacts& c = contacts_;
  const Spheres& s = spheres_;
  {
    // The block's stress sum of f (x) d, column-major (entry 3 e + a is f_a d_e), in nine local
    // scalars that stay in registers (an array or a Mat3 is kept in memory: a store-forwarding
    // stall per contact); each entry adds the same products in pair order.
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0, s5 = 0.0, s6 = 0.0, s7 = 0.0, s8 = 0.0;
    const std::int64_t end = std::min(np, (b + 1) * kStressBlock);
    for (std::int64_t p0 = b * kStressBlock; p0 < end; p0 += CohFrictBatch::kLanes) {
      const int n = static_cast<int>(std::min<std::int64_t>(CohFrictBatch::kLanes, end - p0));
      batch.n = n;
      batch.first = static_cast<std::size_t>(p0);
      // Kinematics of every pair of the run; contacts begin and end (rare: a well-predicted
      // branch). The component loops are written out (-O2 does not unroll them).
      for (int q = 0; q < n; ++q) {
        const std::int64_t p = p0 + q;
        const std::int32_t i = c.i[p];
        const std::int32_t j = c.j[p];
        const Vec3i& kp = c.k[p];
        // H k is exactly zero for the (most common) image k = 0: skip the product.
        const Vec3 d =
            kp.isZero() ? Vec3(s.x[j] - s.x[i]) : Vec3(s.x[j] + h * kp.cast<double>() - s.x[i]);
        const double ri = s.r[i];
        const double rj = s.r[j];
        const double rs = ri + rj;
        const double l2 = d.squaredNorm();
        const bool touching = l2 < rs * rs;
        const Vec3& ui = s.u[i];
        const Vec3& uj = s.u[j];
        const Vec3& wi = s.w[i];
        const Vec3& wj = s.w[j];
        batch.d[0][q] = d[0];
        batch.d[1][q] = d[1];
        batch.d[2][q] = d[2];
        batch.du[0][q] = uj[0] - ui[0];
        batch.du[1][q] = uj[1] - ui[1];
        batch.du[2][q] = uj[2] - ui[2];
        batch.w1[0][q] = wi[0];
        batch.w1[1][q] = wi[1];
        batch.w1[2][q] = wi[2];
        batch.w2[0][q] = wj[0];
        batch.w2[1][q] = wj[1];
        batch.w2[2][q] = wj[2];
        batch.l2[q] = l2;
        batch.r1[q] = ri;
        batch.r2[q] = rj;
        const bool was = c.active[p] != 0;
        batch.touching[q] = touching ? 1 : 0;
        batch.fresh[q] = touching && !was ? 1 : 0;
        if (touching != was) {
          c.active[p] = touching ? 1 : 0;
          if (touching) c.tan_phi[p] = law_.tan_phi();
        }
      }
      law_.apply_batch(batch, c.tan_phi, c.hist, l, dt, c.twist != Contacts::Twist::none);
      for (int q = 0; q < n; ++q) {
        const auto p = static_cast<std::size_t>(p0 + q);
        const double f0 = batch.force[0][q], f1 = batch.force[1][q], f2 = batch.force[2][q];
        const double d0 = batch.d[0][q], d1 = batch.d[1][q], d2 = batch.d[2][q];
        c.force[p] = Vec3(f0, f1, f2);
        c.torque_i[p] = Vec3(batch.torque1[0][q], batch.torque1[1][q], batch.torque1[2][q]);
        c.torque_j[p] = Vec3(batch.torque2[0][q], batch.torque2[1][q], batch.torque2[2][q]);
        c.branch[p] = Vec3(d0, d1, d2);  // every pair's: written, never read here
        s0 += f0 * d0;
        s1 += f1 * d0;
        s2 += f2 * d0;
        s3 += f0 * d1;
        s4 += f1 * d1;
        s5 += f2 * d1;
        s6 += f0 * d2;
        s7 += f1 * d2;
        s8 += f2 * d2;
      }
    }
    const std::array<double, 9> sum{s0, s1, s2, s3, s4, s5, s6, s7, s8};
    block_stress_[static_cast<std::size_t>(b)] = Eigen::Map<const Mat3>(sum.data());
  }
}

void Simulation::size_stress_blocks() {
  // Every block's entry is written by the pair loop: only the size matters.
  const auto np = static_cast<std::int64_t>(contacts_.size());
  const std::int64_t nblocks = (np + kStressBlock - 1) / kStressBlock;
  block_stress_.resize(static_cast<std::size_t>(nblocks));
  pair_split_.prepare(team_size(static_cast<std::int64_t>(spheres_.size())), nblocks);
  // Whether the law may skip its twisting part: no pair twists, and no contact can (the material
  // gives them no twisting stiffness).
  contacts_.classify_twist();
  if (law_.twists()) contacts_.twist = Contacts::Twist::some;
}

void Simulation::finish_stress() {
  Mat3 total = Mat3::Zero();
  for (const Mat3& m : block_stress_) total += m;
  // Love-Weber with the force on sphere 1 (-F) and the branch from 1 to 2: tension positive.
  stress_ = -total / cell_.volume();
}

// Per-sphere sums in the fixed pair order of the CSR lists, without a branch: the sign of the
// entry selects -force and torque_i (s == i) or +force and torque_j (s == j); f + (-F) is f - F
// bit for bit. Pairs out of contact are not skipped: their force and torques are +0 (zeroed when
// a contact ends, zero in a new list), and adding +0 changes nothing, the sums being never -0
// (they start at +0, and a sum is -0 only if both terms are).
inline void Simulation::sum_sphere(std::int64_t q) {
  const Contacts& c = contacts_;
  const Vec3* const force = c.force.data();
  const Vec3* const torque_i = c.torque_i.data();
  const Vec3* const torque_j = c.torque_j.data();
  double f0 = 0.0, f1 = 0.0, f2 = 0.0;
  double t0 = 0.0, t1 = 0.0, t2 = 0.0;
  for (std::int64_t e = c.sphere_offset[q]; e < c.sphere_offset[q + 1]; ++e) {
    const std::int64_t p0 = c.sphere_pairs[e];
    const bool is_j = p0 < 0;
    const std::int64_t p = is_j ? -p0 - 1 : p0;
    const double sg = is_j ? 1.0 : -1.0;
    const Vec3& fp = force[p];
    const Vec3& tp = (is_j ? torque_j : torque_i)[p];
    f0 += sg * fp[0];
    f1 += sg * fp[1];
    f2 += sg * fp[2];
    t0 += tp[0];
    t1 += tp[1];
    t2 += tp[2];
  }
  spheres_.force[q] = Vec3(f0, f1, f2);
  spheres_.torque[q] = Vec3(t0, t1, t2);
}

// Leap-frog with Cundall damping of the fluctuating velocity and the spin (YADE's
// NewtonIntegrator). L x is written out in Eigen's order for a 3x3 by 3 product (rows 0 and 1:
// (l0 x0 + l1 x1) + l2 x2, row 2: l0 x0 + (l1 x1 + l2 x2)), which Eigen calls out of line.
inline void Simulation::integrate_sphere(std::int64_t q, double dt, const Mat3& l) {
  Spheres& s = spheres_;
  if (!s.fixed[q]) {
    // a_k (1 - lambda sgn(a_k v_k)), sgn in integer arithmetic: no branch (the sign is
    // unpredictable; a select of three constants compiled to branches was 35 % slower).
    const double lambda = num_.damping;
    const auto damp = [lambda](double a, double v) {
      const double g = a * v;
      return a * (1.0 - lambda * static_cast<double>((g > 0.0) - (g < 0.0)));
    };
    const Vec3& f = s.force[q];
    const Vec3& t = s.torque[q];
    Vec3& u = s.u[q];
    Vec3& w = s.w[q];
    const double m = s.m[q];
    const double in = s.inertia[q];
    const double a0 = f[0] / m, a1 = f[1] / m, a2 = f[2] / m;
    const double b0 = t[0] / in, b1 = t[1] / in, b2 = t[2] / in;
    const double h = 0.5 * dt;
    const double da0 = damp(a0, u[0] + h * a0), da1 = damp(a1, u[1] + h * a1);
    const double da2 = damp(a2, u[2] + h * a2);
    const double db0 = damp(b0, w[0] + h * b0), db1 = damp(b1, w[1] + h * b1);
    const double db2 = damp(b2, w[2] + h * b2);
    u = Vec3(u[0] + dt * da0, u[1] + dt * da1, u[2] + dt * da2);
    w = Vec3(w[0] + dt * db0, w[1] + dt * db1, w[2] + dt * db2);
  }
  Vec3& x = s.x[q];
  const Vec3& u = s.u[q];
  const double lx0 = (l(0, 0) * x[0] + l(0, 1) * x[1]) + l(0, 2) * x[2];
  const double lx1 = (l(1, 0) * x[0] + l(1, 1) * x[1]) + l(1, 2) * x[2];
  const double lx2 = l(2, 0) * x[0] + (l(2, 1) * x[1] + l(2, 2) * x[2]);
  x = Vec3(x[0] + dt * (u[0] + lx0), x[1] + dt * (u[1] + lx1), x[2] + dt * (u[2] + lx2));
}

void Simulation::compute_forces() {
  // The check of step(): after a step() (an RVE step's end forces) the drift it measured.
  step_neighbors();
  size_stress_blocks();
  const auto ns = static_cast<std::int64_t>(spheres_.size());
  if (one_thread(ns)) {
    pair_forces<false>();
    for (std::int64_t q = 0; q < ns; ++q) sum_sphere(q);
  } else {
#pragma omp parallel num_threads(team_size(ns))
    {
      pair_forces<true>();
      team_for<true>(ns, [this](std::int64_t q) { sum_sphere(q); });
    }
  }
  finish_stress();
}

void Simulation::integrate() {
  drift_.valid = false;
  const double dt = dt_;
  const Mat3 l = cell_.l;
  const auto ns = static_cast<std::int64_t>(spheres_.size());
  if (one_thread(ns)) {
    for (std::int64_t q = 0; q < ns; ++q) integrate_sphere(q, dt, l);
  } else {
#pragma omp parallel for schedule(static) num_threads(team_size(ns))
    for (std::int64_t q = 0; q < ns; ++q) integrate_sphere(q, dt, l);
  }
  advance_cell_and_clock();
}

void Simulation::advance_cell_and_clock() {
  cell_.deform(dt_);
  time_ += dt_;
  ++steps_;
}

void Simulation::step() { step(StepHook{}); }

// The forces, (the hook), the per-sphere sums, the integration and the drift of the new
// positions, called by every thread of its region (kTeam) or by the calling thread alone. Two
// synchronisations (three with a hook): after the pair loop (every force is needed by the sums),
// (after the hook: it sets dt and l,) and the region's end. The hook runs while the other
// threads form their spheres' sums (it reads the stress and the contacts, not the sums).
template <bool kTeam>
void Simulation::step_shared(const StepHook& between, std::int64_t ns, double& amax2, Mat3& h_next,
                             std::exception_ptr& error) {
  pair_forces<kTeam>();
  // This thread's spheres under sphere_split_ (all of them without a team), the same range for
  // the sums, the integration and the drift: no barrier between them. Its time excludes the
  // hook's.
  Range r{0, ns};
  double busy = 0.0;
  double t0 = 0.0;
  if constexpr (kTeam) {
    r = team_range(sphere_split_, kSphereUnit, ns);
    t0 = omp_get_wtime();
  }
  if (between) {
    for (std::int64_t q = r.lo; q < r.hi; ++q) sum_sphere(q);
    if constexpr (kTeam) busy = omp_get_wtime() - t0;
    team_single<kTeam>([this, &between, &error] {
      finish_stress();
      try {
        between(*this);
      } catch (...) {
        error = std::current_exception();  // an exception must not leave the region
      }
    });  // implicit barrier: every sum is formed, every thread sees the hook's dt and cell().l
    if (error) return;
    if constexpr (kTeam) t0 = omp_get_wtime();
  }
  const double dt = dt_;
  const Mat3 l = cell_.l;
  // The cell this step ends with, as advance_cell_and_clock() will deform it (the same
  // operations: the same bits), and the drift measure's F for it.
  PeriodicCell next = cell_;
  next.deform(dt);
  const Mat3 f = rebuild_deformation(next, verlet_);
  const bool sums = !between;
  for (std::int64_t q = r.lo; q < r.hi; ++q) {
    if (sums) sum_sphere(q);
    integrate_sphere(q, dt, l);
  }
  // A second loop: one fused loop was 7 % slower on one thread.
  double m = 0.0;
  for (std::int64_t q = r.lo; q < r.hi; ++q) {
    m = std::max(m, rebuild_drift2(spheres_, f, verlet_, static_cast<std::size_t>(q)));
  }
  if constexpr (kTeam) {
    sphere_split_.record(omp_get_thread_num(), busy + (omp_get_wtime() - t0));
#pragma omp critical(dem_drift_max)
    amax2 = std::max(amax2, m);  // exact in any order; read after the region
#pragma omp master
    h_next = next.h;
  } else {
    amax2 = m;
    h_next = next.h;
  }
}

// The neighbour check: the drift the last step() measured if it still holds (kept with the cell
// matrix it assumed; whatever else moves spheres or changes the list discards it), else measured
// now (the same maximum of the same values: the same bits); every thread count takes the same
// decision. A due rebuild runs here, before the step's region.
void Simulation::step_neighbors() {
  const bool check = !force_rebuild_ && verlet_.x_ref.size() == spheres_.size();
  SkinDecision d{true, verlet_.skin};  // a forced rebuild keeps the skin
  if (check) {
    const Mat3 f = rebuild_deformation(cell_, verlet_);
    const bool held =
        drift_.valid && std::memcmp(drift_.h.data(), cell_.h.data(), sizeof(Mat3)) == 0;
    const double amax2 = held ? drift_.amax2 : max_drift2_region(spheres_, f, verlet_);
    const SkinInputs list = skin_inputs();
    d = neighbor_check(rebuild_measure(amax2, f, verlet_.r_max, list.skin), list);
    if (d.rebuild) verlet_.skin = d.skin;
  }
  if (d.rebuild) update_neighbors(true);
}

void Simulation::step(const StepHook& between) {
  const auto ns = static_cast<std::int64_t>(spheres_.size());
  step_neighbors();
  size_stress_blocks();
  double amax2 = 0.0;
  Mat3 h_next = Mat3::Zero();
  std::exception_ptr error;
  if (one_thread(ns)) {
    step_shared<false>(between, ns, amax2, h_next, error);
  } else {
    const int team = team_size(ns);
    sphere_split_.prepare(team, (ns + kSphereUnit - 1) / kSphereUnit);
#pragma omp parallel num_threads(team)
    step_shared<true>(between, ns, amax2, h_next, error);
    pair_split_.rebalance();
    sphere_split_.rebalance();
  }
  if (error) {
    drift_.valid = false;
    std::rethrow_exception(error);
  }
  if (!between) finish_stress();
  advance_cell_and_clock();
  drift_ = Drift{true, h_next, amax2};
}

double Simulation::critical_dt() const {
  const Spheres& s = spheres_;
  const Contacts& c = contacts_;
  const auto ns = static_cast<std::size_t>(s.size());
  const std::size_t np = c.size();
  // Per-sphere sums of the contacts' translational (kt) and rotational (kr) stiffnesses, in pair
  // order, each contact adding to its two spheres, as a loop over the spheres' lists would. The
  // contacts are taken kLanes at a time (their indices compacted without a branch on the pair's
  // state), their terms computed in vector lanes (stiffness_lanes: the scalar operations, bit
  // for bit), then added in order. In buffers of the calling thread (the farm calls this for
  // many RVEs at once, one per thread); one thread: it is called once per MPM step or dt_refresh
  // steps. 1000 spheres: 21 us a call, 32 us with the scalar terms (docs/design/dem.md "Speed").
  struct Sums {
    Vec3 kt = Vec3::Zero();
    Vec3 kr = Vec3::Zero();
    bool any = false;
  };
  static thread_local std::vector<Sums> sums;
  static thread_local StiffnessLanes lanes;
  sums.assign(ns, Sums{});
  const Material& mat = law_.material();
  const bool overlap = law_.stiffness_uses_overlap();
  std::array<std::size_t, StiffnessLanes::kLanes> idx{};
  for (std::size_t p = 0; p < np;) {
    int n = 0;
    for (; p < np && n < StiffnessLanes::kLanes; ++p) {
      idx[static_cast<std::size_t>(n)] = p;
      n += c.active[p] != 0 ? 1 : 0;
    }
    lanes.n = n;
    for (int q = 0; q < n; ++q) {
      const std::size_t pq = idx[static_cast<std::size_t>(q)];
      lanes.r1[q] = s.r[static_cast<std::size_t>(c.i[pq])];
      lanes.r2[q] = s.r[static_cast<std::size_t>(c.j[pq])];
      lanes.n0[q] = c.hist.normal[0][pq];
      lanes.n1[q] = c.hist.normal[1][pq];
      lanes.n2[q] = c.hist.normal[2][pq];
      if (overlap) {
        lanes.delta[q] = (lanes.r1[q] + lanes.r2[q]) - std::sqrt(c.branch[pq].squaredNorm());
      }
    }
    law_.stiffness_lanes(lanes);
    for (int q = 0; q < n; ++q) {
      const std::size_t pq = idx[static_cast<std::size_t>(q)];
      Sums& a = sums[static_cast<std::size_t>(c.i[pq])];
      Sums& b = sums[static_cast<std::size_t>(c.j[pq])];
      a.any = true;
      a.kt = Vec3(a.kt[0] + lanes.kt[0][q], a.kt[1] + lanes.kt[1][q], a.kt[2] + lanes.kt[2][q]);
      a.kr = Vec3(a.kr[0] + lanes.kr1[0][q], a.kr[1] + lanes.kr1[1][q], a.kr[2] + lanes.kr1[2][q]);
      b.any = true;
      b.kt = Vec3(b.kt[0] + lanes.kt[0][q], b.kt[1] + lanes.kt[1][q], b.kt[2] + lanes.kt[2][q]);
      b.kr = Vec3(b.kr[0] + lanes.kr2[0][q], b.kr[1] + lanes.kr2[1][q], b.kr[2] + lanes.kr2[2][q]);
    }
  }
  // min sqrt(2 v) = sqrt(2 min v): 2 v is exact and the square root correctly rounded and
  // monotone, so one root gives the same bits.
  double vmin = std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < ns; ++q) {
    const Sums& m = sums[q];
    if (!m.any) continue;
    const double v = std::min(s.m[q] / m.kt.maxCoeff(), s.inertia[q] / m.kr.maxCoeff());
    if (v >= 0.0) vmin = std::min(vmin, v);  // (a negative or NaN v, whose root is NaN: left out)
  }
  const double best = std::sqrt(2.0 * vmin);
  if (std::isfinite(best)) return best;
  // No contact: P-wave estimate scaled as on the reference packing.
  const double rmin = s.size() > 0 ? *std::min_element(s.r.begin(), s.r.end()) : 1.0;
  return 0.44 * rmin * std::sqrt(mat.density / mat.young) / num_.dt_safety;
}

void Simulation::refresh_dt() { dt_ = num_.dt_safety * critical_dt(); }

}  // namespace dem
