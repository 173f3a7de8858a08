// The farm's wire: typed records and the two collectives of an MPM step (docs/design/farm.md,
// "Protocol"). Rank 0 scatters [CommandHeader | L block] to every rank with one MPI_Iscatterv;
// every rank gathers [busy | RveRecord...] back to rank 0 with one MPI_Igatherv. Buffers are laid
// out once per partition (no allocation per step); record sizes are sizeof of the structs below.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "farm/micro_model.hpp"
#include "farm/mpi_util.hpp"
#include "farm/placement.hpp"

namespace farm {

/// What rank 0 asks of every rank.
enum class Command : std::int32_t {
  step = 1,         ///< step my RVEs under the L block that follows the header
  checkpoint = 2,   ///< write my RVEs into a collective checkpoint (path broadcast next)
  migrate = 3,      ///< adopt new owners (broadcast next) and move RVEs
  stop = 4,         ///< return from serve()
  stop_error = 5,   ///< throw the error whose text is broadcast next
  error_texts = 6,  ///< send the texts of the last step's RVE failures
  measure = 7,      ///< gather the grain-scale measures of my RVEs (an output row is written)
  grains = 8,       ///< write the grain-scale views of the chosen RVEs I own (list broadcast next)
};

/// In front of every rank's command message (24 bytes).
struct CommandHeader {
  Command cmd = Command::stop;
  std::int32_t flag = 0;  ///< checkpoint: abort mid-write (fault injection); stop_error: ErrorKind
  std::int64_t step = 0;  ///< MPM step being computed (step) or done (checkpoint)
  double value = 0.0;     ///< step: dt [s]; checkpoint: MPM time [s]
};
static_assert(std::is_trivially_copyable_v<CommandHeader>);
static_assert(sizeof(CommandHeader) == 24 && sizeof(CommandHeader) % sizeof(double) == 0);

/// What one RVE's step sends back to rank 0 (160 bytes).
struct RveRecord {
  double stress[9] = {};    ///< Cauchy stress, row-major [Pa, tension positive]
  MicroReport report;       ///< the step's report
  double wave_speed = 0.0;  ///< MicroModel::wave_speed after the step [m/s]
  double cpu_s = 0.0;       ///< CPU time of its step (the RVE's cost: RveFarm::exec_step) [s]
  ErrorKind error = ErrorKind::none;  ///< the step failed: the text follows on request
  std::int32_t dilute = 0;            ///< MicroModel::dilute after the step (1) or not (0)
};
static_assert(std::is_trivially_copyable_v<RveRecord>);
static_assert(sizeof(RveRecord) == 160 && sizeof(RveRecord) % sizeof(double) == 0);

/// What every RVE tells all ranks once created or restored (before any step): the measures of
/// outputs at step 0, the wave speed and the cost estimate. Doubles only, so that a bitwise OR
/// over ranks (each entry set by its owner, zero elsewhere) assembles it exactly.
struct InitRecord {
  double stress[9] = {};  ///< row-major [Pa, tension positive]
  /// The report's state fields (the rows of kReportFields with `state`, in their order).
  double state[report_state_fields()] = {};
  double wave_speed = 0.0;     ///< [m/s]
  double cost_estimate = 0.0;  ///< MicroModel::cost_estimate [arbitrary]
};
static_assert(std::is_trivially_copyable_v<InitRecord>);
static_assert(sizeof(InitRecord) == (11 + report_state_fields()) * sizeof(double));

/// What Command::measure gathers per RVE (the doubles of kMeasureFields, whose size check is in
/// micro_model.hpp), only when an output row is written: the step's RveRecord does not carry it,
/// so the other steps neither compute nor send it.
static_assert(std::is_trivially_copyable_v<MicroMeasures>);

/// Collective over `comm` (Command::measure): `mine` (this rank's RVEs in Placement::local()
/// order) of every rank to rank 0, returned there by RVE index (empty elsewhere). One
/// MPI_Igatherv of MicroMeasures bytes, completed with `wait`.
std::vector<MicroMeasures> gather_measures(MPI_Comm comm, const Placement& placement,
                                           const std::vector<MicroMeasures>& mine, WaitMode wait);

/// Collective over `comm`: every rank's InitRecords (by RVE index, set on the owners) on every
/// rank, exactly (bitwise OR of the 8-byte words; a sum would turn -0.0 into 0.0).
/// @pre the entries this rank does not own are zero
void allgather_owned(MPI_Comm comm, std::vector<InitRecord>& by_index);

/// The step's two collectives with buffers laid out per partition. Every rank holds one; the
/// command side is filled by rank 0, the record side by every rank.
class StepExchange {
 public:
  /// `comm` is not owned and must outlive this object.
  StepExchange(MPI_Comm comm, WaitMode wait);
  /// Lays out the messages of `placement` (after every change of owners).
  void layout(const Placement& placement);

  // ---- command (rank 0 -> every rank) ----
  /// Rank 0: the L of the i-th RVE of rank r (in Placement::members(r) order), 9 doubles to be
  /// written row-major before send().
  [[nodiscard]] double* L_out(int r, std::size_t i);
  /// Rank 0: the header into every rank's message, then the scatter.
  void send(const CommandHeader& header);
  /// Ranks > 0: the next command (its L block stays here).
  [[nodiscard]] CommandHeader receive();
  /// This rank's j-th RVE's L, as sent [1/s].
  [[nodiscard]] common::Mat3 L_in(std::size_t j) const;

  // ---- records (every rank -> rank 0) ----
  /// Sets this rank's j-th record (thread-safe for distinct j).
  void put(std::size_t j, const RveRecord& record);
  /// This rank's RVE loop time of the step [s of wall].
  void set_busy(double s);
  /// Collective: the records of every rank to rank 0.
  void gather();
  /// Rank 0: rank r's busy time [s] and its i-th record (members(r) order).
  [[nodiscard]] double busy(int r) const;
  [[nodiscard]] RveRecord record(int r, std::size_t i) const;

 private:
  static constexpr std::size_t kHeaderWords = sizeof(CommandHeader) / sizeof(double);
  static constexpr std::size_t kRecordWords = sizeof(RveRecord) / sizeof(double);
  MPI_Comm comm_;
  WaitMode wait_;
  int rank_ = 0;
  // Buffers of doubles (8-byte aligned); counts and displacements in bytes (MPI_BYTE).
  std::vector<int> cmd_counts_, cmd_displs_;
  std::vector<double> cmd_send_;  ///< rank 0: [header][L] of every rank
  std::vector<double> cmd_recv_;  ///< my [header][L block]
  std::vector<int> rec_counts_, rec_displs_;
  std::vector<double> rec_;      ///< my [busy][records]
  std::vector<double> rec_all_;  ///< rank 0: every rank's, by rank
};

/// Collective: the texts of every rank's failed RVEs, (RVE index, text), on rank 0.
std::vector<std::pair<std::size_t, std::string>> gather_texts(
    MPI_Comm comm, const std::vector<std::pair<std::size_t, std::string>>& mine);

/// Collective: sends blob b of `to[r]` to rank r (in order) and returns the blobs received from
/// every rank, by source rank, in the order they were sent (migration of saved RVE states).
std::vector<std::vector<std::vector<char>>> exchange_blobs(
    MPI_Comm comm, const std::vector<std::vector<std::vector<char>>>& to);

}  // namespace farm
