// Packing text format: the reference file, exact round trip, input errors with file:line.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "common/errors.hpp"
#include "dem/loading.hpp"
#include "dem/measures.hpp"
#include "dem/packing_io.hpp"
#include "dem_test_util.hpp"

namespace {

TEST(PackingIo, ReadsReferencePacking) {
  const dem::Packing pk = dem_test::reference_packing();
  EXPECT_EQ(pk.r.size(), 1000u);
  EXPECT_DOUBLE_EQ(pk.cell.h(0, 0), 1.7172766453404881e-03);
  EXPECT_EQ(pk.cell.h(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(pk.r[0], 1.3488841590026288e-04);
}

TEST(PackingIo, RoundTripIsExact) {
  dem::Packing pk = dem_test::reference_packing();
  pk.cell.h(0, 1) = 1.234567890123e-4;
  const std::string path = testing::TempDir() + "/dem_roundtrip.txt";
  dem::write_packing(path, pk, "test");
  const dem::Packing back = dem::read_packing(path);
  EXPECT_EQ(back.cell.h, pk.cell.h);
  ASSERT_EQ(back.r.size(), pk.r.size());
  for (std::size_t i = 0; i < pk.r.size(); ++i) {
    EXPECT_EQ(back.x[i], pk.x[i]);
    EXPECT_EQ(back.r[i], pk.r[i]);
  }
  std::remove(path.c_str());
}

TEST(PackingIo, BadLineNamesFileAndLine) {
  const std::string path = testing::TempDir() + "/dem_bad.txt";
  {
    std::ofstream f(path);
    f << "# c\nCELL 1 1 1\n0.1 0.2 0.3 0.01\n0.1 0.2 zz 0.01\n";
  }
  try {
    (void)dem::read_packing(path);
    FAIL() << "no error";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dem_bad.txt:4: 'zz' is not a finite number"),
              std::string::npos)
        << e.what();
  }
  std::remove(path.c_str());
}

TEST(PackingIo, TilingMakesExactCopies) {
  const dem::Packing pk = dem_test::reference_packing();
  const dem::Packing t = dem::tile_packing(pk, 2);
  EXPECT_EQ(t.r.size(), 8000u);
  EXPECT_EQ(t.cell.h, pk.cell.h * 2.0);
}

// 2 x 1 x 1 copies of the reference packing are the same state in a cell twice as long: the same
// stress (to rounding: every contact is there twice, in twice the volume).
TEST(PackingIo, TilingAlongOneAxisKeepsTheStress) {
  const dem::Packing pk = dem_test::reference_packing();
  const dem::Packing t = dem::tile_packing(pk, {2, 1, 1});
  ASSERT_EQ(t.r.size(), 2000u);
  EXPECT_EQ(t.cell.h.col(0), 2.0 * pk.cell.h.col(0));
  EXPECT_EQ(t.cell.h.col(1), pk.cell.h.col(1));
  EXPECT_EQ(t.cell.h.col(2), pk.cell.h.col(2));
  dem::Simulation a = dem::make_simulation(pk, dem_test::reference_material(), dem::Numerics{});
  dem::Simulation b = dem::make_simulation(t, dem_test::reference_material(), dem::Numerics{});
  a.compute_forces();
  b.compute_forces();
  const common::Mat3 sa = dem::measure(a).stress;
  const common::Mat3 sb = dem::measure(b).stress;
  EXPECT_GT(sa.norm(), 1e4);
  EXPECT_LT((sa - sb).norm(), 1e-9 * sa.norm());
  EXPECT_EQ(dem::measure(b).z, dem::measure(a).z);
  EXPECT_THROW((void)dem::tile_packing(pk, {1, 0, 1}), common::InputError);
}

}  // namespace
