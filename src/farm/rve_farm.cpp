// RveFarm: the master/worker protocol over MPI (see header and docs/farm.md, "Protocol").
#include "farm/rve_farm.hpp"

#include <omp.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <numeric>
#include <string>

#include "common/errors.hpp"

namespace farm {

namespace {

enum Command : std::int32_t {
  kStep = 1,
  kCheckpoint = 2,
  kMigrate = 3,
  kStop = 4,
  kStopError = 5,
  kErrorTexts = 6
};

/// Per-RVE record gathered to rank 0 (doubles): stress (9, row-major), p, q, e, z, t_p, wall_s,
/// wave speed, dem_steps, guards, error kind, cost (CPU seconds of the thread that stepped it).
constexpr std::size_t kRecord = 20;

/// CPU time of the calling thread [s]. An RVE's cost for balancing: unlike wall time it leaves
/// out the time its thread was not running (another rank on the same core, a preemption).
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

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

/// Every entry is set by exactly one rank (its owner) and zero bits elsewhere: a bitwise OR of the
/// bit patterns gives every rank the exact values (a floating-point sum would turn -0.0 into 0.0).
void allgather_owned(MPI_Comm comm, std::vector<double>& v) {
  static_assert(sizeof(double) == sizeof(std::uint64_t));
  if (v.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, v.data(), to_count(v.size()), MPI_UINT64_T, MPI_BOR, comm);
}

}  // namespace

struct RveFarm::Header {
  std::int32_t cmd = 0;
  std::int32_t flag = 0;  ///< checkpoint: abort mid-write; stop_error: ErrorKind
  std::int64_t step = 0;  ///< MPM step number being computed (step), or done (checkpoint)
  double value = 0.0;     ///< step: dt [s]; checkpoint: time [s]
  std::int64_t aux = 0;
};

RveFarm::RveFarm(MPI_Comm comm, MicroKind kind, std::vector<std::int64_t> ids,
                 const std::vector<common::Vec3>& x, const mpm::Grid& grid, FarmOptions options)
    : kind_(std::move(kind)), options_(options), grid_(grid), ids_(std::move(ids)) {
  MPI_Comm_dup(comm, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  options_.wait = resolve_wait_mode(comm_, options_.wait);
  MPMXDEM_CHECK(std::is_sorted(ids_.begin(), ids_.end()) &&
                    std::adjacent_find(ids_.begin(), ids_.end()) == ids_.end(),
                "RVE ids must be ascending and unique");
  owner_ = partition_blocks(ids_.size(), size_);
  rebuild_local();
  ErrorKind kind_err = ErrorKind::none;
  std::string msg;
  for (std::int64_t k : local_) {
    try {
      models_[static_cast<std::size_t>(k)] = kind_.create(ids_[static_cast<std::size_t>(k)]);
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = "farm: creating the RVE of point id " +
            std::to_string(ids_[static_cast<std::size_t>(k)]) + " failed: " + e.what();
      break;
    }
  }
  agree_on_errors(comm_, kind_err, msg);
  initial_costs_and_partition(x, grid, nullptr);
}

RveFarm::RveFarm(MPI_Comm comm, MicroKind kind, const CheckpointInfo& info,
                 const std::vector<common::Vec3>& x, const mpm::Grid& grid, FarmOptions options)
    : kind_(std::move(kind)), options_(options), grid_(grid), ids_(info.ids) {
  MPI_Comm_dup(comm, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  options_.wait = resolve_wait_mode(comm_, options_.wait);
  owner_ = partition_blocks(ids_.size(), size_);
  rebuild_local();
  std::vector<common::StateStore> states = read_checkpoint_rves(comm_, info, local_);
  ErrorKind kind_err = ErrorKind::none;
  std::string msg;
  for (std::size_t j = 0; j < local_.size(); ++j) {
    try {
      models_[static_cast<std::size_t>(local_[j])] = kind_.load(states[j]);
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = "checkpoint " + info.path + ": restoring the RVE of point id " +
            std::to_string(ids_[static_cast<std::size_t>(local_[j])]) + " failed: " + e.what();
      break;
    }
  }
  agree_on_errors(comm_, kind_err, msg);
  step_ = info.step;
  initial_costs_and_partition(x, grid, &info.cost);
}

RveFarm::~RveFarm() {
  if (rank_ == 0 && size_ > 1 && !stopped_) {
    // Rank 0 is leaving (an exception unwound the driver): release the workers with an error
    // rather than leave them waiting.
    stop_with_error(ErrorKind::internal, "farm: rank 0 stopped without releasing the workers");
  }
  if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

void RveFarm::rebuild_local() {
  local_.clear();
  models_.resize(ids_.size());
  members_.assign(static_cast<std::size_t>(size_), {});
  for (std::size_t k = 0; k < ids_.size(); ++k) {
    if (owner_[k] == rank_) local_.push_back(static_cast<std::int64_t>(k));
    members_[static_cast<std::size_t>(owner_[k])].push_back(k);
  }
  // Message layouts of the step exchange: rank r's command is [header][9 doubles per RVE], its
  // records [loop wall][kRecord doubles per RVE], both in ascending RVE index order.
  cmd_counts_.assign(static_cast<std::size_t>(size_), 0);
  cmd_displs_.assign(static_cast<std::size_t>(size_), 0);
  rec_counts_.assign(static_cast<std::size_t>(size_), 0);
  rec_displs_.assign(static_cast<std::size_t>(size_), 0);
  std::size_t cmd_total = 0;
  std::size_t rec_total = 0;
  for (std::size_t r = 0; r < members_.size(); ++r) {
    cmd_displs_[r] = to_count(cmd_total);
    cmd_counts_[r] = to_count(sizeof(Header) + 9 * sizeof(double) * members_[r].size());
    cmd_total += static_cast<std::size_t>(cmd_counts_[r]);
    rec_displs_[r] = to_count(rec_total);
    rec_counts_[r] = to_count(1 + kRecord * members_[r].size());
    rec_total += static_cast<std::size_t>(rec_counts_[r]);
  }
  cmd_send_.assign(rank_ == 0 ? cmd_total : 0, 0);
  cmd_recv_.assign(static_cast<std::size_t>(cmd_counts_[static_cast<std::size_t>(rank_)]), 0);
  rec_.assign(1 + kRecord * local_.size(), 0.0);
  rec_all_.assign(rank_ == 0 ? rec_total : 0, 0.0);
  errors_.assign(local_.size(), std::string());
}

void RveFarm::initial_costs_and_partition(const std::vector<common::Vec3>& x, const mpm::Grid& grid,
                                          const std::vector<double>* costs) {
  const std::size_t n = ids_.size();
  std::vector<double> est(n, 0.0);
  std::vector<double> wave(n, 0.0);
  for (std::int64_t k : local_) {
    est[static_cast<std::size_t>(k)] = models_[static_cast<std::size_t>(k)]->cost_estimate();
    wave[static_cast<std::size_t>(k)] = models_[static_cast<std::size_t>(k)]->wave_speed();
  }
  allgather_owned(comm_, est);
  allgather_owned(comm_, wave);
  wave_speed_ = n > 0 ? *std::max_element(wave.begin(), wave.end()) : 0.0;
  cost_window_.assign(n, 0.0);
  cost_total_.assign(n, 0.0);
  wave_ = wave;
  reports_.assign(n, MicroReport{});
  stresses_.assign(n, common::Mat3::Zero());
  bool measured = costs != nullptr && costs->size() == n;
  if (measured) {
    for (double c : *costs) measured = measured && c > 0.0;
  }
  if (measured) cost_total_ = *costs;
  // Stresses and measures before the first step (outputs at step 0).
  constexpr std::size_t kInit = 13;  // stress (9), p, q, e, Z
  std::vector<double> s(kInit * n, 0.0);
  for (std::int64_t k : local_) {
    const MicroModel& m = *models_[static_cast<std::size_t>(k)];
    double* v = s.data() + kInit * static_cast<std::size_t>(k);
    const common::Mat3 sig = m.stress();
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) v[3 * a + b] = sig(a, b);
    }
    const MicroReport r = m.report();
    v[9] = r.p;
    v[10] = r.q;
    v[11] = r.void_ratio;
    v[12] = r.z;
  }
  allgather_owned(comm_, s);
  for (std::size_t k = 0; k < n; ++k) {
    const double* v = s.data() + kInit * k;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) stresses_[k](a, b) = v[3 * a + b];
    }
    reports_[k].p = v[9];
    reports_[k].q = v[10];
    reports_[k].void_ratio = v[11];
    reports_[k].z = v[12];
  }
  std::vector<int> part(n, 0);
  if (rank_ == 0) {
    MPMXDEM_CHECK(x.size() == n, "one position per RVE on rank 0");
    part =
        partition_metis(cell_graph(grid, x), measured ? *costs : est, size_, options_.metis_seed);
    keep_owners(owner_, part, size_);  // move as few RVEs as the partition allows
  }
  if (n > 0) MPI_Bcast(part.data(), to_count(n), MPI_INT, 0, comm_);
  exec_migrate(std::move(part));
}

void RveFarm::send_command(const Header& h) {
  MPMXDEM_CHECK(rank_ == 0, "only rank 0 sends commands");
  for (std::size_t r = 0; r < cmd_displs_.size(); ++r) {
    std::memcpy(cmd_send_.data() + cmd_displs_[r], &h, sizeof(Header));
  }
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Iscatterv(cmd_send_.data(), cmd_counts_.data(), cmd_displs_.data(), MPI_BYTE,
                cmd_recv_.data(), cmd_counts_[0], MPI_BYTE, 0, comm_, &req);
  wait_for(req, options_.wait);
}

RveFarm::Header RveFarm::receive_command() {
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Iscatterv(nullptr, nullptr, nullptr, MPI_BYTE, cmd_recv_.data(),
                cmd_counts_[static_cast<std::size_t>(rank_)], MPI_BYTE, 0, comm_, &req);
  wait_for(req, options_.wait);
  Header h;
  std::memcpy(&h, cmd_recv_.data(), sizeof(Header));
  return h;
}

void RveFarm::update_stress(std::span<const std::int64_t> ids, std::span<const common::Mat3> L,
                            double dt, std::span<common::Mat3> stress) {
  MPMXDEM_CHECK(rank_ == 0, "update_stress is called on rank 0 only");
  MPMXDEM_CHECK(ids.size() == L.size() && ids.size() == stress.size(), "span sizes differ");
  const double t0 = now();
  const std::size_t n = ids_.size();
  MPMXDEM_CHECK(ids.size() == n, "update_stress needs every RVE id once (got " +
                                     std::to_string(ids.size()) + " of " + std::to_string(n) + ")");
  // The solver may hand the points in any order: map RVE index -> slot.
  slot_of_.assign(n, -1);
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const auto it = std::lower_bound(ids_.begin(), ids_.end(), ids[p]);
    MPMXDEM_CHECK(it != ids_.end() && *it == ids[p],
                  "point id " + std::to_string(ids[p]) + " has no RVE");
    const auto k = static_cast<std::size_t>(it - ids_.begin());
    MPMXDEM_CHECK(slot_of_[k] < 0, "point id " + std::to_string(ids[p]) + " given twice");
    slot_of_[k] = static_cast<std::int64_t>(p);
  }
  // L of every rank's RVEs, in ascending index order, after that rank's header.
  for (std::size_t r = 0; r < members_.size(); ++r) {
    char* out = cmd_send_.data() + cmd_displs_[r] + sizeof(Header);
    for (const std::size_t k : members_[r]) {
      const common::Mat3& m = L[static_cast<std::size_t>(slot_of_[k])];
      double v[9];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) v[3 * a + b] = m(a, b);
      }
      std::memcpy(out, v, sizeof v);
      out += sizeof v;
    }
  }
  Header h;
  h.cmd = kStep;
  h.step = step_ + 1;
  h.value = dt;
  send_command(h);
  exec_step(h, stress);
  times_.step_wall += now() - t0;
}

void RveFarm::exec_step(const Header& h, std::span<common::Mat3> stress) {
  const std::size_t n = ids_.size();
  const double dt = h.value;
  step_ = h.step;
  // 1. My L arrived with the command (cmd_recv_ after the header), in ascending index order.
  const char* myL = cmd_recv_.data() + sizeof(Header);

  // 2. Advance my RVEs; failures are caught per RVE and travel to rank 0 as data.
  const std::size_t nloc = local_.size();
  double* rec = rec_.data() + 1;
  const double t_loop = now();
  const auto nl = static_cast<std::int64_t>(nloc);
#pragma omp parallel for schedule(dynamic, 1) if (options_.omp_over_rves && nl > 1)
  for (std::int64_t jj = 0; jj < nl; ++jj) {
    const auto j = static_cast<std::size_t>(jj);
    MicroModel& m = *models_[static_cast<std::size_t>(local_[j])];
    double v[9];
    std::memcpy(v, myL + 9 * sizeof(double) * j, sizeof v);
    common::Mat3 Lj;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) Lj(a, b) = v[3 * a + b];
    }
    double* r = rec + kRecord * j;
    errors_[j].clear();
    try {
      const double cpu0 = thread_cpu_s();
      const MicroReport rep = m.step(Lj, dt);
      r[19] = thread_cpu_s() - cpu0;
      const common::Mat3 s = m.stress();
      if (!s.allFinite())
        throw common::NumericalError("non-finite stress (trace = " + std::to_string(s.trace()) +
                                     " Pa)");
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) r[3 * a + b] = s(a, b);
      }
      r[9] = rep.p;
      r[10] = rep.q;
      r[11] = rep.void_ratio;
      r[12] = rep.z;
      r[13] = rep.t_p;
      r[14] = rep.wall_s;
      r[15] = m.wave_speed();
      r[16] = static_cast<double>(rep.dem_steps);
      r[17] = static_cast<double>(rep.guards);
      r[18] = 0.0;
    } catch (const std::exception& e) {
      ErrorKind k = ErrorKind::internal;
      if (dynamic_cast<const common::InputError*>(&e) != nullptr) k = ErrorKind::input;
      if (dynamic_cast<const common::NumericalError*>(&e) != nullptr) k = ErrorKind::numerical;
      r[18] = static_cast<double>(static_cast<std::int32_t>(k));
      errors_[j] = e.what();
    }
  }
  rec_[0] = now() - t_loop;

  // 3. Gather [loop wall][records] to rank 0: one collective of sizes known to every rank.
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Igatherv(rec_.data(), rec_counts_[static_cast<std::size_t>(rank_)], MPI_DOUBLE,
               rec_all_.data(), rec_counts_.data(), rec_displs_.data(), MPI_DOUBLE, 0, comm_, &req);
  wait_for(req, options_.wait);
  if (rank_ != 0) return;

  // 4. Rank 0: store by RVE index (never by arrival order), then answer the solver.
  double busy_max = 0.0;
  double busy_sum = 0.0;
  struct Failure {
    std::int64_t id;
    int rank;
    ErrorKind kind;
    std::string text;
  };
  std::vector<Failure> failures;
  for (int r = 0; r < size_; ++r) {
    const double* base = rec_all_.data() + rec_displs_[static_cast<std::size_t>(r)];
    const double wall = base[0];
    busy_max = std::max(busy_max, wall);
    busy_sum += wall;
    const double* v = base + 1;
    for (const std::size_t k : members_[static_cast<std::size_t>(r)]) {
      const auto ek = static_cast<ErrorKind>(static_cast<std::int32_t>(v[18]));
      if (ek != ErrorKind::none) {
        failures.push_back({ids_[k], r, ek, ""});
        v += kRecord;
        continue;
      }
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) stresses_[k](a, b) = v[3 * a + b];
      }
      MicroReport& rep = reports_[k];
      rep.p = v[9];
      rep.q = v[10];
      rep.void_ratio = v[11];
      rep.z = v[12];
      rep.t_p = v[13];
      rep.wall_s = v[14];
      wave_[k] = v[15];
      rep.dem_steps = static_cast<std::int64_t>(v[16]);
      rep.guards = static_cast<std::uint32_t>(v[17]);
      cost_total_[k] += v[19];
      cost_window_[k] += v[19];
      v += kRecord;
    }
  }
  times_.critical_busy += busy_max;
  times_.mean_busy += busy_sum / size_;
  ++times_.steps;
  if (!failures.empty()) {
    // Rare: fetch the texts with a command of their own (the step exchange carries none).
    Header e;
    e.cmd = kErrorTexts;
    e.step = step_;
    send_command(e);
    for (const auto& [k, text] : exec_error_texts()) {
      for (Failure& f : failures) {
        if (f.id == ids_[static_cast<std::size_t>(k)]) f.text = text;
      }
    }
    std::sort(failures.begin(), failures.end(),
              [](const Failure& a, const Failure& b) { return a.id < b.id; });
    const Failure& f = failures.front();
    std::string msg = "farm: MPM step " + std::to_string(step_) + ": RVE id " +
                      std::to_string(f.id) + " (rank " + std::to_string(f.rank) +
                      ") failed: " + f.text;
    if (failures.size() > 1)
      msg += " (" + std::to_string(failures.size() - 1) + " more RVE(s) failed)";
    throw_kind(f.kind, msg);
  }
  wave_speed_ = *std::max_element(wave_.begin(), wave_.end());
  for (std::size_t k = 0; k < n; ++k) stress[static_cast<std::size_t>(slot_of_[k])] = stresses_[k];
}

std::vector<std::pair<std::int64_t, std::string>> RveFarm::exec_error_texts() {
  // [index][length][text] for every failed RVE of mine, gathered to rank 0.
  std::vector<char> out;
  for (std::size_t j = 0; j < local_.size(); ++j) {
    if (errors_[j].empty()) continue;
    append(out, local_[j]);
    append(out, static_cast<std::int64_t>(errors_[j].size()));
    out.insert(out.end(), errors_[j].begin(), errors_[j].end());
  }
  const int mine = to_count(out.size());
  std::vector<int> sizes(static_cast<std::size_t>(size_), 0);
  MPI_Gather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm_);
  std::vector<int> displ(static_cast<std::size_t>(size_), 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < sizes.size(); ++r) {
    displ[r] = to_count(total);
    total += static_cast<std::size_t>(sizes[r]);
  }
  std::vector<char> all(rank_ == 0 ? total : 0);
  MPI_Gatherv(out.data(), mine, MPI_CHAR, all.data(), sizes.data(), displ.data(), MPI_CHAR, 0,
              comm_);
  std::vector<std::pair<std::int64_t, std::string>> texts;
  std::size_t pos = 0;
  while (pos < all.size()) {
    const auto k = take<std::int64_t>(all.data(), pos);
    const auto len = take<std::int64_t>(all.data(), pos);
    texts.emplace_back(k, std::string(all.data() + pos, static_cast<std::size_t>(len)));
    pos += static_cast<std::size_t>(len);
  }
  return texts;
}

void RveFarm::checkpoint(const std::string& path, std::int64_t step, double time,
                         const std::string& job_text, const common::StateStore& mpm_state,
                         bool abort_mid_write) {
  MPMXDEM_CHECK(rank_ == 0, "checkpoint is driven by rank 0");
  Header h;
  h.cmd = kCheckpoint;
  h.flag = abort_mid_write ? 1 : 0;
  h.step = step;
  h.value = time;
  send_command(h);
  exec_checkpoint(h, path, job_text, &mpm_state);
}

void RveFarm::exec_checkpoint(const Header& h, std::string path, std::string job_text,
                              const common::StateStore* mpm_state) {
  bcast_string(comm_, path);
  CheckpointData d;
  d.step = h.step;
  d.time = h.value;
  d.job_text = std::move(job_text);
  d.ids = ids_;
  d.owner = owner_;
  d.cost = cost_total_;
  d.local_indices = local_;
  d.local_states.resize(local_.size());
  for (std::size_t j = 0; j < local_.size(); ++j) {
    models_[static_cast<std::size_t>(local_[j])]->save(d.local_states[j]);
  }
  d.mpm = mpm_state;
  write_checkpoint(comm_, path, d, h.flag != 0);
}

double RveFarm::imbalance() const {
  return farm::imbalance(owner_, cost_avg_.windows() > 0 ? cost_avg_.cost() : cost_window_, size_);
}

bool RveFarm::rebalance_if_needed(double threshold, const std::vector<common::Vec3>& x) {
  MPMXDEM_CHECK(rank_ == 0, "rebalancing is driven by rank 0");
  cost_avg_.add_window(cost_window_);
  std::fill(cost_window_.begin(), cost_window_.end(), 0.0);
  Payback pay;
  const std::int64_t window_steps = times_.steps - times_at_check_.steps;
  if (window_steps > 0) {
    pay.step_s =
        (times_.critical_busy - times_at_check_.critical_busy) / static_cast<double>(window_steps);
  }
  times_at_check_ = times_;
  pay.horizon_steps = static_cast<double>(step_ - step_at_migration_);
  if (moved_ > 0) pay.move_s_per_rve = times_.migrate_wall / static_cast<double>(moved_);
  last_plan_ = RebalancePlan{};
  if (size_ == 1 || !cost_avg_.settled()) return false;
  last_plan_ = plan_rebalance(cell_graph(grid_, x), owner_, cost_avg_.cost(), size_, threshold,
                              options_.metis_seed, pay);
  if (!last_plan_.migrate) return false;
  Header h;
  h.cmd = kMigrate;
  send_command(h);
  std::vector<int> owner = last_plan_.owner;
  MPI_Bcast(owner.data(), to_count(owner.size()), MPI_INT, 0, comm_);
  exec_migrate(std::move(owner));
  return true;
}

void RveFarm::migrate_to(std::vector<int> owner) {
  MPMXDEM_CHECK(rank_ == 0, "migration is driven by rank 0");
  MPMXDEM_CHECK(owner.size() == ids_.size(), "one owner per RVE");
  for (int o : owner) MPMXDEM_CHECK(o >= 0 && o < size_, "owner rank out of range");
  if (size_ == 1) return;
  Header h;
  h.cmd = kMigrate;
  send_command(h);
  MPI_Bcast(owner.data(), to_count(owner.size()), MPI_INT, 0, comm_);
  exec_migrate(std::move(owner));
}

void RveFarm::exec_migrate(std::vector<int> new_owner) {
  const double t0 = now();
  const std::size_t n = ids_.size();
  // Send buffers by destination: RVEs in ascending index order, each [u64 length][bytes].
  std::vector<std::vector<char>> to(static_cast<std::size_t>(size_));
  for (std::int64_t k : local_) {
    const int dest = new_owner[static_cast<std::size_t>(k)];
    if (dest == rank_) continue;
    common::StateStore s;
    models_[static_cast<std::size_t>(k)]->save(s);
    const std::vector<char> bytes = s.serialize();
    append(to[static_cast<std::size_t>(dest)], static_cast<std::uint64_t>(bytes.size()));
    to[static_cast<std::size_t>(dest)].insert(to[static_cast<std::size_t>(dest)].end(),
                                              bytes.begin(), bytes.end());
    models_[static_cast<std::size_t>(k)].reset();
  }
  std::vector<int> scount(static_cast<std::size_t>(size_));
  std::vector<int> sdispl(static_cast<std::size_t>(size_));
  std::vector<char> sbuf;
  for (int r = 0; r < size_; ++r) {
    sdispl[static_cast<std::size_t>(r)] = to_count(sbuf.size());
    scount[static_cast<std::size_t>(r)] = to_count(to[static_cast<std::size_t>(r)].size());
    sbuf.insert(sbuf.end(), to[static_cast<std::size_t>(r)].begin(),
                to[static_cast<std::size_t>(r)].end());
  }
  std::vector<int> rcount(static_cast<std::size_t>(size_));
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm_);
  std::vector<int> rdispl(static_cast<std::size_t>(size_));
  std::size_t total = 0;
  for (int r = 0; r < size_; ++r) {
    rdispl[static_cast<std::size_t>(r)] = to_count(total);
    total += static_cast<std::size_t>(rcount[static_cast<std::size_t>(r)]);
  }
  std::vector<char> rbuf(total);
  MPI_Alltoallv(sbuf.data(), scount.data(), sdispl.data(), MPI_CHAR, rbuf.data(), rcount.data(),
                rdispl.data(), MPI_CHAR, comm_);
  ErrorKind kind_err = ErrorKind::none;
  std::string msg;
  std::vector<std::size_t> pos(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r)
    pos[static_cast<std::size_t>(r)] =
        static_cast<std::size_t>(rdispl[static_cast<std::size_t>(r)]);
  for (std::size_t k = 0; k < n; ++k) {
    if (new_owner[k] != rank_ || owner_[k] == rank_) continue;
    auto& p = pos[static_cast<std::size_t>(owner_[k])];
    const auto len = take<std::uint64_t>(rbuf.data(), p);
    try {
      const common::StateStore s = common::StateStore::deserialize(
          std::span<const char>(rbuf.data() + p, static_cast<std::size_t>(len)));
      models_[k] = kind_.load(s);
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = "farm: migrating the RVE of point id " + std::to_string(ids_[k]) + " to rank " +
            std::to_string(rank_) + " failed: " + e.what();
    }
    p += static_cast<std::size_t>(len);
  }
  std::int64_t moved = 0;
  for (std::size_t k = 0; k < n; ++k) moved += new_owner[k] != owner_[k] ? 1 : 0;
  if (moved > 0) ++migrations_;
  moved_ += moved;
  owner_ = std::move(new_owner);
  rebuild_local();
  agree_on_errors(comm_, kind_err, msg);
  times_.migrate_wall += now() - t0;
  step_at_migration_ = step_;
}

void RveFarm::stop() {
  MPMXDEM_CHECK(rank_ == 0, "stop is sent by rank 0");
  if (stopped_) return;
  stopped_ = true;
  if (size_ == 1) return;
  Header h;
  h.cmd = kStop;
  send_command(h);
}

void RveFarm::stop_with_error(ErrorKind kind, const std::string& message) {
  MPMXDEM_CHECK(rank_ == 0, "stop is sent by rank 0");
  if (stopped_) return;
  stopped_ = true;
  if (size_ == 1) return;
  Header h;
  h.cmd = kStopError;
  h.flag = static_cast<std::int32_t>(kind);
  send_command(h);
  std::string m = message;
  bcast_string(comm_, m);
}

void RveFarm::serve() {
  MPMXDEM_CHECK(rank_ != 0, "rank 0 drives the farm; it does not serve");
  for (;;) {
    const Header h = receive_command();
    switch (h.cmd) {
      case kStep:
        exec_step(h, {});
        break;
      case kCheckpoint:
        exec_checkpoint(h, std::string(), std::string(), nullptr);
        break;
      case kMigrate: {
        std::vector<int> part(ids_.size());
        MPI_Bcast(part.data(), to_count(part.size()), MPI_INT, 0, comm_);
        exec_migrate(std::move(part));
        break;
      }
      case kErrorTexts:
        exec_error_texts();
        break;
      case kStop:
        stopped_ = true;
        return;
      case kStopError: {
        stopped_ = true;
        std::string m;
        bcast_string(comm_, m);
        throw_kind(static_cast<ErrorKind>(h.flag), m);
      }
      default:
        throw common::InternalError("farm: unknown command " + std::to_string(h.cmd));
    }
  }
}

}  // namespace farm
