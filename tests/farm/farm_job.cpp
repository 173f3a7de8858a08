// farm_job: the farm test job as a program, for tests that need a real process death.
//   farm_job run <dir> <steps> <checkpoint_every> [<restart checkpoint>]
//   farm_job inspect <checkpoint>          (verifies every checksum; prints the description)
//   farm_job packing <n> <seed> <file>        (writes a small compacted test packing)
//   farm_job compare <results.h5> <results.h5>   (bit-for-bit; exit 1 on a difference)
#include <mpi.h>

#include <iostream>
#include <string>

#include "farm/driver.hpp"
#include "farm_test_job.hpp"

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  if (cmd == "inspect" && argc == 3) {
    try {
      std::cout << farm::describe(farm::inspect_checkpoint(argv[2]));
      return 0;
    } catch (const std::exception& e) {
      std::cerr << e.what() << "\n";
      return 2;
    }
  }
  if (cmd == "packing" && argc == 5) {
    // The small test packings of tests/farm/data: cloud, compaction to 100 kPa, written exactly.
    const dem::Packing pk = farm::testing::small_packing(std::stoll(argv[2]), std::stoull(argv[3]));
    dem::write_packing(argv[4], pk,
                       "farm test packing: farm_job packing " + std::string(argv[2]) + " " +
                           argv[3] + " (cloud, compaction to 100 kPa)");
    return 0;
  }
  if (cmd == "compare" && argc == 4) {
    const std::string diff = farm::testing::compare_results(argv[2], argv[3]);
    if (diff.empty()) return 0;
    std::cerr << "results differ: " << diff << "\n";
    return 1;
  }
  if (cmd != "run" || argc < 5) {
    std::cerr << "usage: farm_job run <dir> <steps> <checkpoint_every> [<restart>] | inspect "
                 "<file> | compare <a> <b>\n";
    return 2;
  }
  MPI_Init(&argc, &argv);
  int rc = 0;
  try {
    farm::CoupledConfig cfg = farm::testing::triaxial_job(argv[2], std::stoll(argv[3]),
                                                          farm::testing::mixed_elastic_kind());
    cfg.checkpoint.every_steps = std::stoll(argv[4]);
    const farm::RunSummary s = argc > 5 ? farm::restart_coupled(cfg, argv[5], MPI_COMM_WORLD)
                                        : farm::run_coupled(cfg, MPI_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) std::cout << "farm_job: " << s.steps << " steps, t = " << s.time << " s\n";
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    rc = 3;
  }
  MPI_Finalize();
  return rc;
}
