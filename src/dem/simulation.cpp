// Simulation: force loop (per pair, parallel), fixed-order per-sphere sums, leap-frog with Cundall
// damping, cell deformation. Determinism: no floating-point sum depends on the thread count.
#include "dem/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "common/errors.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;
using common::Vec3i;

namespace {
constexpr std::int64_t kStressBlock = 512;      // fixed reduction blocks, independent of threads
constexpr std::int64_t kParallelSpheres = 512;  // fewer spheres: one thread (fork costs more)

inline double sgn(double v) { return (v > 0.0) - (v < 0.0); }
}  // namespace

Simulation::Simulation(Spheres spheres, const PeriodicCell& cell, const Material& mat,
                       const Numerics& num)
    : spheres_(std::move(spheres)), cell_(cell), law_(mat), num_(num) {
  mat.validate();
  num.validate();
  if (cell_.volume() <= 0.0) throw common::InputError("dem: cell matrix H has det(H) <= 0");
  spheres_.set_density(mat.density);
  double rmax = 0.0;
  for (double r : spheres_.r) {
    if (!(r > 0.0)) throw common::InputError("dem: sphere radius must be > 0");
    rmax = std::max(rmax, r);
  }
  verlet_.skin = num.skin_factor * rmax;
  contacts_.resize(0);
}

void Simulation::set_friction_deg(double phi_deg, bool existing) {
  law_.set_friction_deg(phi_deg);
  if (existing) {
    const double t = law_.create(1.0, 1.0).tan_phi;
    for (auto& p : contacts_.props) p.tan_phi = t;
  }
}

void Simulation::update_neighbors(bool due) {
  if (due) {
    remap_and_wrap(spheres_, cell_, contacts_, num_.max_skew);
    build_pairs(spheres_, cell_, contacts_, verlet_);
    force_rebuild_ = false;
  }
}

// One parallel region per step: the pair loop and the per-sphere loop are work-shared loops of
// the same team (an implicit barrier between them), not separate regions: on 2 threads each
// region's fork and join cost as much as a few hundred spheres of work (docs/dem.md).

// The pair loop gathers the contacts in overlap of a stress block into batches of
// CohFrictBatch::kLanes, runs the law on a whole batch at once (vectorised, bit-identical to the
// per-contact law), then writes the batch back and adds its stress in pair order.
void Simulation::pair_forces_shared() {
  const auto np = static_cast<std::int64_t>(contacts_.size());
  const Mat3 h = cell_.h;
  const Mat3 l = cell_.l;
  const double dt = dt_;
  Contacts& c = contacts_;
  const Spheres& s = spheres_;
  const std::int64_t nblocks = (np + kStressBlock - 1) / kStressBlock;
  CohFrictBatch batch;  // per thread: each thread has its own frame
  std::array<std::int64_t, CohFrictBatch::kLanes> pair_of{};
  // The block's stress sum of f (x) d in nine scalars (in registers; a Mat3 temporary per
  // contact costs a store-forwarding stall), the same products added in the same order.
  std::array<double, 9> sum{};
  const auto flush = [&] {
    CohFrictLaw::apply_batch(batch, l, dt);
    for (int q = 0; q < batch.n; ++q) {
      const auto p = static_cast<std::size_t>(pair_of[static_cast<std::size_t>(q)]);
      CohFrictHistory& hp = c.hist[p];
      Vec3& fp = c.force[p];
      Vec3& t1 = c.torque_i[p];
      Vec3& t2 = c.torque_j[p];
      for (int a = 0; a < 3; ++a) {
        hp.normal[a] = batch.normal[a][q];
        hp.shear[a] = batch.shear[a][q];
        hp.roll[a] = batch.roll[a][q];
        hp.twist[a] = batch.twist[a][q];
        fp[a] = batch.force[a][q];
        t1[a] = batch.torque1[a][q];
        t2[a] = batch.torque2[a][q];
      }
      c.fn[p] = batch.fn[q];
      for (int a = 0; a < 3; ++a) {
        const double f = batch.force[a][q];
        for (int e = 0; e < 3; ++e) sum[static_cast<std::size_t>(3 * e + a)] += f * batch.d[e][q];
      }
    }
    batch.n = 0;
    batch.twist_on = false;
  };
#pragma omp for schedule(static)
  for (std::int64_t b = 0; b < nblocks; ++b) {
    sum.fill(0.0);
    const std::int64_t end = std::min(np, (b + 1) * kStressBlock);
    batch.n = 0;
    batch.twist_on = false;
    for (std::int64_t p = b * kStressBlock; p < end; ++p) {
      const std::int32_t i = c.i[p];
      const std::int32_t j = c.j[p];
      const Vec3i& kp = c.k[p];
      // H k is exactly zero for the (most common) image k = 0: skip the product.
      const Vec3 d =
          kp.isZero() ? Vec3(s.x[j] - s.x[i]) : Vec3(s.x[j] + h * kp.cast<double>() - s.x[i]);
      const double rs = s.r[i] + s.r[j];
      const double l2 = d.squaredNorm();
      if (l2 >= rs * rs) {
        if (c.active[p]) {
          c.active[p] = 0;
          c.force[p].setZero();
          c.torque_i[p].setZero();
          c.torque_j[p].setZero();
          c.fn[p] = 0.0;
        }
        continue;
      }
      const bool is_new = c.active[p] == 0;
      if (is_new) {
        c.props[p] = law_.create(s.r[i], s.r[j]);
        c.active[p] = 1;
      }
      c.branch[p] = d;
      pair_of[static_cast<std::size_t>(batch.n)] = p;
      batch.push(d, l2, s.u[j] - s.u[i], s.w[i], s.w[j], s.r[i], s.r[j], c.props[p], c.hist[p],
                 is_new);
      if (batch.n == CohFrictBatch::kLanes) flush();
    }
    if (batch.n > 0) flush();
    block_stress_[static_cast<std::size_t>(b)] = Eigen::Map<const Mat3>(sum.data());
  }
}

void Simulation::prepare_pair_pass(bool rebuild_due) {
  update_neighbors(rebuild_due);
  size_stress_blocks();
}

void Simulation::size_stress_blocks() {
  // Every block's entry is written by the pair loop: only the size matters.
  const auto np = static_cast<std::int64_t>(contacts_.size());
  block_stress_.resize(static_cast<std::size_t>((np + kStressBlock - 1) / kStressBlock));
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
  const double lambda = num_.damping;
  if (!s.fixed[q]) {
    Vec3 a = s.force[q] / s.m[q];
    Vec3 al = s.torque[q] / s.inertia[q];
    for (int k = 0; k < 3; ++k) {
      a[k] *= 1.0 - lambda * sgn(a[k] * (s.u[q][k] + 0.5 * dt * a[k]));
      al[k] *= 1.0 - lambda * sgn(al[k] * (s.w[q][k] + 0.5 * dt * al[k]));
    }
    s.u[q] += dt * a;
    s.w[q] += dt * al;
  }
  Vec3& x = s.x[q];
  const Vec3& u = s.u[q];
  const double lx0 = (l(0, 0) * x[0] + l(0, 1) * x[1]) + l(0, 2) * x[2];
  const double lx1 = (l(1, 0) * x[0] + l(1, 1) * x[1]) + l(1, 2) * x[2];
  const double lx2 = l(2, 0) * x[0] + (l(2, 1) * x[1] + l(2, 2) * x[2]);
  x[0] += dt * (u[0] + lx0);
  x[1] += dt * (u[1] + lx1);
  x[2] += dt * (u[2] + lx2);
}

void Simulation::compute_forces() {
  prepare_pair_pass(force_rebuild_ || needs_rebuild(spheres_, cell_, verlet_));
  const auto ns = static_cast<std::int64_t>(spheres_.size());
#pragma omp parallel if (ns > kParallelSpheres)
  {
    pair_forces_shared();
#pragma omp for schedule(static)
    for (std::int64_t q = 0; q < ns; ++q) sum_sphere(q);
  }
  finish_stress();
}

void Simulation::integrate() {
  const double dt = dt_;
  const Mat3 l = cell_.l;
  const auto ns = static_cast<std::int64_t>(spheres_.size());
#pragma omp parallel for schedule(static) if (ns > kParallelSpheres)
  for (std::int64_t q = 0; q < ns; ++q) integrate_sphere(q, dt, l);
  advance_cell_and_clock();
}

void Simulation::advance_cell_and_clock() {
  cell_.deform(dt_);
  time_ += dt_;
  ++steps_;
}

void Simulation::step() { step(StepHook{}); }

// The forces, (the hook), the per-sphere sums and the integration of step(), called by every
// thread of its region.
void Simulation::step_shared(const StepHook& between, std::int64_t ns, std::exception_ptr& error) {
  pair_forces_shared();
  if (between) {
#pragma omp for schedule(static)
    for (std::int64_t q = 0; q < ns; ++q) sum_sphere(q);
#pragma omp single
    {
      finish_stress();
      try {
        between(*this);
      } catch (...) {
        error = std::current_exception();  // an exception must not leave the region
      }
    }  // implicit barrier: every thread sees the hook's dt and cell().l
    if (!error) {
      const double dt = dt_;
      const Mat3 l = cell_.l;
#pragma omp for schedule(static)
      for (std::int64_t q = 0; q < ns; ++q) integrate_sphere(q, dt, l);
    }
  } else {
    const double dt = dt_;
    const Mat3 l = cell_.l;
#pragma omp for schedule(static)
    for (std::int64_t q = 0; q < ns; ++q) {
      sum_sphere(q);
      integrate_sphere(q, dt, l);
    }
  }
}

void Simulation::step(const StepHook& between) {
  const auto ns = static_cast<std::int64_t>(spheres_.size());
  // The neighbour check (needs_rebuild) runs its loop over spheres in the step's region instead
  // of a region of its own: one fork per step. Every thread then takes the same decision from
  // the reduced maximum (inputs copied here: a rebuild changes verlet_), and only a due rebuild
  // costs a `single` and its barrier.
  const bool check = !force_rebuild_ && verlet_.x_ref.size() == spheres_.size();
  const Mat3 f = check ? rebuild_deformation(cell_, verlet_) : Mat3::Identity();
  const double r_max = verlet_.r_max;
  const double skin = verlet_.skin;
  size_stress_blocks();
  double amax2 = 0.0;
  std::exception_ptr error;
#pragma omp parallel if (ns > kParallelSpheres)
  {
    if (check) {
#pragma omp for reduction(max : amax2) schedule(static)
      for (std::int64_t q = 0; q < ns; ++q) {
        amax2 = std::max(amax2, rebuild_drift2(spheres_, f, verlet_, static_cast<std::size_t>(q)));
      }
    }
    if (!check || rebuild_due(amax2, f, r_max, skin)) {
#pragma omp single
      {
        try {
          update_neighbors(true);
          size_stress_blocks();
        } catch (...) {
          error = std::current_exception();
        }
      }  // implicit barrier: every thread sees the new pair list (or the error)
    }
    if (!error) step_shared(between, ns, error);
  }
  if (error) std::rethrow_exception(error);
  if (!between) finish_stress();
  advance_cell_and_clock();
}

double Simulation::critical_dt() const {
  const Spheres& s = spheres_;
  const Contacts& c = contacts_;
  const auto ns = static_cast<std::int64_t>(s.size());
  double best = std::numeric_limits<double>::infinity();
  if (!c.sphere_offset.empty()) {
#pragma omp parallel for reduction(min : best) schedule(static) if (ns > kParallelSpheres)
    for (std::int64_t q = 0; q < ns; ++q) {
      Vec3 kt = Vec3::Zero();
      Vec3 kr = Vec3::Zero();
      bool any = false;
      for (std::int64_t e = c.sphere_offset[q]; e < c.sphere_offset[q + 1]; ++e) {
        const std::int64_t p0 = c.sphere_pairs[e];
        const std::int64_t p = p0 >= 0 ? p0 : -p0 - 1;
        if (!c.active[p]) continue;
        any = true;
        const CohFrictProps& pr = c.props[p];
        const Vec3 n2 = c.hist[p].normal.cwiseAbs2();
        const double r = s.r[q];
        for (int k = 0; k < 3; ++k) {
          kt[k] += pr.ks + (pr.kn - pr.ks) * n2[k];
          kr[k] += pr.ks * r * r * (1.0 - n2[k]) + (pr.kt - pr.kr) * n2[k] + pr.kr;
        }
      }
      if (!any) continue;
      const double v = std::min(s.m[q] / kt.maxCoeff(), s.inertia[q] / kr.maxCoeff());
      best = std::min(best, std::sqrt(2.0 * v));
    }
  }
  if (std::isfinite(best)) return best;
  // No contact: P-wave estimate scaled as on the reference packing.
  const double rmin = s.size() > 0 ? *std::min_element(s.r.begin(), s.r.end()) : 1.0;
  const Material& mat = law_.material();
  return 0.44 * rmin * std::sqrt(mat.density / mat.young) / num_.dt_safety;
}

void Simulation::refresh_dt() { dt_ = num_.dt_safety * critical_dt(); }

}  // namespace dem
