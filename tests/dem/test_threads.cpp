// dem::team_size and dem::one_thread: how many threads a DEM region over n spheres runs on.
#include <gtest/gtest.h>
#include <omp.h>

#include "dem/threads.hpp"

TEST(Threads, TeamSizeIsCappedBySpheresPerThread) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(16);
  EXPECT_EQ(dem::team_size(1000), 8);   // 125 spheres per thread
  EXPECT_EQ(dem::team_size(1999), 15);
  EXPECT_EQ(dem::team_size(2000), 16);  // the OpenMP maximum
  EXPECT_EQ(dem::team_size(27000), 16);
  EXPECT_EQ(dem::team_size(100), 1);
  EXPECT_EQ(dem::team_size(0), 1);
  omp_set_num_threads(2);
  EXPECT_EQ(dem::team_size(1000), 2);
  EXPECT_FALSE(dem::one_thread(1000));
  EXPECT_TRUE(dem::one_thread(dem::kParallelSpheres));
  omp_set_num_threads(saved);
}
