// MPI tests of the farm, run under mpiexec (names carry the rank count: farm.mpi.np2/np3).
// Every rank runs every test. Sub-communicators give runs on 1, 2, ... ranks inside one launch.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "farm/checkpoint.hpp"
#include "farm/driver.hpp"
#include "farm/partition.hpp"
#include "farm/rve_farm.hpp"
#include "farm_test_job.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace fs = std::filesystem;
using farm::testing::compare_results;
using farm::testing::mixed_elastic_kind;
using farm::testing::triaxial_job;

namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int world_size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

/// Scratch root of this launch: rank 0's pid makes concurrent launches (np2, np3, smoke) safe.
const std::string& scratch_root() {
  static const std::string root = [] {
    long pid = world_rank() == 0 ? static_cast<long>(::getpid()) : 0;
    MPI_Bcast(&pid, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    return (fs::temp_directory_path() / ("mpmxdem_farm_test_" + std::to_string(pid))).string();
  }();
  return root;
}

/// Removes the scratch root after the last test.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    MPI_Barrier(MPI_COMM_WORLD);
    if (world_rank() == 0 && !::testing::UnitTest::GetInstance()->Failed())
      fs::remove_all(scratch_root());
  }
};
[[maybe_unused]] const auto* const kCleanup =
    ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

/// A fresh directory shared by all ranks (created by rank 0).
std::string scratch(const std::string& name) {
  const std::string dir = scratch_root() + "/" + name;
  if (world_rank() == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

/// Communicator of the first n world ranks (MPI_COMM_NULL on the others).
MPI_Comm first_ranks(int n) {
  MPI_Comm c = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < n ? 0 : MPI_UNDEFINED, world_rank(), &c);
  return c;
}

void free_comm(MPI_Comm& c) {
  if (c != MPI_COMM_NULL) MPI_Comm_free(&c);
}

/// Runs on the first n ranks; returns the summary there.
farm::RunSummary run_on(int n, const farm::CoupledConfig& cfg,
                        const std::string* restart = nullptr) {
  MPI_Comm c = first_ranks(n);
  farm::RunSummary s;
  if (c != MPI_COMM_NULL)
    s = restart ? farm::restart_coupled(cfg, *restart, c) : farm::run_coupled(cfg, c);
  free_comm(c);
  MPI_Barrier(MPI_COMM_WORLD);
  return s;
}

}  // namespace

// 2-rank smoke test: a tiny coupled job, a few steps, every output present.
TEST(Farm, SmokeTinyCoupledJob) {
  const std::string dir = scratch("smoke");
  farm::CoupledConfig cfg = triaxial_job(dir, 6, mixed_elastic_kind());
  cfg.checkpoint.at_end = true;
  const farm::RunSummary s = farm::run_coupled(cfg, MPI_COMM_WORLD);
  EXPECT_EQ(s.steps, 6);
  EXPECT_GT(s.time, 0.0);
  if (world_rank() == 0) {
    for (const char* f : {"results.h5", "points.xmf", "means.csv", "checkpoint_0000000006.h5"}) {
      EXPECT_TRUE(fs::exists(fs::path(dir) / f)) << f;
    }
    const auto stress = farm::testing::read_words(dir + "/results.h5", "/rve/stress");
    EXPECT_EQ(stress.size(), 7u * 8u * 9u);  // rows for steps 0..6, 8 RVEs
    // The summary's work (the log's "work:" line) is the sum of the rows' /rve/dem_steps (a row
    // every step here; row 0, the start state, has none).
    const auto dem_steps = farm::testing::read_words(dir + "/results.h5", "/rve/dem_steps");
    ASSERT_EQ(dem_steps.size(), 7u * 8u);
    std::int64_t total = 0;
    for (std::size_t k = 8; k < dem_steps.size(); ++k)
      total += static_cast<std::int64_t>(dem_steps[k]);
    EXPECT_GT(total, 0);
    EXPECT_EQ(s.dem_steps, total);
    EXPECT_EQ(s.rve_steps, 6 * 8);
    EXPECT_EQ(s.spared_steps, 0);
    std::ifstream csv(dir + "/means.csv");
    std::string line;
    int lines = 0;
    while (std::getline(csv, line)) ++lines;
    EXPECT_EQ(lines, 1 + 7);  // the header, rows for steps 0..6
    const farm::CheckpointInfo info = farm::inspect_checkpoint(dir + "/checkpoint_0000000006.h5");
    EXPECT_EQ(info.step, 6);
    EXPECT_EQ(info.nranks, world_size());
    EXPECT_EQ(info.ids.size(), 8u);
  }
}

// The same job on 1, 2, ... world ranks gives bit-for-bit identical results.h5 (stresses of every
// RVE and point, p, q, e, ...), with rebalancing active (threshold 1.0, every 3 steps).
TEST(Farm, ResultsIdenticalOnAnyRankCount) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2 or 3";
  const std::string base = scratch("ranks");
  for (int n = 1; n <= world_size(); ++n) {
    farm::CoupledConfig cfg =
        triaxial_job(base + "/n" + std::to_string(n), 12, mixed_elastic_kind());
    run_on(n, cfg);
  }
  if (world_rank() == 0) {
    for (int n = 2; n <= world_size(); ++n) {
      EXPECT_EQ(
          compare_results(base + "/n1/results.h5", base + "/n" + std::to_string(n) + "/results.h5"),
          "")
          << "1 rank vs " << n << " ranks";
    }
  }
}

// farm.rank0_rves = false: rank 0 runs the MPM only, ranks 1.. own every RVE (at the start, after
// the rebalances of threshold 1.0 and in the checkpoint), and the results are the same bits as
// on one rank (where rank 0 owns everything, there being no other).
TEST(Farm, RankZeroLeftToTheMpmOwnsNoRveAndChangesNoResult) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2 or 3";
  const std::string base = scratch("rank0_free");
  for (int n = 1; n <= world_size(); ++n) {
    farm::CoupledConfig cfg =
        triaxial_job(base + "/n" + std::to_string(n), 12, mixed_elastic_kind());
    cfg.farm.rank0_rves = false;
    cfg.checkpoint.at_end = true;
    run_on(n, cfg);
  }
  if (world_rank() == 0) {
    for (int n = 1; n <= world_size(); ++n) {
      const std::string dir = base + "/n" + std::to_string(n);
      if (n > 1) {
        EXPECT_EQ(compare_results(base + "/n1/results.h5", dir + "/results.h5"), "")
            << "1 rank vs " << n << " ranks";
      }
      const auto owner =
          farm::testing::read_words(dir + "/checkpoint_0000000012.h5", "/rve/partition");
      ASSERT_EQ(owner.size(), 8u);
      for (const std::uint64_t o : owner) EXPECT_EQ(o == 0, n == 1) << n << " ranks, owner " << o;
    }
  }
}

// Verification of the seam: ElasticMicro RVEs through the farm (every rank hosting some) give the
// points exactly the stresses and motion of the direct solver with mpm::LinearElastic (both use
// common::HughesWinget; the farm only carries L down and the stress up, row-major, bit for bit).
TEST(Farm, ElasticFarmEqualsDirectSolver) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2 or 3";
  const std::string dir = scratch("elastic_direct");
  const std::int64_t steps = 40;
  const farm::ElasticMicroParams ep = farm::testing::elastic_params();
  const farm::CoupledConfig cfg = triaxial_job(dir, steps, farm::ElasticMicro::kind(ep));
  const farm::RunSummary s = farm::run_coupled(cfg, MPI_COMM_WORLD);
  EXPECT_EQ(s.steps, steps);
  if (world_rank() != 0) return;
  mpm::LinearElastic elastic(ep.material.young_modulus, ep.material.poisson_ratio, ep.density,
                             ep.initial_stress);
  mpm::Solver direct(cfg.solver, cfg.points, {&elastic});
  for (const auto& c : cfg.constraints) direct.add_constraint(c);
  for (const auto& t : cfg.tractions) direct.add_traction(t);
  std::vector<std::uint64_t> stress;  // every row, as results.h5 stores them
  std::vector<std::uint64_t> x;
  auto row = [&] {
    const mpm::MaterialPoints& pts = direct.points();
    for (std::size_t p = 0; p < pts.size(); ++p) {
      double v[9];
      common::to_row_major(pts.stress[p], v);
      std::uint64_t w[9];
      std::memcpy(w, v, sizeof w);
      stress.insert(stress.end(), w, w + 9);
      for (int a = 0; a < 3; ++a) {
        std::uint64_t u = 0;
        std::memcpy(&u, &pts.x[p](a), sizeof u);
        x.push_back(u);
      }
    }
  };
  row();
  for (std::int64_t k = 0; k < steps; ++k) {
    direct.step();
    row();
  }
  const auto farm_stress = farm::testing::read_words(dir + "/results.h5", "/points/stress");
  const auto farm_x = farm::testing::read_words(dir + "/results.h5", "/points/x");
  ASSERT_EQ(farm_stress.size(), stress.size());
  EXPECT_TRUE(farm_stress == stress) << "point stresses differ from the direct solver's";
  EXPECT_TRUE(farm_x == x) << "point positions differ from the direct solver's";
  // The run did something: the axial stress moved away from the confining pressure.
  EXPECT_GT(std::abs(direct.points().stress[0](2, 2) + 100e3), 1.0);
}

// N steps straight == N/2, checkpoint, restart (on min(world, 2) ranks), N/2: bit for bit.
// At np3 the checkpoint is written by 3 ranks and restarted on 2.
TEST(Farm, RestartContinuesBitForBit) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2 or 3";
  const std::string base = scratch("restart");
  const int n_write = world_size();
  const int n_read = std::min(world_size(), 2);
  run_on(n_write, triaxial_job(base + "/straight", 12, mixed_elastic_kind()));
  farm::CoupledConfig half = triaxial_job(base + "/split", 6, mixed_elastic_kind());
  half.checkpoint.at_end = true;
  run_on(n_write, half);
  const std::string ckpt = farm::checkpoint_path(base + "/split", 6);
  if (world_rank() == 0) {
    const farm::CheckpointInfo info = farm::inspect_checkpoint(ckpt);
    EXPECT_EQ(info.nranks, n_write);
    EXPECT_EQ(info.step, 6);
  }
  const farm::RunSummary s =
      run_on(n_read, triaxial_job(base + "/split", 12, mixed_elastic_kind()), &ckpt);
  if (world_rank() == 0) {
    EXPECT_EQ(s.steps, 12);
    EXPECT_EQ(compare_results(base + "/straight/results.h5", base + "/split/results.h5"), "")
        << "written by " << n_write << " ranks, restarted on " << n_read;
  }
}

// A stop asked for on rank 0 (a signal, app/run/stop_signals.hpp) ends the run before the next step
// with a checkpoint, even where the run writes none at its end; every rank learns what stopped it;
// the restart from that checkpoint continues bit for bit. Fails if the stop is not seen, is seen
// a step late, writes no checkpoint or reaches only rank 0.
TEST(Farm, StopRequestEndsTheRunWithACheckpoint) {
  const std::string base = scratch("stop");
  run_on(world_size(), triaxial_job(base + "/straight", 9, mixed_elastic_kind()));
  farm::CoupledConfig cfg = triaxial_job(base + "/split", 9, mixed_elastic_kind());
  ASSERT_FALSE(cfg.checkpoint.at_end);
  std::int64_t done = 0;
  cfg.on_step = [&](std::int64_t step, const farm::FarmTimes&) { done = step; };
  cfg.stop_requested = [&] { return done >= 5 ? 10 : 0; };  // asked during step 5
  const farm::RunSummary s = run_on(world_size(), cfg);
  EXPECT_EQ(s.steps, 5);
  EXPECT_EQ(s.stopped_by, 10);  // on every rank
  const std::string ckpt = farm::checkpoint_path(base + "/split", 5);
  if (world_rank() == 0) {
    ASSERT_EQ(s.checkpoints.size(), 1u);
    EXPECT_EQ(s.checkpoints.back(), ckpt);
    EXPECT_EQ(farm::inspect_checkpoint(ckpt).step, 5);
  }
  const farm::RunSummary r =
      run_on(world_size(), triaxial_job(base + "/split", 9, mixed_elastic_kind()), &ckpt);
  EXPECT_EQ(r.stopped_by, 0);
  if (world_rank() == 0) {
    EXPECT_EQ(r.steps, 9);
    EXPECT_EQ(compare_results(base + "/straight/results.h5", base + "/split/results.h5"), "");
  }
}

// Migration: results do not depend on the partition, whatever moves when.
TEST(Farm, MigrationKeepsResults) {
  const std::int64_t n_rve = 10;
  std::vector<std::int64_t> ids(n_rve);
  std::vector<common::Vec3> x(n_rve);
  for (std::int64_t k = 0; k < n_rve; ++k) {
    ids[static_cast<std::size_t>(k)] = 3 * k + 1;
    x[static_cast<std::size_t>(k)] = common::Vec3(0.05 * static_cast<double>(k), 0.5, 0.5);
  }
  const mpm::Grid grid{common::Vec3::Zero(), common::Vec3::Ones(), common::Vec3i(2, 1, 1)};
  farm::RveFarm f(MPI_COMM_WORLD, mixed_elastic_kind(), ids, x, grid, {});
  // Reference: the same models stepped serially, in this process.
  farm::MicroKind k = mixed_elastic_kind();
  std::vector<std::unique_ptr<farm::MicroModel>> ref;
  for (std::int64_t id : ids) ref.push_back(k.create(id));
  auto L_of = [](std::int64_t id, int step) {
    common::Mat3 L;
    L << 0.01 * id, 0.002 * step, 0.0, -0.003, 0.005, 0.001 * id, 0.0, 0.004, -0.02;
    return L;
  };
  if (world_rank() == 0) {
    // Points in a scrambled order: results are stored by RVE id, never by position.
    std::vector<std::int64_t> order(ids.rbegin(), ids.rend());
    std::vector<common::Mat3> L(order.size());
    std::vector<common::Mat3> stress(order.size());
    for (int step = 1; step <= 9; ++step) {
      for (std::size_t p = 0; p < order.size(); ++p) L[p] = L_of(order[p], step);
      f.update_stress(order, L, 1e-3, stress);
      for (std::size_t p = 0; p < order.size(); ++p) {
        const auto r =
            static_cast<std::size_t>(std::find(ids.begin(), ids.end(), order[p]) - ids.begin());
        ref[r]->step(L_of(order[p], step), 1e-3);
        ASSERT_EQ(std::memcmp(stress[p].data(), ref[r]->stress().data(), sizeof(double) * 9), 0)
            << "RVE id " << order[p] << " step " << step;
      }
      if (step % 3 == 0) {
        // Rotate the owners: every RVE moves at every migration (when there are 2+ ranks).
        std::vector<int> owner = f.owner();
        for (int& o : owner) o = (o + 1) % f.size();
        f.migrate_to(owner);
      }
    }
    EXPECT_EQ(f.migrations() > 0, world_size() > 1);
    f.stop();
  } else {
    f.serve();
  }
}

namespace {

/// An ElasticMicro that says it is dilute when its id is odd (a stand-in for a DEM spray).
class OddDiluteMicro final : public farm::MicroModel {
 public:
  OddDiluteMicro(std::unique_ptr<farm::MicroModel> inner, std::int64_t id)
      : inner_(std::move(inner)), id_(id) {}
  farm::MicroReport step(const common::Mat3& L, double dt) override { return inner_->step(L, dt); }
  [[nodiscard]] common::Mat3 stress() const override { return inner_->stress(); }
  [[nodiscard]] farm::MicroReport report() const override { return inner_->report(); }
  [[nodiscard]] farm::MicroMeasures measures() const override { return inner_->measures(); }
  void save(common::StateWriter& w) const override { inner_->save(w); }
  [[nodiscard]] double cost_estimate() const override { return inner_->cost_estimate(); }
  [[nodiscard]] double wave_speed() const override { return inner_->wave_speed(); }
  [[nodiscard]] bool dilute() const override { return id_ % 2 == 1; }

 private:
  std::unique_ptr<farm::MicroModel> inner_;
  std::int64_t id_;
};

farm::MicroKind odd_dilute_kind() {
  farm::MicroKind k;
  const farm::MicroKind inner = mixed_elastic_kind();
  k.create = [inner](std::int64_t id) -> std::unique_ptr<farm::MicroModel> {
    return std::make_unique<OddDiluteMicro>(inner.create(id), id);
  };
  k.load = [](const common::StateReader& r) -> std::unique_ptr<farm::MicroModel> {
    return std::make_unique<OddDiluteMicro>(farm::ElasticMicro::load(r),
                                            common::read_scalar_i64(r, "elastic/id"));
  };
  return k;
}

}  // namespace

// mark_dilute answers, for the points of the last step in the solver's order, what each point's
// RVE said after that step on whichever rank stepped it: the same before and after a migration.
TEST(Farm, DiluteRvesAreMarkedByPoint) {
  const std::int64_t n_rve = 10;
  std::vector<std::int64_t> ids(n_rve);
  std::vector<common::Vec3> x(n_rve);
  for (std::int64_t k = 0; k < n_rve; ++k) {
    ids[static_cast<std::size_t>(k)] = 3 * k + 1;  // 1, 4, 7, ...: odd and even ids
    x[static_cast<std::size_t>(k)] = common::Vec3(0.05 * static_cast<double>(k), 0.5, 0.5);
  }
  const mpm::Grid grid{common::Vec3::Zero(), common::Vec3::Ones(), common::Vec3i(2, 1, 1)};
  farm::RveFarm f(MPI_COMM_WORLD, odd_dilute_kind(), ids, x, grid, {});
  if (world_rank() == 0) {
    const std::vector<std::int64_t> order{7, 4, 1, 28, 25, 22, 19, 16, 13, 10};
    const std::vector<common::Mat3> L(order.size(), 0.01 * common::Mat3::Identity());
    std::vector<common::Mat3> stress(order.size());
    for (int round = 0; round < 2; ++round) {
      f.update_stress(order, L, 1e-3, stress);
      std::vector<std::uint8_t> dilute(order.size(), 7);
      f.mark_dilute(order, dilute);
      for (std::size_t p = 0; p < order.size(); ++p)
        EXPECT_EQ(dilute[p], order[p] % 2 == 1 ? 1 : 0) << "RVE id " << order[p];
      std::vector<int> owner = f.owner();
      for (int& o : owner) o = (o + 1) % f.size();
      f.migrate_to(owner);
    }
    f.stop();
  } else {
    f.serve();
  }
}

// An RVE failure on any rank stops the job on every rank with the RVE id, the step and the cause;
// nothing is left hanging, and no checkpoint is written after the failure.
TEST(Farm, RveFailureStopsEveryRank) {
  const std::string dir = scratch("failure");
  // RVE id 7 is the last point: owned by the last rank after METIS on 2+ ranks.
  farm::CoupledConfig cfg = triaxial_job(dir, 10, mixed_elastic_kind(7, 4));
  cfg.checkpoint.every_steps = 2;
  try {
    farm::run_coupled(cfg, MPI_COMM_WORLD);
    ADD_FAILURE() << "the run should have failed";
  } catch (const common::NumericalError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("RVE id 7"), std::string::npos) << m;
    EXPECT_NE(m.find("MPM step 4"), std::string::npos) << m;
    EXPECT_NE(m.find("injected failure"), std::string::npos) << m;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    EXPECT_TRUE(fs::exists(farm::checkpoint_path(dir, 2)));
    EXPECT_FALSE(fs::exists(farm::checkpoint_path(dir, 4)));
  }
}

namespace {

/// Edits a copy of a checkpoint with HDF5 (rank 0).
void tamper(const std::string& path, const std::function<void(hid_t)>& edit) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  edit(f);
  H5Fclose(f);
}

void expect_refused(const farm::CoupledConfig& cfg, const std::string& path,
                    const std::vector<std::string>& needles) {
  try {
    farm::restart_coupled(cfg, path, MPI_COMM_WORLD);
    ADD_FAILURE() << "restart from " << path << " should have been refused";
  } catch (const common::InputError& e) {
    const std::string m = e.what();
    for (const std::string& n : needles) EXPECT_NE(m.find(n), std::string::npos) << m;
  }
  if (world_rank() == 0) {
    EXPECT_THROW(farm::inspect_checkpoint(path), common::InputError);
  }
}

}  // namespace

// A damaged or incompatible checkpoint is refused with a message naming the file and the dataset.
TEST(Farm, DamagedCheckpointRefused) {
  const std::string dir = scratch("damaged");
  farm::CoupledConfig cfg = triaxial_job(dir, 4, mixed_elastic_kind());
  cfg.checkpoint.at_end = true;
  farm::run_coupled(cfg, MPI_COMM_WORLD);
  const std::string good = farm::checkpoint_path(dir, 4);
  const std::string flipped = dir + "/flipped.h5";
  const std::string version = dir + "/version.h5";
  const std::string missing = dir + "/missing.h5";
  const std::string truncated = dir + "/truncated.h5";
  if (world_rank() == 0) {
    for (const auto& p : {flipped, version, missing, truncated}) fs::copy_file(good, p);
    tamper(flipped, [](hid_t f) {
      const hid_t d = H5Dopen2(f, "/rve/fields/elastic/stress", H5P_DEFAULT);
      const hid_t s = H5Dget_space(d);
      const hsize_t start[1] = {13};
      const hsize_t count[1] = {1};
      H5Sselect_hyperslab(s, H5S_SELECT_SET, start, nullptr, count, nullptr);
      const hid_t m = H5Screate_simple(1, count, nullptr);
      const double v = 12345.0;
      H5Dwrite(d, H5T_NATIVE_DOUBLE, m, s, H5P_DEFAULT, &v);
      H5Sclose(m);
      H5Sclose(s);
      H5Dclose(d);
    });
    tamper(version, [](hid_t f) {
      const hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
      const std::int64_t v = 99;
      H5Awrite(a, H5T_NATIVE_INT64, &v);
      H5Aclose(a);
    });
    tamper(missing, [](hid_t f) { H5Ldelete(f, "/mpm/points/x", H5P_DEFAULT); });
    fs::resize_file(truncated, fs::file_size(truncated) / 2);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  farm::CoupledConfig again = triaxial_job(dir + "/again", 8, mixed_elastic_kind());
  expect_refused(again, flipped, {flipped, "/rve/fields/elastic/stress", "checksum mismatch"});
  expect_refused(again, version, {version, "format_version = 99"});
  expect_refused(again, missing, {missing, "/mpm/points/x", "missing"});
  expect_refused(again, truncated, {truncated});
  expect_refused(again, dir + "/nothing.h5", {"nothing.h5", "does not exist"});
}

// DemMicro (dem::Rve, 40 and 70 spheres): identical results on 1, 2, ... ranks, and a restart
// from a checkpoint written by all ranks onto min(world, 2) ranks continues bit for bit.
TEST(Farm, DemResultsIdenticalOnAnyRankCountAndRestart) {
  ASSERT_GE(world_size(), 2) << "run with mpiexec -n 2 or 3";
  const std::string base = scratch("dem");
  const std::int64_t steps = 4;
  for (int n = 1; n <= world_size(); ++n) {
    run_on(n,
           triaxial_job(base + "/n" + std::to_string(n), steps, farm::testing::small_dem_kind()));
  }
  farm::CoupledConfig half =
      triaxial_job(base + "/split", steps / 2, farm::testing::small_dem_kind());
  half.checkpoint.at_end = true;
  run_on(world_size(), half);
  const std::string ckpt = farm::checkpoint_path(base + "/split", steps / 2);
  run_on(std::min(world_size(), 2),
         triaxial_job(base + "/split", steps, farm::testing::small_dem_kind()), &ckpt);
  if (world_rank() == 0) {
    for (int n = 2; n <= world_size(); ++n) {
      EXPECT_EQ(
          compare_results(base + "/n1/results.h5", base + "/n" + std::to_string(n) + "/results.h5"),
          "")
          << "DEM: 1 rank vs " << n << " ranks";
    }
    EXPECT_EQ(compare_results(base + "/n1/results.h5", base + "/split/results.h5"), "")
        << "DEM restart: written by " << world_size() << " ranks, restarted on "
        << std::min(world_size(), 2);
    // The DEM did something: non-zero DEM steps and coordination.
    const auto z = farm::testing::read_words(base + "/n1/results.h5", "/rve/dem_steps");
    ASSERT_FALSE(z.empty());
    EXPECT_GT(z.back(), 0u);
    // Row 0 (before the first step) holds the measures of the prepared RVEs, not zeros: the
    // coordination number is positive and close to that after the first (small) step.
    const auto zw = farm::testing::read_words(base + "/n1/results.h5", "/rve/z");
    const auto ids = farm::testing::read_words(base + "/n1/results.h5", "/rve/id");
    ASSERT_GE(zw.size(), 2 * ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) {
      double z0 = 0.0;
      double z1 = 0.0;
      std::memcpy(&z0, &zw[k], sizeof z0);
      std::memcpy(&z1, &zw[ids.size() + k], sizeof z1);
      EXPECT_GT(z0, 2.0) << "RVE " << k;
      EXPECT_NEAR(z0, z1, 0.5) << "RVE " << k;
    }
    // ... and the points start with their RVE's stress (compressive), not zero.
    const auto ps = farm::testing::read_words(base + "/n1/results.h5", "/points/stress");
    ASSERT_GE(ps.size(), 9u);
    double sxx0 = 0.0;
    std::memcpy(&sxx0, &ps[0], sizeof sxx0);
    EXPECT_LT(sxx0, -1e3);
  }
}
