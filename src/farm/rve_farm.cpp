// RveFarm: the collective farm of RVEs, driven by rank 0 (see header and docs/design/farm.md,
// "Protocol"): step, checkpoint, migrate, serve, stop.
#include "farm/rve_farm.hpp"

#include <omp.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "farm/cost_trace.hpp"

namespace farm {

namespace {

/// CPU time of the calling thread [s]: a system call (about a microsecond on a VM), so it is read
/// once per thread and step, not once per RVE (exec_step).
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

MPI_Comm dup_comm(MPI_Comm comm) {
  MPI_Comm c = MPI_COMM_NULL;
  MPI_Comm_dup(comm, &c);
  return c;
}

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

int size_of(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}

FarmOptions resolved(MPI_Comm comm, FarmOptions options) {
  options.wait = resolve_wait_mode(comm, options.wait);
  return options;
}

/// The lowest rank that owns RVEs: 1 when rank 0 is left to the MPM and there is another rank.
int first_worker(const FarmOptions& options, int size) {
  return !options.rank0_rves && size > 1 ? 1 : 0;
}

}  // namespace

RveFarm::RveFarm(Setup /*tag*/, MPI_Comm comm, MicroKind kind, std::vector<std::int64_t> ids,
                 const mpm::Grid& grid, FarmOptions options)
    : comm_(dup_comm(comm)),
      rank_(rank_of(comm_)),
      size_(size_of(comm_)),
      kind_(std::move(kind)),
      options_(resolved(comm_, options)),
      grid_(grid),
      placement_(std::move(ids), rank_, size_, first_worker(options, size_)),
      models_(placement_.size()),
      exchange_(comm_, options_.wait) {}

RveFarm::RveFarm(MPI_Comm comm, MicroKind kind, std::vector<std::int64_t> ids,
                 const std::vector<common::Vec3>& x, const mpm::Grid& grid, FarmOptions options)
    : RveFarm(Setup{}, comm, std::move(kind), std::move(ids), grid, options) {
  ErrorKind kind_err = ErrorKind::none;
  std::string msg;
  if (kind_.prepare) {
    std::vector<std::int64_t> local_ids;
    for (const std::size_t k : placement_.local()) local_ids.push_back(placement_.ids()[k]);
    try {
      kind_.prepare(local_ids, comm_);
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = std::string("farm: preparing the RVEs failed: ") + e.what();
    }
  }
  for (const std::size_t k : placement_.local()) {
    if (kind_err != ErrorKind::none) break;
    try {
      models_[k] = kind_.create(placement_.ids()[k]);
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = "farm: creating the RVE of point id " + std::to_string(placement_.ids()[k]) +
            " failed: " + e.what();
      break;
    }
  }
  agree_on_errors(comm_, kind_err, msg);
  initial_costs_and_partition(x, nullptr);
  stopped_ = false;  // the workers serve from here on
}

RveFarm::RveFarm(MPI_Comm comm, MicroKind kind, const CheckpointInfo& info,
                 const std::vector<common::Vec3>& x, const mpm::Grid& grid, FarmOptions options)
    : RveFarm(Setup{}, comm, std::move(kind), info.ids, grid, options) {
  const std::vector<std::size_t>& local = placement_.local();
  std::vector<std::int64_t> local_i64(local.begin(), local.end());
  std::vector<common::StateStore> states = read_checkpoint_rves(comm_, info, local_i64);
  ErrorKind kind_err = ErrorKind::none;
  std::string msg;
  for (std::size_t j = 0; j < local.size(); ++j) {
    try {
      models_[local[j]] = kind_.load(states[j]);
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = "checkpoint " + info.path + ": restoring the RVE of point id " +
            std::to_string(placement_.ids()[local[j]]) + " failed: " + e.what();
      break;
    }
  }
  agree_on_errors(comm_, kind_err, msg);
  set_step(info.step);
  initial_costs_and_partition(x, &info.cost);
  stopped_ = false;  // the workers serve from here on
}

RveFarm::~RveFarm() {
  if (rank_ == 0 && size_ > 1 && !stopped_) {
    // Rank 0 is leaving (an exception unwound the driver): release the workers with an error
    // rather than leave them waiting.
    stop_with_error(ErrorKind::internal, "farm: rank 0 stopped without releasing the workers");
  }
  if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

void RveFarm::initial_costs_and_partition(const std::vector<common::Vec3>& x,
                                          const std::vector<double>* costs) {
  const std::size_t n = placement_.size();
  // Stresses, measures, wave speeds and cost estimates before the first step (outputs at step 0),
  // from the owners to every rank in one collective.
  std::vector<InitRecord> init(n);
  for (const std::size_t k : placement_.local()) {
    const MicroModel& m = model(k);
    InitRecord& r = init[k];
    common::row_major_out(r.stress) = m.stress();
    const MicroReport rep = m.report();
    std::size_t i = 0;
    for (const ReportField& f : kReportFields) {
      if (f.state) r.state[i++] = report_real(rep, f);
    }
    r.wave_speed = m.wave_speed();
    r.cost_estimate = m.cost_estimate();
  }
  allgather_owned(comm_, init);
  std::vector<double> est(n, 0.0);
  wave_.assign(n, 0.0);
  dilute_.assign(n, 0);
  reports_.assign(n, MicroReport{});
  stresses_.assign(n, common::Mat3::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    stresses_[k] = common::row_major(init[k].stress);
    std::size_t i = 0;
    for (const ReportField& f : kReportFields) {
      if (f.state) set_report_real(reports_[k], f, init[k].state[i++]);
    }
    wave_[k] = init[k].wave_speed;
    est[k] = init[k].cost_estimate;
  }
  wave_speed_ = n > 0 ? *std::max_element(wave_.begin(), wave_.end()) : 0.0;
  const bool measured = ledger_.reset(n, costs);
  std::vector<int> part(n, 0);
  ErrorKind trace_err = ErrorKind::none;
  std::string trace_msg;
  if (rank_ == 0) {
    MPMXDEM_CHECK(x.size() == n, "one position per RVE on rank 0");
    const int workers = placement_.workers();
    const RveGraph graph = cell_graph(grid_, x);
    if (const std::string path = cost_trace_path_from_env(); !path.empty()) {
      try {
        trace_ = std::make_unique<CostTrace>(path, graph, placement_.ids(),
                                             measured ? ledger_.total() : est);
        step_cpu_.assign(n, 0.0);
        step_dem_steps_.assign(n, 0);
        step_rebuilds_.assign(n, 0);
      } catch (const std::exception& e) {
        trace_err = current_error_kind();
        trace_msg = std::string("farm: MPMXDEM_COST_TRACE: ") + e.what();
      }
    }
    part = partition_fresh(options_.partition, graph, measured ? ledger_.total() : est, workers,
                           options_.metis_seed);
    keep_owners(placement_.parts(), part, workers);  // move as few RVEs as the partition allows
    part = placement_.owners_of(std::move(part));
  }
  agree_on_errors(comm_, trace_err, trace_msg);
  if (n > 0) MPI_Bcast(part.data(), to_count(n), MPI_INT, 0, comm_);
  exec_migrate(std::move(part));
}

void RveFarm::update_stress(std::span<const std::int64_t> ids, std::span<const common::Mat3> L,
                            double dt, std::span<common::Mat3> stress) {
  MPMXDEM_CHECK(rank_ == 0, "update_stress is called on rank 0 only");
  MPMXDEM_CHECK(ids.size() == L.size() && ids.size() == stress.size(), "span sizes differ");
  const double t0 = now();
  // The solver may hand the points in any order; the map is built once for that order.
  if (points_.size() != ids.size() || !points_.matches(ids))
    points_ = PointIndex(placement_.ids(), ids);
  // L of every rank's RVEs, in ascending index order, after that rank's header.
  for (int r = 0; r < size_; ++r) {
    const std::vector<std::size_t>& members = placement_.members(r);
    for (std::size_t i = 0; i < members.size(); ++i) {
      common::row_major_out(exchange_.L_out(r, i)) = L[points_.slot_of(members[i])];
    }
  }
  CommandHeader h;
  h.cmd = Command::step;
  h.step = step_ + 1;
  h.value = dt;
  exchange_.send(h);
  exec_step(h, stress);
  ledger_.add_step_wall(now() - t0);
}

void RveFarm::mark_dilute(std::span<const std::int64_t> ids, std::span<std::uint8_t> dilute) const {
  MPMXDEM_CHECK(rank_ == 0, "mark_dilute is called on rank 0 only");
  MPMXDEM_CHECK(ids.size() == dilute.size() && points_.size() == ids.size() && points_.matches(ids),
                "mark_dilute needs the ids of the last update_stress");
  for (std::size_t p = 0; p < ids.size(); ++p) dilute[p] = dilute_[points_.rve_of(p)];
}

void RveFarm::exec_step(const CommandHeader& h, std::span<common::Mat3> stress) {
  const double dt = h.value;
  step_ = h.step;
  // Advance my RVEs under the L that came with the command; failures are caught per RVE and
  // travel to rank 0 as data.
  const std::vector<std::size_t>& local = placement_.local();
  const double t_loop = now();
  const auto nl = static_cast<std::int64_t>(local.size());
  // An RVE's cost for balancing is the CPU time its step took: its wall time times the share of
  // the loop its thread was running (its CPU time over its wall time), which leaves out the time
  // the thread was not running (another rank on the same core, a preemption). The thread's CPU
  // clock is a system call, longer than a spared RVE's step: read once per thread, not per RVE.
  const bool team = options_.omp_over_rves && nl > 1;
  records_.assign(local.size(), RveRecord{});
  stepped_by_.assign(local.size(), 0);
  std::vector<double> running(static_cast<std::size_t>(team ? omp_get_max_threads() : 1), 1.0);
#pragma omp parallel if (team)
  {
    const int t = omp_get_thread_num();
    const double cpu0 = thread_cpu_s();
    const double wall0 = now();
#pragma omp for schedule(dynamic, 1) nowait
    for (std::int64_t jj = 0; jj < nl; ++jj) {
      const auto j = static_cast<std::size_t>(jj);
      MicroModel& m = model(local[j]);
      RveRecord& rec = records_[j];
      stepped_by_[j] = t;
      errors_[j].clear();
      try {
        const double w0 = now();
        rec.report = m.step(exchange_.L_in(j), dt);
        rec.cpu_s = now() - w0;  // its wall time: scaled below
        const common::Mat3 s = m.stress();
        if (!s.allFinite())
          throw common::NumericalError("non-finite stress (trace = " + std::to_string(s.trace()) +
                                       " Pa)");
        common::row_major_out(rec.stress) = s;
        rec.wave_speed = m.wave_speed();
        rec.dilute = m.dilute() ? 1 : 0;
      } catch (const std::exception& e) {
        rec.error = current_error_kind();
        errors_[j] = e.what();
      }
    }
    const double wall = now() - wall0;
    const double cpu = thread_cpu_s() - cpu0;
    running[static_cast<std::size_t>(t)] = wall > 0.0 ? std::clamp(cpu / wall, 0.0, 1.0) : 1.0;
  }
  for (std::size_t j = 0; j < local.size(); ++j) {
    records_[j].cpu_s *= running[static_cast<std::size_t>(stepped_by_[j])];
    exchange_.put(j, records_[j]);
  }
  exchange_.set_busy(now() - t_loop);
  exchange_.gather();
  if (rank_ == 0) collect_records(stress);
}

void RveFarm::collect_records(std::span<common::Mat3> stress) {
  // Store by RVE index (never by arrival order), then answer the solver.
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
    const double busy = exchange_.busy(r);
    busy_max = std::max(busy_max, busy);
    busy_sum += busy;
    const std::vector<std::size_t>& members = placement_.members(r);
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::size_t k = members[i];
      const RveRecord rec = exchange_.record(r, i);
      if (rec.error != ErrorKind::none) {
        failures.push_back({placement_.ids()[k], r, rec.error, ""});
        continue;
      }
      stresses_[k] = common::row_major(rec.stress);
      reports_[k] = rec.report;
      wave_[k] = rec.wave_speed;
      dilute_[k] = static_cast<std::uint8_t>(rec.dilute);
      ledger_.add_rve(k, rec.cpu_s);
      if (trace_) {
        step_cpu_[k] = rec.cpu_s;
        step_dem_steps_[k] = rec.report.dem_steps;
        step_rebuilds_[k] = rec.report.rebuilds;
      }
    }
  }
  ledger_.add_step(busy_max, busy_sum / placement_.workers());
  if (trace_ && failures.empty()) {
    std::vector<double> busy(static_cast<std::size_t>(size_));
    for (int r = 0; r < size_; ++r) busy[static_cast<std::size_t>(r)] = exchange_.busy(r);
    trace_->record(step_, placement_.owner(), step_cpu_, busy, step_dem_steps_, step_rebuilds_);
  }
  if (!failures.empty()) {
    // Rare: fetch the texts with a command of their own (the step exchange carries none).
    CommandHeader e;
    e.cmd = Command::error_texts;
    e.step = step_;
    exchange_.send(e);
    for (const auto& [k, text] : exec_error_texts()) {
      for (Failure& f : failures) {
        if (f.id == placement_.ids()[k]) f.text = text;
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
  for (std::size_t k = 0; k < stresses_.size(); ++k) stress[points_.slot_of(k)] = stresses_[k];
}

std::vector<std::pair<std::size_t, std::string>> RveFarm::exec_error_texts() {
  std::vector<std::pair<std::size_t, std::string>> mine;
  const std::vector<std::size_t>& local = placement_.local();
  for (std::size_t j = 0; j < local.size(); ++j) {
    if (!errors_[j].empty()) mine.emplace_back(local[j], errors_[j]);
  }
  return gather_texts(comm_, mine);
}

std::vector<MicroMeasures> RveFarm::measure() {
  MPMXDEM_CHECK(rank_ == 0, "measures are requested by rank 0");
  CommandHeader h;
  h.cmd = Command::measure;
  h.step = step_;
  exchange_.send(h);
  return exec_measure();
}

std::vector<MicroMeasures> RveFarm::exec_measure() {
  const std::vector<std::size_t>& local = placement_.local();
  std::vector<MicroMeasures> mine(local.size());
  const auto nl = static_cast<std::int64_t>(local.size());
#pragma omp parallel for schedule(dynamic, 1) if (options_.omp_over_rves && nl > 1)
  for (std::int64_t jj = 0; jj < nl; ++jj) {
    const auto j = static_cast<std::size_t>(jj);
    // Measures only read the state; a failure here (none is expected) leaves NaN in the row
    // rather than an exception inside the parallel loop or a rank missing the gather.
    try {
      mine[j] = model(local[j]).measures();
    } catch (...) {
      mine[j] = MicroMeasures::none();
    }
  }
  return gather_measures(comm_, placement_, mine, options_.wait);
}

void RveFarm::checkpoint(const std::string& path, std::int64_t step, double time,
                         const std::string& job_text, const common::StateStore& mpm_state,
                         bool abort_mid_write) {
  MPMXDEM_CHECK(rank_ == 0, "checkpoint is driven by rank 0");
  CommandHeader h;
  h.cmd = Command::checkpoint;
  h.flag = abort_mid_write ? 1 : 0;
  h.step = step;
  h.value = time;
  exchange_.send(h);
  exec_checkpoint(h, path, job_text, &mpm_state);
}

void RveFarm::exec_checkpoint(const CommandHeader& h, std::string path, std::string job_text,
                              const common::StateStore* mpm_state) {
  bcast_string(comm_, path);
  const std::vector<std::size_t>& local = placement_.local();
  CheckpointData d;
  d.step = h.step;
  d.time = h.value;
  d.job_text = std::move(job_text);
  d.ids = placement_.ids();
  d.owner = placement_.owner();
  d.cost = ledger_.total();
  d.local_indices.assign(local.begin(), local.end());
  d.local_states.resize(local.size());
  for (std::size_t j = 0; j < local.size(); ++j) model(local[j]).save(d.local_states[j]);
  d.mpm = mpm_state;
  try {
    write_checkpoint(comm_, path, d, h.flag != 0);
  } catch (...) {
    // Its failures are thrown on every rank (agreed): the workers leave serve() with it, and
    // rank 0 must not send them a stop they would never receive.
    stopped_ = true;
    throw;
  }
}

bool RveFarm::rebalance_if_needed(double threshold, const std::vector<common::Vec3>& x) {
  MPMXDEM_CHECK(rank_ == 0, "rebalancing is driven by rank 0");
  const Payback pay = ledger_.close_window(step_);
  last_plan_ = RebalancePlan{};
  if (placement_.workers() == 1 || !ledger_.average().settled()) return false;
  last_plan_ =
      plan_rebalance(cell_graph(grid_, x), placement_.parts(), ledger_.average().cost(),
                     placement_.workers(), threshold, options_.metis_seed, pay, options_.partition);
  last_plan_.owner = placement_.owners_of(std::move(last_plan_.owner));  // parts -> ranks
  if (!last_plan_.migrate) return false;
  migrate_to(last_plan_.owner);
  return true;
}

void RveFarm::migrate_to(std::vector<int> owner) {
  MPMXDEM_CHECK(rank_ == 0, "migration is driven by rank 0");
  MPMXDEM_CHECK(owner.size() == placement_.size(), "one owner per RVE");
  for (int o : owner)
    MPMXDEM_CHECK(o >= placement_.first_worker() && o < size_, "owner rank out of range");
  if (size_ == 1) return;
  CommandHeader h;
  h.cmd = Command::migrate;
  exchange_.send(h);
  MPI_Bcast(owner.data(), to_count(owner.size()), MPI_INT, 0, comm_);
  exec_migrate(std::move(owner));
}

void RveFarm::exec_migrate(std::vector<int> new_owner) {
  const double t0 = now();
  const std::size_t n = placement_.size();
  const std::vector<int>& owner = placement_.owner();
  // Saved states by destination, in ascending index order.
  std::vector<std::vector<std::vector<char>>> to(static_cast<std::size_t>(size_));
  for (const std::size_t k : placement_.local()) {
    const int dest = new_owner[k];
    if (dest == rank_) continue;
    common::StateStore s;
    models_[k]->save(s);
    to[static_cast<std::size_t>(dest)].push_back(s.serialize());
    models_[k].reset();
  }
  const std::vector<std::vector<std::vector<char>>> from = exchange_blobs(comm_, to);
  ErrorKind kind_err = ErrorKind::none;
  std::string msg;
  std::vector<std::size_t> next(static_cast<std::size_t>(size_), 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (new_owner[k] != rank_ || owner[k] == rank_) continue;
    const auto src = static_cast<std::size_t>(owner[k]);
    const std::vector<char>& bytes = from[src][next[src]++];
    try {
      models_[k] = kind_.load(common::StateStore::deserialize(bytes));
    } catch (const std::exception& e) {
      kind_err = current_error_kind();
      msg = "farm: migrating the RVE of point id " + std::to_string(placement_.ids()[k]) +
            " to rank " + std::to_string(rank_) + " failed: " + e.what();
    }
  }
  const std::int64_t moved = placement_.moves_to(new_owner);
  placement_.set_owner(std::move(new_owner));
  exchange_.layout(placement_);
  errors_.assign(placement_.local().size(), std::string());
  agree_on_errors(comm_, kind_err, msg);
  ledger_.add_migration(moved, now() - t0, step_);
}

void RveFarm::stop() {
  MPMXDEM_CHECK(rank_ == 0, "stop is sent by rank 0");
  if (stopped_) return;
  stopped_ = true;
  if (size_ == 1) return;
  CommandHeader h;
  h.cmd = Command::stop;
  exchange_.send(h);
}

void RveFarm::stop_with_error(ErrorKind kind, const std::string& message) {
  MPMXDEM_CHECK(rank_ == 0, "stop is sent by rank 0");
  if (stopped_) return;
  stopped_ = true;
  if (size_ == 1) return;
  CommandHeader h;
  h.cmd = Command::stop_error;
  h.flag = static_cast<std::int32_t>(kind);
  exchange_.send(h);
  std::string m = message;
  bcast_string(comm_, m);
}

void RveFarm::serve() {
  MPMXDEM_CHECK(rank_ != 0, "rank 0 drives the farm; it does not serve");
  for (;;) {
    const CommandHeader h = exchange_.receive();
    switch (h.cmd) {
      case Command::step:
        exec_step(h, {});
        break;
      case Command::checkpoint:
        exec_checkpoint(h, std::string(), std::string(), nullptr);
        break;
      case Command::migrate: {
        std::vector<int> part(placement_.size());
        MPI_Bcast(part.data(), to_count(part.size()), MPI_INT, 0, comm_);
        exec_migrate(std::move(part));
        break;
      }
      case Command::error_texts:
        exec_error_texts();
        break;
      case Command::measure:
        (void)exec_measure();
        break;
      case Command::grains:
        (void)exec_grains(h, {}, std::string());
        break;
      case Command::stop:
        stopped_ = true;
        return;
      case Command::stop_error: {
        stopped_ = true;
        std::string m;
        bcast_string(comm_, m);
        throw_kind(static_cast<ErrorKind>(h.flag), m);
      }
      default:
        throw common::InternalError("farm: unknown command " +
                                    std::to_string(static_cast<std::int32_t>(h.cmd)));
    }
  }
}

}  // namespace farm
