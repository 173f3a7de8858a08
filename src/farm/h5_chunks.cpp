// HDF5's shuffle + deflate pipeline: see h5_chunks.hpp.
#include "farm/h5_chunks.hpp"

#include <zlib.h>

#include <cstring>
#include <vector>

#include "common/errors.hpp"

namespace farm::h5 {

template <class T>
std::string encode_chunk(std::span<const T> values, std::size_t chunk_len, int level) {
  MPMXDEM_CHECK(values.size() <= chunk_len, "a chunk holds at most chunk_len values");
  constexpr std::size_t s = sizeof(T);
  const std::size_t nbytes = chunk_len * s;
  std::vector<unsigned char> raw(nbytes, 0);
  if (!values.empty()) std::memcpy(raw.data(), values.data(), values.size() * s);
  // Shuffle: byte j of element i goes to j * chunk_len + i.
  std::vector<unsigned char> shuffled(s == 1 ? 0 : nbytes);
  for (std::size_t i = 0; s > 1 && i < chunk_len; ++i) {
    for (std::size_t j = 0; j < s; ++j) shuffled[j * chunk_len + i] = raw[i * s + j];
  }
  const unsigned char* in = s == 1 ? raw.data() : shuffled.data();
  uLongf size = compressBound(static_cast<uLong>(nbytes));
  std::string out(size, '\0');
  const int rc =
      compress2(reinterpret_cast<Bytef*>(out.data()), &size, in, static_cast<uLong>(nbytes), level);
  if (rc != Z_OK)
    throw common::InternalError("zlib compress2 failed with code " + std::to_string(rc));
  out.resize(size);
  return out;
}

template std::string encode_chunk<double>(std::span<const double>, std::size_t, int);
template std::string encode_chunk<std::int64_t>(std::span<const std::int64_t>, std::size_t, int);
template std::string encode_chunk<std::uint8_t>(std::span<const std::uint8_t>, std::size_t, int);

}  // namespace farm::h5
