// study_mpm: verification figures of the MPM module (docs/design/mpm.md, "Verification").
// Run: build/src/mpm/study_mpm [bar|column|triaxial|all]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

#include "mpm/verification_cases.hpp"

namespace {

using mpm::ShapeKind;
constexpr ShapeKind kShapes[] = {ShapeKind::linear, ShapeKind::ugimp, ShapeKind::bspline2};

void bar() {
  std::printf("# elastic bar, first mode (L=25, E=100, rho=1, v0=0.1), 2 periods, CFL 0.1\n");
  std::printf("%-9s %-5s %6s %12s %12s %12s\n", "shape", "upd", "cells", "period", "rel_err",
              "energy_drift");
  for (ShapeKind s : kShapes) {
    for (auto scheme : {mpm::StressUpdate::usf, mpm::StressUpdate::musl}) {
      for (int cells : {25, 50}) {
        const mpm::BarResult r = mpm::run_elastic_bar(s, cells, 2.0, 0.1, scheme);
        std::printf("%-9s %-5s %6d %12.6f %12.3e %12.3e\n", mpm::to_string(s).data(),
                    scheme == mpm::StressUpdate::usf ? "usf" : "musl", cells, r.period,
                    r.period / r.period_analytic - 1, r.energy_drift);
      }
    }
  }
}

void column() {
  std::printf(
      "# self-weight column (H=1, rho=1000, g=10, E=1e7, nu=0), point stress error / (rho g H)\n");
  std::printf("%-9s %6s %12s %8s %12s %8s %10s\n", "shape", "cells", "rms", "order", "max", "order",
              "ke_ratio");
  for (ShapeKind s : kShapes) {
    double prev_rms = 0, prev_max = 0;
    for (int cells : {4, 8, 16, 32, 64}) {
      const mpm::ColumnResult r = mpm::run_self_weight_column(s, cells);
      const double orms = prev_rms > 0 ? std::log2(prev_rms / r.rms_error) : 0;
      const double omax = prev_max > 0 ? std::log2(prev_max / r.max_error) : 0;
      std::printf("%-9s %6d %12.4e %8.2f %12.4e %8.2f %10.2e\n", mpm::to_string(s).data(), cells,
                  r.rms_error, orms, r.max_error, omax, r.kinetic_ratio);
      prev_rms = r.rms_error;
      prev_max = r.max_error;
    }
  }
}

void triaxial() {
  std::printf(
      "# single-cell triaxial (paper section 3), p=100 kPa, E=50 MPa, nu=0.25, to 3%% axial "
      "strain, CFL 0.2, D 0.2\n");
  std::printf("# offsets: points displaced inside the cell (cell units)\n");
  std::printf("%-9s %-28s %12s %12s %12s %12s\n", "shape", "offsets", "lat_err_max", "lat_err_end",
              "axial_err", "eps_zz");
  struct Pattern {
    const char* name;
    std::vector<common::Vec3> offsets;
  };
  std::vector<Pattern> patterns;
  patterns.push_back({"none (paper)", {}});
  std::vector<common::Vec3> shift(8, common::Vec3(0.05, 0, 0));
  patterns.push_back({"all +0.05 x", shift});
  std::vector<common::Vec3> shift2(8, common::Vec3(0.1, 0.05, 0));
  patterns.push_back({"all (+0.1, +0.05, 0)", shift2});
  std::vector<common::Vec3> inward(8);
  for (int p = 0; p < 8; ++p) {
    const common::Vec3 pos(p % 2 ? 0.75 : 0.25, (p / 2) % 2 ? 0.75 : 0.25, p / 4 ? 0.75 : 0.25);
    inward[static_cast<std::size_t>(p)] = -0.2 * (pos - common::Vec3::Constant(0.5));
    inward[static_cast<std::size_t>(p)][2] = 0;
  }
  patterns.push_back({"x,y towards centre 20%", inward});
  std::vector<common::Vec3> one(8, common::Vec3::Zero());
  one[0] = common::Vec3(0.1, 0.1, 0.0);
  patterns.push_back({"one point (+0.1, +0.1, 0)", one});
  for (const Pattern& pat : patterns) {
    for (ShapeKind s : kShapes) {
      mpm::TriaxialConfig tc;
      tc.shape = s;
      tc.offsets = pat.offsets;
      tc.cfl = 0.2;  // B-splines on the padded cell are unstable at 0.5 (light ghost nodes)
      try {
        const mpm::TriaxialResult r = mpm::run_single_cell_triaxial(tc);
        std::printf("%-9s %-28s %12.3e %12.3e %12.3e %12.4f\n", mpm::to_string(s).data(), pat.name,
                    r.lateral_error, r.lateral_error_end, r.axial_error, r.axial_strain);
      } catch (const std::exception& e) {
        std::printf("%-9s %-28s run stopped: %s\n", mpm::to_string(s).data(), pat.name, e.what());
      }
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const char* what = argc > 1 ? argv[1] : "all";
  try {
    if (!std::strcmp(what, "bar") || !std::strcmp(what, "all")) bar();
    if (!std::strcmp(what, "column") || !std::strcmp(what, "all")) column();
    if (!std::strcmp(what, "triaxial") || !std::strcmp(what, "all")) triaxial();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "study_mpm: %s\n", e.what());
    return 1;
  }
  return 0;
}
