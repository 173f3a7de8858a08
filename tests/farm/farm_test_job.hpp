// A tiny coupled job for the farm tests and farm_job: the paper's single-cell triaxial (one 1 m
// cell, 8 points at 1/4 and 3/4, confining pressure on the x and y faces, top platen moving down)
// with ElasticMicro RVEs of different costs (substeps 1 + id % 3), plus result comparisons.
#pragma once

#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "farm/driver.hpp"
#include "farm/elastic_micro.hpp"
#include "mpm/material_points.hpp"

namespace farm::testing {

inline ElasticMicroParams elastic_params() {
  ElasticMicroParams p;
  p.material.young_modulus = 50e6;
  p.material.poisson_ratio = 0.25;
  p.density = 1600.0;
  p.void_ratio0 = 0.6;
  p.initial_stress = -100e3 * common::Mat3::Identity();
  return p;
}

/// ElasticMicro with substeps 1 + id % 3 (RVEs of unequal cost, as DEM RVEs would be).
inline MicroKind mixed_elastic_kind(std::int64_t fail_id = -1, std::int64_t fail_step = -1) {
  ElasticMicroParams base = elastic_params();
  base.fail_id = fail_id;
  base.fail_step = fail_step;
  MicroKind k;
  k.create = [base](std::int64_t id) {
    ElasticMicroParams p = base;
    p.substeps = 1 + id % 3;
    return std::make_unique<ElasticMicro>(id, p);
  };
  k.load = [](const common::StateReader& r) { return ElasticMicro::load(r); };
  return k;
}

/// The single-cell triaxial job: max_steps steps, outputs in `dir` (created).
inline CoupledConfig triaxial_job(const std::string& dir, std::int64_t max_steps, MicroKind kind) {
  using common::Vec3;
  CoupledConfig c;
  c.solver.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i::Ones()};
  c.solver.damping = 0.2;
  c.solver.cfl = 0.5;
  const double rho = 1600.0;
  const double p = 100e3;
  mpm::fill_box(c.points, c.solver.grid, Vec3::Zero(), Vec3::Ones(), 2, rho, 0);
  for (auto& s : c.points.stress) s = -p * common::Mat3::Identity();
  // A faster platen than eq. (13) so that a few steps deform visibly.
  const double v_top = -1e-2 * std::sqrt(p / rho);
  c.constraints.push_back(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  c.constraints.push_back(
      {Vec3(-10, -10, 1), Vec3::Constant(10), {false, false, true}, Vec3(0, 0, v_top), {}});
  for (int axis : {0, 1}) {
    for (int side : {-1, 1}) c.tractions.push_back({axis, side, p, Vec3::Zero()});
  }
  c.max_steps = max_steps;
  c.micro = std::move(kind);
  c.job_text = "# farm test job: single-cell triaxial, ElasticMicro\n[run]\nmax_steps = " +
               std::to_string(max_steps) + "\n";
  c.output.dir = dir;
  c.output.every = 1;  // a results row every step: the tests compare every step (job default: 10)
  c.output.log_every_s = 1e9;
  c.checkpoint.at_end = false;
  c.balance.threshold = 1.0;  // rebalance whenever METIS finds a better split
  c.balance.check_every = 3;
  std::filesystem::create_directories(dir);
  return c;
}

/// Reads a whole dataset as raw 8-byte words (double or int64).
inline std::vector<std::uint64_t> read_words(const std::string& file, const std::string& name) {
  std::vector<std::uint64_t> out;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return out;
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  if (d >= 0) {
    const hid_t s = H5Dget_space(d);
    const hssize_t n = H5Sget_simple_extent_npoints(s);
    const hid_t t = H5Dget_type(d);
    out.resize(static_cast<std::size_t>(n));
    if (n > 0) H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    H5Tclose(t);
    H5Sclose(s);
    H5Dclose(d);
  }
  H5Fclose(f);
  return out;
}

/// Every time series of results.h5; compared bit for bit by the tests.
inline const std::vector<std::string>& result_series() {
  static const std::vector<std::string> names{
      "/time", "/step", "/rve/id", "/rve/stress", "/rve/p", "/rve/q", "/rve/void_ratio", "/rve/z",
      "/rve/t_p", "/rve/dem_steps", "/rve/guards", "/points/id", "/points/x", "/points/stress",
      "/points/p", "/points/q", "/means/eps_ax", "/means/eps_v", "/means/p", "/means/q",
      // issue 19: grain-scale measures (output rows only) and point fields
      "/rve/fabric", "/rve/z_mech", "/rve/unbalanced", "/rve/kinetic_energy", "/points/volume",
      "/points/velocity", "/points/displacement", "/points/F"};
  return names;
}

/// Empty if results a and b are identical bit for bit; otherwise the first differing dataset.
inline std::string compare_results(const std::string& a, const std::string& b) {
  for (const std::string& name : result_series()) {
    const auto x = read_words(a, name);
    const auto y = read_words(b, name);
    if (x.empty() && y.empty()) return name + " missing in both";
    if (x != y)
      return name + " differs (" + std::to_string(x.size()) + " vs " + std::to_string(y.size()) +
             " values)";
  }
  return {};
}

}  // namespace farm::testing

// ---- small DEM RVEs (needs dem::Rve) ----
#include "dem/loading.hpp"
#include "dem/reference_material.hpp"
#include "farm/dem_micro.hpp"

namespace farm::testing {

/// A small periodic packing compacted to 100 kPa (deterministic for n and seed).
inline dem::Packing small_packing(std::int64_t n, std::uint64_t seed) {
  dem::Psd psd;
  psd.diameter = {1.5e-4, 3e-4};
  psd.passing = {0.0, 1.0};
  const dem::Packing cloud = dem::make_cloud(psd, n, 0.3, seed);
  dem::Simulation sim = dem::make_simulation(cloud, dem::reference_material(), dem::Numerics{});
  dem::Preparation prep;
  prep.target.pressure = 1e5;
  prep.target.stress_tol = 0.02;
  prep.target.unbalanced_tol = 0.05;
  dem::prepare(sim, prep);
  dem::Packing pk;
  pk.cell.h = sim.cell().h;
  pk.x = sim.spheres().x;
  pk.r = sim.spheres().r;
  return pk;
}

/// DemMicro RVEs of 40 or 70 spheres (even / odd ids) from tests/farm/data (made by
/// `farm_job packing 40 11 ...` and `farm_job packing 70 12 ...`: small_packing above; stored
/// because compaction is slow under the sanitizers).
inline MicroKind small_dem_kind() {
  static const dem::Packing a = dem::read_packing(MPMXDEM_FARM_TEST_DATA "/packing_N40_seed11.txt");
  static const dem::Packing b = dem::read_packing(MPMXDEM_FARM_TEST_DATA "/packing_N70_seed12.txt");
  DemMicroParams p;
  p.rve.material = dem::reference_material();
  return DemMicro::kind(p, [](std::int64_t id) { return id % 2 == 0 ? a : b; });
}

}  // namespace farm::testing
