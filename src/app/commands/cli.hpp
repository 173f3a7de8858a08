// Command-line interface (CLI11 is confined to cli.cpp to keep compile times down).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace app {

struct Options {
  std::string command;          ///< "run", "check", "schema", "dem", "bench", "inspect"
  std::string job;              ///< job file (inspect: the checkpoint)
  std::string out;              ///< output directory ("" = results/<job stem>)
  std::string restart;          ///< checkpoint to continue from
  std::int64_t max_steps = -1;  ///< stop after this many steps (-1: no limit)
  double max_wall_s = 0.0;      ///< run: stop with a checkpoint before this wall time [s] (0: none)
  bool force = false;           ///< write into a non-empty output directory
  bool schema_outputs = false;  ///< schema: print the results.h5 reference instead
  int verbosity = 0;            ///< -v count
  std::string bench;            ///< bench target: "dem" or "mpm"
  std::int64_t bench_size = 0;  ///< bench: problem size (0: the target's default)
  int bench_steps = 0;          ///< bench: timed steps (0: default)
  std::vector<std::string> rve;  ///< inspect: RVE (point) ids, or "all"
  std::string vtk;               ///< inspect: directory for the grain-scale VTK views ("" = none)
};

/// Parses the command line. Returns nullopt when the program should exit at once (help, version,
/// usage error) with `exit_code`; prints only when `print` is true (rank 0).
[[nodiscard]] std::optional<Options> parse_cli(int argc, char** argv, bool print, int& exit_code);

}  // namespace app
