// Farm checkpoints: the format (what goes where, docs/reference/checkpoint.md) on top of the typed
// HDF5 layer (farm/h5_file.hpp: blocks with checksums) and the atomic publication
// (common/atomic_file.hpp).
#include "farm/checkpoint.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>
#include <variant>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "farm/h5_file.hpp"
#include "farm/mpi_util.hpp"

namespace farm {

namespace {

using Field = common::StateStore::Field;

/// One entry of /rve/field_names or /mpm/field_names. In the file a line "f:<name>" (64-bit
/// float) or "i:<name>" (64-bit integer); here the name and an empty Field whose alternative is
/// the element type, so that every use dispatches with std::visit (with_type).
struct FieldSpec {
  std::string name;
  Field type;
};

/// Calls f(std::type_identity<T>{}) with the element type T of `type`.
template <class F>
decltype(auto) with_type(const Field& type, F&& f) {
  return std::visit(
      [&f](const auto& v) -> decltype(auto) {
        return f(std::type_identity<typename std::decay_t<decltype(v)>::value_type>{});
      },
      type);
}

/// The listed form of a field: its type letter, ':' and its name.
std::string listed(const std::string& name, const Field& type) {
  return with_type(type, [&name]<class T>(std::type_identity<T>) {
    return std::string(std::is_same_v<T, double> ? "f:" : "i:") + name;
  });
}

/// Inverse of listed(); nullopt for a malformed line.
std::optional<FieldSpec> parse_listed(const std::string& line) {
  if (line.size() < 3 || line[1] != ':') return std::nullopt;
  for (const Field& type : {Field(std::vector<double>()), Field(std::vector<std::int64_t>())}) {
    if (listed(line.substr(2), type) == line) return FieldSpec{line.substr(2), type};
  }
  return std::nullopt;
}

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

std::vector<std::string> listed_fields(const common::StateStore& s) {
  std::vector<std::string> out;
  for (const auto& [name, field] : s.fields()) out.push_back(listed(name, field));
  return out;
}

/// Parses a field list read from `file`; fail()s on a malformed line.
std::vector<FieldSpec> parse_fields(const h5::File& file, const std::vector<std::string>& lines,
                                    const std::string& dataset) {
  std::vector<FieldSpec> out;
  for (const std::string& line : lines) {
    std::optional<FieldSpec> f = parse_listed(line);
    if (!f) file.fail("dataset " + dataset + " is malformed");
    out.push_back(std::move(*f));
  }
  return out;
}

/// Parses a field list this program wrote (or read_checkpoint_info checked).
std::vector<FieldSpec> parse_fields(const std::vector<std::string>& lines) {
  std::vector<FieldSpec> out;
  for (const std::string& line : lines) {
    std::optional<FieldSpec> f = parse_listed(line);
    MPMXDEM_CHECK(f.has_value(), "field list entry '" + line + "'");
    out.push_back(std::move(*f));
  }
  return out;
}

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

/// Offsets of every RVE's values in /rve/fields/<name> from /rve/counts/<name> (-1: absent).
std::vector<std::uint64_t> offsets_of(const std::vector<std::int64_t>& counts) {
  std::vector<std::uint64_t> offset(counts.size() + 1, 0);
  for (std::size_t k = 0; k < counts.size(); ++k) {
    offset[k + 1] = offset[k] + static_cast<std::uint64_t>(std::max<std::int64_t>(0, counts[k]));
  }
  return offset;
}

constexpr auto kIntMax = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

/// The RVE indices whose values rank r writes: [n r / size, n (r + 1) / size).
std::size_t run_begin(std::size_t n, int r, int size) {
  return n * static_cast<std::size_t>(r) / static_cast<std::size_t>(size);
}

/// Collective: the values of this rank's RVEs (`local`, ascending indices; `values`, null where
/// absent) sent to the ranks that write them, so that rank r holds the values of RVE indices
/// [run_begin(r), run_begin(r + 1)) in index order: one contiguous run of /rve/fields/<name>.
/// A selection of one block per rank makes the collective write cost the same whatever the
/// owners; with METIS's interleaved owners, one block per RVE made it grow with the square of
/// the RVEs per rank (docs/validation/scaling.md, finding 4). Returns false (nothing sent) on one
/// rank (its blocks are one run already) and where a rank would send or receive more than INT_MAX
/// values (MPI's int counts): the caller then writes the blocks of its own RVEs.
template <class T>
bool gather_runs(MPI_Comm comm, const std::vector<int>& owner,
                 const std::vector<std::int64_t>& counts, const std::vector<std::uint64_t>& offset,
                 const std::vector<std::int64_t>& local,
                 const std::vector<const std::vector<T>*>& values, std::vector<T>& run) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) return false;
  const std::size_t n = counts.size();
  const auto nr = static_cast<std::size_t>(size);
  auto count_of = [&](std::size_t k) {
    return static_cast<std::uint64_t>(std::max<std::int64_t>(0, counts[k]));
  };
  // Values to every rank (local indices ascending, so each rank's share is contiguous).
  std::vector<std::uint64_t> send(nr, 0);
  std::vector<T> out;
  int dest = 0;
  for (std::size_t j = 0; j < local.size(); ++j) {
    const auto k = static_cast<std::size_t>(local[j]);
    while (k >= run_begin(n, dest + 1, size)) ++dest;
    if (values[j] == nullptr) continue;
    send[static_cast<std::size_t>(dest)] += values[j]->size();
    out.insert(out.end(), values[j]->begin(), values[j]->end());
  }
  // Values from every rank: the RVEs of my run that rank owns.
  const std::size_t k_lo = run_begin(n, rank, size);
  const std::size_t k_hi = run_begin(n, rank + 1, size);
  std::vector<std::uint64_t> recv(nr, 0);
  for (std::size_t k = k_lo; k < k_hi; ++k) recv[static_cast<std::size_t>(owner[k])] += count_of(k);
  // Counts and displacements are ints of the element type: exchange only where they fit.
  std::vector<int> sc(nr), sd(nr), rc(nr), rd(nr);
  std::uint64_t sp = 0;
  std::uint64_t rp = 0;
  for (std::size_t r = 0; r < nr; ++r) {
    sc[r] = static_cast<int>(std::min<std::uint64_t>(send[r], kIntMax));
    rc[r] = static_cast<int>(std::min<std::uint64_t>(recv[r], kIntMax));
    sd[r] = static_cast<int>(std::min<std::uint64_t>(sp, kIntMax));
    rd[r] = static_cast<int>(std::min<std::uint64_t>(rp, kIntMax));
    sp += send[r];
    rp += recv[r];
  }
  std::uint64_t too_large = sp > kIntMax || rp > kIntMax ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &too_large, 1, MPI_UINT64_T, MPI_MAX, comm);
  if (too_large != 0) return false;
  MPI_Datatype type = MPI_DATATYPE_NULL;
  MPI_Type_contiguous(static_cast<int>(sizeof(T)), MPI_BYTE, &type);
  MPI_Type_commit(&type);
  std::vector<T> in(rp);
  T sink{};  // a valid address for an empty buffer
  MPI_Alltoallv(out.empty() ? &sink : out.data(), sc.data(), sd.data(), type,
                in.empty() ? &sink : in.data(), rc.data(), rd.data(), type, comm);
  MPI_Type_free(&type);
  // Each source's values arrive in index order: interleave them by owner.
  run.resize(rp);
  std::vector<std::uint64_t> next(rd.begin(), rd.end());
  for (std::size_t k = k_lo; k < k_hi; ++k) {
    const std::uint64_t c = count_of(k);
    if (c == 0) continue;
    std::uint64_t& from = next[static_cast<std::size_t>(owner[k])];
    std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(from), c,
                run.begin() + static_cast<std::ptrdiff_t>(offset[k] - offset[k_lo]));
    from += c;
  }
  return true;
}

/// Collective: /rve/counts/<name> (values per RVE, -1 where absent) and /rve/fields/<name> (every
/// RVE's values, in RVE index order), each rank writing one contiguous run (gather_runs), or the
/// blocks of its own RVEs where the runs are too large to exchange.
template <class T>
void write_rve_field(h5::File& file, MPI_Comm comm, const CheckpointData& d,
                     const std::string& name) {
  const std::size_t n = d.ids.size();
  // count + 1 of every local RVE (0: absent elsewhere), summed over ranks.
  std::vector<std::int64_t> c1(n, 0);
  std::vector<const std::vector<T>*> values(d.local_indices.size(), nullptr);
  for (std::size_t j = 0; j < d.local_indices.size(); ++j) {
    const auto it = d.local_states[j].fields().find(name);
    if (it == d.local_states[j].fields().end()) continue;
    values[j] = &std::get<std::vector<T>>(it->second);
    c1[static_cast<std::size_t>(d.local_indices[j])] =
        static_cast<std::int64_t>(values[j]->size()) + 1;
  }
  std::vector<std::int64_t> counts(n, 0);
  MPI_Allreduce(c1.data(), counts.data(), to_count(n), MPI_INT64_T, MPI_SUM, comm);
  for (std::int64_t& c : counts) c -= 1;
  const std::vector<std::uint64_t> offset = offsets_of(counts);
  file.write_from_root<std::int64_t>("/rve/counts/" + name, counts.size(), counts.data());
  std::vector<Block> blocks;
  std::vector<T> data;
  if (gather_runs<T>(comm, d.owner, counts, offset, d.local_indices, values, data)) {
    int rank = 0;
    int size = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    if (!data.empty()) blocks.push_back({offset[run_begin(n, rank, size)], data.size()});
  } else {
    for (std::size_t j = 0; j < d.local_indices.size(); ++j) {
      if (values[j] == nullptr || values[j]->empty()) continue;
      blocks.push_back({offset[static_cast<std::size_t>(d.local_indices[j])], values[j]->size()});
      data.insert(data.end(), values[j]->begin(), values[j]->end());
    }
  }
  file.write_blocks<T>("/rve/fields/" + name, offset[n], blocks, data.data());
}

/// Collective: /mpm/<name>, held by rank 0.
template <class T>
void write_mpm_field(h5::File& file, MPI_Comm comm, const common::StateStore* mpm,
                     const std::string& name) {
  const std::vector<T>* v =
      mpm != nullptr ? &std::get<std::vector<T>>(mpm->fields().at(name)) : nullptr;
  std::uint64_t n = v != nullptr ? v->size() : 0;
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
  file.write_from_root<T>("/mpm/" + name, n, v != nullptr ? v->data() : nullptr);
}

/// This rank's RVEs' values of one field (verified later: `partial` and `stored` checksums).
template <class T>
void read_rve_field(const h5::File& file, const std::string& name,
                    const std::vector<std::int64_t>& local, std::vector<common::StateStore>& out,
                    std::uint64_t& partial, std::uint64_t& stored) {
  const auto counts = file.read<std::int64_t>("/rve/counts/" + name);
  const std::size_t n = counts.size();
  const std::vector<std::uint64_t> offset = offsets_of(counts);
  std::vector<Block> blocks;
  for (std::int64_t k : local) {
    if (k < 0 || static_cast<std::size_t>(k) >= n)
      file.fail("dataset /rve/counts/" + name + " has fewer entries than there are RVEs");
    const auto c = counts[static_cast<std::size_t>(k)];
    if (c > 0)
      blocks.push_back({offset[static_cast<std::size_t>(k)], static_cast<std::uint64_t>(c)});
  }
  const std::vector<T> v = file.read_blocks<T>("/rve/fields/" + name, blocks, partial, stored);
  std::size_t pos = 0;
  for (std::size_t j = 0; j < local.size(); ++j) {
    const auto c = counts[static_cast<std::size_t>(local[j])];
    if (c < 0) continue;  // absent in this RVE
    out[j].write(name, std::span<const T>(v.data() + pos, static_cast<std::size_t>(c)));
    pos += static_cast<std::size_t>(c);
  }
}

}  // namespace

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

// long-function: one collective sequence (create, every rank's datasets, checksums,
// close, publish) that every rank runs in the same order, read in one place.
void write_checkpoint(MPI_Comm comm, const std::string& final_path, const CheckpointData& d,
                      bool abort_mid_write) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const bool root = rank == 0;
  MPMXDEM_CHECK(d.local_indices.size() == d.local_states.size(), "one state per local RVE");
  MPMXDEM_CHECK(!root || d.mpm != nullptr, "rank 0 holds the MPM state");
  const std::string tmp = common::staging_path(final_path).string();

  // Field lists: the union over all RVEs (sorted) and rank 0's MPM fields.
  std::set<std::string> mine;
  for (const common::StateStore& s : d.local_states) {
    for (std::string& t : listed_fields(s)) mine.insert(std::move(t));
  }
  const std::vector<std::string> all =
      allgather_strings(comm, std::vector<std::string>(mine.begin(), mine.end()));
  const std::set<std::string> rve_set(all.begin(), all.end());
  const std::vector<std::string> rve_fields(rve_set.begin(), rve_set.end());
  std::string mpm_list = root ? join_lines(listed_fields(*d.mpm)) : std::string();
  bcast_string(comm, mpm_list);
  std::string job = d.job_text;
  bcast_string(comm, job);

  // Rank 0 writes the file (h5::File); a failure of the storage (disk full, quota, I/O error) is
  // thrown by create() or close() on every rank, the file removed, the earlier checkpoints kept.
  h5::File file = h5::File::create(comm, tmp);
  // Any other failure may have happened on one rank only, inside a collective: it aborts the job
  // (docs/design/architecture.md: a run never hangs).
  try {
    file.write_attribute("format", std::string(kCheckpointFormat));
    file.write_attribute("format_version", kCheckpointVersion);
    file.write_attribute("step", d.step);
    file.write_attribute("time", d.time);
    file.write_attribute("nranks", static_cast<std::int64_t>(size));
    file.write_attribute("n_rve", static_cast<std::int64_t>(d.ids.size()));

    const std::vector<std::uint8_t> job_bytes = bytes_of(job);
    file.write_from_root<std::uint8_t>("/job", job_bytes.size(), job_bytes.data());
    file.write_from_root<std::int64_t>("/rve/ids", d.ids.size(), d.ids.data());
    const std::vector<std::int64_t> part(d.owner.begin(), d.owner.end());
    file.write_from_root<std::int64_t>("/rve/partition", part.size(), part.data());
    file.write_from_root<double>("/rve/cost", d.cost.size(), d.cost.data());
    const std::vector<std::uint8_t> rve_names = bytes_of(join_lines(rve_fields));
    file.write_from_root<std::uint8_t>("/rve/field_names", rve_names.size(), rve_names.data());
    const std::vector<std::uint8_t> mpm_names = bytes_of(mpm_list);
    file.write_from_root<std::uint8_t>("/mpm/field_names", mpm_names.size(), mpm_names.data());
    for (const FieldSpec& f : parse_fields(split_lines(mpm_list))) {
      with_type(f.type, [&]<class T>(std::type_identity<T>) {
        write_mpm_field<T>(file, comm, root ? d.mpm : nullptr, f.name);
      });
    }
    if (abort_mid_write) {
      // Fault injection: die in the middle of the write, as a node failure would.
      file.flush();
      MPI_Barrier(comm);
      if (root)
        std::cerr << "farm: fault injection: aborting in the middle of writing " << tmp << "\n";
      MPI_Abort(comm, 86);
    }
    for (const FieldSpec& f : parse_fields(rve_fields)) {
      with_type(f.type,
                [&]<class T>(std::type_identity<T>) { write_rve_field<T>(file, comm, d, f.name); });
    }
  } catch (const std::exception& e) {
    std::cerr << "farm: rank " << rank << ": writing checkpoint " << tmp << " failed: " << e.what()
              << "; aborting the job\n";
    MPI_Abort(comm, 4);
  }
  file.close();  // collective: everything is on disk (up to the OS cache), or rank 0's failure

  // Atomic publication by rank 0; its failure (common::IoError) is thrown on every rank.
  ErrorKind kind = ErrorKind::none;
  std::string msg;
  if (root) {
    try {
      common::publish_file(tmp, final_path);
    } catch (...) {
      kind = current_error_kind();
      msg = "checkpoint " + final_path + ": " + common::current_error_text();
    }
  }
  agree_on_errors(comm, kind, msg);
}

CheckpointInfo read_checkpoint_info(const std::string& path) {
  const h5::File r = h5::File::open(path, "checkpoint");
  CheckpointInfo info;
  info.path = path;
  const std::string format = r.attribute_string("format");
  if (format != kCheckpointFormat) {
    r.fail("attribute /format = '" + format + "': not a farm checkpoint (expected '" +
           kCheckpointFormat + "')");
  }
  info.version = r.attribute_i64("format_version");
  if (info.version != kCheckpointVersion) {
    r.fail("attribute /format_version = " + std::to_string(info.version) +
           ": this build reads version " + std::to_string(kCheckpointVersion) + " only");
  }
  info.step = r.attribute_i64("step");
  info.time = r.attribute_f64("time");
  info.nranks = r.attribute_i64("nranks");
  const std::int64_t n_rve = r.attribute_i64("n_rve");
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
  for (const FieldSpec& f : parse_fields(r, info.rve_fields, "/rve/field_names")) {
    for (const char* group : {"/rve/fields/", "/rve/counts/"}) {
      if (!r.exists(group + f.name))
        r.fail(std::string("dataset ") + group + f.name + " is missing");
    }
  }
  for (const FieldSpec& f : parse_fields(r, info.mpm_fields, "/mpm/field_names")) {
    if (!r.exists("/mpm/" + f.name)) r.fail("dataset /mpm/" + f.name + " is missing");
  }
  return info;
}

common::StateStore read_checkpoint_mpm(const std::string& path) {
  const CheckpointInfo info = read_checkpoint_info(path);
  const h5::File r = h5::File::open(path, "checkpoint");
  common::StateStore s;
  for (const FieldSpec& f : parse_fields(info.mpm_fields)) {
    with_type(f.type, [&]<class T>(std::type_identity<T>) {
      s.write(f.name, r.read<T>("/mpm/" + f.name));
    });
  }
  return s;
}

std::vector<common::StateStore> read_checkpoint_rves(MPI_Comm comm, const CheckpointInfo& info,
                                                     const std::vector<std::int64_t>& local) {
  std::vector<common::StateStore> out(local.size());
  const std::vector<FieldSpec> fields = parse_fields(info.rve_fields);
  const std::size_t nf = fields.size();
  std::vector<std::uint64_t> partial(nf, 0);
  std::vector<std::uint64_t> stored(nf, 0);
  ErrorKind kind = ErrorKind::none;
  std::string msg;
  try {
    const h5::File r = h5::File::open(info.path, "checkpoint");
    for (std::size_t i = 0; i < nf; ++i) {
      with_type(fields[i].type, [&]<class T>(std::type_identity<T>) {
        read_rve_field<T>(r, fields[i].name, local, out, partial[i], stored[i]);
      });
    }
  } catch (...) {
    kind = current_error_kind();
    msg = common::current_error_text();
  }
  agree_on_errors(comm, kind, msg);
  std::vector<std::uint64_t> total(nf, 0);
  MPI_Allreduce(partial.data(), total.data(), to_count(nf), MPI_UINT64_T, MPI_SUM, comm);
  for (std::size_t i = 0; i < nf; ++i) {
    if (total[i] != stored[i]) {
      throw common::InputError("checkpoint " + info.path + ": dataset /rve/fields/" +
                               fields[i].name + ": checksum mismatch (stored " + hex(stored[i]) +
                               ", computed " + hex(total[i]) + "): the file is damaged");
    }
  }
  return out;
}

std::vector<common::StateStore> read_checkpoint_rve_states(const CheckpointInfo& info,
                                                           const std::vector<std::int64_t>& indices,
                                                           const std::vector<std::string>& only) {
  std::vector<common::StateStore> out(indices.size());
  const h5::File r = h5::File::open(info.path, "checkpoint");
  for (std::int64_t k : indices) {
    MPMXDEM_CHECK(k >= 0 && static_cast<std::size_t>(k) < info.ids.size(),
                  "RVE index " + std::to_string(k) + " of " + std::to_string(info.ids.size()));
  }
  for (const FieldSpec& f : parse_fields(info.rve_fields)) {
    if (!only.empty() && std::find(only.begin(), only.end(), f.name) == only.end()) continue;
    const auto counts = r.read<std::int64_t>("/rve/counts/" + f.name);
    if (counts.size() != info.ids.size())
      r.fail("dataset /rve/counts/" + f.name + " must have one entry per RVE");
    const std::vector<std::uint64_t> offset = offsets_of(counts);
    with_type(f.type, [&]<class T>(std::type_identity<T>) {
      const std::vector<T> v = r.read<T>("/rve/fields/" + f.name);
      if (v.size() < offset.back())
        r.fail("dataset /rve/fields/" + f.name + " is shorter than its counts say");
      for (std::size_t j = 0; j < indices.size(); ++j) {
        const auto k = static_cast<std::size_t>(indices[j]);
        if (counts[k] < 0) continue;  // absent in this RVE
        out[j].write(f.name,
                     std::span<const T>(v.data() + offset[k], static_cast<std::size_t>(counts[k])));
      }
    });
  }
  return out;
}

void verify_checkpoint(const std::string& path) {
  const CheckpointInfo info = read_checkpoint_info(path);
  (void)read_checkpoint_mpm(path);
  const h5::File r = h5::File::open(path, "checkpoint");
  for (const FieldSpec& f : parse_fields(info.rve_fields)) {
    (void)r.read<std::int64_t>("/rve/counts/" + f.name);
    with_type(f.type,
              [&]<class T>(std::type_identity<T>) { (void)r.read<T>("/rve/fields/" + f.name); });
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
  for (const FieldSpec& f : parse_fields(info.rve_fields)) os << " " << f.name;
  os << "\n  MPM fields    " << info.mpm_fields.size() << ":";
  for (const FieldSpec& f : parse_fields(info.mpm_fields)) os << " " << f.name;
  const std::string first = info.job_text.substr(0, info.job_text.find('\n'));
  os << "\n  job text      " << info.job_text.size() << " bytes; first line: " << first << "\n";
  return os.str();
}

}  // namespace farm
