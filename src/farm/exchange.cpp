// The farm's wire (see header and docs/design/farm.md, "Protocol").
#include "farm/exchange.hpp"

#include <cstring>

#include "common/errors.hpp"
#include "common/tensor.hpp"

namespace farm {

namespace {

template <class T>
void append(std::vector<char>& out, const T& v) {
  const auto* p = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

template <class T>
T take(const char* data, std::size_t& pos) {
  T v;
  std::memcpy(&v, data + pos, sizeof(T));
  pos += sizeof(T);
  return v;
}

/// Displacements of `counts` laid end to end; returns the total.
std::size_t displacements(const std::vector<int>& counts, std::vector<int>& displs) {
  displs.assign(counts.size(), 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = to_count(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  return total;
}

}  // namespace

void allgather_owned(MPI_Comm comm, std::vector<InitRecord>& by_index) {
  static_assert(sizeof(double) == sizeof(std::uint64_t));
  if (by_index.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, by_index.data(),
                to_count(by_index.size() * sizeof(InitRecord) / sizeof(std::uint64_t)),
                MPI_UINT64_T, MPI_BOR, comm);
}

StepExchange::StepExchange(MPI_Comm comm, WaitMode wait) : comm_(comm), wait_(wait) {
  MPI_Comm_rank(comm_, &rank_);
}

void StepExchange::layout(const Placement& pl) {
  // Rank r's command is [header][9 doubles per RVE], its records [busy][RveRecord per RVE], both
  // in ascending RVE index order (Placement::members).
  const auto nr = static_cast<std::size_t>(pl.nranks());
  cmd_counts_.assign(nr, 0);
  rec_counts_.assign(nr, 0);
  for (std::size_t r = 0; r < nr; ++r) {
    const std::size_t m = pl.members(static_cast<int>(r)).size();
    cmd_counts_[r] = to_count(sizeof(double) * (kHeaderWords + 9 * m));
    rec_counts_[r] = to_count(sizeof(double) * (1 + kRecordWords * m));
  }
  const std::size_t cmd_total = displacements(cmd_counts_, cmd_displs_);
  const std::size_t rec_total = displacements(rec_counts_, rec_displs_);
  const auto mine = static_cast<std::size_t>(rank_);
  cmd_send_.assign(rank_ == 0 ? cmd_total / sizeof(double) : 0, 0.0);
  cmd_recv_.assign(static_cast<std::size_t>(cmd_counts_[mine]) / sizeof(double), 0.0);
  rec_.assign(static_cast<std::size_t>(rec_counts_[mine]) / sizeof(double), 0.0);
  rec_all_.assign(rank_ == 0 ? rec_total / sizeof(double) : 0, 0.0);
}

double* StepExchange::L_out(int r, std::size_t i) {
  const auto start = static_cast<std::size_t>(cmd_displs_[static_cast<std::size_t>(r)]);
  return cmd_send_.data() + start / sizeof(double) + kHeaderWords + 9 * i;
}

void StepExchange::send(const CommandHeader& h) {
  MPMXDEM_CHECK(rank_ == 0, "only rank 0 sends commands");
  for (const int d : cmd_displs_) {
    std::memcpy(cmd_send_.data() + static_cast<std::size_t>(d) / sizeof(double), &h, sizeof h);
  }
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Iscatterv(cmd_send_.data(), cmd_counts_.data(), cmd_displs_.data(), MPI_BYTE,
                cmd_recv_.data(), cmd_counts_[0], MPI_BYTE, 0, comm_, &req);
  wait_for(req, wait_);
}

CommandHeader StepExchange::receive() {
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Iscatterv(nullptr, nullptr, nullptr, MPI_BYTE, cmd_recv_.data(),
                cmd_counts_[static_cast<std::size_t>(rank_)], MPI_BYTE, 0, comm_, &req);
  wait_for(req, wait_);
  CommandHeader h;
  std::memcpy(static_cast<void*>(&h), cmd_recv_.data(), sizeof h);
  return h;
}

common::Mat3 StepExchange::L_in(std::size_t j) const {
  return common::row_major(cmd_recv_.data() + kHeaderWords + 9 * j);
}

void StepExchange::put(std::size_t j, const RveRecord& record) {
  std::memcpy(rec_.data() + 1 + kRecordWords * j, &record, sizeof record);
}

void StepExchange::set_busy(double s) { rec_[0] = s; }

void StepExchange::gather() {
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Igatherv(rec_.data(), rec_counts_[static_cast<std::size_t>(rank_)], MPI_BYTE, rec_all_.data(),
               rec_counts_.data(), rec_displs_.data(), MPI_BYTE, 0, comm_, &req);
  wait_for(req, wait_);
}

double StepExchange::busy(int r) const {
  return rec_all_[static_cast<std::size_t>(rec_displs_[static_cast<std::size_t>(r)]) /
                  sizeof(double)];
}

RveRecord StepExchange::record(int r, std::size_t i) const {
  const auto start = static_cast<std::size_t>(rec_displs_[static_cast<std::size_t>(r)]);
  RveRecord rec;
  std::memcpy(static_cast<void*>(&rec),
              rec_all_.data() + start / sizeof(double) + 1 + kRecordWords * i, sizeof rec);
  return rec;
}

std::vector<MicroMeasures> gather_measures(MPI_Comm comm, const Placement& pl,
                                           const std::vector<MicroMeasures>& mine, WaitMode wait) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPMXDEM_CHECK(mine.size() == pl.local().size(), "one measure per local RVE");
  const auto nr = static_cast<std::size_t>(pl.nranks());
  std::vector<int> counts(nr, 0);
  for (std::size_t r = 0; r < nr; ++r) {
    counts[r] = to_count(sizeof(MicroMeasures) * pl.members(static_cast<int>(r)).size());
  }
  std::vector<int> displs;
  const std::size_t total = displacements(counts, displs);
  std::vector<MicroMeasures> all(rank == 0 ? total / sizeof(MicroMeasures) : 0);
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Igatherv(mine.data(), counts[static_cast<std::size_t>(rank)], MPI_BYTE, all.data(),
               counts.data(), displs.data(), MPI_BYTE, 0, comm, &req);
  wait_for(req, wait);
  if (rank != 0) return {};
  // By rank, members(r) order -> by RVE index.
  std::vector<MicroMeasures> by_index(pl.size());
  for (std::size_t r = 0; r < nr; ++r) {
    const std::vector<std::size_t>& members = pl.members(static_cast<int>(r));
    const std::size_t first = static_cast<std::size_t>(displs[r]) / sizeof(MicroMeasures);
    for (std::size_t i = 0; i < members.size(); ++i) by_index[members[i]] = all[first + i];
  }
  return by_index;
}

std::vector<std::pair<std::size_t, std::string>> gather_texts(
    MPI_Comm comm, const std::vector<std::pair<std::size_t, std::string>>& mine) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // [u64 index][i64 length][text] per failure.
  std::vector<char> out;
  for (const auto& [k, text] : mine) {
    append(out, static_cast<std::uint64_t>(k));
    append(out, static_cast<std::int64_t>(text.size()));
    out.insert(out.end(), text.begin(), text.end());
  }
  const int n_out = to_count(out.size());
  std::vector<int> sizes(static_cast<std::size_t>(size), 0);
  MPI_Gather(&n_out, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm);
  std::vector<int> displs;
  const std::size_t total = displacements(sizes, displs);
  std::vector<char> all(rank == 0 ? total : 0);
  MPI_Gatherv(out.data(), n_out, MPI_CHAR, all.data(), sizes.data(), displs.data(), MPI_CHAR, 0,
              comm);
  std::vector<std::pair<std::size_t, std::string>> texts;
  std::size_t pos = 0;
  while (pos < all.size()) {
    const auto k = take<std::uint64_t>(all.data(), pos);
    const auto len = static_cast<std::size_t>(take<std::int64_t>(all.data(), pos));
    texts.emplace_back(static_cast<std::size_t>(k), std::string(all.data() + pos, len));
    pos += len;
  }
  return texts;
}

std::vector<std::vector<std::vector<char>>> exchange_blobs(
    MPI_Comm comm, const std::vector<std::vector<std::vector<char>>>& to) {
  const std::size_t size = to.size();
  // One buffer by destination: [u64 length][bytes] per blob.
  std::vector<int> scount(size, 0);
  std::vector<char> sbuf;
  std::size_t bytes = 0;
  for (const auto& blobs : to) {
    for (const std::vector<char>& b : blobs) bytes += sizeof(std::uint64_t) + b.size();
  }
  sbuf.reserve(bytes);  // one allocation: a growing buffer of MBs reallocates into fresh pages
  std::vector<int> sdispl(size, 0);
  for (std::size_t r = 0; r < size; ++r) {
    sdispl[r] = to_count(sbuf.size());
    for (const std::vector<char>& b : to[r]) {
      append(sbuf, static_cast<std::uint64_t>(b.size()));
      sbuf.insert(sbuf.end(), b.begin(), b.end());
    }
    scount[r] = to_count(sbuf.size()) - sdispl[r];
  }
  std::vector<int> rcount(size, 0);
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm);
  std::vector<int> rdispl;
  const std::size_t total = displacements(rcount, rdispl);
  std::vector<char> rbuf(total);
  MPI_Alltoallv(sbuf.data(), scount.data(), sdispl.data(), MPI_CHAR, rbuf.data(), rcount.data(),
                rdispl.data(), MPI_CHAR, comm);
  std::vector<std::vector<std::vector<char>>> from(size);
  for (std::size_t r = 0; r < size; ++r) {
    std::size_t pos = static_cast<std::size_t>(rdispl[r]);
    const std::size_t end = pos + static_cast<std::size_t>(rcount[r]);
    while (pos < end) {
      const auto len = static_cast<std::size_t>(take<std::uint64_t>(rbuf.data(), pos));
      from[r].emplace_back(rbuf.data() + pos, rbuf.data() + pos + len);
      pos += len;
    }
  }
  return from;
}

}  // namespace farm
