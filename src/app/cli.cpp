// CLI11 definition of the mpmxdem command line: see cli.hpp and README.md.
#include "app/cli.hpp"

#include <CLI/CLI.hpp>

#include <sstream>

#include "app/version.hpp"

namespace app {

std::optional<Options> parse_cli(int argc, char** argv, bool print, int& exit_code) {
  Options o;
  CLI::App cli{
      "mpmxdem: multi-scale granular mechanics. Every material point of an MPM grid takes its\n"
      "stress from its own periodic DEM cell (an RVE). Run in parallel with\n"
      "  mpirun -n N mpmxdem run JOB.toml\n"
      "Job files are TOML; `mpmxdem schema` prints the reference of every key.",
      "mpmxdem"};
  cli.set_version_flag("--version", std::string("mpmxdem ") + kVersion);
  cli.require_subcommand(1);
  cli.add_flag("-v,--verbose", o.verbosity,
               "More log output (-v debug, -vv trace; all ranks at -vv)");

  auto* run = cli.add_subcommand(
      "run",
      "Run a coupled MPM x DEM job: validate it, then simulate, writing results.h5 (time series),\n"
      "points.xmf (ParaView), means.csv, log.txt and checkpoint_<step>.h5 files into --out");
  run->add_option("job", o.job, "Job file (TOML)")->required();
  run->add_option("-o,--out", o.out, "Output directory (default: results/<job file name>)");
  run->add_option(
      "--restart", o.restart,
      "Continue from this checkpoint file (HDF5), on any number of ranks, bit for bit; --out\n"
      "should be the run's directory (results.h5 is cut back to the checkpoint's step)");
  run->add_option("--max-steps", o.max_steps,
                  "Stop after this many MPM steps in total, restarts included (trials, tests); a "
                  "checkpoint\n"
                  "is written at the end")
      ->check(CLI::PositiveNumber);
  run->add_flag("--force", o.force,
                "Write into a non-empty output directory (files of the same name are replaced)");

  auto* check = cli.add_subcommand(
      "check", "Validate a job file and print the resolved job (no output written)");
  check->add_option("job", o.job, "Job file (TOML)")->required();

  auto* inspect =
      cli.add_subcommand("inspect",
                         "Describe a checkpoint (step, time, RVEs, ranks that wrote it) "
                         "and verify its checksums");
  inspect->add_option("checkpoint", o.job, "Checkpoint file (HDF5)")->required();

  auto* demc = cli.add_subcommand(
      "dem", "Run a pure DEM job: prepare a sample, then the loading of [dem.loading]");
  demc->add_option("job", o.job, "Job file (TOML)")->required();
  demc->add_option("-o,--out", o.out, "Output directory (default: results/<job file name>)");
  demc->add_option("--max-steps", o.max_steps, "Stop the loading after this many DEM steps")
      ->check(CLI::NonNegativeNumber);
  demc->add_flag("--force", o.force, "Write into a non-empty output directory");

  auto* bench = cli.add_subcommand(
      "bench", "Print performance figures (never a test): `bench dem`, `bench mpm`");
  bench->add_option("what", o.bench, "What to measure")
      ->required()
      ->check(CLI::IsMember({"dem", "mpm"}));
  bench
      ->add_option("--size", o.bench_size,
                   "dem: tiling n of the reference packing (n^3 x 1000 spheres); "
                   "mpm: number of material points")
      ->check(CLI::PositiveNumber);
  bench->add_option("--steps", o.bench_steps, "Timed steps")->check(CLI::PositiveNumber);

  cli.add_subcommand("schema", "Print the job-file reference (Markdown) generated from the schema");

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream out;
    std::ostringstream err;
    exit_code = cli.exit(e, out, err);
    if (print) {
      std::fputs(out.str().c_str(), stdout);
      std::fputs(err.str().c_str(), stderr);
    }
    return std::nullopt;
  }
  for (const auto* sub : cli.get_subcommands()) o.command = sub->get_name();
  exit_code = 0;
  return o;
}

}  // namespace app
