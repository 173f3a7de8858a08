// dem::contact_stiffness_tangent: a simple cubic lattice against its analytic stiffness and
// against the DEM's own response to a small affine increment (exact for this lattice: every
// sphere is a centre of symmetry, so nothing relaxes), symmetries, no contacts.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/loading.hpp"
#include "dem/rve.hpp"
#include "dem/tangent.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Mat3;
using common::Vec3;

constexpr double kR = 1e-4;                  // radius [m]
constexpr double kSpacing = 2 * kR * 0.999;  // centre distance: overlap 2e-7 m

// 3 x 3 x 3 equal spheres on a simple cubic lattice in their periodic cell: 81 contacts, 6 per
// sphere, all at the same overlap.
dem::Simulation lattice() {
  const dem::Material mat = dem_test::reference_material();
  dem::Spheres s;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        s.add(Vec3(a + 0.5, b + 0.5, c + 0.5) * kSpacing, kR, mat.density);
  dem::PeriodicCell cell;
  cell.h = Mat3::Identity() * 3 * kSpacing;
  dem::Simulation sim(s, cell, mat, dem::Numerics{});
  sim.set_dt(0.0);
  sim.compute_forces();
  return sim;
}

int idx(int i, int j) { return 3 * i + j; }

TEST(Tangent, SimpleCubicLatticeMatchesAnalyticStiffness) {
  const dem::Simulation sim = lattice();
  std::int64_t active = 0;
  for (auto a : sim.contacts().active) active += a;
  ASSERT_EQ(active, 81);
  const dem::Tangent c = dem::contact_stiffness_tangent(sim);
  const dem::Material mat = dem_test::reference_material();
  const double kn = mat.young * kR;  // 2 E R1 R2 / (R1 + R2)
  const double ks = mat.ks_over_kn * kn;
  const double a = 2 * kR / kSpacing;  // the law's (R1 + R2) / |d|
  // Each direction: 27 contacts of length l in a volume 27 l^3 -> C_xxxx = k_n / l; shear
  // C_xyxy = a k_s / (2 l) (half from the contacts along x, half from those along y, after
  // symmetrisation); no Poisson coupling in a simple cubic lattice.
  const double rel = 1e-12;  // round-off of sums of 81 equal terms
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(c(idx(i, i), idx(i, i)), kn / kSpacing, rel * kn / kSpacing);
    for (int j = 0; j < 3; ++j) {
      if (j == i) continue;
      EXPECT_NEAR(c(idx(i, i), idx(j, j)), 0.0, rel * kn / kSpacing);
      EXPECT_NEAR(c(idx(i, j), idx(i, j)), a * ks / (2 * kSpacing), rel * kn / kSpacing);
      EXPECT_NEAR(c(idx(i, j), idx(j, i)), a * ks / (2 * kSpacing), rel * kn / kSpacing);
    }
  }
  // Major and minor symmetries of any contact-stiffness tangent.
  EXPECT_LT((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-12 * c.cwiseAbs().maxCoeff());
}

// With either end-of-step scheme: the first RVE step of a carried RVE once counted one contact
// increment of a motion not yet made (its shear twice the tangent's here).
TEST(Tangent, PredictsTheDemIncrementOfTheLattice) {
  for (const bool carried : {false, true}) {
    SCOPED_TRACE(carried ? "end_forces = carried" : "end_forces = separate");
    dem::RveParams p;
    p.material = dem_test::reference_material();
    p.carry_end_forces = carried;
    dem::Rve rve = dem::Rve::from_simulation(lattice(), p);
    const dem::Tangent c = dem::contact_stiffness_tangent(rve.simulation());
    Mat3 e;  // a mixed increment: compression, extension, shear
    e << -1e-6, 3e-7, 0.0, 3e-7, 5e-7, -2e-7, 0.0, -2e-7, -4e-7;
    const Mat3 s0 = rve.stress();
    rve.step(e / 1e-3, 1e-3);
    const Mat3 ds = rve.stress() - s0;
    const Mat3 predicted = dem::apply_tangent(c, e);
    // The tangent leaves out the geometric terms of order sigma e (volume change, rotation of the
    // forces): |sigma| / C_xxxx = 150 kPa / 150 MPa = 1e-3 of the increment; 3e-3 bounds them.
    EXPECT_LT((ds - predicted).norm(), 3e-3 * predicted.norm()) << "DEM\n"
                                                                << ds << "\npredicted\n"
                                                                << predicted;
    EXPECT_GT(predicted.norm(), 100.0);  // a real increment (about 150 Pa), not two zeros
  }
}

// The sum as the header writes it, term by term over the 81 entries (the function sums 27 on
// the index pairs): the same operator on a disordered packing of 1000 spheres to round-off.
dem::Tangent tangent_by_definition(const dem::Simulation& sim) {
  const dem::Contacts& c = sim.contacts();
  dem::Tangent a = dem::Tangent::Zero();
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p] == 0) continue;
    const Vec3& d = c.branch[p];
    const Vec3 n = d.normalized();
    const double kt = (sim.spheres().r[static_cast<std::size_t>(c.i[p])] +
                       sim.spheres().r[static_cast<std::size_t>(c.j[p])]) /
                      d.norm() * sim.contact_props(p).ks;
    const Mat3 k =
        sim.contact_props(p).kn * n * n.transpose() + kt * (Mat3::Identity() - n * n.transpose());
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int kk = 0; kk < 3; ++kk)
          for (int l = 0; l < 3; ++l) a(idx(i, j), idx(kk, l)) += k(i, kk) * d(l) * d(j);
  }
  dem::Tangent t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int kk = 0; kk < 3; ++kk)
        for (int l = 0; l < 3; ++l)
          t(idx(i, j), idx(kk, l)) = 0.25 * (a(idx(i, j), idx(kk, l)) + a(idx(j, i), idx(kk, l)) +
                                             a(idx(i, j), idx(l, kk)) + a(idx(j, i), idx(l, kk)));
  return t / sim.cell().volume();
}

TEST(Tangent, IsTheContactSumOnADisorderedPacking) {
  dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                             dem_test::reference_material(), dem::Numerics{});
  sim.set_dt(0.0);
  sim.compute_forces();
  std::int64_t active = 0;
  for (auto a : sim.contacts().active) active += a;
  ASSERT_GT(active, 1000);  // a real network, every direction
  const dem::Tangent c = dem::contact_stiffness_tangent(sim);
  const dem::Tangent ref = tangent_by_definition(sim);
  // Sums of a few thousand terms in another order: round-off, 1e-12 of the largest entry.
  EXPECT_LT((c - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff());
  EXPECT_LT((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-12 * c.cwiseAbs().maxCoeff());
  EXPECT_GT(ref(idx(0, 1), idx(0, 1)), 0.0);  // a shear stiffness, not zeros
}

TEST(Tangent, NoContactsGivesZero) {
  const dem::Material mat = dem_test::reference_material();
  dem::Spheres s;
  s.add(Vec3(1e-3, 1e-3, 1e-3), kR, mat.density);
  s.add(Vec3(2e-3, 2e-3, 2e-3), kR, mat.density);
  dem::PeriodicCell cell;
  cell.h = Mat3::Identity() * 4e-3;
  dem::Simulation sim(s, cell, mat, dem::Numerics{});
  sim.compute_forces();
  EXPECT_EQ(dem::contact_stiffness_tangent(sim), dem::Tangent::Zero());
}

}  // namespace
