// farm::h5::encode_chunk: chunks encoded by the caller and stored with H5Dwrite_chunk read back
// through HDF5's own filter pipeline (shuffle, deflate) as the values that were encoded, for each
// element type of the checkpoints, whole and edge chunks alike.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "farm/h5_chunks.hpp"
#include "farm/h5_util.hpp"

namespace {

using farm::h5::Handle;

/// Writes `values` into a chunked (shuffle + deflate 4) dataset of an in-memory file through
/// encode_chunk + H5Dwrite_chunk, then reads it back with H5Dread.
template <class T>
std::vector<T> round_trip(const std::vector<T>& values, hsize_t chunk) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_core(fapl.get(), 1 << 20, 0);
  Handle file(H5Fcreate("chunks.h5", H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  const hsize_t n[1] = {values.size()};
  Handle space(H5Screate_simple(1, n, nullptr), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  const hsize_t dim[1] = {chunk};
  H5Pset_chunk(dcpl.get(), 1, dim);
  H5Pset_shuffle(dcpl.get());
  H5Pset_deflate(dcpl.get(), 4);
  Handle dset(H5Dcreate2(file.get(), "d", farm::h5::native_type<T>(), space.get(), H5P_DEFAULT,
                         dcpl.get(), H5P_DEFAULT),
              H5Dclose);
  EXPECT_TRUE(dset.valid());
  for (hsize_t at = 0; at < values.size(); at += chunk) {
    const hsize_t count = std::min<hsize_t>(chunk, values.size() - at);
    const std::string e =
        farm::h5::encode_chunk(std::span<const T>(values.data() + at, count), chunk, 4);
    const hsize_t offset[1] = {at};
    EXPECT_GE(H5Dwrite_chunk(dset.get(), H5P_DEFAULT, 0, offset, e.size(), e.data()), 0);
  }
  std::vector<T> back(values.size());
  EXPECT_GE(
      H5Dread(dset.get(), farm::h5::native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()),
      0);
  return back;
}

TEST(H5Chunks, EncodedChunksReadBackThroughHdf5sPipeline) {
  std::vector<double> d(1000);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = 1e-3 * static_cast<double>(i * i) - 0.5;
  d[7] = -0.0;
  EXPECT_EQ(round_trip(d, 256), d);   // three whole chunks and an edge chunk of 232
  EXPECT_EQ(round_trip(d, 1000), d);  // one chunk
  std::vector<std::int64_t> k(777);
  std::iota(k.begin(), k.end(), -300);
  EXPECT_EQ(round_trip(k, 100), k);
  std::vector<std::uint8_t> b(300);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = static_cast<std::uint8_t>(i * 7);
  EXPECT_EQ(round_trip(b, 64), b);
}

TEST(H5Chunks, IncompressibleChunksStillReadBack) {
  // Random bits: deflate grows them a little; the chunk is stored as it came out.
  std::vector<std::int64_t> r(4096);
  std::uint64_t x = 12345;
  for (auto& v : r) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    v = static_cast<std::int64_t>(x);
  }
  EXPECT_EQ(round_trip(r, 1024), r);
}

}  // namespace
