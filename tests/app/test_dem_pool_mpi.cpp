// app::DemPool::prepare under mpiexec (2 and 3 ranks): the preparations a coupled job needs, made
// once, spread over the ranks and their threads and sent to the ranks that need them, give every
// point the same RVE, bit for bit, as the lazy path (each rank making what it needs alone).
#include <gtest/gtest.h>
#include <mpi.h>
#include <omp.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/job/job.hpp"
#include "app/setup/coupled_setup.hpp"
#include "app/setup/insitu.hpp"
#include "farm/dem_micro.hpp"
#include "insitu_test_job.hpp"

namespace {

// The job of test_insitu.cpp with a pool of samples (`pool`: the [dem.initial_state] lines that
// set it): 4 points (a geostatic column of 2, one uniform, one prepared), 3 groups; with 2 samples
// in turn, 4 (group, sample) RVEs from 2 samples. Rank r creates the
// points id with id mod 2 = r (ranks 0 and 1) and point 3 as well (two ranks need one RVE); with
// 3 ranks the last creates none but still makes its share. 2 threads per rank. Compared: the
// stress, the step count and every sphere's position, velocity and spin.
void check_pool(const std::string& pool) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpiexec with 2 or more ranks";
  const app::Job job = app::Job::parse(app_test::insitu_job(R"(
[dem.initial_state]
pressure_floor = "10 kPa"
group_tolerance = 0.01
)" + pool),
                                       "insitu.toml");
  std::vector<std::int64_t> ids;
  if (!(size >= 3 && rank == size - 1)) {
    for (std::int64_t id = 0; id < 4; ++id)
      if (id % 2 == rank || id == 3) ids.push_back(id);
  }
  const farm::CoupledConfig lazy = app::coupled_setup(job, app::RunLimits{"unused", -1});
  const farm::CoupledConfig ahead = app::coupled_setup(job, app::RunLimits{"unused", -1});
  ASSERT_TRUE(ahead.micro.prepare);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(2);
  ahead.micro.prepare(ids, MPI_COMM_WORLD);
  omp_set_num_threads(threads);
  for (const std::int64_t id : ids) {
    const std::unique_ptr<farm::MicroModel> a = lazy.micro.create(id);
    const std::unique_ptr<farm::MicroModel> b = ahead.micro.create(id);
    const auto* da = dynamic_cast<const farm::DemMicro*>(a.get());
    const auto* db = dynamic_cast<const farm::DemMicro*>(b.get());
    ASSERT_NE(da, nullptr);
    ASSERT_NE(db, nullptr);
    const dem::Simulation& sa = da->rve().simulation();
    const dem::Simulation& sb = db->rve().simulation();
    EXPECT_EQ(a->stress(), b->stress()) << "rank " << rank << ", point " << id;
    EXPECT_EQ(sa.steps(), sb.steps()) << id;
    EXPECT_EQ(sa.spheres().x, sb.spheres().x) << id;
    EXPECT_EQ(sa.spheres().u, sb.spheres().u) << id;
    EXPECT_EQ(sa.spheres().w, sb.spheres().w) << id;
  }
}

TEST(DemPool, PreparationsSpreadOverRanksAndThreadsGiveTheSameRves) { check_pool("samples = 2\n"); }

// The same with 3 samples scattered over the points (sample_draw, a hash of the id and the job's
// seed 5): points 0-3 draw samples 2, 1, 0, 1 where in turn they would draw 0, 1, 2, 0, and every
// rank must draw them as the lazy path does.
TEST(DemPool, ScatteredSamplesGiveTheSameRvesOnEveryRank) {
  app::InsituOptions o;
  o.samples = 3;
  o.draw = app::SampleDraw::scattered;
  o.draw_seed = 5;
  ASSERT_EQ(app::sample_of(0, o), 2);
  ASSERT_EQ(app::sample_of(3, o), 1);
  check_pool("samples = 3\nsample_draw = \"scattered\"\n");
}

}  // namespace
