// Collective HDF5 checkpoints of the farm: writer, verified readers, inspection (see header).
#include "farm/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "common/errors.hpp"
#include "farm/h5_util.hpp"
#include "farm/mpi_util.hpp"

namespace farm {

namespace {

using h5::check;
using h5::Handle;

struct Block {
  std::uint64_t off = 0;
  std::uint64_t cnt = 0;
};

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

/// Checksum of elements (each zero-extended to a 64-bit word) at global positions first...
template <class T>
std::uint64_t hash_elems(const T* data, std::size_t n, std::uint64_t first) {
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t w = 0;
    std::memcpy(&w, data + i, sizeof(T));
    sum += splitmix64(w ^ splitmix64(first + i));
  }
  return sum;
}

template <class T>
std::uint64_t hash_blocks(const std::vector<Block>& blocks, const T* data) {
  std::uint64_t sum = 0;
  std::size_t pos = 0;
  for (const Block& b : blocks) {
    sum += hash_elems(data + pos, b.cnt, b.off);
    pos += b.cnt;
  }
  return sum;
}

std::string hex(std::uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// ---------------------------------------------------------------- writing (collective)

void attr_write(hid_t obj, const char* name, hid_t type, const void* value) {
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
  Handle attr(check(H5Acreate2(obj, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                    std::string("create attribute ") + name),
              H5Aclose);
  check(H5Awrite(attr.get(), type, value), std::string("write attribute ") + name);
}

void attr_string(hid_t obj, const char* name, const std::string& value) {
  Handle type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  check(H5Tset_size(type.get(), std::max<std::size_t>(1, value.size())), "H5Tset_size");
  std::string v = value.empty() ? std::string(1, '\0') : value;
  attr_write(obj, name, type.get(), v.data());
}

class Writer {
 public:
  Writer(MPI_Comm comm, hid_t file) : comm_(comm), file_(file) {
    lcpl_ = Handle(check(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate"), H5Pclose);
    check(H5Pset_create_intermediate_group(lcpl_.get(), 1), "H5Pset_create_intermediate_group");
    dxpl_ = Handle(check(H5Pcreate(H5P_DATASET_XFER), "H5Pcreate"), H5Pclose);
    check(H5Pset_dxpl_mpio(dxpl_.get(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
  }

  /// Collective: dataset `name` of global_n elements; this rank writes `blocks` (ascending,
  /// disjoint) from `data` (their concatenation). Adds the attribute hash64.
  template <class T>
  void write(const std::string& name, std::uint64_t global_n, const std::vector<Block>& blocks,
             const T* data) {
    std::uint64_t local = hash_blocks(blocks, data);
    std::uint64_t total = 0;
    MPI_Allreduce(&local, &total, 1, MPI_UINT64_T, MPI_SUM, comm_);
    const hsize_t dims[1] = {global_n};
    Handle fspace(check(H5Screate_simple(1, dims, nullptr), "H5Screate_simple"), H5Sclose);
    Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
    if (global_n > 0) {
      const hsize_t chunk[1] = {std::min<hsize_t>(global_n, hsize_t{1} << 16U)};
      check(H5Pset_chunk(dcpl.get(), 1, chunk), "H5Pset_chunk " + name);
      check(H5Pset_shuffle(dcpl.get()), "H5Pset_shuffle");
      check(H5Pset_deflate(dcpl.get(), 4), "H5Pset_deflate");
    }
    Handle dset(check(H5Dcreate2(file_, name.c_str(), h5::native_type<T>(), fspace.get(),
                                 lcpl_.get(), dcpl.get(), H5P_DEFAULT),
                      "create dataset " + name),
                H5Dclose);
    if (global_n > 0) {
      std::uint64_t local_n = 0;
      for (const Block& b : blocks) local_n += b.cnt;
      const hsize_t mdims[1] = {local_n};
      Handle mspace(check(H5Screate_simple(1, mdims, nullptr), "H5Screate_simple"), H5Sclose);
      if (local_n == 0) {
        check(H5Sselect_none(fspace.get()), "H5Sselect_none");
        check(H5Sselect_none(mspace.get()), "H5Sselect_none");
      } else {
        bool first = true;
        for (const Block& b : blocks) {
          if (b.cnt == 0) continue;
          const hsize_t start[1] = {b.off};
          const hsize_t count[1] = {b.cnt};
          check(H5Sselect_hyperslab(fspace.get(), first ? H5S_SELECT_SET : H5S_SELECT_OR, start,
                                    nullptr, count, nullptr),
                "H5Sselect_hyperslab");
          first = false;
        }
      }
      const T dummy{};
      check(H5Dwrite(dset.get(), h5::native_type<T>(), mspace.get(), fspace.get(), dxpl_.get(),
                     local_n == 0 ? &dummy : data),
            "write dataset " + name);
    }
    attr_write(dset.get(), "hash64", H5T_NATIVE_UINT64, &total);
  }

  /// Collective: rank 0 writes the whole of `v` (identical sizes known everywhere).
  template <class T>
  void write_root(const std::string& name, const std::vector<T>& v, bool is_root) {
    std::vector<Block> blocks;
    if (is_root && !v.empty()) blocks.push_back({0, v.size()});
    write(name, v.size(), blocks, v.data());
  }

 private:
  MPI_Comm comm_;
  hid_t file_;
  Handle lcpl_;
  Handle dxpl_;
};

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

std::string join_lines(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& s : v) out += s + "\n";
  return out;
}

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) out.push_back(line);
  }
  return out;
}

/// "f:name" or "i:name" for every field of a store.
std::vector<std::string> typed_names(const common::StateStore& s) {
  std::vector<std::string> out;
  for (const auto& [name, field] : s.fields())
    out.push_back((field.index() == 0 ? "f:" : "i:") + name);
  return out;
}

void fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) throw common::InputError("checkpoint " + path + ": cannot open for fsync");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw common::InputError("checkpoint " + path + ": fsync failed");
}

template <class T>
std::vector<T> field_values(const common::StateStore& s, const std::string& name) {
  auto it = s.fields().find(name);
  if (it == s.fields().end()) return {};
  return std::get<std::vector<T>>(it->second);
}

template <class T>
void write_rve_field(Writer& w, MPI_Comm comm, const CheckpointData& d, const std::string& name,
                     bool is_root) {
  const std::size_t n = d.ids.size();
  // counts + 1 per owned RVE (0: absent), summed over ranks.
  std::vector<std::int64_t> c1(n, 0);
  std::vector<std::vector<T>> values(d.local_indices.size());
  for (std::size_t j = 0; j < d.local_indices.size(); ++j) {
    const auto k = static_cast<std::size_t>(d.local_indices[j]);
    if (d.local_states[j].has(name)) {
      values[j] = field_values<T>(d.local_states[j], name);
      c1[k] = static_cast<std::int64_t>(values[j].size()) + 1;
    }
  }
  std::vector<std::int64_t> counts(n, 0);
  MPI_Allreduce(c1.data(), counts.data(), to_count(n), MPI_INT64_T, MPI_SUM, comm);
  std::vector<std::uint64_t> offset(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    counts[k] -= 1;
    offset[k + 1] = offset[k] + static_cast<std::uint64_t>(std::max<std::int64_t>(0, counts[k]));
  }
  w.write_root("/rve/counts/" + name, counts, is_root);
  std::vector<Block> blocks;
  std::vector<T> data;
  for (std::size_t j = 0; j < d.local_indices.size(); ++j) {
    const auto k = static_cast<std::size_t>(d.local_indices[j]);
    if (values[j].empty()) continue;
    blocks.push_back({offset[k], values[j].size()});
    data.insert(data.end(), values[j].begin(), values[j].end());
  }
  w.write("/rve/fields/" + name, offset[n], blocks, data.data());
}

// ---------------------------------------------------------------- reading (serial per rank)

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    h5::silence_errors();
    if (!std::filesystem::exists(path)) fail("the file does not exist");
    const htri_t is = H5Fis_hdf5(path.c_str());
    if (is <= 0) fail("is not an HDF5 file (damaged, truncated or not a checkpoint)");
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) fail("cannot be opened as HDF5 (damaged or truncated)");
    file_ = Handle(f, H5Fclose);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw common::InputError("checkpoint " + path_ + ": " + what);
  }

  [[nodiscard]] bool exists(const std::string& name) const {
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

  [[nodiscard]] bool has_attr(const char* name) const { return H5Aexists(file_.get(), name) > 0; }

  template <class T>
  T attr(const char* name, hid_t type) const {
    if (!has_attr(name)) fail("attribute /" + std::string(name) + " is missing");
    Handle a(H5Aopen(file_.get(), name, H5P_DEFAULT), H5Aclose);
    T v{};
    if (!a.valid() || H5Aread(a.get(), type, &v) < 0) {
      fail("attribute /" + std::string(name) + " cannot be read as the expected type");
    }
    return v;
  }

  [[nodiscard]] std::string attr_string(const char* name) const {
    if (!has_attr(name)) fail("attribute /" + std::string(name) + " is missing");
    Handle a(H5Aopen(file_.get(), name, H5P_DEFAULT), H5Aclose);
    Handle t(a.valid() ? H5Aget_type(a.get()) : -1, H5Tclose);
    if (!t.valid() || H5Tget_class(t.get()) != H5T_STRING) {
      fail("attribute /" + std::string(name) + " is not a string");
    }
    std::string s(H5Tget_size(t.get()), '\0');
    if (H5Aread(a.get(), t.get(), s.data()) < 0)
      fail("attribute /" + std::string(name) + " unreadable");
    s.erase(std::find(s.begin(), s.end(), '\0'), s.end());
    return s;
  }

  /// Opens a dataset checking presence, rank and type; returns its size.
  template <class T>
  Handle open(const std::string& name, std::uint64_t& n) const {
    if (!exists(name)) fail("dataset " + name + " is missing");
    Handle d(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail("dataset " + name + " cannot be opened");
    Handle t(H5Dget_type(d.get()), H5Tclose);
    const H5T_class_t cls = H5Tget_class(t.get());
    const H5T_class_t want = std::is_floating_point_v<T> ? H5T_FLOAT : H5T_INTEGER;
    if (cls != want || H5Tget_size(t.get()) != sizeof(T)) {
      fail("dataset " + name + " has the wrong element type (expected " +
           (std::is_floating_point_v<T> ? std::string("64-bit float")
                                        : std::to_string(8 * sizeof(T)) + "-bit integer") +
           ")");
    }
    Handle s(H5Dget_space(d.get()), H5Sclose);
    if (H5Sget_simple_extent_ndims(s.get()) != 1)
      fail("dataset " + name + " is not one-dimensional");
    hsize_t dims[1] = {0};
    H5Sget_simple_extent_dims(s.get(), dims, nullptr);
    n = dims[0];
    return d;
  }

  std::uint64_t stored_hash(hid_t dset, const std::string& name) const {
    if (H5Aexists(dset, "hash64") <= 0) fail("dataset " + name + ": attribute hash64 is missing");
    Handle a(H5Aopen(dset, "hash64", H5P_DEFAULT), H5Aclose);
    std::uint64_t h = 0;
    if (!a.valid() || H5Aread(a.get(), H5T_NATIVE_UINT64, &h) < 0) {
      fail("dataset " + name + ": attribute hash64 unreadable");
    }
    return h;
  }

  /// Whole dataset, checksum verified.
  template <class T>
  std::vector<T> read(const std::string& name) const {
    std::uint64_t n = 0;
    Handle d = open<T>(name, n);
    std::vector<T> v(n);
    if (n > 0 &&
        H5Dread(d.get(), h5::native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0) {
      fail("dataset " + name + " cannot be read (damaged data)");
    }
    const std::uint64_t stored = stored_hash(d.get(), name);
    const std::uint64_t computed = hash_elems(v.data(), v.size(), 0);
    if (stored != computed) {
      fail("dataset " + name + ": checksum mismatch (stored " + hex(stored) + ", computed " +
           hex(computed) + "): the file is damaged");
    }
    return v;
  }

  /// Blocks of a dataset; adds their partial checksum to `partial` and returns the stored one.
  template <class T>
  std::vector<T> read_blocks(const std::string& name, const std::vector<Block>& blocks,
                             std::uint64_t& partial, std::uint64_t& stored) const {
    std::uint64_t n = 0;
    Handle d = open<T>(name, n);
    stored = stored_hash(d.get(), name);
    std::uint64_t local_n = 0;
    for (const Block& b : blocks) {
      if (b.off + b.cnt > n) fail("dataset " + name + " is shorter than its counts say");
      local_n += b.cnt;
    }
    std::vector<T> v(local_n);
    if (local_n == 0) return v;
    Handle fspace(H5Dget_space(d.get()), H5Sclose);
    bool first = true;
    for (const Block& b : blocks) {
      if (b.cnt == 0) continue;
      const hsize_t start[1] = {b.off};
      const hsize_t count[1] = {b.cnt};
      H5Sselect_hyperslab(fspace.get(), first ? H5S_SELECT_SET : H5S_SELECT_OR, start, nullptr,
                          count, nullptr);
      first = false;
    }
    const hsize_t mdims[1] = {local_n};
    Handle mspace(H5Screate_simple(1, mdims, nullptr), H5Sclose);
    if (H5Dread(d.get(), h5::native_type<T>(), mspace.get(), fspace.get(), H5P_DEFAULT, v.data()) <
        0) {
      fail("dataset " + name + " cannot be read (damaged data)");
    }
    partial += hash_blocks(blocks, v.data());
    return v;
  }

  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
  Handle file_;
};

std::string strip_type(const std::string& typed) { return typed.substr(2); }

}  // namespace

std::uint64_t hash_words(const void* data, std::size_t n, std::uint64_t first) {
  return hash_elems(static_cast<const std::uint64_t*>(data), n, first);
}

std::string checkpoint_path(const std::string& dir, std::int64_t step) {
  char name[64];
  std::snprintf(name, sizeof name, "checkpoint_%010lld.h5", static_cast<long long>(step));
  return (std::filesystem::path(dir) / name).string();
}

std::vector<std::string> list_checkpoints(const std::string& dir) {
  // Names checkpoint_<digits>.h5 (no std::regex: its libstdc++ headers warn under sanitizers).
  const std::string head = "checkpoint_";
  const std::string tail = ".h5";
  std::vector<std::pair<std::int64_t, std::string>> found;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() <= head.size() + tail.size() || name.rfind(head, 0) != 0 ||
        name.compare(name.size() - tail.size(), tail.size(), tail) != 0) {
      continue;
    }
    const std::string digits = name.substr(head.size(), name.size() - head.size() - tail.size());
    if (digits.size() > 18 || !std::all_of(digits.begin(), digits.end(),
                                           [](char ch) { return ch >= '0' && ch <= '9'; })) {
      continue;
    }
    found.emplace_back(std::stoll(digits), e.path().string());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> out;
  for (auto& f : found) out.push_back(f.second);
  return out;
}

void write_checkpoint(MPI_Comm comm, const std::string& final_path, const CheckpointData& d,
                      bool abort_mid_write) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const bool root = rank == 0;
  MPMXDEM_CHECK(d.local_indices.size() == d.local_states.size(), "one state per local RVE");
  MPMXDEM_CHECK(!root || d.mpm != nullptr, "rank 0 holds the MPM state");
  h5::silence_errors();
  const std::string tmp = final_path + ".tmp";

  // Field lists: the union over all RVEs (sorted) and rank 0's MPM fields.
  std::set<std::string> mine;
  for (const common::StateStore& s : d.local_states) {
    for (std::string& t : typed_names(s)) mine.insert(std::move(t));
  }
  const std::vector<std::string> all =
      allgather_strings(comm, std::vector<std::string>(mine.begin(), mine.end()));
  const std::set<std::string> rve_set(all.begin(), all.end());
  const std::vector<std::string> rve_fields(rve_set.begin(), rve_set.end());
  std::string mpm_list = root ? join_lines(typed_names(*d.mpm)) : std::string();
  bcast_string(comm, mpm_list);
  std::string job = d.job_text;
  bcast_string(comm, job);

  // From here on, HDF5 collectives: a failure on one rank would leave the others waiting in a
  // collective, so it aborts the job (docs/architecture.md: a run never hangs).
  try {
    Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
    check(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), "H5Pset_fapl_mpio");
    Handle file(
        check(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "create " + tmp),
        H5Fclose);
    const hid_t f = file.get();
    attr_string(f, "format", kCheckpointFormat);
    const std::int64_t version = kCheckpointVersion;
    attr_write(f, "format_version", H5T_NATIVE_INT64, &version);
    attr_write(f, "step", H5T_NATIVE_INT64, &d.step);
    attr_write(f, "time", H5T_NATIVE_DOUBLE, &d.time);
    const std::int64_t nranks = size;
    attr_write(f, "nranks", H5T_NATIVE_INT64, &nranks);
    const auto n_rve = static_cast<std::int64_t>(d.ids.size());
    attr_write(f, "n_rve", H5T_NATIVE_INT64, &n_rve);

    Writer w(comm, f);
    w.write_root("/job", bytes_of(job), root);
    w.write_root("/rve/ids", d.ids, root);
    std::vector<std::int64_t> part(d.owner.begin(), d.owner.end());
    w.write_root("/rve/partition", part, root);
    w.write_root("/rve/cost", d.cost, root);
    w.write_root("/rve/field_names", bytes_of(join_lines(rve_fields)), root);
    w.write_root("/mpm/field_names", bytes_of(mpm_list), root);
    for (const std::string& typed : split_lines(mpm_list)) {
      const std::string name = strip_type(typed);
      if (typed[0] == 'f') {
        const auto v = root ? field_values<double>(*d.mpm, name) : std::vector<double>();
        std::uint64_t n = v.size();
        MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
        std::vector<Block> b;
        if (root && n > 0) b.push_back({0, n});
        w.write("/mpm/" + name, n, b, v.data());
      } else {
        const auto v =
            root ? field_values<std::int64_t>(*d.mpm, name) : std::vector<std::int64_t>();
        std::uint64_t n = v.size();
        MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
        std::vector<Block> b;
        if (root && n > 0) b.push_back({0, n});
        w.write("/mpm/" + name, n, b, v.data());
      }
    }
    if (abort_mid_write) {
      // Fault injection: die in the middle of the write, as a node failure would.
      H5Fflush(f, H5F_SCOPE_GLOBAL);
      MPI_Barrier(comm);
      if (root)
        std::cerr << "farm: fault injection: aborting in the middle of writing " << tmp << "\n";
      MPI_Abort(comm, 86);
    }
    for (const std::string& typed : rve_fields) {
      const std::string name = strip_type(typed);
      if (typed[0] == 'f') {
        write_rve_field<double>(w, comm, d, name, root);
      } else {
        write_rve_field<std::int64_t>(w, comm, d, name, root);
      }
    }
    file.reset();  // collective close: everything is on disk (up to the OS cache)
  } catch (const std::exception& e) {
    std::cerr << "farm: rank " << rank << ": writing checkpoint " << tmp << " failed: " << e.what()
              << "; aborting the job\n";
    MPI_Abort(comm, 4);
  }

  // Atomic publication: fsync the data, rename, fsync the directory.
  ErrorKind kind = ErrorKind::none;
  std::string msg;
  if (root) {
    try {
      fsync_path(tmp, false);
      std::error_code ec;
      std::filesystem::rename(tmp, final_path, ec);
      if (ec)
        throw common::InputError("checkpoint " + final_path + ": rename failed: " + ec.message());
      const std::filesystem::path dir = std::filesystem::path(final_path).parent_path();
      fsync_path(dir.empty() ? std::string(".") : dir.string(), true);
    } catch (...) {
      kind = current_error_kind();
      try {
        throw;
      } catch (const std::exception& e) {
        msg = e.what();
      }
    }
  }
  agree_on_errors(comm, kind, msg);
}

CheckpointInfo read_checkpoint_info(const std::string& path) {
  Reader r(path);
  CheckpointInfo info;
  info.path = path;
  const std::string format = r.attr_string("format");
  if (format != kCheckpointFormat) {
    r.fail("attribute /format = '" + format + "': not a farm checkpoint (expected '" +
           kCheckpointFormat + "')");
  }
  info.version = r.attr<std::int64_t>("format_version", H5T_NATIVE_INT64);
  if (info.version != kCheckpointVersion) {
    r.fail("attribute /format_version = " + std::to_string(info.version) +
           ": this build reads version " + std::to_string(kCheckpointVersion) + " only");
  }
  info.step = r.attr<std::int64_t>("step", H5T_NATIVE_INT64);
  info.time = r.attr<double>("time", H5T_NATIVE_DOUBLE);
  info.nranks = r.attr<std::int64_t>("nranks", H5T_NATIVE_INT64);
  const auto n_rve = r.attr<std::int64_t>("n_rve", H5T_NATIVE_INT64);
  const auto job = r.read<std::uint8_t>("/job");
  info.job_text.assign(job.begin(), job.end());
  info.ids = r.read<std::int64_t>("/rve/ids");
  if (static_cast<std::int64_t>(info.ids.size()) != n_rve) {
    r.fail("dataset /rve/ids has " + std::to_string(info.ids.size()) +
           " entries, attribute /n_rve says " + std::to_string(n_rve));
  }
  const auto part = r.read<std::int64_t>("/rve/partition");
  info.cost = r.read<double>("/rve/cost");
  if (part.size() != info.ids.size() || info.cost.size() != info.ids.size()) {
    r.fail("datasets /rve/partition and /rve/cost must have one entry per RVE");
  }
  for (std::int64_t o : part) {
    if (o < 0 || o >= info.nranks) r.fail("dataset /rve/partition holds rank " + std::to_string(o));
  }
  info.partition.assign(part.begin(), part.end());
  const auto rf = r.read<std::uint8_t>("/rve/field_names");
  const auto mf = r.read<std::uint8_t>("/mpm/field_names");
  info.rve_fields = split_lines(std::string(rf.begin(), rf.end()));
  info.mpm_fields = split_lines(std::string(mf.begin(), mf.end()));
  for (const std::string& t : info.rve_fields) {
    if (t.size() < 3 || (t[0] != 'f' && t[0] != 'i') || t[1] != ':')
      r.fail("dataset /rve/field_names is malformed");
    if (!r.exists("/rve/fields/" + strip_type(t)))
      r.fail("dataset /rve/fields/" + strip_type(t) + " is missing");
    if (!r.exists("/rve/counts/" + strip_type(t)))
      r.fail("dataset /rve/counts/" + strip_type(t) + " is missing");
  }
  for (const std::string& t : info.mpm_fields) {
    if (t.size() < 3 || (t[0] != 'f' && t[0] != 'i') || t[1] != ':')
      r.fail("dataset /mpm/field_names is malformed");
    if (!r.exists("/mpm/" + strip_type(t))) r.fail("dataset /mpm/" + strip_type(t) + " is missing");
  }
  return info;
}

common::StateStore read_checkpoint_mpm(const std::string& path) {
  const CheckpointInfo info = read_checkpoint_info(path);
  Reader r(path);
  common::StateStore s;
  for (const std::string& t : info.mpm_fields) {
    const std::string name = strip_type(t);
    if (t[0] == 'f') {
      s.write(name, r.read<double>("/mpm/" + name));
    } else {
      s.write(name, r.read<std::int64_t>("/mpm/" + name));
    }
  }
  return s;
}

namespace {

template <class T>
void read_rve_field(const Reader& r, const std::string& name,
                    const std::vector<std::int64_t>& local, std::vector<common::StateStore>& out,
                    std::uint64_t& partial, std::uint64_t& stored) {
  const auto counts = r.read<std::int64_t>("/rve/counts/" + name);
  const std::size_t n = counts.size();
  std::vector<std::uint64_t> offset(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    offset[k + 1] = offset[k] + static_cast<std::uint64_t>(std::max<std::int64_t>(0, counts[k]));
  }
  std::vector<Block> blocks;
  for (std::int64_t k : local) {
    if (k < 0 || static_cast<std::size_t>(k) >= n) {
      r.fail("dataset /rve/counts/" + name + " has fewer entries than there are RVEs");
    }
    const auto c = counts[static_cast<std::size_t>(k)];
    if (c > 0)
      blocks.push_back({offset[static_cast<std::size_t>(k)], static_cast<std::uint64_t>(c)});
  }
  const std::vector<T> v = r.read_blocks<T>("/rve/fields/" + name, blocks, partial, stored);
  std::size_t pos = 0;
  for (std::size_t j = 0; j < local.size(); ++j) {
    const auto c = counts[static_cast<std::size_t>(local[j])];
    if (c < 0) continue;  // absent in this RVE
    out[j].write(name, std::span<const T>(v.data() + pos, static_cast<std::size_t>(c)));
    pos += static_cast<std::size_t>(c);
  }
}

}  // namespace

std::vector<common::StateStore> read_checkpoint_rves(MPI_Comm comm, const CheckpointInfo& info,
                                                     const std::vector<std::int64_t>& local) {
  std::vector<common::StateStore> out(local.size());
  const std::size_t nf = info.rve_fields.size();
  std::vector<std::uint64_t> partial(nf, 0);
  std::vector<std::uint64_t> stored(nf, 0);
  ErrorKind kind = ErrorKind::none;
  std::string msg;
  try {
    Reader r(info.path);
    for (std::size_t i = 0; i < nf; ++i) {
      const std::string& t = info.rve_fields[i];
      if (t[0] == 'f') {
        read_rve_field<double>(r, strip_type(t), local, out, partial[i], stored[i]);
      } else {
        read_rve_field<std::int64_t>(r, strip_type(t), local, out, partial[i], stored[i]);
      }
    }
  } catch (...) {
    kind = current_error_kind();
    try {
      throw;
    } catch (const std::exception& e) {
      msg = e.what();
    }
  }
  agree_on_errors(comm, kind, msg);
  std::vector<std::uint64_t> total(nf, 0);
  MPI_Allreduce(partial.data(), total.data(), to_count(nf), MPI_UINT64_T, MPI_SUM, comm);
  for (std::size_t i = 0; i < nf; ++i) {
    if (total[i] != stored[i]) {
      throw common::InputError("checkpoint " + info.path + ": dataset /rve/fields/" +
                               strip_type(info.rve_fields[i]) + ": checksum mismatch (stored " +
                               hex(stored[i]) + ", computed " + hex(total[i]) +
                               "): the file is damaged");
    }
  }
  return out;
}

void verify_checkpoint(const std::string& path) {
  const CheckpointInfo info = read_checkpoint_info(path);
  (void)read_checkpoint_mpm(path);
  Reader r(path);
  for (const std::string& t : info.rve_fields) {
    const std::string name = strip_type(t);
    (void)r.read<std::int64_t>("/rve/counts/" + name);
    if (t[0] == 'f') {
      (void)r.read<double>("/rve/fields/" + name);
    } else {
      (void)r.read<std::int64_t>("/rve/fields/" + name);
    }
  }
}

std::string describe(const CheckpointInfo& info) {
  std::ostringstream os;
  os.precision(17);
  os << "checkpoint " << info.path << "\n"
     << "  format        " << kCheckpointFormat << " version " << info.version << "\n"
     << "  step          " << info.step << "\n"
     << "  time          " << info.time << " s\n"
     << "  RVEs          " << info.ids.size() << "\n"
     << "  written by    " << info.nranks << " rank(s); RVEs per rank:";
  std::map<int, int> per;
  for (int o : info.partition) ++per[o];
  for (std::int64_t r = 0; r < info.nranks; ++r) os << " " << per[static_cast<int>(r)];
  os << "\n  RVE fields    " << info.rve_fields.size() << ":";
  for (const std::string& f : info.rve_fields) os << " " << f.substr(2);
  os << "\n  MPM fields    " << info.mpm_fields.size() << ":";
  for (const std::string& f : info.mpm_fields) os << " " << f.substr(2);
  const std::string first = info.job_text.substr(0, info.job_text.find('\n'));
  os << "\n  job text      " << info.job_text.size() << " bytes; first line: " << first << "\n";
  return os.str();
}

}  // namespace farm
