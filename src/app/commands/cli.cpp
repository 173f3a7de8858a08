// CLI11 definition of the mpmxdem command line: see cli.hpp and README.md.
#include "app/commands/cli.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "app/commands/version.hpp"
#include "app/job/job.hpp"
#include "app/job/units.hpp"

namespace app {

namespace {

// Short texts for user input echoed in messages (a 100 kB argument is not printed whole).
std::string clip(const std::string& s) { return s.size() > 80 ? s.substr(0, 77) + "..." : s; }

// An integer option's rule, with a short message ("must be an integer >= 1, not 'abc'") instead of
// CLI11's range text with its 309-digit bound.
CLI::Validator integer_at_least(std::int64_t min,
                                std::int64_t max = std::numeric_limits<std::int64_t>::max()) {
  const std::string rule =
      max == std::numeric_limits<std::int64_t>::max()
          ? "an integer >= " + std::to_string(min)
          : "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  return CLI::Validator(
      [min, max, rule](std::string& text) -> std::string {
        std::int64_t v = 0;
        const char* end = text.data() + text.size();
        const auto res = std::from_chars(text.data(), end, v);
        if (res.ec != std::errc() || res.ptr != end || v < min || v > max) {
          return "must be " + rule + ", not '" + clip(text) + "'";
        }
        return "";
      },
      "INT");
}

constexpr std::array<const char*, 6> kCommands = {"run",     "check", "dem",
                                                  "inspect", "bench", "schema"};

// --max-wall: "23.5 h", "90 min" or bare seconds, > 0 and finite.
double parse_max_wall(const std::string& text) {
  std::string why;
  // A bare number is seconds (a job's time keys read "<number> <unit>" strings).
  double seconds = 0.0;
  const char* end = text.data() + text.size();
  const auto bare = std::from_chars(text.data(), end, seconds);
  const auto v = bare.ec == std::errc() && bare.ptr == end
                     ? std::optional<double>(seconds)
                     : parse_quantity(text, Quantity::Time, why);
  if (!v || !(*v > 0.0) || !std::isfinite(*v)) {
    throw CLI::ValidationError("--max-wall",
                               "must be a duration > 0 (\"23.5 h\", \"90 min\", "
                               "or seconds), not '" +
                                   clip(text) + "'" + (why.empty() ? "" : ": " + why));
  }
  return *v;
}

void add_run(CLI::App& cli, Options& o) {
  auto* run = cli.add_subcommand(
      "run",
      "Run a coupled MPM x DEM job: validate it, then simulate, writing results.h5 (time series),\n"
      "points.xmf (ParaView), means.csv, log.txt and checkpoint_<step>.h5 files into --out");
  run->footer(
      "A signal (SIGUSR1 to mpirun, which forwards it; SIGTERM, SIGUSR1 or SIGUSR2 to every\n"
      "rank, as a batch system sends before or at a time limit) ends the run after its current\n"
      "MPM step with a checkpoint; it exits 128 + the signal, and --restart latest continues it\n"
      "(docs/reference/errors.md, \"Stopping a run\").");
  run->add_option("job", o.job, "Job file (TOML)")->required();
  run->add_option("-o,--out", o.out, "Output directory (default: results/<job file name>)");
  run->add_option(
      "--restart", o.restart,
      "Continue from this checkpoint file (HDF5), on any number of ranks, bit for bit; --out\n"
      "should be the run's directory (results.h5 is cut back to the checkpoint's step).\n"
      "`latest`: the newest valid checkpoint of --out, or the beginning when it has none yet\n"
      "(one command line for every link of a chain of batch jobs: jobs/slurm/)");
  run->add_option("--max-steps", o.max_steps,
                  "Stop after this many MPM steps in total, restarts included (trials, tests); a "
                  "checkpoint\n"
                  "is written at the end")
      ->check(integer_at_least(1));
  run->add_option_function<std::string>(
         "--max-wall", [&o](const std::string& text) { o.max_wall_s = parse_max_wall(text); },
         "Stop with a checkpoint before this much wall time has passed since the start (\"23.5 "
         "h\",\n"
         "\"90 min\", or seconds): for a batch job's time limit; exit 75, --restart latest "
         "continues")
      ->type_name("DURATION");
  run->add_flag("--force", o.force,
                "Write into a non-empty output directory (files of the same name are replaced)");
}

void add_inspect(CLI::App& cli, Options& o) {
  auto* inspect =
      cli.add_subcommand("inspect",
                         "Describe a checkpoint (step, time, RVEs, ranks that wrote it) "
                         "and verify its checksums;\nwith --rve, measure DEM RVEs; with --vtk, "
                         "write their grains and contacts for ParaView");
  inspect->add_option("checkpoint", o.job, "Checkpoint file (HDF5)")->required();
  auto* rve_opt =
      inspect
          ->add_option("--rve", o.rve,
                       "Also measure the RVE of this point id (repeat for several; `all`: every "
                       "DEM RVE):\np, q, void ratio, Z, Z without rattlers, unbalanced force, "
                       "kinetic energy")
          ->allow_extra_args(false)
          ->check(CLI::Validator(
              [](std::string& text) -> std::string {
                if (text == "all") return "";
                std::int64_t v = 0;
                const char* end = text.data() + text.size();
                const auto res = std::from_chars(text.data(), end, v);
                if (res.ec != std::errc() || res.ptr != end || v < 0) {
                  return "must be a point id (an integer >= 0) or 'all', not '" + clip(text) + "'";
                }
                return "";
              },
              "ID|all"));
  inspect
      ->add_option(
          "--vtk", o.vtk,
          "Write the grain-scale views of the --rve RVEs into this directory (created if\n"
          "needed): spheres, contact network and periodic cell as VTK files for ParaView,\n"
          "rve_<id>_step_<step>.vtm each, and rve_<id>.pvd: every step written there\n"
          "(docs/design/dem.md, \"Grain-scale views\")")
      ->needs(rve_opt);
}

// dem, bench and schema.
void add_other_commands(CLI::App& cli, Options& o) {
  auto* demc = cli.add_subcommand(
      "dem", "Run a pure DEM job: prepare a sample, then the loading of [dem.loading]");
  demc->add_option("job", o.job, "Job file (TOML)")->required();
  demc->add_option("-o,--out", o.out, "Output directory (default: results/<job file name>)");
  demc->add_option("--max-steps", o.max_steps, "Stop the loading after this many DEM steps")
      ->check(integer_at_least(0));
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
      ->check(integer_at_least(1, 100'000'000));
  bench->add_option("--steps", o.bench_steps, "Timed steps")
      ->check(integer_at_least(1, 1'000'000'000));

  auto* schema = cli.add_subcommand(
      "schema", "Print the job-file reference (Markdown) generated from the schema");
  schema->add_flag("--outputs", o.schema_outputs,
                   "Print the reference of results.h5 instead (every dataset, its shape, unit and "
                   "description)");
}

// What CLI11 would report badly, named before it parses: an empty output directory (a missing
// value to CLI11, or none at all) and an unknown command (CLI11: "a subcommand is required").
std::optional<std::string> argument_error(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool next_empty = i + 1 < argc && argv[i + 1][0] == '\0';
    const bool empty_out = ((a == "-o" || a == "--out") && next_empty) || a == "--out=";
    const bool empty_vtk = (a == "--vtk" && next_empty) || a == "--vtk=";
    if (empty_out || empty_vtk) {
      return std::string(empty_out ? "--out" : "--vtk") +
             " \"\": the output directory must not be an empty path";
    }
  }
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.empty() || a[0] == '-') continue;
    if (std::find(kCommands.begin(), kCommands.end(), a) != kCommands.end()) break;
    std::string msg = "unknown command '" + clip(a) + "'";
    std::size_t best_d = 3;
    std::string best;
    for (const char* c : kCommands) {
      if (const std::size_t d = edit_distance(a, c); d < best_d) {
        best_d = d;
        best = c;
      }
    }
    if (!best.empty()) msg += "; did you mean '" + best + "'?";
    return msg + " (commands: run, check, dem, inspect, bench, schema; mpmxdem --help)";
  }
  return std::nullopt;
}

}  // namespace

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
  add_run(cli, o);
  auto* check = cli.add_subcommand(
      "check", "Validate a job file and print the resolved job (no output written)");
  check->add_option("job", o.job, "Job file (TOML)")->required();
  add_inspect(cli, o);
  add_other_commands(cli, o);

  exit_code = 2;  // every input error
  if (const auto error = argument_error(argc, argv)) {
    if (print) std::fprintf(stderr, "error: %s\n", error->c_str());
    return std::nullopt;
  }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream out;
    std::ostringstream err;
    if (cli.exit(e, out, err) == 0) {  // --help, --version
      if (print) std::fputs(out.str().c_str(), stdout);
      exit_code = 0;
      return std::nullopt;
    }
    // A usage error: one short line.
    std::string what = e.what();
    if (what.size() > 300) what = what.substr(0, 297) + "...";
    if (print) {
      std::fprintf(stderr, "error: %s (mpmxdem %s--help for the usage)\n", what.c_str(),
                   cli.get_subcommands().empty()
                       ? ""
                       : (cli.get_subcommands().front()->get_name() + " ").c_str());
    }
    return std::nullopt;
  }
  for (const auto* sub : cli.get_subcommands()) o.command = sub->get_name();
  exit_code = 0;
  return o;
}

}  // namespace app
