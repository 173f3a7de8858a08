// Physics invariants of the periodic simulation: energy in a frictionless undamped collision,
// zero stress of a contact-free gas under affine deformation, objectivity under a rigid rotation,
// invariance under a lattice translation, bit-for-bit equality between 1 and 2 OpenMP threads
// and between the fused step() and compute_forces(); integrate().
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "dem/loading.hpp"
#include "dem/measures.hpp"
#include "dem/simulation.hpp"
#include "dem/threads.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Mat3;
using common::Vec3;

double kinetic(const dem::Simulation& sim) {
  const auto& s = sim.spheres();
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    e += 0.5 * (s.m[i] * s.u[i].squaredNorm() + s.inertia[i] * s.w[i].squaredNorm());
  }
  return e;
}

// Steps until the spheres have touched and separated again (at most 200,000 steps); whether they
// touched.
bool collide(dem::Simulation& sim) {
  bool touched = false;
  for (int k = 0; k < 200000; ++k) {
    sim.step();
    bool any = false;
    for (auto a : sim.contacts().active) any = any || a;
    touched = touched || any;
    if (touched && !any) break;
  }
  return touched;
}

// Oblique collision of two spheres, no friction, no rolling stiffness, no damping: the kinetic
// energy after separation equals the one before (leap-frog on a linear spring; error O(dt^2)).
TEST(Simulation, FrictionlessUndampedCollisionConservesEnergy) {
  dem::Material mat = dem_test::reference_material();
  mat.friction_deg = 0.0;
  mat.alpha_r = 0.0;
  dem::Numerics num;
  num.damping = 0.0;
  dem::Spheres s;
  s.add(Vec3(1e-3, 1e-3, 1e-3), 1e-4, mat.density);
  s.add(Vec3(1e-3 + 2.5e-4, 1e-3 + 0.5e-4, 1e-3), 0.8e-4, mat.density);
  s.u[0] = Vec3(0.5, 0.0, 0.0);
  s.u[1] = Vec3(-0.5, 0.1, 0.0);
  dem::PeriodicCell cell;
  cell.h = Mat3::Identity() * 2e-3;
  dem::Simulation sim(s, cell, mat, num);
  sim.set_dt(2e-9);
  const double e0 = kinetic(sim);
  ASSERT_TRUE(collide(sim));
  const double e1 = kinetic(sim);
  EXPECT_NEAR(e1 / e0, 1.0, 1e-6);
  // Frictionless: no spin is created.
  EXPECT_EQ(sim.spheres().w[0].norm(), 0.0);
}

// Cundall's non-viscous damping lambda on a head-on collision of two equal spheres on a linear
// contact: the force is (1 + lambda) k x while they approach and (1 - lambda) k x while they
// separate, so the kinetic energy given back is (1 - lambda) / (1 + lambda) of the one taken and
// the restitution coefficient is e = sqrt((1 - lambda) / (1 + lambda)) (0.95 at 0.05, 0.82 at
// 0.2): what a damping value means for a flow (docs/design/dem.md, "Damping"). Tolerance 0.1 %:
// the leap-frog switches the sign within one step of the turning point (about 700 steps per
// contact here; measured within 1e-5).
TEST(Simulation, CundallDampingGivesTheRestitutionOfALinearContact) {
  dem::Material mat = dem_test::reference_material();
  mat.friction_deg = 0.0;
  mat.alpha_r = 0.0;
  for (const double lambda : {0.0, 0.05, 0.2, 0.5}) {
    SCOPED_TRACE(lambda);
    dem::Numerics num;
    num.damping = lambda;
    dem::Spheres s;
    s.add(Vec3(1e-3, 1e-3, 1e-3), 1e-4, mat.density);
    s.add(Vec3(1e-3 + 2.5e-4, 1e-3, 1e-3), 1e-4, mat.density);
    s.u[0] = Vec3(0.5, 0.0, 0.0);
    s.u[1] = Vec3(-0.5, 0.0, 0.0);
    dem::PeriodicCell cell;
    cell.h = Mat3::Identity() * 2e-3;
    dem::Simulation sim(s, cell, mat, num);
    sim.set_dt(2e-9);
    ASSERT_TRUE(collide(sim));
    const double approach = 1.0;  // the relative speed before the contact [m/s]
    const double e = (sim.spheres().u[1].x() - sim.spheres().u[0].x()) / approach;
    EXPECT_NEAR(e, std::sqrt((1.0 - lambda) / (1.0 + lambda)), 1e-3);
    std::printf("damping %.2f: restitution %.5f (sqrt((1 - l)/(1 + l)) = %.5f)\n", lambda, e,
                std::sqrt((1.0 - lambda) / (1.0 + lambda)));
  }
}

// A gas (no contact) under an affine deformation with spin keeps zero stress and zero
// fluctuating velocity, and stays affine in reduced coordinates.
TEST(Simulation, ContactFreeGasHasZeroStressUnderAffineDeformation) {
  dem::Spheres s;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      for (int c = 0; c < 4; ++c) s.add(Vec3(a + 0.5, b + 0.5, c + 0.5) * 1e-3, 1e-4, 2650.0);
    }
  }
  dem::PeriodicCell cell;
  cell.h = Mat3::Identity() * 4e-3;
  dem::Simulation sim(s, cell, dem_test::reference_material(), dem::Numerics{});
  Mat3 l;
  l << -2.0, 3.0, 0.5, -1.0, 1.0, 0.2, 0.3, -0.4, 0.5;
  sim.cell().l = l;
  sim.set_dt(1e-6);
  const Mat3 hinv0 = sim.cell().h.inverse();
  const Vec3 xi0 = hinv0 * sim.spheres().x[5];
  for (int k = 0; k < 2000; ++k) {
    sim.step();
    ASSERT_EQ(sim.stress().norm(), 0.0);
  }
  EXPECT_EQ(sim.spheres().u[5].norm(), 0.0);
  const Vec3 xi = sim.cell().h.inverse() * sim.spheres().x[5];
  Vec3 dxi = xi - xi0;
  for (int a = 0; a < 3; ++a) dxi[a] -= std::round(dxi[a]);  // wrapping
  EXPECT_LT(dxi.norm(), 1e-12);
  EXPECT_GT(std::abs(sim.cell().h(0, 1)), 1e-5);  // the cell did shear
}

// Large simple shear of a gas: the cell is re-mapped to a less skewed equivalent cell (same
// lattice) on neighbour rebuilds; positions stay affine modulo the lattice, stress stays zero.
// Masses and moments of inertia divide the forces: spheres whose r^5 rho underflows (radii of
// 1e-70 m, in a cell the packing checks accept) or whose r^3 rho overflows are refused, naming the
// sphere, instead of giving 0/0 accelerations.
TEST(Simulation, MassOrInertiaOutsideDoublePrecisionIsRefused) {
  for (const double scale : {1e-70, 1e+70}) {
    dem::Spheres s;
    for (int a = 0; a < 2; ++a) s.add(Vec3(a + 0.5, 0.5, 0.5) * scale, 0.25 * scale, 2650.0);
    dem::PeriodicCell cell;
    cell.h = Mat3::Identity() * 2.0 * scale;
    try {
      dem::Simulation sim(s, cell, dem_test::reference_material(), dem::Numerics{});
      ADD_FAILURE() << "radius " << 0.25 * scale << " m accepted";
    } catch (const common::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("sphere 0 (radius"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("not ordinary positive numbers in double precision"),
                std::string::npos)
          << e.what();
    }
  }
}

// A sphere whose position is no longer finite (a blow-up) stops the simulation with a numerical
// error naming it, at the next step's neighbour check, on one thread and on two; a NaN used to
// drop out of the drift maximum, and an infinite one to reach an undefined conversion.
TEST(Simulation, NonFinitePositionIsANumericalError_threads_1_2) {
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    for (const int threads : {1, 2}) {
      omp_set_num_threads(threads);
      dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                                 dem_test::reference_material(), dem::Numerics{});
      sim.step();
      sim.spheres().x[17][1] = bad;
      try {
        for (int k = 0; k < 3; ++k) sim.step();
        ADD_FAILURE() << "a position of " << bad << " went on (" << threads << " threads)";
      } catch (const common::NumericalError& e) {
        EXPECT_NE(std::string(e.what()).find("has a position that is not finite"),
                  std::string::npos)
            << e.what();
      }
    }
  }
  omp_set_num_threads(1);
}

TEST(Simulation, LargeShearRemapsCell) {
  dem::Spheres s;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      for (int c = 0; c < 3; ++c) s.add(Vec3(a + 0.5, b + 0.5, c + 0.5) * 1e-3, 1e-4, 2650.0);
    }
  }
  dem::PeriodicCell cell;
  cell.h = Mat3::Identity() * 3e-3;
  dem::Simulation sim(s, cell, dem_test::reference_material(), dem::Numerics{});
  sim.cell().l(0, 1) = 1000.0;  // simple shear, total gamma = 2.5
  sim.set_dt(1e-6);
  const Vec3 x0 = sim.spheres().x[7];
  for (int k = 0; k < 2500; ++k) sim.step();
  EXPECT_EQ(sim.stress().norm(), 0.0);
  // Re-mapped: |H01| <= 0.5 |H00|, volume unchanged.
  EXPECT_LE(std::abs(sim.cell().h(0, 1)), 0.5 * sim.cell().h(0, 0) + 1e-15);
  EXPECT_NEAR(sim.cell().volume(), 27e-9, 1e-18);
  // Affine image of x0 (exact deformation gradient of the 2500 steps) modulo the new lattice.
  Mat3 f = Mat3::Identity();
  for (int k = 0; k < 2500; ++k) f = f + (1e-6 * sim.cell().l) * f;
  Vec3 dxi = sim.cell().h.inverse() * (sim.spheres().x[7] - f * x0);
  for (int a = 0; a < 3; ++a) dxi[a] -= std::round(dxi[a]);
  EXPECT_LT(dxi.norm(), 1e-9);
}

Mat3 run_fixed(const dem::Packing& pk, const Mat3& l, int steps, double dt, double damping) {
  dem::Numerics num;
  num.damping = damping;
  dem::Simulation sim = dem::make_simulation(pk, dem_test::reference_material(), num);
  sim.set_dt(dt);
  sim.cell().l = l;
  for (int k = 0; k < steps; ++k) sim.step();
  sim.set_dt(0.0);
  sim.compute_forces();
  return sim.stress();
}

// Rigid rotation of a stressed packing (positions and cell) rotates the stress: R sigma R^T.
// Undamped: Cundall's damping acts per Cartesian component (as YADE's), so it is frame dependent
// (with damping 0.2 the difference after 100 steps is 2e-5 relative).
TEST(Simulation, RigidRotationRotatesStress) {
  const dem::Packing pk = dem_test::reference_packing();
  const Mat3 rot = Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  dem::Packing pr = pk;
  pr.cell.h = rot * pk.cell.h;
  for (auto& x : pr.x) x = rot * x;
  Mat3 l = Mat3::Zero();
  l(2, 2) = -10.0;
  l(0, 1) = 3.0;
  const Mat3 s0 = run_fixed(pk, l, 100, 8e-8, 0.0);
  const Mat3 s1 = run_fixed(pr, rot * l * rot.transpose(), 100, 8e-8, 0.0);
  const double err = (s1 - rot * s0 * rot.transpose()).norm() / s0.norm();
  std::cout << "  rotation: relative error " << err << "\n";
  EXPECT_LT(err, 1e-9);
}

// Translating all spheres by a lattice vector changes nothing (up to round-off).
TEST(Simulation, LatticeTranslationChangesNothing) {
  const dem::Packing pk = dem_test::reference_packing();
  dem::Packing pt = pk;
  const Vec3 shift = pk.cell.h * Vec3(1.0, -2.0, 3.0);
  for (auto& x : pt.x) x += shift;
  Mat3 l = Mat3::Zero();
  l(2, 2) = -10.0;
  l(1, 0) = 2.0;
  const Mat3 s0 = run_fixed(pk, l, 100, 8e-8, 0.2);
  const Mat3 s1 = run_fixed(pt, l, 100, 8e-8, 0.2);
  const double err = (s1 - s0).norm() / s0.norm();
  std::cout << "  translation: relative error " << err << "\n";
  EXPECT_LT(err, 1e-9);
}

struct Snapshot {
  std::vector<Vec3> x, u, w;
  Mat3 stress;
};

Snapshot run_threads(int threads) {
  omp_set_num_threads(threads);
  dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                             dem_test::reference_material(), dem::Numerics{});
  dem::MixedController ctl(dem::triaxial_control(50.0, 1e5, 200.0));
  dem::advance(sim, &ctl, 300);
  omp_set_num_threads(omp_get_num_procs());
  return {sim.spheres().x, sim.spheres().u, sim.spheres().w, sim.stress()};
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same_snapshot(const Snapshot& a, const Snapshot& b) {
  EXPECT_TRUE(same_bits(a.x, b.x));
  EXPECT_TRUE(same_bits(a.u, b.u));
  EXPECT_TRUE(same_bits(a.w, b.w));
  EXPECT_EQ(std::memcmp(a.stress.data(), b.stress.data(), sizeof(Mat3)), 0);
}

TEST(Simulation, BitForBitAcrossThreadCounts_threads_1_2) {
  expect_same_snapshot(run_threads(1), run_threads(2));
}

// 16 threads allowed: the 1000 spheres run on a team of 8 (dem::team_size), the same bits.
TEST(Simulation, BitForBitWithACappedTeam) {
  omp_set_num_threads(16);
  EXPECT_EQ(dem::team_size(1000), 8);
  expect_same_snapshot(run_threads(1), run_threads(16));
}

// Everything a step writes: spheres, contacts (with their history), stress, cell, clock.
void expect_same_state(const dem::Simulation& a, const dem::Simulation& b) {
  EXPECT_TRUE(same_bits(a.spheres().x, b.spheres().x));
  EXPECT_TRUE(same_bits(a.spheres().u, b.spheres().u));
  EXPECT_TRUE(same_bits(a.spheres().w, b.spheres().w));
  EXPECT_TRUE(same_bits(a.spheres().force, b.spheres().force));
  EXPECT_TRUE(same_bits(a.spheres().torque, b.spheres().torque));
  EXPECT_TRUE(same_bits(a.contacts().i, b.contacts().i));
  EXPECT_TRUE(same_bits(a.contacts().j, b.contacts().j));
  EXPECT_TRUE(same_bits(a.contacts().active, b.contacts().active));
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(same_bits(a.contacts().hist.normal[k], b.contacts().hist.normal[k]));
    EXPECT_TRUE(same_bits(a.contacts().hist.shear[k], b.contacts().hist.shear[k]));
    EXPECT_TRUE(same_bits(a.contacts().hist.roll[k], b.contacts().hist.roll[k]));
    EXPECT_TRUE(same_bits(a.contacts().hist.twist[k], b.contacts().hist.twist[k]));
  }
  EXPECT_TRUE(same_bits(a.contacts().force, b.contacts().force));
  EXPECT_EQ(std::memcmp(a.stress().data(), b.stress().data(), sizeof(Mat3)), 0);
  EXPECT_EQ(std::memcmp(a.cell().h.data(), b.cell().h.data(), sizeof(Mat3)), 0);
  EXPECT_EQ(a.steps(), b.steps());
  EXPECT_EQ(a.time(), b.time());
  EXPECT_EQ(a.dt(), b.dt());
  EXPECT_EQ(a.verlet().builds, b.verlet().builds);
}

// The fused step() (one parallel region, forces summed and integrated per sphere) and the
// step with a hook give the same bits as compute_forces(); [hook;] integrate() (simulation.hpp),
// on the reference packing under compression and shear, with neighbour rebuilds and 2 threads.
TEST(Simulation, StepEqualsComputeForcesThenIntegrate_threads_2) {
  omp_set_num_threads(2);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -50.0;
  l(0, 1) = 20.0;
  const auto make = [&] {
    dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                               dem_test::reference_material(), dem::Numerics{});
    sim.cell().l = l;
    // Fluctuating velocities of about 1 m/s: the spheres move past the Verlet skin.
    auto& u = sim.spheres().u;
    for (std::size_t q = 0; q < u.size(); ++q) {
      const auto t = static_cast<double>(q);
      u[q] = Vec3(std::sin(t), std::cos(1.7 * t), std::sin(2.3 * t));
    }
    return sim;
  };
  const int steps = 400;
  dem::Simulation fused = make();
  dem::Simulation split = make();
  ASSERT_GT(fused.spheres().size(), 512u);  // above the threshold of the parallel region
  for (int k = 0; k < steps; ++k) {
    fused.step();
    split.compute_forces();
    split.integrate();
  }
  EXPECT_GT(fused.verlet().builds, 1);  // the neighbour lists were rebuilt on the way
  expect_same_state(fused, split);

  // With a hook that moves the cell (the triaxial servo, as dem::advance runs it).
  dem::Simulation hooked = make();
  dem::Simulation manual = make();
  dem::MixedController c1(dem::triaxial_control(50.0, 1e5, 200.0));
  dem::MixedController c2(dem::triaxial_control(50.0, 1e5, 200.0));
  for (int k = 0; k < steps; ++k) {
    hooked.step([&](dem::Simulation& s) { c1.update(s); });
    manual.compute_forces();
    c2.update(manual);
    manual.integrate();
  }
  expect_same_state(hooked, manual);
  omp_set_num_threads(omp_get_num_procs());
}

// step() measures the drift of the positions it ends with for the next step's neighbour check;
// a sphere moved through spheres() between steps must still be seen (the measure is taken
// again): moved by the skin, the next step rebuilds the list, on 1 and 2 threads.
TEST(Simulation, SphereMovedBetweenStepsIsSeenByTheNeighbourCheck) {
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                               dem_test::reference_material(), dem::Numerics{});
    const dem::Simulation& view = sim;  // reads only: the mutable accessors discard the measure
    for (int k = 0; k < 3; ++k) sim.step();
    const std::int64_t builds = view.verlet().builds;
    sim.step();
    ASSERT_EQ(view.verlet().builds, builds) << "no rebuild while the spheres barely move";
    sim.spheres().x[17] += Vec3(0.0, 0.0, 0.6 * view.verlet().skin);
    sim.step();
    EXPECT_EQ(view.verlet().builds, builds + 1) << threads << " thread(s)";
  }
  omp_set_num_threads(omp_get_num_procs());
}

// YADE's GlobalStiffnessTimeStepper as the scalar loop it was written as (per active contact,
// both spheres, in pair order), against critical_dt(), which takes the contacts in vector lanes:
// the same bits, with ended contacts among the pairs and with a twisting stiffness.
double critical_dt_scalar(const dem::Simulation& sim) {
  const dem::Spheres& s = sim.spheres();
  const dem::Contacts& c = sim.contacts();
  const dem::Material& mat = sim.law().material();
  std::vector<Vec3> kt(s.size(), Vec3::Zero()), kr(s.size(), Vec3::Zero());
  std::vector<bool> any(s.size(), false);
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p] == 0) continue;
    const auto i = static_cast<std::size_t>(c.i[p]);
    const auto j = static_cast<std::size_t>(c.j[p]);
    const dem::CohFrictStiffness k = dem::cohfrict_stiffness(mat, s.r[i], s.r[j]);
    const Vec3 n2 = Vec3(c.hist.normal[0][p], c.hist.normal[1][p], c.hist.normal[2][p]).cwiseAbs2();
    for (const std::size_t q : {i, j}) {
      any[q] = true;
      const double r = s.r[q];
      for (int a = 0; a < 3; ++a) {
        kt[q][a] += k.ks + (k.kn - k.ks) * n2[a];
        kr[q][a] += k.ks * r * r * (1.0 - n2[a]) + (k.kt - k.kr) * n2[a] + k.kr;
      }
    }
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (!any[q]) continue;
    const double v = std::min(s.m[q] / kt[q].maxCoeff(), s.inertia[q] / kr[q].maxCoeff());
    best = std::min(best, std::sqrt(2.0 * v));
  }
  return best;
}

TEST(Simulation, CriticalTimeStepLanesEqualTheScalarSums) {
  for (const double alpha_t : {0.0, 1.5}) {
    dem::Material mat = dem_test::reference_material();
    mat.alpha_t = alpha_t;
    dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(), mat, dem::Numerics{});
    // Extension with fluctuating velocities: contacts open, their pairs stay listed.
    Mat3 l = Mat3::Zero();
    l(2, 2) = 200.0;
    l(0, 1) = 50.0;
    sim.cell().l = l;
    std::vector<Vec3>& u = sim.spheres().u;
    for (std::size_t q = 0; q < u.size(); ++q) {
      const auto t = static_cast<double>(q);
      u[q] = 0.1 * Vec3(std::sin(t), std::cos(1.3 * t), std::sin(0.7 * t));
    }
    for (int k = 0; k < 200; ++k) sim.step();
    std::size_t active = 0;
    for (const auto a : sim.contacts().active) active += a != 0 ? 1 : 0;
    ASSERT_LT(active, sim.contacts().size() * 9 / 10) << "some listed pairs out of contact";
    ASSERT_GT(active, 100u);
    const double a = sim.critical_dt();
    const double b = critical_dt_scalar(sim);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << a << " vs " << b << ", alpha_t " << alpha_t;
  }
}

TEST(Simulation, CriticalTimeStepOfReferencePacking) {
  dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                             dem_test::reference_material(), dem::Numerics{});
  // README section 4: 8.5e-8 s on this packing (YADE's CSV: 8.4775e-8 with its shear history).
  EXPECT_NEAR(sim.dt(), 8.5e-8, 0.01 * 8.5e-8);
  const auto m = dem::measure(sim);
  EXPECT_NEAR(m.p, 1e5, 0.01e5);  // the packing's header: p = 1e5 Pa
  EXPECT_NEAR(m.void_ratio, 0.561758, 1e-6);
  EXPECT_NEAR(m.z, 5.694, 1e-9);  // 2847 contacts, as the header
}

}  // namespace
