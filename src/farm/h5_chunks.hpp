// HDF5's filter pipeline of the farm's datasets (shuffle, then deflate), run by the caller: every
// rank compresses the chunks it holds, and rank 0 only stores them (H5Dwrite_chunk), so the
// deflate of a checkpoint is spread over the ranks (docs/reference/checkpoint.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace farm::h5 {

/// The bytes a chunk of a shuffled + deflated dataset holds (H5Dwrite_chunk with filter mask 0):
/// `values` (at most `chunk_len`) padded with zeros to `chunk_len` elements (HDF5 stores an edge
/// chunk whole), byte-shuffled (H5Zshuffle.c; nothing for 1-byte elements), then deflated with
/// zlib at `level` (H5Zdeflate.c: compress2 into a compressBound buffer).
template <class T>
[[nodiscard]] std::string encode_chunk(std::span<const T> values, std::size_t chunk_len, int level);

}  // namespace farm::h5
