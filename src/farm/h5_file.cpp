// Typed HDF5 layer: see h5_file.hpp.
#include "farm/h5_file.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <type_traits>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "farm/h5_chunks.hpp"
#include "farm/mpi_util.hpp"

namespace farm::h5 {

namespace {

/// Chunk length of a checkpoint dataset (elements); a chunk may not exceed a fixed-size dataset.
constexpr hsize_t kChunk = hsize_t{1} << 16U;
constexpr unsigned kDeflateLevel = 4;
/// Growth step of a file built in memory (bytes).
constexpr std::size_t kCoreIncrement = std::size_t{64} << 20U;

/// `blocks` (ascending, disjoint) with empty ones dropped and adjacent ones merged: one
/// hyperslab per run of consecutive RVEs, so that the collective filtered-chunk path exchanges
/// one piece per run instead of one per RVE (docs/validation/scaling.md, finding 4). The file
/// layout and the checksums (position-keyed) do not depend on how a selection is split.
std::vector<Block> merged(std::span<const Block> blocks) {
  std::vector<Block> out;
  for (const Block& b : blocks) {
    if (b.count == 0) continue;
    if (!out.empty() && out.back().offset + out.back().count == b.offset) {
      out.back().count += b.count;
    } else {
      out.push_back(b);
    }
  }
  return out;
}

/// Selects `blocks` in `space` (none selected when they are all empty).
void select_blocks(hid_t space, std::span<const Block> blocks) {
  bool first = true;
  for (const Block& b : merged(blocks)) {
    const hsize_t start[1] = {b.offset};
    const hsize_t count[1] = {b.count};
    check(H5Sselect_hyperslab(space, first ? H5S_SELECT_SET : H5S_SELECT_OR, start, nullptr, count,
                              nullptr),
          "H5Sselect_hyperslab");
    first = false;
  }
  if (first) check(H5Sselect_none(space), "H5Sselect_none");
}

std::uint64_t total_count(std::span<const Block> blocks) {
  std::uint64_t n = 0;
  for (const Block& b : blocks) n += b.count;
  return n;
}

}  // namespace

File File::create(MPI_Comm comm, const std::string& path) {
  silence_errors();
  File f;
  f.path_ = path;
  f.what_ = "file";
  f.comm_ = comm;
  MPI_Comm_rank(comm, &f.rank_);
  f.on_root("create", [&] {
    // The file is built in memory (the core driver, no backing store) and written by close() in
    // one piece with plain system calls: HDF5 never meets a failing disk, whose errors leave its
    // file objects half closed (HDF5 1.10 then crashes in MPI_Finalize).
    Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
    check(H5Pset_fapl_core(fapl.get(), kCoreIncrement, 0), "H5Pset_fapl_core");
    f.file_ = Handle(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()),
                           "create HDF5 file " + path),
                     H5Fclose);
    f.lcpl_ = Handle(check(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate"), H5Pclose);
    check(H5Pset_create_intermediate_group(f.lcpl_.get(), 1), "H5Pset_create_intermediate_group");
    // Nothing is on disk yet: make sure the file can be created at all, now.
    common::write_new_file(path, "");
  });
  f.agree();  // a file that cannot be created fails every rank here
  return f;
}

template <class F>
void File::on_root(const char* what, F&& f) {
  if (rank_ != 0 || !error_.empty()) return;
  try {
    f();
  } catch (...) {
    error_kind_ = current_error_kind();
    error_ = common::current_error_text();
    // Name the file where the failure does not (an HDF5 call's).
    if (error_.find(path_) == std::string::npos)
      error_ = "writing '" + path_ + "' (" + what + "): " + error_;
  }
}

void File::agree() {
  if (rank_ == 0 && !error_.empty()) {
    // Nothing of a file that failed is kept: it would only hold the disk's last free bytes.
    lcpl_.reset();
    file_.reset();
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  agree_on_errors(comm_, error_.empty() ? ErrorKind::none : error_kind_, error_);
}

File File::open(const std::string& path, const std::string& what) {
  silence_errors();
  File f;
  f.path_ = path;
  f.what_ = what;
  if (!std::filesystem::exists(path)) f.fail("the file does not exist");
  if (H5Fis_hdf5(path.c_str()) <= 0)
    f.fail("is not an HDF5 file (damaged, truncated or not a " + what + ")");
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) f.fail("cannot be opened as HDF5 (damaged or truncated)");
  f.file_ = Handle(id, H5Fclose);
  return f;
}

// ---------------------------------------------------------------- writing

void File::attribute(const char* name, hid_t type, const void* value) {
  on_root(name, [&] {
    Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    Handle attr(check(H5Acreate2(file_.get(), name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      std::string("create attribute ") + name),
                H5Aclose);
    check(H5Awrite(attr.get(), type, value), std::string("write attribute ") + name);
    check(attr.close(), std::string("close attribute ") + name);
  });
}

void File::write_attribute(const char* name, std::int64_t value) {
  attribute(name, H5T_NATIVE_INT64, &value);
}

void File::write_attribute(const char* name, double value) {
  attribute(name, H5T_NATIVE_DOUBLE, &value);
}

void File::write_attribute(const char* name, const std::string& value) {
  // A fixed-length string of the text's size (HDF5 has no zero-length string type: "" is "\0").
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  on_root(name, [&] {
    Handle type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
    check(H5Tset_size(type.get(), v.size()), "H5Tset_size");
    Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    Handle attr(
        check(H5Acreate2(file_.get(), name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              std::string("create attribute ") + name),
        H5Aclose);
    check(H5Awrite(attr.get(), type.get(), v.data()), std::string("write attribute ") + name);
    check(attr.close(), std::string("close attribute ") + name);
  });
}

namespace {

/// Largest number of elements sent in one message (MPI counts are ints).
constexpr std::uint64_t kMessage = std::uint64_t{1} << 28U;

/// Sends (rank > 0) or receives (rank 0, from `from`) a vector in messages of at most kMessage
/// elements; the receiver learns the length first.
template <class T>
void send_vector(MPI_Comm comm, const std::vector<T>& v) {
  std::uint64_t n = v.size();
  MPI_Send(&n, 1, MPI_UINT64_T, 0, 0, comm);
  for (std::uint64_t at = 0; at < n; at += kMessage) {
    const int c = static_cast<int>(std::min(kMessage, n - at) * sizeof(T));
    MPI_Send(v.data() + at, c, MPI_BYTE, 0, 0, comm);
  }
}

template <class T>
std::vector<T> receive_vector(MPI_Comm comm, int from) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, 0, comm, MPI_STATUS_IGNORE);
  std::vector<T> v(n);
  for (std::uint64_t at = 0; at < n; at += kMessage) {
    const int c = static_cast<int>(std::min(kMessage, n - at) * sizeof(T));
    MPI_Recv(v.data() + at, c, MPI_BYTE, from, 0, comm, MPI_STATUS_IGNORE);
  }
  return v;
}

}  // namespace

namespace {

/// What one rank gives rank 0 of a dataset: the chunks its pieces cover whole, encoded (shuffled
/// and deflated here, spreading the compression over the ranks), and the raw values of the chunks
/// they cover in part (the ends of a rank's run), which rank 0 completes with the other ranks'.
template <class T>
struct Share {
  std::vector<std::uint64_t> chunks;  ///< (chunk index, encoded bytes) pairs
  std::vector<char> bytes;            ///< the encoded chunks, concatenated
  std::vector<std::uint64_t> parts;   ///< (offset, count) pairs of the raw values
  std::vector<T> values;              ///< the raw values, concatenated
};

template <class T>
Share<T> share_of(std::span<const Block> blocks, const T* data, std::uint64_t chunk,
                  std::uint64_t n) {
  Share<T> out;
  std::uint64_t pos = 0;
  for (const Block& b : blocks) {
    const std::uint64_t end = b.offset + b.count;
    for (std::uint64_t at = b.offset; at < end;) {
      const std::uint64_t c = at / chunk;
      const std::uint64_t c_end = std::min((c + 1) * chunk, n);
      const std::uint64_t to = std::min(c_end, end);
      const T* v = data + pos + (at - b.offset);
      if (at == c * chunk && to == c_end) {  // the whole chunk
        const std::string e = encode_chunk(std::span<const T>(v, to - at), chunk, kDeflateLevel);
        out.chunks.insert(out.chunks.end(), {c, e.size()});
        out.bytes.insert(out.bytes.end(), e.begin(), e.end());
      } else {
        out.parts.insert(out.parts.end(), {at, to - at});
        out.values.insert(out.values.end(), v, v + (to - at));
      }
      at = to;
    }
    pos += b.count;
  }
  return out;
}

/// Creates the dataset `name` of global_n values of T in `file` (rank 0's), in chunks of `chunk`
/// values, shuffled and deflated (an empty one unchunked); lcpl: the link creation properties.
template <class T>
Handle create_chunked(hid_t file, hid_t lcpl, const std::string& name, std::uint64_t global_n,
                      std::uint64_t chunk) {
  const hsize_t dims[1] = {global_n};
  Handle fspace(check(H5Screate_simple(1, dims, nullptr), "H5Screate_simple"), H5Sclose);
  Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
  if (global_n > 0) {
    const hsize_t dim[1] = {chunk};
    check(H5Pset_chunk(dcpl.get(), 1, dim), "H5Pset_chunk " + name);
    check(H5Pset_shuffle(dcpl.get()), "H5Pset_shuffle");
    check(H5Pset_deflate(dcpl.get(), kDeflateLevel), "H5Pset_deflate");
  }
  return Handle(check(H5Dcreate2(file, name.c_str(), native_type<T>(), fspace.get(), lcpl,
                                 dcpl.get(), H5P_DEFAULT),
                      "create dataset " + name),
                H5Dclose);
}

}  // namespace

template <Element T>
void File::write_blocks(const std::string& name, std::uint64_t global_n,
                        std::span<const Block> blocks, const T* data) {
  MPMXDEM_CHECK(comm_ != MPI_COMM_NULL, "write to a file opened for reading: " + path_);
  const std::uint64_t local = checksum(blocks, data);
  std::uint64_t total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_UINT64_T, MPI_SUM, comm_);
  const std::uint64_t chunk = std::min<std::uint64_t>(std::max<std::uint64_t>(global_n, 1), kChunk);
  Share<T> share = share_of(std::span<const Block>(merged(blocks)), data, chunk, global_n);
  int size = 1;
  MPI_Comm_size(comm_, &size);
  if (rank_ != 0) {
    // Rank 0 writes the file: this rank's share goes to it, whether or not its writing failed
    // (the messages are the same either way, so no rank can be left waiting).
    send_vector(comm_, share.chunks);
    send_vector(comm_, share.bytes);
    send_vector(comm_, share.parts);
    send_vector(comm_, share.values);
    return;
  }
  Handle dset;
  on_root(name.c_str(),
          [&] { dset = create_chunked<T>(file_.get(), lcpl_.get(), name, global_n, chunk); });
  // Chunks covered in part by a rank's share, filled from every rank's raw values.
  std::map<std::uint64_t, std::vector<T>> partial;
  const auto store = [&](const Share<T>& sh) {
    on_root(name.c_str(), [&] {
      std::uint64_t at = 0;
      for (std::size_t i = 0; i + 1 < sh.chunks.size(); i += 2) {
        const hsize_t offset[1] = {sh.chunks[i] * chunk};
        check(H5Dwrite_chunk(dset.get(), H5P_DEFAULT, 0, offset, sh.chunks[i + 1],
                             sh.bytes.data() + at),
              "write dataset " + name);
        at += sh.chunks[i + 1];
      }
    });
    std::uint64_t pos = 0;
    for (std::size_t i = 0; i + 1 < sh.parts.size(); i += 2) {
      const std::uint64_t c = sh.parts[i] / chunk;
      std::vector<T>& buf = partial[c];
      buf.resize(std::min(chunk, global_n - c * chunk));
      std::copy_n(sh.values.begin() + static_cast<std::ptrdiff_t>(pos), sh.parts[i + 1],
                  buf.begin() + static_cast<std::ptrdiff_t>(sh.parts[i] - c * chunk));
      pos += sh.parts[i + 1];
    }
  };
  store(share);
  share = Share<T>();
  for (int r = 1; r < size; ++r) {
    Share<T> sh;
    sh.chunks = receive_vector<std::uint64_t>(comm_, r);
    sh.bytes = receive_vector<char>(comm_, r);
    sh.parts = receive_vector<std::uint64_t>(comm_, r);
    sh.values = receive_vector<T>(comm_, r);
    store(sh);
  }
  on_root(name.c_str(), [&] {
    for (const auto& [c, values] : partial) {
      const std::string e = encode_chunk(std::span<const T>(values), chunk, kDeflateLevel);
      const hsize_t offset[1] = {c * chunk};
      check(H5Dwrite_chunk(dset.get(), H5P_DEFAULT, 0, offset, e.size(), e.data()),
            "write dataset " + name);
    }
    Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    Handle attr(check(H5Acreate2(dset.get(), "hash64", H5T_NATIVE_UINT64, space.get(), H5P_DEFAULT,
                                 H5P_DEFAULT),
                      "create attribute hash64 of " + name),
                H5Aclose);
    check(H5Awrite(attr.get(), H5T_NATIVE_UINT64, &total), "write attribute hash64 of " + name);
    check(attr.close(), "close attribute hash64 of " + name);
    check(dset.close(), "close dataset " + name);
  });
}

template <Element T>
void File::write_from_root(const std::string& name, std::uint64_t n, const T* data) {
  const Block whole{0, n};
  const bool mine = rank_ == 0 && n > 0;
  write_blocks<T>(name, n, mine ? std::span<const Block>(&whole, 1) : std::span<const Block>(),
                  data);
}

void File::flush() {
  // The file is in memory until close(): what a crash would leave is an empty file.
  on_root("flush", [&] { check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "H5Fflush " + path_); });
}

void File::close() {
  if (comm_ == MPI_COMM_NULL) {  // opened for reading
    file_ = Handle();
    return;
  }
  lcpl_.reset();
  on_root("close", [&] {
    if (!file_.valid()) return;
    check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "H5Fflush " + path_);
    const ssize_t n = check(H5Fget_file_image(file_.get(), nullptr, 0), "H5Fget_file_image");
    std::string image(static_cast<std::size_t>(n), '\0');
    check(H5Fget_file_image(file_.get(), image.data(), image.size()), "H5Fget_file_image");
    check(file_.close(), "H5Fclose " + path_);
    common::write_new_file(path_, image);
  });
  agree();
  file_ = Handle();
}

// ---------------------------------------------------------------- reading

void File::fail(const std::string& message) const {
  throw common::InputError(what_ + " " + path_ + ": " + message);
}

bool File::exists(const std::string& name) const {
  // H5Lexists needs every group on the way to exist.
  std::string partial;
  std::istringstream in(name);
  std::string part;
  while (std::getline(in, part, '/')) {
    if (part.empty()) continue;
    partial += "/" + part;
    if (H5Lexists(file_.get(), partial.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return !partial.empty();
}

namespace {

// An attribute holding one value (a scalar or a one-element array): H5Aread writes every element,
// so an array attribute read into one value would overrun it.
void check_single(const File& f, hid_t attribute, const char* name) {
  Handle space(attribute >= 0 ? H5Aget_space(attribute) : -1, H5Sclose);
  const hssize_t n = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
  if (n != 1) {
    f.fail("attribute /" + std::string(name) + " holds " + std::to_string(n) + " values, not one");
  }
}

template <class T>
T read_attribute(const File& f, hid_t file, const char* name, hid_t type) {
  if (H5Aexists(file, name) <= 0) f.fail("attribute /" + std::string(name) + " is missing");
  Handle a(H5Aopen(file, name, H5P_DEFAULT), H5Aclose);
  check_single(f, a.get(), name);
  T v{};
  if (!a.valid() || H5Aread(a.get(), type, &v) < 0)
    f.fail("attribute /" + std::string(name) + " cannot be read as the expected type");
  return v;
}

}  // namespace

std::int64_t File::attribute_i64(const char* name) const {
  return read_attribute<std::int64_t>(*this, file_.get(), name, H5T_NATIVE_INT64);
}

double File::attribute_f64(const char* name) const {
  return read_attribute<double>(*this, file_.get(), name, H5T_NATIVE_DOUBLE);
}

std::string File::attribute_string(const char* name) const {
  if (H5Aexists(file_.get(), name) <= 0) fail("attribute /" + std::string(name) + " is missing");
  Handle a(H5Aopen(file_.get(), name, H5P_DEFAULT), H5Aclose);
  Handle t(a.valid() ? H5Aget_type(a.get()) : -1, H5Tclose);
  if (!t.valid() || H5Tget_class(t.get()) != H5T_STRING)
    fail("attribute /" + std::string(name) + " is not a string");
  check_single(*this, a.get(), name);
  if (H5Tis_variable_str(t.get()) > 0) {
    // A variable-length string (h5py's default, and /format of results.h5): read as a C string.
    Handle m(H5Tcopy(H5T_C_S1), H5Tclose);
    char* c = nullptr;
    if (!m.valid() || H5Tset_size(m.get(), H5T_VARIABLE) < 0 ||
        H5Tset_cset(m.get(), H5Tget_cset(t.get())) < 0 || H5Aread(a.get(), m.get(), &c) < 0)
      fail("attribute /" + std::string(name) + " unreadable");
    std::string s = c != nullptr ? std::string(c) : std::string();
    H5free_memory(c);
    return s;
  }
  std::string s(H5Tget_size(t.get()), '\0');
  if (H5Aread(a.get(), t.get(), s.data()) < 0)
    fail("attribute /" + std::string(name) + " unreadable");
  s.erase(std::find(s.begin(), s.end(), '\0'), s.end());
  return s;
}

template <Element T>
Handle File::open_dataset(const std::string& name, std::uint64_t& n) const {
  if (!exists(name)) fail("dataset " + name + " is missing");
  Handle d(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) fail("dataset " + name + " cannot be opened");
  Handle t(H5Dget_type(d.get()), H5Tclose);
  const H5T_class_t want = std::is_floating_point_v<T> ? H5T_FLOAT : H5T_INTEGER;
  if (H5Tget_class(t.get()) != want || H5Tget_size(t.get()) != sizeof(T)) {
    fail("dataset " + name + " has the wrong element type (expected " +
         (std::is_floating_point_v<T> ? std::string("64-bit float")
                                      : std::to_string(8 * sizeof(T)) + "-bit integer") +
         ")");
  }
  Handle s(H5Dget_space(d.get()), H5Sclose);
  if (H5Sget_simple_extent_ndims(s.get()) != 1) fail("dataset " + name + " is not one-dimensional");
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(s.get(), dims, nullptr);
  n = dims[0];
  // What the file stores of a dataset bounds what it can hold: our datasets are deflated, and
  // zlib inflates at most 1032-fold. A dataset claiming more (an unwritten extent of 1e11 values,
  // say) is damaged or foreign, and reading it would first allocate its claimed size
  // (std::bad_alloc, a crash instead of an error).
  constexpr std::uint64_t kMaxInflation = 1032;
  constexpr std::uint64_t kSlack = 65536;
  const auto stored = static_cast<std::uint64_t>(H5Dget_storage_size(d.get()));
  const std::uint64_t limit = kMaxInflation * stored + kSlack;
  if (n > limit / sizeof(T)) {
    fail("dataset " + name + " claims " + std::to_string(n) + " values, more than the " +
         std::to_string(stored) +
         " bytes the file stores of it can hold: damaged, or not "
         "written by mpmxdem");
  }
  return d;
}

std::uint64_t File::stored_checksum(hid_t dset, const std::string& name) const {
  if (H5Aexists(dset, "hash64") <= 0) fail("dataset " + name + ": attribute hash64 is missing");
  Handle a(H5Aopen(dset, "hash64", H5P_DEFAULT), H5Aclose);
  std::uint64_t h = 0;
  if (!a.valid() || H5Aread(a.get(), H5T_NATIVE_UINT64, &h) < 0)
    fail("dataset " + name + ": attribute hash64 unreadable");
  return h;
}

template <Element T>
std::vector<T> File::read(const std::string& name) const {
  std::uint64_t n = 0;
  const Handle d = open_dataset<T>(name, n);
  std::vector<T> v(n);
  if (n > 0 && H5Dread(d.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    fail("dataset " + name + " cannot be read (damaged data)");
  const std::uint64_t stored = stored_checksum(d.get(), name);
  const std::uint64_t computed = checksum(std::span<const T>(v), 0);
  if (stored != computed) {
    fail("dataset " + name + ": checksum mismatch (stored " + hex(stored) + ", computed " +
         hex(computed) + "): the file is damaged");
  }
  return v;
}

template <Element T>
std::vector<T> File::read_blocks(const std::string& name, std::span<const Block> blocks,
                                 std::uint64_t& partial, std::uint64_t& stored) const {
  std::uint64_t n = 0;
  const Handle d = open_dataset<T>(name, n);
  stored = stored_checksum(d.get(), name);
  for (const Block& b : blocks) {
    if (b.offset + b.count > n) fail("dataset " + name + " is shorter than its counts say");
  }
  const std::uint64_t local_n = total_count(blocks);
  std::vector<T> v(local_n);
  if (local_n == 0) return v;
  Handle fspace(H5Dget_space(d.get()), H5Sclose);
  select_blocks(fspace.get(), blocks);
  const hsize_t mdims[1] = {local_n};
  Handle mspace(H5Screate_simple(1, mdims, nullptr), H5Sclose);
  if (H5Dread(d.get(), native_type<T>(), mspace.get(), fspace.get(), H5P_DEFAULT, v.data()) < 0)
    fail("dataset " + name + " cannot be read (damaged data)");
  partial += checksum(blocks, v.data());
  return v;
}

#define MPMXDEM_H5_FILE_INSTANTIATE(T)                                                           \
  template void File::write_blocks<T>(const std::string&, std::uint64_t, std::span<const Block>, \
                                      const T*);                                                 \
  template void File::write_from_root<T>(const std::string&, std::uint64_t, const T*);           \
  template std::vector<T> File::read<T>(const std::string&) const;                               \
  template std::vector<T> File::read_blocks<T>(const std::string&, std::span<const Block>,       \
                                               std::uint64_t&, std::uint64_t&) const;
MPMXDEM_H5_FILE_INSTANTIATE(double)
MPMXDEM_H5_FILE_INSTANTIATE(std::int64_t)
MPMXDEM_H5_FILE_INSTANTIATE(std::uint8_t)
#undef MPMXDEM_H5_FILE_INSTANTIATE

}  // namespace farm::h5
