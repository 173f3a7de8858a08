// app::Progress::clock: the elapsed time and ETA of `mpmxdem dem`'s progress lines.
#include <gtest/gtest.h>

#include <limits>

#include "app/run/progress.hpp"

TEST(Progress, Clock) {
  EXPECT_EQ(app::Progress::clock(3723.4), "01:02:03");
  EXPECT_EQ(app::Progress::clock(-1.0), "--:--:--");
  EXPECT_EQ(app::Progress::clock(std::numeric_limits<double>::infinity()), "--:--:--");
  // Beyond a million hours, years (the seconds would overflow the integer they are rounded to).
  EXPECT_EQ(app::Progress::clock(3.6e9 - 1.0), "999999:59:59");
  EXPECT_EQ(app::Progress::clock(1e300), "3.17e+292 years");
}
