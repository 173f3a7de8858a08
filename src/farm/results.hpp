// Run outputs of the coupled driver (rank 0 only): results.h5 (extendible time series of every RVE
// and material point), points.xmf (XDMF index for ParaView) and means.csv (sample means).
// Layout: docs/reference/outputs.md.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "farm/h5_util.hpp"
#include "farm/micro_model.hpp"
#include "mpm/material_points.hpp"

namespace farm {

/// Sample means of one output row. Compression positive.
struct SampleMeans {
  double eps_ax = 0.0;  ///< 1 - mean_p F_aa (a = axial axis) [-]
  double eps_v = 0.0;   ///< 1 - sum V_p / sum V0_p [-]
  double p = 0.0;       ///< mean over RVEs of p [Pa]
  double q = 0.0;       ///< mean over RVEs of q [Pa]
};

[[nodiscard]] SampleMeans sample_means(const mpm::MaterialPoints& points,
                                       const std::vector<MicroReport>& reports, int axial_axis);

struct SeriesSpec;  ///< one dataset of results.h5 (results.cpp)

class ResultsWriter {
 public:
  /// Creates `dir`/results.h5, or, when restart_step >= 0 and the file exists, reopens it and
  /// drops the rows after restart_step (so a restarted run's file equals the uninterrupted one).
  /// rve_ids: ascending; the points' ids and order must stay those of `points`.
  /// constraint_names (mpm::Solver::constraint_names): when not empty, /constraints/reaction and
  /// /constraints/displacement are written and reactions.csv beside means.csv.
  /// initial: the points at t = 0 (the job's, also on a restart): /points/displacement is
  /// x - x0 with x0 their position of the same id (NaN for an id they lack); nullptr: x0 =
  /// `points`' positions now.
  ResultsWriter(const std::string& dir, const std::vector<std::int64_t>& rve_ids,
                const mpm::MaterialPoints& points, std::int64_t restart_step,
                std::vector<std::string> constraint_names = {},
                const mpm::MaterialPoints* initial = nullptr);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// One output row. rve_stress/reports by RVE index (ascending ids). Rows are kept in memory
  /// and written in blocks (kRowsPerWrite rows or kBytesPerWrite bytes), by flush() and by the
  /// destructor (a run that stops on an error keeps its completed rows, in results.h5 and in the
  /// indexes: points.xmf, means.csv, reactions.csv).
  /// reactions, displacements: one per constraint name (mpm::Solver::reactions and
  /// constraint_displacements) [N], [m]; ignored without constraint names.
  /// measures: grain-scale measures by RVE index (RveFarm::measure); empty: NaN rows.
  void append(std::int64_t step, double time, const std::vector<common::Mat3>& rve_stress,
              const std::vector<MicroReport>& reports, const mpm::MaterialPoints& points,
              const SampleMeans& means, const std::vector<common::Vec3>& reactions = {},
              const std::vector<common::Vec3>& displacements = {},
              const std::vector<MicroMeasures>& measures = {});
  /// Writes the pending rows, flushes results.h5 and rewrites points.xmf, means.csv and
  /// reactions.csv (atomic
  /// rename each). With `indexes` false the two are rewritten only if the time since their last
  /// rewrite is at least their cost over kIndexShare (progress lines of long runs).
  void flush(bool indexes = true);
  /// Rows appended so far (written or pending), restart rows included.
  [[nodiscard]] std::int64_t rows() const { return rows_ + pending_; }

  static constexpr std::int64_t kRowsPerWrite = 64;
  static constexpr std::size_t kBytesPerWrite = 8u << 20;
  /// Room reserved beyond a block's rows before HDF5 writes it (chunk and metadata overhead).
  static constexpr std::size_t kReserveSlack = 1u << 20;
  static constexpr double kIndexShare = 0.005;  ///< wall-time share of index rewrites [-]
  /// Root attributes "format" and "format_version" of results.h5 (the layout of
  /// docs/design/farm.md).
  static constexpr const char* kFormat = "mpmxdem results";
  static constexpr std::int64_t kFormatVersion = 1;
  /// First line of means.csv: the column names, units as suffixes (strains are [-]).
  static constexpr const char* kMeansCsvHeader = "step,time_s,eps_ax,eps_v,p_mean_Pa,q_mean_Pa";

 private:
  struct Series;
  void create_series(const SeriesSpec& spec);
  /// A series missing from a file being continued (written by an earlier version): created
  /// with `keep` rows of NaN.
  void create_nan_series(const SeriesSpec& spec, std::uint64_t keep);
  void open_constraints(std::uint64_t keep);
  void describe_constraints();
  void stage_row(const std::string& name, const void* data);
  void write_pending();
  // append()'s parts: the constraints' reactions and displacements, the RVEs' series, the
  // points' series.
  void stage_constraints(const std::vector<common::Vec3>& reactions,
                         const std::vector<common::Vec3>& displacements);
  void stage_rves(const std::vector<common::Mat3>& rve_stress,
                  const std::vector<MicroReport>& reports,
                  const std::vector<MicroMeasures>& measures);
  void stage_points(const mpm::MaterialPoints& points);
  void write_xdmf() const;
  void write_csv() const;

  std::string dir_;
  std::vector<std::int64_t> rve_ids_;
  std::vector<std::int64_t> point_ids_;
  std::vector<std::size_t> rve_of_point_;  ///< RVE index of every point slot
  std::vector<common::Vec3> x0_;           ///< position at t = 0 of every point slot [m]
  h5::Handle file_;
  std::map<std::string, std::unique_ptr<Series>> series_;
  std::int64_t rows_ = 0;     ///< rows written to results.h5
  std::int64_t pending_ = 0;  ///< rows appended, not written yet
  std::size_t pending_bytes_ = 0;
  std::vector<std::int64_t> steps_;  ///< of every row (written or pending)
  std::vector<double> times_;
  std::vector<std::array<double, 4>> means_;  ///< eps_ax, eps_v, p, q of every row
  std::vector<std::string> constraint_names_;
  std::vector<std::vector<double>> constraint_rows_;  ///< per row: rx ry rz ux uy uz per constraint
  std::chrono::steady_clock::time_point index_written_{};  ///< last rewrite of xmf + csv
  double index_cost_s_ = 0.0;                              ///< its duration [s]
  std::int64_t indexed_rows_ = -1;  ///< rows() when the indexes were last rewritten (-1: never)
};

/// The reference of results.h5 (Markdown): every dataset with its shape, unit and description,
/// from the tables the writer creates them with (docs/reference/results_h5.md, printed by
/// `mpmxdem schema --outputs`).
[[nodiscard]] std::string results_reference_markdown();

}  // namespace farm
