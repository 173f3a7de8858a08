// Packing text format: the reference file, exact round trip, input errors with file:line.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

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

// The cell lines may be comments (what write_packing writes, so that YADE's ymport.text reads the
// file as it is); a comment that only starts with the word stays a comment.
TEST(PackingIo, CellLinesWrittenAsCommentsAreRead) {
  const std::string path = testing::TempDir() + "/dem_commented_cell.txt";
  {
    std::ofstream f(path);
    f << "# CELL sizes in m\n#  CELL 2 3 4.5\n# HSIZE 2 0 0 0 3 0 0 0 4.5\n# x y z r\n"
         "0.5 0.5 0.5 0.5\n1.5 1.5 2.5 0.5\n";
  }
  const dem::Packing pk = dem::read_packing(path);
  EXPECT_EQ(pk.cell.h(2, 2), 4.5);
  EXPECT_EQ(pk.cell.h(1, 1), 3.0);
  EXPECT_EQ(pk.r.size(), 2u);
  std::ifstream written;
  const std::string out = testing::TempDir() + "/dem_written.txt";
  dem::write_packing(out, pk, "test");
  written.open(out);
  std::string line;
  while (std::getline(written, line)) {
    if (line.empty()) continue;
    // every line is a comment or "x y z r": nothing YADE's text import would choke on
    if (line[0] != '#') {
      std::istringstream is(line);
      double v[4];
      EXPECT_TRUE(is >> v[0] >> v[1] >> v[2] >> v[3]) << line;
    }
  }
}

// CELL (the side lengths, YADE's O.cell.size) and HSIZE (the matrix, whose column norms are those
// lengths) must describe one cell: a file whose lines disagree is refused naming both lines,
// not read with one of them silently preferred.
TEST(PackingIo, DisagreeingCellLinesAreRefused) {
  const std::string path = testing::TempDir() + "/dem_two_cells.txt";
  {
    std::ofstream f(path);
    f << "# CELL 2 3 4\n# HSIZE 2 0 0 0 3 0 0 0 4.5\n0.5 0.5 0.5 0.5\n1.5 1.5 2.5 0.5\n";
  }
  try {
    (void)dem::read_packing(path);
    ADD_FAILURE() << "two cells read";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2: this cell line (side lengths 2, 3, 4.5 m) "
                                                "disagrees with the cell of line 1 (2, 3, 4 m)"),
              std::string::npos)
        << e.what();
  }
  {
    std::ofstream f(path);  // a sheared cell: CELL gives the column norms of HSIZE
    f << "CELL 2 3.1622776601683795 4\nHSIZE 2 1 0 0 3 0 0 0 4\n0.5 0.5 0.5 0.5\n1.5 1.5 2.5 0.5\n";
  }
  EXPECT_EQ(dem::read_packing(path).cell.h(0, 1), 1.0);
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

// check_packing: each rule of a packing that cannot be simulated, named with the packing line.
dem::Packing lattice() {
  dem::Packing pk;
  pk.cell.h = common::Mat3::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) {
        pk.x.emplace_back((i + 0.5) / 3, (j + 0.5) / 3, (k + 0.5) / 3);
        pk.r.push_back(0.1);
      }
    }
  }
  return pk;
}

std::string packing_error(const dem::Packing& pk) {
  std::vector<long> lines;
  for (std::size_t i = 0; i < pk.r.size(); ++i) lines.push_back(static_cast<long>(i) + 10);
  try {
    dem::check_packing(pk, "p.txt", lines);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PackingIo, CheckAcceptsAPlainLattice) { EXPECT_EQ(packing_error(lattice()), ""); }

TEST(PackingIo, CheckRefusesRadiusLargerThanTheCell) {
  dem::Packing pk = lattice();
  pk.r[4] = 0.6;
  EXPECT_NE(packing_error(pk).find("p.txt:14: radius 0.6 m: the diameter must be below the "
                                   "cell's smallest width 1 m"),
            std::string::npos)
      << packing_error(pk);
}

TEST(PackingIo, CheckRefusesNonFiniteOrNonPositiveRadius) {
  dem::Packing pk = lattice();
  pk.r[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(packing_error(pk).find("p.txt:12: radius nan"), std::string::npos) << packing_error(pk);
  pk.r[2] = -0.1;
  EXPECT_NE(packing_error(pk).find("p.txt:12: radius -0.1 must be > 0"), std::string::npos);
}

TEST(PackingIo, CheckRefusesCentreFarOutsideRatherThanWrapping) {
  dem::Packing pk = lattice();
  pk.x[5].x() = 2900.5;
  EXPECT_NE(packing_error(pk).find("p.txt:15: centre (2900.5, "), std::string::npos)
      << packing_error(pk);
  EXPECT_NE(packing_error(pk).find("2899.5 cell lengths outside the cell"), std::string::npos);
  pk = lattice();
  pk.x[5].x() = 1.9;  // within one cell length: a periodic packing may hold it
  EXPECT_EQ(packing_error(pk), "");
}

TEST(PackingIo, CheckRefusesSpheresAtOnePoint) {
  dem::Packing pk = lattice();
  for (auto& x : pk.x) x = common::Vec3(0.5, 0.5, 0.5);
  const std::string e = packing_error(pk);
  EXPECT_NE(e.find("p.txt:11: the centre is 0 m from the centre of the sphere at p.txt:10"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("degenerate packing"), std::string::npos);
}

TEST(PackingIo, CheckRefusesASingleSphereAndUnitMismatch) {
  dem::Packing pk = lattice();
  pk.x.resize(1);
  pk.r.resize(1);
  EXPECT_NE(packing_error(pk).find("p.txt: 1 sphere(s): a packing needs at least 2 spheres"),
            std::string::npos);
  pk = lattice();
  pk.cell.h *= 1000.0;  // cell in mm written as m: solid fraction 1e-10
  for (auto& x : pk.x) x *= 1000.0;
  EXPECT_NE(packing_error(pk).find("solid volume fraction 1.13097e-10"), std::string::npos)
      << packing_error(pk);
}

TEST(PackingIo, ReferencePackingPassesTheChecks) {
  const dem::Packing pk = dem_test::reference_packing();  // read_packing checks it
  EXPECT_NO_THROW(dem::check_packing(pk, "reference"));
}

// YADE's text export (yade.export.text, written by tools/mpmxdem_tools/references/yade_export_packing.py with YADE 2023.02a)
// with the cell lines the script adds after '#format x_y_z_r': read as it is. YADE writes 6
// significant digits, so the values are compared with the text of the file, exactly.
TEST(PackingIo, ReadsAYadeExportWithTheCellAdded) {
  const dem::Packing pk = dem::read_packing(dem_test::data_path("yade_export_periodic.txt"));
  ASSERT_EQ(pk.r.size(), 30u);
  EXPECT_EQ(pk.cell.h, (1e-3 * common::Mat3::Identity()).eval());
  EXPECT_EQ(pk.x[0], common::Vec3(0.000997185, 0.000932557, 0.000128124));
  EXPECT_EQ(pk.r[0], 0.000129032);
}

// YADE's export as it is has no cell: refused with the file, the line, what is missing and how to
// add it (an InputError: exit 2).
TEST(PackingIo, YadeExportWithoutCellNamesWhatIsMissing) {
  const std::string path = dem_test::data_path("yade_export_no_cell.txt");
  try {
    (void)dem::read_packing(path);
    FAIL() << "a packing without a cell was accepted";
  } catch (const common::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path + ":2: sphere line before any cell line"), std::string::npos) << m;
    EXPECT_NE(m.find("line 1 says this is a YADE text export"), std::string::npos) << m;
    EXPECT_NE(m.find("'# CELL' + O.cell.size"), std::string::npos) << m;
  }
}

// The same export without its cell line, with the cell given by the job (dem.sample.cell): the
// spheres and cell of the file that carries the line, exactly; a cell line that contradicts the
// job's cell is refused naming the line; one that agrees is accepted.
TEST(PackingIo, YadeExportTakesTheCellFromTheJob) {
  const common::Vec3 cell(1e-3, 1e-3, 1e-3);
  const dem::Packing with = dem::read_packing(dem_test::data_path("yade_export_periodic.txt"));
  const dem::Packing given =
      dem::read_packing(dem_test::data_path("yade_export_no_cell.txt"), cell);
  EXPECT_EQ(given.cell.h, with.cell.h);
  EXPECT_EQ(given.x, with.x);
  EXPECT_EQ(given.r, with.r);
  EXPECT_NO_THROW((void)dem::read_packing(dem_test::data_path("yade_export_periodic.txt"), cell));
  const std::string path = dem_test::data_path("yade_export_periodic.txt");
  try {
    (void)dem::read_packing(path, common::Vec3(2e-3, 1e-3, 1e-3));
    FAIL() << "a cell line contradicting the job's cell was accepted";
  } catch (const common::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path + ":2: this cell line disagrees with the job's cell"), std::string::npos)
        << m;
  }
}

// The sphere lines of a text file as YADE's ymport.text reads them: '#' lines skipped, the
// first four numbers of every other line (Python's float: correctly rounded, as strtod).
std::vector<std::array<double, 4>> ymport_text(const std::string& path) {
  std::vector<std::array<double, 4>> spheres;
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::array<double, 4> s{};
    std::string word;
    for (double& v : s) {
      in >> word;
      v = std::strtod(word.c_str(), nullptr);
    }
    spheres.push_back(s);
  }
  return spheres;
}

// YADE -> mpmxdem -> YADE: YADE's export, read as an RVE sample and written by write_packing,
// reads back in YADE (ymport.text's parse) with every sphere bit for bit (17 digits, cell lines as
// comments).
TEST(PackingIo, YadeRoundTripKeepsEverySphereBitForBit) {
  const std::string yade_file = dem_test::data_path("yade_export_periodic.txt");
  const dem::Packing pk = dem::read_packing(yade_file);
  const std::string path = testing::TempDir() + "/dem_yade_roundtrip.txt";
  dem::write_packing(path, pk, "round trip");
  const auto before = ymport_text(yade_file);
  const auto after = ymport_text(path);
  ASSERT_EQ(before.size(), 30u);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(std::memcmp(&after[i][k], &before[i][k], sizeof(double)), 0)
          << "sphere " << i << " number " << k << ": " << after[i][k] << " != " << before[i][k];
    }
  }
  EXPECT_EQ(dem::read_packing(path).cell.h, pk.cell.h);  // and the cell, for mpmxdem
  // A sample with every digit (YADE's export has 6; a state in memory has 17): what YADE reads
  // of our file is the state itself.
  const dem::Packing full = dem_test::reference_packing();
  dem::write_packing(path, full, "round trip");
  const auto read = ymport_text(path);
  ASSERT_EQ(read.size(), full.r.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    const std::array<double, 4> want{full.x[i].x(), full.x[i].y(), full.x[i].z(), full.r[i]};
    EXPECT_EQ(std::memcmp(read[i].data(), want.data(), sizeof want), 0) << "sphere " << i;
  }
  std::remove(path.c_str());
}

}  // namespace
