// Typed HDF5 layer of the farm: one file, created collectively (rank 0 writes it, the other ranks
// send it their pieces) or opened read-only by one process; one-dimensional datasets of double,
// int64 or uint8 (text) written and read as blocks with the checksum built in (attribute hash64,
// farm/checksum.hpp); scalar attributes. It knows nothing of what a checkpoint holds:
// farm/checkpoint.cpp keeps the format.
#pragma once

#include <mpi.h>

#include <concepts>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "farm/checksum.hpp"
#include "farm/h5_util.hpp"
#include "farm/mpi_util.hpp"

namespace farm::h5 {

/// Element types of the layer's datasets.
template <class T>
concept Element =
    std::same_as<T, double> || std::same_as<T, std::int64_t> || std::same_as<T, std::uint8_t>;

class File {
 public:
  /// Collective over `comm`: rank 0 creates (truncates) `path`; every write call below is then
  /// collective, and rank 0 writes what every rank sends it. Not MPI-IO: parallel HDF5 has no
  /// collective error handling, and a write that fails on one rank (a full disk) leaves the others
  /// waiting forever inside H5Fclose (docs/reference/errors.md, "Storage that fails"). Rank 0
  /// keeps its first failure and goes on with the messages, skipping HDF5; close() then throws it
  /// on every rank (common::IoError naming the file and the system's reason) and removes the file.
  /// Throws common::IoError on every rank when the file cannot be created.
  [[nodiscard]] static File create(MPI_Comm comm, const std::string& path);
  /// Opens `path` read-only in this process. `what` starts every error message ("checkpoint").
  /// Throws common::InputError "<what> <path>: ..." when the file does not exist, is not HDF5
  /// (damaged, truncated) or cannot be opened.
  [[nodiscard]] static File open(const std::string& path, const std::string& what);

  File(File&&) noexcept = default;
  File& operator=(File&&) noexcept = default;
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  ~File() = default;

  // ------------------------------------------------------------ writing (collective)

  /// Scalar attribute of the root group; identical values on every rank.
  void write_attribute(const char* name, std::int64_t value);
  void write_attribute(const char* name, double value);
  void write_attribute(const char* name, const std::string& value);

  /// Dataset `name` (groups created on the way) of `global_n` elements, chunked, shuffled and
  /// deflated. This rank writes `blocks` (ascending, disjoint; may be none) whose elements are
  /// concatenated in `data`. The attribute hash64 holds the checksum of the whole dataset.
  template <Element T>
  void write_blocks(const std::string& name, std::uint64_t global_n, std::span<const Block> blocks,
                    const T* data);
  /// Dataset of `n` elements that rank 0 holds in `data` (ignored elsewhere).
  /// @pre n is the same on every rank.
  template <Element T>
  void write_from_root(const std::string& name, std::uint64_t n, const T* data);
  /// Writes the buffered data of every rank to the file.
  void flush();
  /// Closes the file (collective for a created file): what was written is complete on disk, up
  /// to the operating system's cache; or every rank throws rank 0's first failure.
  void close();

  // ------------------------------------------------------------ reading (this process)

  /// Throws common::InputError "<what> <path>: <message>".
  [[noreturn]] void fail(const std::string& message) const;
  /// Whether the object `name` (an absolute path, every group on the way) exists.
  [[nodiscard]] bool exists(const std::string& name) const;
  /// Scalar attributes of the root group; fail() when missing or of another type.
  [[nodiscard]] std::int64_t attribute_i64(const char* name) const;
  [[nodiscard]] double attribute_f64(const char* name) const;
  [[nodiscard]] std::string attribute_string(const char* name) const;
  /// The whole dataset, checked for presence, rank, element type and checksum (fail() naming
  /// the dataset on any mismatch).
  template <Element T>
  [[nodiscard]] std::vector<T> read(const std::string& name) const;
  /// The concatenation of `blocks` of a dataset. Adds their partial checksum to `partial` and
  /// sets `stored` to the dataset's hash64: the caller compares once every piece is summed
  /// (over ranks: MPI_SUM of the partial sums).
  template <Element T>
  [[nodiscard]] std::vector<T> read_blocks(const std::string& name, std::span<const Block> blocks,
                                           std::uint64_t& partial, std::uint64_t& stored) const;

  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  File() = default;
  template <Element T>
  Handle open_dataset(const std::string& name, std::uint64_t& n) const;
  [[nodiscard]] std::uint64_t stored_checksum(hid_t dset, const std::string& name) const;
  void attribute(const char* name, hid_t type, const void* value);
  /// Runs `f` on rank 0 unless an earlier call failed there; keeps its failure.
  template <class F>
  void on_root(const char* what, F&& f);
  /// Collective: every rank throws rank 0's failure, if any (its file removed first).
  void agree();

  std::string path_;
  std::string what_;
  MPI_Comm comm_ = MPI_COMM_NULL;  ///< set when created collectively
  int rank_ = 0;
  Handle file_;
  Handle lcpl_;                             ///< creates intermediate groups
  std::string error_;                       ///< rank 0's first failure while writing
  ErrorKind error_kind_ = ErrorKind::none;  ///< its kind (common::IoError for the system's)
};

}  // namespace farm::h5
