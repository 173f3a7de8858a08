// Per-step cost trace of a farm: what balancing saw, step by step, for an offline replay
// (bench_farm replay) or a look in pandas. A diagnostic, switched on by the environment
// (MPMXDEM_COST_TRACE=<path>), written by rank 0 only; results are never touched by it.
//
// <path>: one CSV row per MPM step and RVE:
//   step, rve (index), id (point id), rank (owner during the step), cpu_s (thread CPU time of the
//   RVE's step [s]), busy_s (wall time of its rank's RVE loop in that step [s]), dem_steps and
//   rebuilds (the DEM steps and neighbour-list builds the RVE ran in that step: the work its cost
//   follows; traces written before these two columns were added read back without them)
// <path>.graph.csv: the RVE graph the partitions are made on (rve, neighbour: both directions),
// as it was at the start of the run (cell_graph of the start-up positions).
// <path>.start.csv: rve, id, weight: what the start-up partition was weighted by (the models'
// cost estimates, or a checkpoint's measured costs on a restart).
#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "farm/partition.hpp"

namespace farm {

/// The trace's path from the environment: MPMXDEM_COST_TRACE, empty when unset or empty.
[[nodiscard]] std::string cost_trace_path_from_env();

class CostTrace {
 public:
  /// Creates (truncates) `path` and writes `path`.graph.csv from `graph` and `path`.start.csv
  /// from `start_weight` (by RVE index). Throws common::IoError naming the file and the system's
  /// reason.
  CostTrace(std::string path, const RveGraph& graph, std::vector<std::int64_t> ids,
            const std::vector<double>& start_weight);
  /// One MPM step: owner, cpu_s, dem_steps and rebuilds by RVE index, busy_s by rank. Throws
  /// common::IoError.
  void record(std::int64_t step, std::span<const int> owner, std::span<const double> cpu_s,
              std::span<const double> busy_s, std::span<const std::int64_t> dem_steps,
              std::span<const std::int64_t> rebuilds);
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::int64_t> ids_;
  std::ofstream out_;
};

/// One trace read back: cost[s][k] for the steps in file order, the steps' numbers, the graph.
struct CostTraceData {
  std::vector<std::int64_t> steps;
  std::vector<std::vector<double>> cpu_s;   ///< [step row][rve index]
  std::vector<std::vector<double>> busy_s;  ///< [step row][rank] as recorded
  /// [step row][rve index]; both empty for a trace written without the columns.
  std::vector<std::vector<std::int64_t>> dem_steps;
  std::vector<std::vector<std::int64_t>> rebuilds;
  RveGraph graph;
  std::vector<double> start_weight;  ///< by RVE index
};

/// Reads `path`, `path`.graph.csv and `path`.start.csv. Throws common::InputError naming the file
/// and line of a malformed row, common::IoError when a file cannot be read.
[[nodiscard]] CostTraceData read_cost_trace(const std::string& path);

}  // namespace farm
