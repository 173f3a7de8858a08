// Grain-scale VTK views (dem/vtk_export.hpp): well-formed XML, one point per sphere wrapped into
// the cell, one line per active contact drawn along the branch (a contact across the periodic
// boundary has its true length, not the length across the cell), the arrays and their values,
// the cell hexahedron, and the all-or-nothing writer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "dem/measures.hpp"
#include "dem/simulation.hpp"
#include "dem/vtk_export.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Mat3;
using common::Vec3;

/// Minimal XML well-formedness: the prolog, then one root element whose tags nest and close.
/// Returns "" or what is wrong.
std::string xml_problem(const std::string& t) {
  std::vector<std::string> stack;
  int roots = 0;
  std::size_t pos = 0;
  if (t.rfind("<?xml", 0) != 0) return "no XML prolog";
  while ((pos = t.find('<', pos)) != std::string::npos) {
    const std::size_t end = t.find('>', pos);
    if (end == std::string::npos) return "unterminated tag";
    const std::string tag = t.substr(pos + 1, end - pos - 1);
    if (tag.find('<') != std::string::npos) return "'<' inside a tag";
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "unbalanced quotes: " + tag;
    pos = end + 1;
    if (tag.front() == '?') continue;
    if (tag.front() == '/') {
      if (stack.empty() || stack.back() != tag.substr(1)) return "mismatched </" + tag + ">";
      stack.pop_back();
      continue;
    }
    if (stack.empty()) ++roots;
    if (tag.back() == '/') continue;
    stack.push_back(tag.substr(0, tag.find_first_of(" \n")));
  }
  if (!stack.empty()) return "unclosed <" + stack.back() + ">";
  return roots == 1 ? "" : "not one root element";
}

/// Values of the <DataArray Name="name"> (or, for name "Points", of the one inside <Points>).
std::vector<double> array(const std::string& t, const std::string& name) {
  const std::size_t at = name == "Points" ? t.find("<Points>") : t.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const std::size_t open = t.find('>', name == "Points" ? t.find("<DataArray", at) : at);
  const std::size_t close = t.find("</DataArray>", open);
  std::istringstream in(t.substr(open + 1, close - open - 1));
  std::vector<double> v;
  for (double x = 0; in >> x;) v.push_back(x);
  return v;
}

/// The value of attribute `attr` of the first <tag ...>.
std::string attribute(const std::string& t, const std::string& tag, const std::string& attr) {
  const std::size_t at = t.find('<' + tag);
  const std::size_t a = t.find(attr + "=\"", at);
  if (at == std::string::npos || a == std::string::npos || a > t.find('>', at)) return "";
  const std::size_t b = a + attr.size() + 2;
  return t.substr(b, t.find('"', b) - b);
}

Vec3 at(const std::vector<double>& v, std::size_t k) {
  return Vec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
}

/// Three spheres in a 1 mm cube: 0 and 1 touch ACROSS the x boundary (their centres 0.9 mm
/// apart inside the cell, 0.1 mm apart through the boundary, radii 0.06 mm: overlap 0.02 mm);
/// 2 is free and spins.
dem::Simulation three_spheres() {
  dem::Spheres s;
  const double rho = dem_test::reference_material().density;
  s.add(Vec3(0.08e-3, 0.5e-3, 0.5e-3), 0.06e-3, rho);
  s.add(Vec3(0.98e-3, 0.5e-3, 0.5e-3), 0.06e-3, rho);
  s.add(Vec3(0.5e-3, 0.2e-3, 0.7e-3), 0.05e-3, rho);
  s.u[1] = Vec3(0.1, 0.0, 0.0);
  s.w[2] = Vec3(0.0, 0.0, 3.0);
  dem::PeriodicCell cell;
  cell.h = Mat3::Identity() * 1e-3;
  cell.h(0, 1) = 0.1e-3;  // a sheared cell: the images are not axis-aligned
  cell.l(0, 2) = 0.5;     // a velocity gradient: velocity = u + L x
  dem::Simulation sim(s, cell, dem_test::reference_material(), dem::Numerics{});
  sim.set_dt(1e-8);
  sim.compute_forces();
  return sim;
}

TEST(VtkExport, FilesAreWellFormedXmlWithTheirNames) {
  const dem::Simulation sim = three_spheres();
  const auto files = dem::vtk_view(sim, "rve_7_step_3");
  ASSERT_EQ(files.size(), 4U);
  EXPECT_EQ(files[0].name, "rve_7_step_3_spheres.vtp");
  EXPECT_EQ(files[1].name, "rve_7_step_3_contacts.vtp");
  EXPECT_EQ(files[2].name, "rve_7_step_3_cell.vtu");
  EXPECT_EQ(files[3].name, "rve_7_step_3.vtm");
  for (const auto& f : files) EXPECT_EQ(xml_problem(f.text), "") << f.name;
  // The checker itself fails on broken XML.
  EXPECT_NE(xml_problem("<?xml version=\"1.0\"?>\n<a><b></a></b>"), "");
  EXPECT_NE(xml_problem("<?xml version=\"1.0\"?>\n<a><b/>"), "");
  // The multiblock names its three blocks and their files.
  const std::string& vtm = files[3].text;
  EXPECT_NE(vtm.find("name=\"spheres\" file=\"rve_7_step_3_spheres.vtp\""), std::string::npos);
  EXPECT_NE(vtm.find("name=\"contacts\" file=\"rve_7_step_3_contacts.vtp\""), std::string::npos);
  EXPECT_NE(vtm.find("name=\"cell\" file=\"rve_7_step_3_cell.vtu\""), std::string::npos);
}

TEST(VtkExport, SpheresArePointsWrappedIntoTheCellWithTheirArrays) {
  dem::Simulation sim = three_spheres();
  // Sphere 2 drifts out of the cell through y = 0 between two neighbour rebuilds (as it may):
  // it is drawn at its image inside the cell.
  const Vec3 drift(0.0, -0.25e-3, 0.0);
  sim.spheres().x[2] += drift;
  const std::string t = dem::vtk_view(sim, "s")[0].text;
  const auto& s = sim.spheres();
  EXPECT_EQ(attribute(t, "Piece", "NumberOfPoints"), "3");
  EXPECT_EQ(attribute(t, "Piece", "NumberOfVerts"), "3");
  const auto x = array(t, "Points");
  const auto r = array(t, "radius");
  const auto id = array(t, "id");
  const auto v = array(t, "velocity");
  const auto u = array(t, "fluctuating_velocity");
  const auto w = array(t, "spin");
  const auto nc = array(t, "contacts");
  ASSERT_EQ(x.size(), 9U);
  ASSERT_EQ(r.size(), 3U);
  ASSERT_EQ(v.size(), 9U);
  ASSERT_EQ(w.size(), 9U);
  ASSERT_EQ(nc.size(), 3U);
  EXPECT_EQ(array(t, "force").size(), 9U);
  EXPECT_EQ(array(t, "torque").size(), 9U);
  const Mat3 hinv = sim.cell().h.inverse();
  for (std::size_t q = 0; q < 3; ++q) {
    EXPECT_EQ(id[q], static_cast<double>(q));
    EXPECT_EQ(r[q], s.r[q]);  // 17 digits: exact round trip
    const Vec3 frac = hinv * at(x, q);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(frac[a], 0.0) << "sphere " << q;
      EXPECT_LT(frac[a], 1.0) << "sphere " << q;
    }
    // The drawn point is an image of the centre: their difference is a lattice vector.
    const Vec3 m = hinv * (s.x[q] - at(x, q));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(m[a], std::round(m[a]), 1e-12);
    // velocity = u + L x at the drawn point; tolerance: 17-digit text of values ~0.1 m/s.
    EXPECT_LT((at(v, q) - (s.u[q] + sim.cell().l * at(x, q))).norm(), 1e-15);
    EXPECT_EQ(at(u, q), s.u[q]);
    EXPECT_EQ(at(w, q), s.w[q]);
  }
  EXPECT_NEAR(hinv.row(1).dot(at(x, 2)), hinv.row(1).dot(s.x[2]) + 1.0, 1e-12);
  EXPECT_EQ(nc[0], 1.0);
  EXPECT_EQ(nc[1], 1.0);
  EXPECT_EQ(nc[2], 0.0);
}

TEST(VtkExport, PeriodicContactIsDrawnAcrossTheBoundaryWithItsTrueLength) {
  const dem::Simulation sim = three_spheres();
  const auto& c = sim.contacts();
  std::size_t active = 0;
  std::size_t p_act = 0;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p]) {
      ++active;
      p_act = p;
    }
  }
  ASSERT_EQ(active, 1U);  // the setup holds one contact, across the x boundary
  ASSERT_NE(c.k[p_act], common::Vec3i::Zero());
  const std::string t = dem::vtk_view(sim, "s")[1].text;
  EXPECT_EQ(xml_problem(t), "");
  EXPECT_EQ(attribute(t, "Piece", "NumberOfLines"), "1");
  EXPECT_EQ(attribute(t, "Piece", "NumberOfPoints"), "2");
  const auto x = array(t, "Points");
  ASSERT_EQ(x.size(), 6U);
  // 0.1 mm through the boundary, not the 0.9 mm between the centres inside the cell; the start
  // is sphere 0's centre, the end its neighbour's image outside the cell. Tolerance: rounding of
  // positions ~1e-3 m (1e-18 m).
  const Vec3 a = at(x, 0);
  const Vec3 b = at(x, 1);
  EXPECT_NEAR((b - a).norm(), 0.1e-3, 1e-15);
  EXPECT_LT((a - sim.spheres().x[0]).norm(), 1e-18);
  EXPECT_NEAR(b[0], -0.02e-3, 1e-15);
  // Cell data: the law's values of this contact.
  EXPECT_EQ(array(t, "sphere1"), std::vector<double>{0.0});
  EXPECT_EQ(array(t, "sphere2"), std::vector<double>{1.0});
  const auto fn = array(t, "normal_force");
  ASSERT_EQ(fn.size(), 1U);
  EXPECT_GT(fn[0], 0.0);
  EXPECT_EQ(fn[0], sim.normal_force(p_act));
  // Linear law: fn = kn * overlap (overlap 0.02 mm); 1e-12 relative: the branch is recomputed.
  const auto overlap = array(t, "overlap");
  ASSERT_EQ(overlap.size(), 1U);
  EXPECT_NEAR(overlap[0], 0.02e-3, 1e-15);
  EXPECT_NEAR(fn[0], sim.contact_props(p_act).kn * overlap[0], 1e-12 * fn[0]);
  const auto fnv = array(t, "normal_force_vector");
  ASSERT_EQ(fnv.size(), 3U);
  // The normal points from sphere 0 to its neighbour's image: -x.
  EXPECT_NEAR(fnv[0], -fn[0], 1e-12 * fn[0]);
  for (const char* name : {"shear_force", "force", "normal", "rolling_moment", "twisting_moment"})
    EXPECT_EQ(array(t, name).size(), 3U) << name;
  EXPECT_EQ(array(t, "shear_force_magnitude").size(), 1U);
  EXPECT_EQ(at(array(t, "force"), 0), c.force[p_act]);
}

TEST(VtkExport, CellIsTheHexahedronOfTheCellMatrixWithTheMeasures) {
  const dem::Simulation sim = three_spheres();
  const std::string t = dem::vtk_view(sim, "s")[2].text;
  EXPECT_EQ(attribute(t, "Piece", "NumberOfPoints"), "8");
  EXPECT_EQ(attribute(t, "Piece", "NumberOfCells"), "1");
  EXPECT_EQ(array(t, "types"), std::vector<double>{12.0});  // VTK_HEXAHEDRON
  const auto x = array(t, "Points");
  ASSERT_EQ(x.size(), 24U);
  const Mat3& h = sim.cell().h;
  EXPECT_EQ(at(x, 0), Vec3::Zero());
  EXPECT_EQ(at(x, 1), h.col(0));
  EXPECT_EQ(at(x, 3), h.col(1));
  EXPECT_EQ(at(x, 4), h.col(2));
  EXPECT_LT((at(x, 6) - (h.col(0) + h.col(1) + h.col(2))).norm(), 1e-18);
  // The hexahedron's volume (two-tet decomposition is not needed: the cell is a parallelepiped)
  // is det H; the array volume says so too.
  EXPECT_EQ(array(t, "volume"), std::vector<double>{h.determinant()});
  const dem::Measures m = dem::measure(sim);
  EXPECT_EQ(array(t, "p"), std::vector<double>{m.p});
  EXPECT_EQ(array(t, "z"), std::vector<double>{m.z});
  ASSERT_EQ(array(t, "stress").size(), 9U);
  EXPECT_EQ(array(t, "stress")[1], m.stress(0, 1));
  EXPECT_EQ(array(t, "fabric").size(), 9U);
}

TEST(VtkExport, WriterPublishesEverythingOrNothing) {
  const dem::Simulation sim = three_spheres();
  const auto files = dem::vtk_view(sim, "rve_1_step_0");
  const auto dir = std::filesystem::path(::testing::TempDir()) / "vtk_export_writer";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  dem::write_vtk_files(dir, files);
  std::size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    ++n;
    EXPECT_EQ(e.path().extension() == ".tmp", false) << e.path();
  }
  EXPECT_EQ(n, 4U);
  std::ifstream in(dir / "rve_1_step_0_contacts.vtp");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), files[1].text);
  // A directory that does not exist: an I/O error naming the file, and nothing left behind.
  const auto missing = dir / "no_such_dir";
  try {
    dem::write_vtk_files(missing, files);
    ADD_FAILURE() << "no error";
  } catch (const common::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_dir"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(missing));
  std::filesystem::remove_all(dir);
}

TEST(VtkExport, SeriesRoundTripsMergesAndRefusesForeignFiles) {
  std::vector<dem::VtkSeriesEntry> e;
  e = dem::merge_vtk_series(e, {2.5, "rve_1_step_20.vtm"});
  e = dem::merge_vtk_series(e, {0.1 + 0.2, "rve_1_step_3.vtm"});
  e = dem::merge_vtk_series(e, {2.75, "rve_1_step_20.vtm"});  // the same view again: replaced
  ASSERT_EQ(e.size(), 2U);
  EXPECT_EQ(e[0].file, "rve_1_step_3.vtm");  // sorted by time
  EXPECT_EQ(e[1].time, 2.75);
  const std::string text = dem::vtk_series(e);
  EXPECT_EQ(xml_problem(text), "");
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos);
  const auto back = dem::read_vtk_series(text, "x.pvd");
  ASSERT_EQ(back.size(), 2U);
  EXPECT_EQ(back[0].time, 0.1 + 0.2);  // 17 digits: exact
  EXPECT_EQ(back[0].file, "rve_1_step_3.vtm");
  EXPECT_EQ(back[1].time, 2.75);
  EXPECT_TRUE(dem::read_vtk_series(dem::vtk_series({}), "x.pvd").empty());
  for (const std::string& bad :
       {std::string("hello"), dem::vtk_series(e).replace(text.find("timestep=\"") + 10, 1, "x"),
        std::string(text).erase(text.find(" file="), 6)}) {
    try {
      (void)dem::read_vtk_series(bad, "dir/rve_1.pvd");
      ADD_FAILURE() << "accepted:\n" << bad;
    } catch (const common::InputError& err) {
      EXPECT_NE(std::string(err.what()).find("dir/rve_1.pvd: not a time series"), std::string::npos)
          << err.what();
    }
  }
}

// The names shared by `inspect --vtk` and [output.grains], and the series file reader: a missing
// file is an empty series, a foreign one an InputError naming it.
TEST(VtkExport, ViewNamesAndSeriesFiles) {
  EXPECT_EQ(dem::rve_view_stem(3, 40), "rve_3_step_40");
  EXPECT_EQ(dem::rve_series_name(12), "rve_12.pvd");
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "mpmxdem_vtk_series_file";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(dem::read_vtk_series_file(dir / "rve_1.pvd").empty());
  const std::vector<dem::VtkSeriesEntry> entries = {{0.5, "rve_1_step_10.vtm"}};
  std::ofstream(dir / "rve_1.pvd") << dem::vtk_series(entries);
  const auto back = dem::read_vtk_series_file(dir / "rve_1.pvd");
  ASSERT_EQ(back.size(), 1U);
  EXPECT_EQ(back[0].file, "rve_1_step_10.vtm");
  EXPECT_EQ(back[0].time, 0.5);
  std::ofstream(dir / "rve_2.pvd") << "not a collection";
  try {
    (void)dem::read_vtk_series_file(dir / "rve_2.pvd");
    FAIL() << "a foreign file was read as a series";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rve_2.pvd"), std::string::npos) << e.what();
  }
}

}  // namespace
