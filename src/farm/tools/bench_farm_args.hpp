// Shared by the programs of bench_farm (bench_farm.cpp, bench_farm_partition.cpp): the command
// line's options, a wall clock and a lattice of RVE positions.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "mpm/grid.hpp"

namespace bench_farm {

struct Args {
  std::string mode = "overhead";
  std::map<std::string, std::string> opt;
  std::string get(const std::string& k, const std::string& def) const {
    auto it = opt.find(k);
    return it == opt.end() ? def : it->second;
  }
};

inline double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// n points on a cubic lattice in the unit cube, about 8 per cell of the grid.
struct Lattice {
  mpm::Grid grid;
  std::vector<common::Vec3> x;
};
inline Lattice lattice(int n) {
  const int c = std::max(1, static_cast<int>(std::ceil(std::cbrt(n / 8.0))));
  const int m = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
  Lattice l{{common::Vec3::Zero(), common::Vec3::Constant(1.0 / c), common::Vec3i::Constant(c)},
            {}};
  for (int k = 0; k < n; ++k)
    l.x.emplace_back((k % m + 0.5) / m, ((k / m) % m + 0.5) / m, (k / (m * m) + 0.5) / m);
  return l;
}

// METIS partition and rebalance check at scale (bench_farm_partition.cpp).
void partition(const Args& a);

}  // namespace bench_farm
