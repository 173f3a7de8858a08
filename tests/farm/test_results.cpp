// Tests of src/farm/results.*: rows are kept in memory and written in blocks; what is read back
// must be every row, in order, with the values given, whether written by a block, by flush() or by
// the destructor (a run stopping on an error).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "farm/results.hpp"

namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("mpmxdem_results_test_" + std::to_string(getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

/// The whole dataset `name` of `file` as doubles (integers converted by HDF5).
std::vector<double> read_all(const std::string& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t s = H5Dget_space(d);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(s));
  std::vector<double> v(n);
  if (n > 0) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  return v;
}

// Data rows of means.csv; its first line must be the header (what pandas.read_csv takes as such).
int csv_rows(const std::string& dir) {
  std::ifstream csv(dir + "/means.csv");
  int lines = 0;
  std::string first;
  for (std::string l; std::getline(csv, l);) {
    if (lines++ == 0) first = l;
  }
  EXPECT_EQ(first, farm::ResultsWriter::kMeansCsvHeader);
  return lines - 1;
}

// Three RVEs (ids 1, 5, 9); the points come in another order (9, 1, 5).
struct Sample {
  std::vector<std::int64_t> rve_ids{1, 5, 9};
  mpm::MaterialPoints points;
  Sample() {
    points.resize(3);
    points.id = {9, 1, 5};
    for (std::size_t p = 0; p < 3; ++p) {
      points.x[p] = common::Vec3(0.1 * static_cast<double>(p), 0.5, 0.5);
      points.volume[p] = 1.0;
      points.volume0[p] = 1.0;
      points.F[p] = common::Mat3::Identity();
    }
  }
  /// Row r's RVE reports: p = 1000 r + k (k: RVE index), dem_steps = r + k.
  std::vector<farm::MicroReport> reports(int r) const {
    std::vector<farm::MicroReport> out(3);
    for (std::size_t k = 0; k < 3; ++k) {
      out[k].p = 1000.0 * r + static_cast<double>(k);
      out[k].dem_steps = r + static_cast<std::int64_t>(k);
    }
    return out;
  }
  void append(farm::ResultsWriter& w, int r) const {
    const std::vector<common::Mat3> stress(3, -1.0 * r * common::Mat3::Identity());
    farm::SampleMeans m;
    m.q = 7.0 * r;
    w.append(10 * r, 0.5 * r, stress, reports(r), points, m);
  }
};

TEST(Results, RowsWrittenInBlocksReadBackInOrder) {
  const std::string dir = scratch("blocks");
  const Sample smp;
  const int rows = 2 * static_cast<int>(farm::ResultsWriter::kRowsPerWrite) + 7;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    for (int r = 0; r < rows; ++r) {
      smp.append(w, r);
      EXPECT_EQ(w.rows(), r + 1);
    }
    w.flush();
  }
  const std::string h5 = dir + "/results.h5";
  const std::vector<double> step = read_all(h5, "/step");
  const std::vector<double> rve_p = read_all(h5, "/rve/p");
  const std::vector<double> pts_p = read_all(h5, "/points/p");
  const std::vector<double> ds = read_all(h5, "/rve/dem_steps");
  const std::vector<double> q = read_all(h5, "/means/q");
  const std::vector<double> stress = read_all(h5, "/rve/stress");
  ASSERT_EQ(step.size(), static_cast<std::size_t>(rows));
  ASSERT_EQ(rve_p.size(), 3u * rows);
  ASSERT_EQ(stress.size(), 27u * rows);
  const std::size_t rve_of_point[3] = {2, 0, 1};  // point ids 9, 1, 5
  for (int r = 0; r < rows; ++r) {
    const auto ru = static_cast<std::size_t>(r);
    EXPECT_EQ(step[ru], 10.0 * r);
    EXPECT_EQ(q[ru], 7.0 * r);
    EXPECT_EQ(stress[27 * ru + 9 * 2 + 8], -1.0 * r);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(rve_p[3 * ru + k], 1000.0 * r + static_cast<double>(k));
      EXPECT_EQ(ds[3 * ru + k], static_cast<double>(r + static_cast<int>(k)));
      EXPECT_EQ(pts_p[3 * ru + k], 1000.0 * r + static_cast<double>(rve_of_point[k]));
    }
  }
  // means.csv: one line per row.
  EXPECT_EQ(csv_rows(dir), rows);
}

/// Variable-length string attribute `name` of object `obj` of `file` ("" when missing).
std::string string_attr(hid_t file, const char* obj, const char* name) {
  if (H5Aexists_by_name(file, obj, name, H5P_DEFAULT) <= 0) return "";
  const hid_t a = H5Aopen_by_name(file, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  char* text = nullptr;
  std::string v;
  if (H5Aread(a, t, &text) >= 0 && text != nullptr) v = text;
  H5free_memory(text);
  H5Tclose(t);
  H5Aclose(a);
  return v;
}

// Every dataset says what it is (unit, description); the file says its format and version.
TEST(Results, EveryDatasetIsDescribed) {
  const std::string dir = scratch("attributes");
  const Sample smp;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    smp.append(w, 0);
  }
  const hid_t f = H5Fopen((dir + "/results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(string_attr(f, "/", "format"), farm::ResultsWriter::kFormat);
  std::int64_t version = 0;
  const hid_t va = H5Aopen_by_name(f, "/", "format_version", H5P_DEFAULT, H5P_DEFAULT);
  H5Aread(va, H5T_NATIVE_INT64, &version);
  H5Aclose(va);
  EXPECT_EQ(version, farm::ResultsWriter::kFormatVersion);
  EXPECT_FALSE(string_attr(f, "/", "software_version").empty());
  EXPECT_NE(string_attr(f, "/", "conventions").find("TENSION positive"), std::string::npos);
  std::vector<std::string> names;
  H5Ovisit(
      f, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5O_info_t* info, void* out) -> herr_t {
        if (info->type == H5O_TYPE_DATASET)
          static_cast<std::vector<std::string>*>(out)->push_back(name);
        return 0;
      },
      &names);
  EXPECT_EQ(names.size(), 30u);  // 23 until issue 19 (point fields, grain-scale measures)
  for (const std::string& n : names) {
    EXPECT_FALSE(string_attr(f, n.c_str(), "description").empty()) << n;
    EXPECT_EQ(H5Aexists_by_name(f, n.c_str(), "unit", H5P_DEFAULT), 1) << n;
  }
  EXPECT_EQ(string_attr(f, "rve/stress", "unit"), "Pa");
  EXPECT_EQ(string_attr(f, "points/x", "unit"), "m");
  EXPECT_EQ(string_attr(f, "means/eps_ax", "unit"), "-");
  H5Fclose(f);
}

// A progress-line flush (indexes = false) writes the indexes the first time; a forced flush
// (checkpoint, end of run) always brings them up to date. results.h5 has every row after either.
TEST(Results, ForcedFlushRewritesTheIndexes) {
  const std::string dir = scratch("indexes");
  const Sample smp;
  farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
  for (int r = 0; r < 10; ++r) smp.append(w, r);
  w.flush(false);
  EXPECT_EQ(csv_rows(dir), 10);
  for (int r = 10; r < 20; ++r) smp.append(w, r);
  w.flush(true);
  EXPECT_EQ(csv_rows(dir), 20);
  std::ifstream xmf(dir + "/points.xmf");
  const std::string text((std::istreambuf_iterator<char>(xmf)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("step_190"), std::string::npos);
  EXPECT_NE(text.find(":20 3 3</DataItem>"), std::string::npos);  // all rows of the datasets
  // Rewritten atomically (common::write_file_atomic): nothing is left staged.
  EXPECT_FALSE(fs::exists(dir + "/points.xmf.tmp"));
  EXPECT_FALSE(fs::exists(dir + "/means.csv.tmp"));
}

// An index that cannot be written is a common::IoError naming the file, not an input error.
TEST(Results, UnwritableIndexIsAnIoError) {
  const std::string dir = scratch("unwritable");
  const Sample smp;
  farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
  smp.append(w, 0);
  fs::create_directory(dir + "/means.csv");  // rename(file, non-empty directory) fails
  std::ofstream(dir + "/means.csv/keep") << "x";
  try {
    w.flush(true);
    ADD_FAILURE() << "means.csv replaced a directory";
  } catch (const common::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("means.csv"), std::string::npos) << e.what();
  }
}

// Rows not yet written when the writer goes away (an error unwinding the driver) are written, and
// the indexes list them: means.csv has every row, points.xmf names the last step.
TEST(Results, PendingRowsAreWrittenByTheDestructor) {
  const std::string dir = scratch("pending");
  const Sample smp;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    smp.append(w, 0);
    w.flush();  // the indexes as of row 0 (a run's first output)
    for (int r = 1; r < 5; ++r) smp.append(w, r);
  }
  const std::vector<double> step = read_all(dir + "/results.h5", "/step");
  ASSERT_EQ(step.size(), 5u);
  EXPECT_EQ(step[4], 40.0);
  EXPECT_EQ(csv_rows(dir), 5);
  std::ifstream xmf(dir + "/points.xmf");
  const std::string text((std::istreambuf_iterator<char>(xmf)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Name=\"step_40\""), std::string::npos) << "points.xmf lacks the last step";
}

// A restarted writer keeps the rows up to the checkpoint's step and continues after them.
TEST(Results, RestartKeepsRowsUpToTheCheckpointAndAppends) {
  const std::string dir = scratch("restart");
  const Sample smp;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    for (int r = 0; r < 100; ++r) smp.append(w, r);
  }
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, 500);  // rows of steps 0..500 stay
    EXPECT_EQ(w.rows(), 51);
    for (int r = 51; r < 60; ++r) smp.append(w, r);
    w.flush();
  }
  const std::vector<double> step = read_all(dir + "/results.h5", "/step");
  ASSERT_EQ(step.size(), 60u);
  for (std::size_t r = 0; r < 60; ++r) EXPECT_EQ(step[r], 10.0 * static_cast<double>(r));
}

// Constraints: /constraints/reaction and /displacement [rows, nc, 3] with their unit and
// description, the names as an attribute, reactions.csv with its header and one row per output
// row; a restart truncates and continues them (values read back exactly: 17 digits).
TEST(Results, ConstraintSeriesAndReactionsCsvContinueOnRestart) {
  const std::string dir = scratch("constraints");
  const Sample smp;
  const std::vector<std::string> names{"base", "platen"};
  auto append = [&](farm::ResultsWriter& w, int r) {
    const std::vector<common::Mat3> stress(3, common::Mat3::Identity());
    const std::vector<common::Vec3> reactions{common::Vec3(r, 0, 1), common::Vec3(0, 0, -0.1 * r)};
    const std::vector<common::Vec3> disp{common::Vec3::Zero(), common::Vec3(0, 0, -1e-3 * r)};
    w.append(10 * r, 0.5 * r, stress, smp.reports(r), smp.points, farm::SampleMeans{}, reactions,
             disp);
  };
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1, names);
    for (int r = 0; r < 100; ++r) append(w, r);
  }
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, 500, names);
    EXPECT_EQ(w.rows(), 51);
    for (int r = 51; r < 60; ++r) append(w, r);
    w.flush();
  }
  const std::vector<double> reaction = read_all(dir + "/results.h5", "/constraints/reaction");
  const std::vector<double> disp = read_all(dir + "/results.h5", "/constraints/displacement");
  ASSERT_EQ(reaction.size(), 60u * 2 * 3);
  ASSERT_EQ(disp.size(), 60u * 2 * 3);
  for (std::size_t r = 0; r < 60; ++r) {
    EXPECT_EQ(reaction[6 * r + 0], static_cast<double>(r));
    EXPECT_EQ(reaction[6 * r + 5], -0.1 * static_cast<double>(r));
    EXPECT_EQ(disp[6 * r + 5], -1e-3 * static_cast<double>(r));
  }
  const hid_t f = H5Fopen((dir + "/results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(string_attr(f, "constraints", "names"), "base,platen");
  EXPECT_EQ(string_attr(f, "constraints/reaction", "unit"), "N");
  EXPECT_EQ(string_attr(f, "constraints/displacement", "unit"), "m");
  EXPECT_FALSE(string_attr(f, "constraints/reaction", "description").empty());
  H5Fclose(f);
  std::ifstream csv(dir + "/reactions.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(csv, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 61u);
  EXPECT_EQ(lines[0],
            "step,time_s,base_rx_N,base_ry_N,base_rz_N,base_ux_m,base_uy_m,base_uz_m,platen_rx_N,"
            "platen_ry_N,platen_rz_N,platen_ux_m,platen_uy_m,platen_uz_m");
  EXPECT_EQ(lines[4], "30,1.5,3,0,1,0,0,0,0,0,-0.30000000000000004,0,0,-0.0030000000000000001");
}

// Without constraint names nothing of the kind is written (the file of a run without any).
TEST(Results, NoConstraintsNoConstraintOutputs) {
  const std::string dir = scratch("no_constraints");
  const Sample smp;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    smp.append(w, 0);
  }
  EXPECT_FALSE(fs::exists(dir + "/reactions.csv"));
  const hid_t f = H5Fopen((dir + "/results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_EQ(H5Lexists(f, "constraints", H5P_DEFAULT), 0);
  H5Fclose(f);
}

// A results.h5 written before constraints were recorded, continued by a run that records them:
// the kept rows get NaN, the new rows their values; reactions.csv has every row. The same for
// /points/volume.
TEST(Results, RestartOfAnOlderFileFillsConstraintRowsWithNaN) {
  const std::string dir = scratch("constraints_old_file");
  const Sample smp;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    for (int r = 0; r < 5; ++r) smp.append(w, r);
  }
  {  // /points/volume came with /constraints (issue 15): an older file has neither.
    const hid_t f = H5Fopen((dir + "/results.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(H5Ldelete(f, "points/volume", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, 20, {"platen"});
    EXPECT_EQ(w.rows(), 3);
    const std::vector<common::Mat3> stress(3, common::Mat3::Identity());
    w.append(30, 1.5, stress, smp.reports(3), smp.points, farm::SampleMeans{},
             {common::Vec3(1, 2, 3)}, {common::Vec3(0, 0, -1)});
    w.flush();
  }
  const std::vector<double> reaction = read_all(dir + "/results.h5", "/constraints/reaction");
  ASSERT_EQ(reaction.size(), 4u * 3);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_TRUE(std::isnan(reaction[i])) << i;
  EXPECT_EQ(reaction[9], 1.0);
  EXPECT_EQ(reaction[11], 3.0);
  const std::vector<double> volume = read_all(dir + "/results.h5", "/points/volume");
  ASSERT_EQ(volume.size(), 4u * 3);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_TRUE(std::isnan(volume[i])) << i;
  EXPECT_EQ(volume[9], 1.0);  // the sample's points have volume 1
  std::ifstream csv(dir + "/reactions.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(csv, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[4], "30,1.5,1,2,3,0,0,-1");
}

// Point fields (issue 19): velocity, displacement from the INITIAL points matched by id (here
// given in another order and with one id they lack: NaN), F; grain-scale measures by RVE index,
// NaN rows when none are given. Exact: the writer copies doubles.
TEST(Results, PointFieldsAndGrainMeasures) {
  const std::string dir = scratch("point_fields");
  Sample smp;
  mpm::MaterialPoints initial;
  initial.resize(2);
  initial.id = {1, 9};  // no id 5
  initial.x = {common::Vec3(1.0, 2.0, 3.0), common::Vec3(-1.0, 0.0, 0.5)};
  for (std::size_t p = 0; p < 3; ++p) {
    smp.points.v[p] = common::Vec3(static_cast<double>(p), -2.0, 0.25);
    smp.points.F[p](0, 1) = 0.5 + static_cast<double>(p);
  }
  std::vector<farm::MicroMeasures> mm(3);
  for (std::size_t k = 0; k < 3; ++k) {
    mm[k].fabric[0] = 0.5;
    mm[k].fabric[4] = 0.25 + static_cast<double>(k);
    mm[k].z_mech = 4.0 + static_cast<double>(k);
    mm[k].unbalanced = 1e-3;
    mm[k].kinetic = 2e-9;
  }
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1, {}, &initial);
    const std::vector<common::Mat3> stress(3, common::Mat3::Zero());
    w.append(0, 0.0, stress, smp.reports(0), smp.points, farm::SampleMeans{}, {}, {}, mm);
    w.append(1, 0.5, stress, smp.reports(1), smp.points, farm::SampleMeans{});
    w.flush();  // points.xmf
  }
  const std::string f = dir + "/results.h5";
  const std::vector<double> v = read_all(f, "/points/velocity");
  ASSERT_EQ(v.size(), 2u * 3 * 3);
  EXPECT_EQ(v[3], 1.0);  // slot 1: x component = 1
  EXPECT_EQ(v[4], -2.0);
  const std::vector<double> u = read_all(f, "/points/displacement");
  ASSERT_EQ(u.size(), 2u * 3 * 3);
  // Slot 0 is id 9 at (0, 0.5, 0.5), initially (-1, 0, 0.5); slot 1 is id 1 at (0.1, 0.5, 0.5),
  // initially (1, 2, 3); slot 2 is id 5, not among the initial points.
  EXPECT_EQ(u[0], 0.0 - (-1.0));
  EXPECT_EQ(u[1], 0.5 - 0.0);
  EXPECT_EQ(u[3], 0.1 - 1.0);
  EXPECT_EQ(u[5], 0.5 - 3.0);
  for (int a = 6; a < 9; ++a) EXPECT_TRUE(std::isnan(u[static_cast<std::size_t>(a)])) << a;
  const std::vector<double> F = read_all(f, "/points/F");
  ASSERT_EQ(F.size(), 2u * 3 * 9);
  EXPECT_EQ(F[9 * 2 + 1], 2.5);  // row-major (0, 1) of slot 2
  EXPECT_EQ(F[9 * 2 + 3], 0.0);
  const std::vector<double> fab = read_all(f, "/rve/fabric");
  ASSERT_EQ(fab.size(), 2u * 3 * 9);
  EXPECT_EQ(fab[9 * 2 + 4], 2.25);
  const std::vector<double> zm = read_all(f, "/rve/z_mech");
  ASSERT_EQ(zm.size(), 6u);
  EXPECT_EQ(zm[1], 5.0);
  for (std::size_t i = 3; i < 6; ++i) EXPECT_TRUE(std::isnan(zm[i])) << i;  // row without
  EXPECT_EQ(read_all(f, "/rve/unbalanced")[0], 1e-3);
  EXPECT_EQ(read_all(f, "/rve/kinetic_energy")[2], 2e-9);
  EXPECT_TRUE(std::isnan(read_all(f, "/rve/fabric")[9 * 3]));
  // points.xmf names every point field (ParaView arrays).
  std::ifstream xmf(dir + "/points.xmf");
  const std::string text((std::istreambuf_iterator<char>(xmf)), std::istreambuf_iterator<char>());
  for (const char* a :
       {"velocity\" AttributeType=\"Vector", "displacement\" AttributeType=\"Vector",
        "F\" AttributeType=\"Tensor", "volume\" AttributeType=\"Scalar"}) {
    EXPECT_NE(text.find(a), std::string::npos) << a;
  }
}

// A file written before issue 19 lacks the point fields and measures: a restart adds them with
// NaN rows up to the restart.
TEST(Results, RestartOfAFileWithoutIssue19SeriesFillsThemWithNaN) {
  const std::string dir = scratch("issue19_old_file");
  const Sample smp;
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, -1);
    for (int r = 0; r < 5; ++r) smp.append(w, r);
  }
  {
    const hid_t f = H5Fopen((dir + "/results.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    for (const char* n : {"points/velocity", "points/displacement", "points/F", "rve/fabric",
                          "rve/z_mech", "rve/unbalanced", "rve/kinetic_energy"}) {
      ASSERT_GE(H5Ldelete(f, n, H5P_DEFAULT), 0) << n;
    }
    H5Fclose(f);
  }
  {
    farm::ResultsWriter w(dir, smp.rve_ids, smp.points, 20);
    EXPECT_EQ(w.rows(), 3);
    smp.append(w, 3);
  }
  const std::vector<double> v = read_all(dir + "/results.h5", "/points/velocity");
  ASSERT_EQ(v.size(), 4u * 3 * 3);
  for (std::size_t i = 0; i < 27; ++i) EXPECT_TRUE(std::isnan(v[i])) << i;
  EXPECT_EQ(v[27], 0.0);  // the sample's points are at rest
  EXPECT_EQ(read_all(dir + "/results.h5", "/rve/z_mech").size(), 4u * 3);
}

}  // namespace
