// bench_average: the regularisation's average per MPM step (prepare, apply, apply_adjoint: what
// GradientRegularisation does once a step) by the pairs' sum and through the lattice, on the
// plane-strain biaxial's points (50 x 100 mm, 2 x 2 points per cell, l = 5 mm by default), the
// two alternated and repeated, medians and spreads printed (a benchmark, never a test).
// Run: build/src/mpm/bench_average [l_mm=5] [repeats=5]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

#include "mpm/lattice_average.hpp"
#include "mpm/nonlocal_average.hpp"

namespace {

using common::Mat3;
using common::Vec3;

double step_seconds(mpm::PointAverage& avg, const std::vector<Vec3>& x,
                    const std::vector<double>& vol, const std::vector<std::int32_t>& group,
                    const std::vector<Mat3>& field, std::vector<Mat3>& out) {
  const auto t0 = std::chrono::steady_clock::now();
  avg.prepare(x, vol, group);
  avg.apply(field, out);
  avg.apply_adjoint(field, out);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const double l = (argc > 1 ? std::atof(argv[1]) : 5.0) * 1e-3;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
    std::printf("| mesh | points | point spacing [mm] | pairs [ms/step] | lattice [ms/step] | ratio | "
                "max |difference| / |field| |\n|---|---|---|---|---|---|---|\n");
    for (const int nx : {8, 16, 32, 64}) {
      const int nz = 2 * nx;
      const double h = 0.05 / nx;
      std::vector<Vec3> x;
      std::vector<double> vol;
      std::vector<Mat3> field;
      for (int k = 0; k < 2 * nz; ++k) {
        for (int i = 0; i < 2 * nx; ++i) {
          x.emplace_back((i + 0.5) * 0.5 * h, 0.0, (k + 0.5) * 0.5 * h);
          vol.push_back(0.25 * h * h);
          Mat3 m = Mat3::Identity();
          m(0, 2) = m(2, 0) = std::sin(x.back()[0] / l) * std::cos(x.back()[2] / l);
          field.push_back(m);
        }
      }
      const std::vector<std::int32_t> group(x.size(), 0);
      mpm::NonlocalAverage pairs(l);
      mpm::LatticeAverage lattice(l);
      std::vector<double> tp, tl;
      std::vector<Mat3> op, ol;
      const int n = nx >= 64 ? std::max(1, repeats / 2) : repeats;
      for (int r = 0; r < n; ++r) {
        tp.push_back(step_seconds(pairs, x, vol, group, field, op));
        tl.push_back(step_seconds(lattice, x, vol, group, field, ol));
      }
      double diff = 0.0;
      for (std::size_t p = 0; p < x.size(); ++p) diff = std::max(diff, (op[p] - ol[p]).norm());
      std::sort(tp.begin(), tp.end());
      std::sort(tl.begin(), tl.end());
      const double mp = 1e3 * tp[tp.size() / 2], ml = 1e3 * tl[tl.size() / 2];
      std::printf("| %d x %d | %zu | %.3f | %.1f (%.1f-%.1f) | %.2f (%.2f-%.2f) | %.0f | %.3f |\n",
                  nx, nz, x.size(), 0.5 * h * 1e3, mp, 1e3 * tp.front(), 1e3 * tp.back(), ml,
                  1e3 * tl.front(), 1e3 * tl.back(), mp / ml, diff / field[0].norm());
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_average: %s\n", e.what());
    return 1;
  }
  return 0;
}
