// ElasticMicro: hypoelastic verification micro model (see header).
#include "farm/elastic_micro.hpp"

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/tensor.hpp"

namespace farm {

namespace {

void bad(const char* key, double value, const char* rule) {
  throw common::InputError(std::string("farm elastic micro model: ") + key + " = " +
                           std::to_string(value) + ": " + rule);
}

}  // namespace

void ElasticMicroParams::validate() const {
  if (!(young > 0.0)) bad("young", young, "must be > 0 Pa");
  if (!(poisson > -1.0 && poisson < 0.5)) bad("poisson", poisson, "must be in (-1, 0.5)");
  if (!(density > 0.0)) bad("density", density, "must be > 0 kg/m^3");
  if (!(void_ratio0 >= 0.0)) bad("void_ratio0", void_ratio0, "must be >= 0");
  if (substeps < 1) bad("substeps", static_cast<double>(substeps), "must be >= 1");
  if (!initial_stress.allFinite()) bad("initial_stress", initial_stress.trace(), "must be finite");
}

ElasticMicro::ElasticMicro(std::int64_t id, const ElasticMicroParams& params)
    : id_(id), params_(params), stress_(params.initial_stress) {
  params_.validate();
}

MicroReport ElasticMicro::step(const common::Mat3& L, double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  ++steps_;
  if (id_ == params_.fail_id && steps_ == params_.fail_step) {
    throw common::NumericalError(
        "elastic micro model: injected failure (fail_id = " + std::to_string(params_.fail_id) +
        ", fail_step = " + std::to_string(params_.fail_step) + ")");
  }
  const double h = dt / static_cast<double>(params_.substeps);
  const common::HughesWinget update(L, h, common::lame(params_.young, params_.poisson));
  const double dj = (common::Mat3::Identity() + h * L).determinant();
  for (std::int64_t k = 0; k < params_.substeps; ++k) {
    stress_ = update.apply(stress_);
    j_ *= dj;
  }
  if (!stress_.allFinite()) {
    throw common::NumericalError("elastic micro model: non-finite stress (trace = " +
                                 std::to_string(stress_.trace()) + " Pa)");
  }
  MicroReport r = report();
  r.dem_steps = params_.substeps;
  r.t_p = dt;
  r.guards = 0;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

MicroReport ElasticMicro::report() const {
  MicroReport r;
  r.p = common::pressure(stress_);
  r.q = common::deviatoric(stress_);
  r.void_ratio = (1.0 + params_.void_ratio0) * j_ - 1.0;
  return r;
}

double ElasticMicro::wave_speed() const {
  const common::Lame c = common::lame(params_.young, params_.poisson);
  return std::sqrt((c.lambda + 2.0 * c.mu) / params_.density);
}

void ElasticMicro::save(common::StateWriter& w) const {
  w.write("elastic/id", std::vector<std::int64_t>{id_});
  std::vector<double> p{params_.young, params_.poisson, params_.density, params_.void_ratio0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) p.push_back(params_.initial_stress(i, j));
  }
  w.write("elastic/params", p);
  w.write("elastic/int_params",
          std::vector<std::int64_t>{params_.substeps, params_.fail_id, params_.fail_step});
  std::vector<double> s(9);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) s[static_cast<std::size_t>(3 * i + j)] = stress_(i, j);
  }
  w.write("elastic/stress", s);
  w.write("elastic/j", std::vector<double>{j_});
  w.write("elastic/steps", std::vector<std::int64_t>{steps_});
}

std::unique_ptr<MicroModel> ElasticMicro::load(const common::StateReader& r) {
  auto sized = [](auto v, std::size_t n, const char* name) {
    if (v.size() != n) {
      throw common::InputError(std::string("elastic micro state: field '") + name + "' has " +
                               std::to_string(v.size()) + " values, expected " + std::to_string(n));
    }
    return v;
  };
  const auto id = sized(r.read_i64("elastic/id"), 1, "elastic/id");
  const auto p = sized(r.read_f64("elastic/params"), 13, "elastic/params");
  const auto ip = sized(r.read_i64("elastic/int_params"), 3, "elastic/int_params");
  const auto s = sized(r.read_f64("elastic/stress"), 9, "elastic/stress");
  const auto j = sized(r.read_f64("elastic/j"), 1, "elastic/j");
  const auto steps = sized(r.read_i64("elastic/steps"), 1, "elastic/steps");
  ElasticMicroParams params;
  params.young = p[0];
  params.poisson = p[1];
  params.density = p[2];
  params.void_ratio0 = p[3];
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b)
      params.initial_stress(a, b) = p[static_cast<std::size_t>(4 + 3 * a + b)];
  }
  params.substeps = ip[0];
  params.fail_id = ip[1];
  params.fail_step = ip[2];
  auto m = std::make_unique<ElasticMicro>(id[0], params);
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) m->stress_(a, b) = s[static_cast<std::size_t>(3 * a + b)];
  }
  m->j_ = j[0];
  m->steps_ = steps[0];
  return m;
}

MicroKind ElasticMicro::kind(const ElasticMicroParams& params) {
  params.validate();
  MicroKind k;
  k.create = [params](std::int64_t id) { return std::make_unique<ElasticMicro>(id, params); };
  k.load = [](const common::StateReader& r) { return ElasticMicro::load(r); };
  return k;
}

}  // namespace farm
