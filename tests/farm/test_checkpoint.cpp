// Tests of farm/checkpoint.hpp and the typed HDF5 layer under it (farm/h5_file.hpp), on 2 ranks:
// a checkpoint written by all ranks reads back exactly (any field type, absent and empty fields,
// any distribution of the RVEs over the readers), its checksums catch a flipped value, a field
// of the wrong element type is refused, nothing is left staged, and attributes as other writers
// store them (variable-length strings, arrays) are read or refused by name.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "farm/checkpoint.hpp"
#include "farm/h5_file.hpp"

namespace {

namespace fs = std::filesystem;

/// This rank and the rank count of MPI_COMM_WORLD.
struct World {
  int rank = 0;
  int size = 1;
};
World world() {
  World w;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  return w;
}
int world_rank() { return world().rank; }
int world_size() { return world().size; }

/// A directory shared by the ranks (rank 0's pid), emptied.
std::string scratch(const std::string& name) {
  int pid = ::getpid();
  MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
  const fs::path dir = fs::temp_directory_path() / ("mpmxdem_ckpt_" + std::to_string(pid)) / name;
  if (world_rank() == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return dir.string();
}

constexpr std::size_t kRves = 7;

/// The state of RVE k: a float field of k + 1 values, an integer field, a field present only
/// in even RVEs and a field that is empty in RVE 3.
common::StateStore rve_state(std::size_t k) {
  common::StateStore s;
  std::vector<double> x(k + 1);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 1.0 / static_cast<double>(k + 1 + i);
  s.write("spheres/x", x);
  s.write("spheres/fixed", std::vector<std::int64_t>{static_cast<std::int64_t>(k), -1});
  if (k % 2 == 0) s.write("even/only", std::vector<double>{-0.0, static_cast<double>(k)});
  s.write("maybe/empty", std::vector<double>(k == 3 ? 0 : 2, 3.5));
  return s;
}

common::StateStore mpm_state() {
  common::StateStore s;
  s.write("points/x", std::vector<double>{0.1, 0.2, 0.3});
  s.write("points/id", std::vector<std::int64_t>{5, 6, 7, 8});
  return s;
}

/// Writes a checkpoint: rank r holds RVEs k with k % size == r.
std::string write_sample(const std::string& dir) {
  farm::CheckpointData d;
  d.step = 12;
  d.time = 3.25e-3;
  d.job_text = "[mpm]\nfirst line\n";
  for (std::size_t k = 0; k < kRves; ++k) {
    d.ids.push_back(static_cast<std::int64_t>(10 * k + 1));
    d.owner.push_back(static_cast<int>(k % static_cast<std::size_t>(world_size())));
    d.cost.push_back(0.5 + static_cast<double>(k));
    if (d.owner.back() == world_rank()) {
      d.local_indices.push_back(static_cast<std::int64_t>(k));
      d.local_states.push_back(rve_state(k));
    }
  }
  const common::StateStore mpm = mpm_state();
  d.mpm = world_rank() == 0 ? &mpm : nullptr;
  const std::string path = farm::checkpoint_path(dir, d.step);
  farm::write_checkpoint(MPI_COMM_WORLD, path, d, false);
  return path;
}

}  // namespace

TEST(Checkpoint, RoundTripOnAnyDistributionOfTheRves) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2";
  const std::string dir = scratch("roundtrip");
  const std::string path = write_sample(dir);
  EXPECT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(farm::list_checkpoints(dir), std::vector<std::string>{path});

  const farm::CheckpointInfo info = farm::read_checkpoint_info(path);
  EXPECT_EQ(info.step, 12);
  EXPECT_EQ(info.time, 3.25e-3);
  EXPECT_EQ(info.nranks, world_size());
  EXPECT_EQ(info.ids.size(), kRves);
  EXPECT_EQ(info.cost[6], 6.5);
  EXPECT_EQ(info.partition[3], 3 % world_size());
  EXPECT_EQ(info.job_text, "[mpm]\nfirst line\n");
  // The field lists carry each field's element type (the file format: f: float, i: integer);
  // the RVE list is sorted as listed, the MPM list in field name order.
  EXPECT_EQ(info.rve_fields, (std::vector<std::string>{"f:even/only", "f:maybe/empty",
                                                       "f:spheres/x", "i:spheres/fixed"}));
  EXPECT_EQ(info.mpm_fields, (std::vector<std::string>{"i:points/id", "f:points/x"}));
  EXPECT_TRUE(farm::read_checkpoint_mpm(path).fields() == mpm_state().fields());

  // Read back by other ranks than wrote: rank r takes RVEs k with (k + 1) % size == r.
  std::vector<std::int64_t> mine;
  for (std::size_t k = 0; k < kRves; ++k) {
    if (static_cast<int>((k + 1) % static_cast<std::size_t>(world_size())) == world_rank())
      mine.push_back(static_cast<std::int64_t>(k));
  }
  const std::vector<common::StateStore> got =
      farm::read_checkpoint_rves(MPI_COMM_WORLD, info, mine);
  ASSERT_EQ(got.size(), mine.size());
  for (std::size_t j = 0; j < mine.size(); ++j) {
    EXPECT_TRUE(got[j].fields() == rve_state(static_cast<std::size_t>(mine[j])).fields())
        << "RVE " << mine[j];
  }
  if (world_rank() == 0) {
    EXPECT_NO_THROW(farm::verify_checkpoint(path));
    const std::string text = farm::describe(info);
    EXPECT_NE(text.find("RVE fields    4: even/only maybe/empty spheres/x spheres/fixed"),
              std::string::npos)
        << text;
  }
}

// A flipped value is caught by the checksum of its dataset, on every rank, naming the dataset.
TEST(Checkpoint, FlippedValueIsRefusedOnEveryRank) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2";
  const std::string dir = scratch("flipped");
  const std::string path = write_sample(dir);
  if (world_rank() == 0) {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/rve/fields/spheres/x", H5P_DEFAULT);
    const hid_t s = H5Dget_space(d);
    const hsize_t start[1] = {20};  // inside RVE 5, read below by rank 0 of 2 and 3
    const hsize_t count[1] = {1};
    H5Sselect_hyperslab(s, H5S_SELECT_SET, start, nullptr, count, nullptr);
    const hid_t m = H5Screate_simple(1, count, nullptr);
    const double v = 99.0;
    H5Dwrite(d, H5T_NATIVE_DOUBLE, m, s, H5P_DEFAULT, &v);
    H5Sclose(m);
    H5Sclose(s);
    H5Dclose(d);
    H5Fclose(f);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const farm::CheckpointInfo info = farm::read_checkpoint_info(path);  // small datasets intact
  // Rank 1 reads nothing of spheres/x: the mismatch is found from the sum over the ranks.
  const std::vector<std::int64_t> mine = world_rank() == 0
                                             ? std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6}
                                             : std::vector<std::int64_t>{};
  try {
    (void)farm::read_checkpoint_rves(MPI_COMM_WORLD, info, mine);
    ADD_FAILURE() << "a damaged checkpoint was read";
  } catch (const common::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("/rve/fields/spheres/x: checksum mismatch"), std::string::npos) << msg;
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
  }
  if (world_rank() == 0) {
    EXPECT_THROW(farm::verify_checkpoint(path), common::InputError);
  }
}

// The typed layer: blocks interleaved over the ranks read back whole with a valid checksum; a
// dataset read as the wrong element type is refused naming it.
TEST(H5File, InterleavedBlocksAndTypeChecks) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2";
  const std::string path = scratch("blocks") + "/blocks.h5";
  const auto size = static_cast<std::uint64_t>(world_size());
  const std::uint64_t n = 10 * size + 3;
  {
    farm::h5::File f = farm::h5::File::create(MPI_COMM_WORLD, path);
    std::vector<farm::Block> blocks;
    std::vector<std::int64_t> data;
    for (std::uint64_t i = static_cast<std::uint64_t>(world_rank()); i < n; i += size) {
      blocks.push_back({i, 1});
      data.push_back(static_cast<std::int64_t>(i * i));
    }
    f.write_blocks<std::int64_t>("/a/b/squares", n, blocks, data.data());
    f.write_attribute("answer", std::int64_t{42});
    f.write_attribute("label", std::string("x"));
    f.write_attribute("empty", std::string());
    f.close();
  }
  if (world_rank() == 0) {
    const farm::h5::File r = farm::h5::File::open(path, "test file");
    const std::vector<std::int64_t> v = r.read<std::int64_t>("/a/b/squares");
    ASSERT_EQ(v.size(), n);
    for (std::uint64_t i = 0; i < n; ++i) EXPECT_EQ(v[i], static_cast<std::int64_t>(i * i));
    EXPECT_EQ(r.attribute_i64("answer"), 42);
    EXPECT_EQ(r.attribute_string("label"), "x");
    EXPECT_EQ(r.attribute_string("empty"), "");
    EXPECT_TRUE(r.exists("/a/b/squares"));
    EXPECT_FALSE(r.exists("/a/c/squares"));
    try {
      (void)r.read<double>("/a/b/squares");
      ADD_FAILURE() << "integers read as doubles";
    } catch (const common::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("test file " + path +
                                           ": dataset /a/b/squares has the wrong element type"),
                std::string::npos)
          << e.what();
    }
    EXPECT_THROW((void)r.attribute_f64("label"), common::InputError);
    EXPECT_THROW((void)farm::h5::File::open(path + ".none", "test file"), common::InputError);
  }
}

// Attributes as other writers store them (h5py, our results.h5): a variable-length string reads
// as its text (a results file given as a checkpoint is named as such), and an attribute holding
// several values is refused by name instead of being read past one value.
TEST(H5File, ForeignAttributes) {
  const std::string path = scratch("foreign") + "/foreign.h5";
  if (world_rank() != 0) return;
  {
    const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t scalar = H5Screate(H5S_SCALAR);
    const hid_t vstr = H5Tcopy(H5T_C_S1);
    H5Tset_size(vstr, H5T_VARIABLE);
    H5Tset_cset(vstr, H5T_CSET_UTF8);
    const char* text = "mpmxdem results";
    hid_t a = H5Acreate2(f, "format", vstr, scalar, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, vstr, &text);
    H5Aclose(a);
    const hsize_t four[1] = {4};
    const hid_t arr = H5Screate_simple(1, four, nullptr);
    const std::int64_t versions[4] = {1, 2, 3, 4};
    a = H5Acreate2(f, "format_version", H5T_NATIVE_INT64, arr, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_INT64, versions);
    H5Aclose(a);
    const hid_t fstr = H5Tcopy(H5T_C_S1);
    H5Tset_size(fstr, 8);
    const char names[4][8] = {"aaaaaaa", "bbbbbbb", "ccccccc", "ddddddd"};
    a = H5Acreate2(f, "names", fstr, arr, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, fstr, names);
    H5Aclose(a);
    H5Tclose(fstr);
    H5Sclose(arr);
    H5Tclose(vstr);
    H5Sclose(scalar);
    H5Fclose(f);
  }
  const farm::h5::File r = farm::h5::File::open(path, "test file");
  EXPECT_EQ(r.attribute_string("format"), "mpmxdem results");
  const auto refused = [&](auto read, const std::string& what) {
    try {
      read();
      ADD_FAILURE() << "read: " << what;
    } catch (const common::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused([&] { (void)r.attribute_i64("format_version"); },
          "attribute /format_version holds 4 values, not one");
  refused([&] { (void)r.attribute_string("names"); }, "attribute /names holds 4 values, not one");
  refused([&] { (void)farm::read_checkpoint_info(path); },
          "attribute /format = 'mpmxdem results': not a farm checkpoint");
}

// A dataset whose extent claims more values than the file stores of it (an unwritten chunked
// extent of 1e11 values) is refused by name before anything is allocated for it.
TEST(H5File, ExtentBeyondTheStoredBytesIsRefused) {
  const std::string path = scratch("extent") + "/extent.h5";
  if (world_rank() != 0) return;
  {
    const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t n[1] = {100000000000ULL};
    const hsize_t chunk[1] = {1024};
    const hid_t space = H5Screate_simple(1, n, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, chunk);
    const hid_t d = H5Dcreate2(f, "/x", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  }
  const farm::h5::File r = farm::h5::File::open(path, "test file");
  try {
    (void)r.read<double>("/x");
    ADD_FAILURE() << "an extent of 1e11 unstored values was read";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dataset /x claims 100000000000 values, more than the 0 "
                                         "bytes the file stores of it can hold"),
              std::string::npos)
        << e.what();
  }
}
