// study_sparing: which tangent predicts a spared DEM RVE best (a program, never a test). One RVE
// (default: the 1000-sphere reference packing at 100 kPa) is driven along prescribed strain paths
// by the plain DemMicro and by SparedMicro with each tangent and tolerance; printed per run: DEM
// steps, the error of the stress against the plain run (max and RMS over the steps, relative to
// p) and the prediction error at the DEM updates that follow spared steps (the drift).
//   study_sparing [--packing file] [--inertial 1e-3] [--steps 400]
// Figures: docs/design/sparing.md "Which tangent".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/tensor.hpp"
#include "dem/packing_io.hpp"
#include "dem/reference_material.hpp"
#include "farm/dem_micro.hpp"
#include "farm/spared_micro.hpp"

namespace {

using common::Mat3;

struct Path {
  std::string name;
  std::vector<Mat3> g;  ///< strain increment of each MPM step [-]
};

// Strain-controlled triaxial-like compression (axial -e, lateral +e/2 per step), then unloading.
Path load_unload(int steps, double e) {
  Path p{"load " + std::to_string(steps / 2) + " x " + std::to_string(e) + ", unload", {}};
  Mat3 g = Mat3::Zero();
  g(0, 0) = g(1, 1) = 0.5 * e;
  g(2, 2) = -e;
  for (int s = 0; s < steps; ++s) p.g.push_back(s < steps / 2 ? g : Mat3(-0.5 * g));
  return p;
}

// An RVE at rest: small oscillating increments (an elastic wave passing, amplitude a), with a
// slow drift, as in a settled column.
Path idle(int steps, double a) {
  Path p{"idle, amplitude " + std::to_string(a), {}};
  for (int s = 0; s < steps; ++s) {
    Mat3 g = Mat3::Zero();
    g(2, 2) = -a * std::sin(0.3 * s) - 0.05 * a;
    g(0, 0) = g(1, 1) = 0.25 * a * std::sin(0.3 * s);
    g(0, 2) = g(2, 0) = 0.1 * a * std::cos(0.2 * s);
    p.g.push_back(g);
  }
  return p;
}

struct Result {
  std::int64_t dem_steps = 0;
  std::vector<Mat3> stress;
  std::vector<double> drift;  ///< prediction errors at updates after spared steps [p]
  std::int64_t spared = 0;
};

Result run(farm::MicroModel& m, const Path& path, double dt) {
  Result r;
  const auto* sm = dynamic_cast<const farm::SparedMicro*>(&m);
  for (const Mat3& g : path.g) {
    const std::int64_t before = sm != nullptr ? sm->spared_now() : 0;
    const farm::MicroReport rep = m.step(g / dt, dt);
    r.dem_steps += rep.dem_steps;
    r.spared += (rep.guards & farm::kGuardSpared) != 0 ? 1 : 0;
    r.stress.push_back(m.stress());
    if (sm != nullptr && before > 0 && sm->spared_now() == 0) r.drift.push_back(sm->last_drift());
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string packing = MPMXDEM_DEFAULT_PACKING;
  double inertial = 1e-3;
  int steps = 400;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string k = argv[a];
    if (k == "--packing") packing = argv[a + 1];
    if (k == "--inertial") inertial = std::atof(argv[a + 1]);
    if (k == "--steps") steps = std::atoi(argv[a + 1]);
  }
  const dem::Packing pk = dem::read_packing(packing);
  farm::DemMicroParams params;
  params.rve.material = dem::reference_material();
  params.rve.inertial_number = inertial;
  params.fail_guards = 0;
  const farm::MicroKind kind = farm::DemMicro::kind(params, [&pk](std::int64_t) { return pk; });
  const double dt = 1e-4;  // the MPM step: only L dt matters to the DEM
  std::printf("# study_sparing: %zu spheres, I = %g, %d MPM steps per path\n", pk.r.size(),
              inertial, steps);
  std::printf("%-34s %-8s %-9s %10s %8s %9s %9s %9s %9s\n", "path", "tangent", "tolerance",
              "DEM steps", "spared", "max err", "rms err", "drift med", "drift max");
  for (const Path& path : {load_unload(steps, 2e-5), idle(steps, 2e-7), idle(steps, 2e-6)}) {
    auto plain = kind.create(0);
    const Result ref = run(*plain, path, dt);
    std::printf("%-34s %-8s %-9s %10lld %8d %9s %9s %9s %9s\n", path.name.c_str(), "-", "0",
                static_cast<long long>(ref.dem_steps), 0, "-", "-", "-", "-");
    for (const double tol : {1e-5, 1e-4}) {
      for (const auto t : {farm::SparingTangent::contact, farm::SparingTangent::scaled}) {
        farm::SparingOptions o;
        o.tolerance = tol;
        o.max_spared_steps = 20;
        o.tangent = static_cast<std::int64_t>(t);
        farm::SparedMicro m(kind.create(0), o, farm::dem_micro_tangent);
        Result r = run(m, path, dt);
        double emax = 0.0;
        double esum = 0.0;
        for (std::size_t s = 0; s < r.stress.size(); ++s) {
          const double p = std::max(common::pressure(ref.stress[s]), 1e3);
          const double e = (r.stress[s] - ref.stress[s]).norm() / p;
          emax = std::max(emax, e);
          esum += e * e;
        }
        std::sort(r.drift.begin(), r.drift.end());
        const double med = r.drift.empty() ? 0.0 : r.drift[r.drift.size() / 2];
        const double dmax = r.drift.empty() ? 0.0 : r.drift.back();
        std::printf("%-34s %-8s %-9g %10lld %8lld %9.4f %9.4f %9.4f %9.4f\n", path.name.c_str(),
                    t == farm::SparingTangent::contact ? "contact" : "scaled", tol,
                    static_cast<long long>(r.dem_steps), static_cast<long long>(r.spared), emax,
                    std::sqrt(esum / static_cast<double>(r.stress.size())), med, dmax);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
