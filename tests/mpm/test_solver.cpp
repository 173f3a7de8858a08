// Tests of solver.hpp: checkpoint continues bit for bit, failures carry their context,
// configuration errors name the key, CFL time step, multi-material dispatch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "mpm/benchmark.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Vec3;

mpm::SolverConfig small_config(mpm::ShapeKind kind) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.25), common::Vec3i(6, 6, 8)};
  cfg.shape = kind;
  cfg.gravity = Vec3(0, 0, -9.81);
  cfg.cfl = 0.5;
  cfg.damping = 0.05;
  return cfg;
}

mpm::MaterialPoints small_block(const mpm::Grid& g) {
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, g, Vec3(0.25, 0.25, 0.25), Vec3(1.25, 1.0, 1.5), 2, 1800.0, 0);
  return pts;
}

void expect_message(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    FAIL() << "no exception";
  } catch (const std::exception& e) {
    for (const auto& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "'" << part << "' not in: " << e.what();
    }
  }
}

TEST(Solver, CheckpointContinuesBitForBit) {
  for (auto [scheme, transfer] : {std::pair{mpm::StressUpdate::usf, mpm::Transfer::flip},
                                  std::pair{mpm::StressUpdate::musl, mpm::Transfer::flip},
                                  std::pair{mpm::StressUpdate::usf, mpm::Transfer::apic},
                                  std::pair{mpm::StressUpdate::musl, mpm::Transfer::apic}}) {
    mpm::SolverConfig cfg = small_config(mpm::ShapeKind::ugimp);
    cfg.stress_update = scheme;
    cfg.flip = 0.95;
    cfg.transfer = transfer;
    mpm::LinearElastic mat_a(1e5, 0.3, 1800.0);
    mpm::Solver a(cfg, small_block(cfg.grid), {&mat_a});
    a.add_constraint(mpm::face_constraint(cfg.grid, 2, -1, {true, true, true}));
    a.add_constraint({Vec3(0, 0, 0), Vec3(2, 2, 0.25), {false, false, true}, Vec3::Zero(), {}});
    a.add_traction({0, +1, 500.0, Vec3::Zero()});
    a.run(8);
    common::StateStore store;
    a.save(store);
    mat_a.save(store, "material/0/");
    EXPECT_EQ(store.has("points/C"), transfer == mpm::Transfer::apic);
    a.run(8);

    mpm::LinearElastic mat_b(1e5, 0.3, 1800.0);
    mpm::MaterialPoints other = small_block(cfg.grid);
    mpm::Solver b(cfg, other, {&mat_b});
    b.add_constraint(mpm::face_constraint(cfg.grid, 2, -1, {true, true, true}));
    b.add_constraint({Vec3(0, 0, 0), Vec3(2, 2, 0.25), {false, false, true}, Vec3::Zero(), {}});
    b.add_traction({0, +1, 500.0, Vec3::Zero()});
    b.load(store);
    mat_b.load(store, "material/0/");
    EXPECT_EQ(b.step_count(), 8);
    b.run(8);
    EXPECT_EQ(a.time(), b.time());
    for (std::size_t p = 0; p < a.points().size(); ++p) {
      ASSERT_EQ(a.points().x[p], b.points().x[p]);
      ASSERT_EQ(a.points().v[p], b.points().v[p]);
      ASSERT_EQ(a.points().stress[p], b.points().stress[p]);
      ASSERT_EQ(a.points().F[p], b.points().F[p]);
      ASSERT_EQ(a.points().volume[p], b.points().volume[p]);
      ASSERT_EQ(a.points().C[p], b.points().C[p]);
    }
  }
}

namespace {
/// A copy of `store` without the field `name`.
common::StateStore without(const common::StateStore& store, const std::string& name) {
  common::StateStore out;
  for (const auto& [n, field] : store.fields()) {
    if (n != name) std::visit([&](const auto& v) { out.write(n, v); }, field);
  }
  return out;
}
}  // namespace

TEST(Solver, CheckpointMissingFieldIsInputError) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::Solver s(cfg, small_block(cfg.grid), {&mat});
  common::StateStore store;
  s.save(store);
  expect_message([&] { s.load(without(store, "points/v")); }, {"points/v"});
}

// A checkpoint's numbers are input: one that is not finite (a NaN position would pass the grid's
// bounds checks) is refused naming the field and the value's index, as is a negative step.
TEST(Solver, CheckpointValuesNotFiniteAreInputErrors) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::Solver s(cfg, small_block(cfg.grid), {&mat});
  common::StateStore store;
  s.save(store);
  const auto with = [&store](const std::string& field, std::size_t k, double value) {
    common::StateStore out = without(store, field);
    std::vector<double> v = store.read_f64(field);
    v.at(k) = value;
    out.write(field, v);
    return out;
  };
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  expect_message([&] { s.load(with("points/x", 4, nan)); }, {"points/x value 4 is nan", "finite"});
  expect_message([&] { s.load(with("points/v", 0, inf)); }, {"points/v value 0 is inf"});
  expect_message([&] { s.load(with("points/stress", 17, nan)); }, {"points/stress value 17"});
  expect_message([&] { s.load(with("points/mass", 2, inf)); }, {"points/mass value 2 is inf"});
  expect_message([&] { s.load(with("solver/time", 0, nan)); }, {"solver/time value 0 is nan"});
  common::StateStore negative = without(store, "solver/step");
  negative.write("solver/step", std::vector<std::int64_t>{-3});
  expect_message([&] { s.load(negative); }, {"solver/step = -3", ">= 0"});
  EXPECT_NO_THROW(s.load(store));
}

TEST(Solver, PointLeavingTheGridNamesIdStepAndPosition) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.gravity = Vec3::Zero();
  cfg.dt = 0.01;
  cfg.refuse_unstable_dt = false;  // 100 m/s on purpose: the point must leave the grid
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::MaterialPoints pts = small_block(cfg.grid);
  pts.v[5] = Vec3(100.0, 0, 0);  // leaves the 1.5 m grid within two steps
  mpm::Solver s(cfg, pts, {&mat});
  expect_message([&] { s.run(5); }, {"point id 5", "mpm step", "left the grid", "x = ("});
  EXPECT_EQ(s.points().size(), pts.size());  // nothing deleted
}

TEST(Solver, NegativeVolumeStopsWithContext) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.gravity = Vec3::Zero();
  cfg.dt = 1.0;
  cfg.refuse_unstable_dt = false;  // the blow-up is the point of the test
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::MaterialPoints pts = small_block(cfg.grid);
  for (std::size_t p = 0; p < pts.size(); ++p) pts.v[p] = Vec3(0, 0, -2.0 * (pts.x[p][2] - 0.9));
  mpm::Solver s(cfg, pts, {&mat});
  expect_message([&] { s.step(); }, {"mpm step 0", "t = 1", "point id", "volume = -"});
}

TEST(Solver, FixedDtAboveTheStabilityLimitIsRefused) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.gravity = Vec3::Zero();
  cfg.dt = 1.0;  // h / c = 0.25 / 9.7 = 0.026 s for this material
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::Solver s(cfg, small_block(cfg.grid), {&mat});
  expect_message([&] { s.step(); }, {"mpm step 0 (t = 0 s)",
                                     "fixed dt = 1 s is above the stability limit", "h = 0.25 m"});
  cfg.dt = 0.01;  // below the limit: runs
  mpm::Solver ok(cfg, small_block(cfg.grid), {&mat});
  EXPECT_NO_THROW(ok.run(3));
}

TEST(Solver, VolumeBeyondTheBlowUpBoundStopsWithContext) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.gravity = Vec3::Zero();
  cfg.max_volume_ratio = 1.1;
  mpm::LinearElastic mat(10.0, 0.3, 1800.0);  // soft: nothing holds the expansion back
  mpm::MaterialPoints pts = small_block(cfg.grid);
  for (std::size_t p = 0; p < pts.size(); ++p) pts.v[p] = 0.2 * (pts.x[p] - Vec3(0.75, 0.6, 0.9));
  mpm::Solver s(cfg, pts, {&mat});
  expect_message(
      [&] { s.run(200); },
      {"mpm step 0 (t = 0.5", "point id 0", "volume / initial volume = 1.2", "outside [1/1.1, 1.1]",
       "(its pressure ", " Pa, |v| = ", "blown up", "dem.coupling.contact_loss"});
  cfg.max_volume_ratio = 1.0;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"max_volume_ratio = 1", "must be > 1"});
}

// A material without stress (an RVE that lost its contacts: a disconnected material).
class StressFreeMaterial : public mpm::MaterialModel {
 public:
  void update_stress(std::span<const std::int64_t> /*ids*/, std::span<const common::Mat3> /*L*/,
                     double /*dt*/, std::span<common::Mat3> stress) override {
    for (auto& s : stress) s.setZero();
  }
  [[nodiscard]] double wave_speed() const override { return 10.0; }
};

// A stress-free point expands beyond the bound without stopping the run (its volume carries no
// force: a spray of grains); compressed below V0 / ratio it still stops it.
TEST(Solver, AStressFreePointMayExpandBeyondTheBlowUpBound) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.gravity = Vec3::Zero();
  cfg.max_volume_ratio = 1.1;
  StressFreeMaterial mat;
  mpm::MaterialPoints pts = small_block(cfg.grid);
  for (std::size_t p = 0; p < pts.size(); ++p) pts.v[p] = 0.2 * (pts.x[p] - Vec3(0.75, 0.6, 0.9));
  mpm::Solver s(cfg, pts, {&mat});
  s.run(200);
  double largest = 0.0;
  for (std::size_t p = 0; p < s.points().size(); ++p) {
    largest = std::max(largest, s.points().volume[p] / s.points().volume0[p]);
  }
  EXPECT_GT(largest, 1.1);
  mpm::MaterialPoints in = small_block(cfg.grid);
  for (std::size_t p = 0; p < in.size(); ++p) in.v[p] = -0.2 * (in.x[p] - Vec3(0.75, 0.6, 0.9));
  mpm::Solver c(cfg, in, {&mat});
  expect_message([&] { c.run(200); }, {"volume / initial volume = 0.", "outside [1/1.1, 1.1]"});
}

// A material that keeps a small pressure (a spray whose grains collide now and then) and says
// whether it is dilute (MaterialModel::mark_dilute).
class SprayMaterial : public mpm::MaterialModel {
 public:
  explicit SprayMaterial(bool dilute) : dilute_(dilute) {}
  void update_stress(std::span<const std::int64_t> /*ids*/, std::span<const common::Mat3> /*L*/,
                     double /*dt*/, std::span<common::Mat3> stress) override {
    for (auto& s : stress) s = -0.0625 * common::Mat3::Identity();  // 1/16 Pa: exact in binary
  }
  [[nodiscard]] double wave_speed() const override { return 10.0; }
  void mark_dilute(std::span<const std::int64_t> /*ids*/,
                   std::span<std::uint8_t> dilute) const override {
    std::fill(dilute.begin(), dilute.end(), static_cast<std::uint8_t>(dilute_ ? 1 : 0));
  }

 private:
  bool dilute_;
};

// A dilute point with a stress expands beyond the bound without stopping the run (its volume
// carries no lasting force); the same stress on a point that is not dilute stops it, and so does a
// dilute point compressed below V0 / ratio.
TEST(Solver, ADilutePointMayExpandBeyondTheBlowUpBound) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.gravity = Vec3::Zero();
  cfg.max_volume_ratio = 1.1;
  const auto block = [&](double rate) {
    mpm::MaterialPoints pts = small_block(cfg.grid);
    for (std::size_t p = 0; p < pts.size(); ++p)
      pts.v[p] = rate * (pts.x[p] - Vec3(0.75, 0.6, 0.9));
    return pts;
  };
  SprayMaterial spray(true);
  mpm::Solver s(cfg, block(0.2), {&spray});
  s.run(200);
  double largest = 0.0;
  for (std::size_t p = 0; p < s.points().size(); ++p) {
    largest = std::max(largest, s.points().volume[p] / s.points().volume0[p]);
    EXPECT_FALSE(s.points().stress[p].isZero(0.0));
  }
  EXPECT_GT(largest, 1.1);
  SprayMaterial dense(false);
  mpm::Solver d(cfg, block(0.2), {&dense});
  expect_message([&] { d.run(200); }, {"volume / initial volume = 1.", "outside [1/1.1, 1.1]",
                                       "its pressure 0.0625 Pa"});
  mpm::Solver c(cfg, block(-0.2), {&spray});
  expect_message([&] { c.run(200); }, {"volume / initial volume = 0.", "outside [1/1.1, 1.1]"});
}

// A material that fails at its third update, as an RVE of the farm may.
class FailingMaterial : public mpm::MaterialModel {
 public:
  void update_stress(std::span<const std::int64_t> /*ids*/, std::span<const common::Mat3> /*L*/,
                     double /*dt*/, std::span<common::Mat3> stress) override {
    if (++calls_ == 3) throw common::NumericalError("RVE id 7 failed: stress not finite");
    for (auto& s : stress) s.setZero();
  }
  [[nodiscard]] double wave_speed() const override { return 10.0; }

 private:
  int calls_ = 0;
};

TEST(Solver, AMaterialFailureGainsTheStepAndSimulatedTime) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  FailingMaterial mat;
  mpm::Solver s(cfg, small_block(cfg.grid), {&mat});
  expect_message([&] { s.run(5); },
                 {"mpm step 2 (t = 0.037", ", dt = 0.012", "s): RVE id 7 failed"});
}

TEST(Solver, ConfigErrorsNameKeyValueAndRule) {
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  cfg.damping = 1.5;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.damping = 1.5", "[0, 1)"});
  cfg = small_config(mpm::ShapeKind::linear);
  cfg.cfl = 0.0;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.cfl = 0", "(0, 1]"});
  // The job key, not a C++ synonym (the job holds flip; the PIC share is 1 - flip).
  cfg = small_config(mpm::ShapeKind::linear);
  cfg.flip = -0.5;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.flip = -0.5", "[0, 1]"});
  // The PIC share per step (flip) and in time (pic_time) are one or the other; APIC has none.
  cfg = small_config(mpm::ShapeKind::linear);
  cfg.pic_time = 1e-3;
  cfg.flip = 0.95;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.pic_time = 0.001 s", "mpm.flip = 0.95", "not both"});
  cfg.flip = 1.0;
  cfg.transfer = mpm::Transfer::apic;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.pic_time", "apic"});
  cfg = small_config(mpm::ShapeKind::linear);
  cfg.pic_time = -1.0;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); }, {"mpm.pic_time = -1"});
  // XPIC shapes the PIC share: it needs one (flip < 1 or pic_time), not with APIC, order 1-8.
  cfg = small_config(mpm::ShapeKind::linear);
  cfg.xpic_order = 3;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.xpic_order = 3", "no PIC share"});
  cfg.transfer = mpm::Transfer::apic;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.xpic_order = 3", "apic"});
  cfg = small_config(mpm::ShapeKind::linear);
  cfg.flip = 0.0;
  cfg.xpic_order = 0;
  expect_message([&] { mpm::Solver(cfg, small_block(cfg.grid), {&mat}); },
                 {"mpm.xpic_order = 0", "[1, 8]"});
  cfg.xpic_order = 2;
  EXPECT_NO_THROW(mpm::Solver(cfg, small_block(cfg.grid), {&mat}));
  cfg = small_config(mpm::ShapeKind::linear);
  mpm::MaterialPoints pts = small_block(cfg.grid);
  pts.material[0] = 1;
  expect_message([&] { mpm::Solver(cfg, pts, {&mat}); }, {"point id 0", "material 1"});
}

TEST(Solver, CflTimeStepUsesWaveSpeedAndPointSpeed) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);
  mpm::MaterialPoints pts = small_block(cfg.grid);
  pts.v[0] = Vec3(0, 3, 4);
  mpm::Solver s(cfg, pts, {&mat});
  EXPECT_DOUBLE_EQ(s.next_dt(), 0.5 * 0.25 / (mat.wave_speed() + 5.0));
}

TEST(Solver, TwoMaterialsEachSeeTheirPoints) {
  mpm::SolverConfig cfg = small_config(mpm::ShapeKind::linear);
  mpm::LinearElastic soft(1e5, 0.3, 1800.0), stiff(1e7, 0.3, 1800.0);
  mpm::MaterialPoints pts = small_block(cfg.grid);
  for (std::size_t p = 0; p < pts.size(); p += 2) pts.material[p] = 1;
  mpm::Solver s(cfg, pts, {&soft, &stiff});
  s.add_constraint(mpm::face_constraint(cfg.grid, 2, -1, {true, true, true}));
  s.run(3);
  for (std::size_t p = 0; p < s.points().size(); ++p) {
    const auto& m = s.points().material[p] == 0 ? soft : stiff;
    EXPECT_EQ(s.points().stress[p], m.stress(s.points().id[p]));
  }
}

}  // namespace

namespace {

// benchmark.hpp: the library entry point of `mpmxdem bench mpm` runs and reports a rate
// (no timing is asserted: tests never assert on wall time).
TEST(Benchmark, RunsAndReportsARate) {
  const mpm::BenchmarkResult r = mpm::run_benchmark(1000, 1, 1, "ugimp");
  EXPECT_GE(r.points, 1000);
  EXPECT_EQ(r.steps, 1);
  EXPECT_GT(r.updates_per_second, 0.0);
  EXPECT_NE(mpm::to_string(r).find("shape=ugimp"), std::string::npos);
  EXPECT_THROW((void)mpm::run_benchmark(1000, 1, 1, "cubic"), common::InputError);
}

}  // namespace
