// Hypoelastic linear elasticity, Jaumann rate, Hughes-Winget rotation (see header).
#include "mpm/linear_elastic.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "mpm/parallel.hpp"

namespace mpm {

LinearElastic::LinearElastic(double youngs_modulus, double poisson_ratio, double density,
                             const common::Mat3& initial_stress)
    : density_(density), initial_(initial_stress) {
  if (!(youngs_modulus > 0.0)) {
    throw common::InputError("mpm linear elastic: E = " + std::to_string(youngs_modulus) +
                             ": must be > 0 Pa");
  }
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5)) {
    throw common::InputError("mpm linear elastic: nu = " + std::to_string(poisson_ratio) +
                             ": must be in (-1, 0.5)");
  }
  if (!(density > 0.0)) {
    throw common::InputError("mpm linear elastic: density = " + std::to_string(density) +
                             ": must be > 0 kg/m^3");
  }
  const common::Lame c = common::lame(youngs_modulus, poisson_ratio);
  lambda_ = c.lambda;
  mu_ = c.mu;
}

void LinearElastic::ensure(std::int64_t id) {
  MPMXDEM_CHECK(id >= 0, "point id " + std::to_string(id) + " must be >= 0");
  const auto need = static_cast<std::size_t>(id) + 1;
  if (stress_.size() < need) stress_.resize(need, initial_);
}

void LinearElastic::update_stress(std::span<const std::int64_t> ids,
                                  std::span<const common::Mat3> L, double dt,
                                  std::span<common::Mat3> stress) {
  MPMXDEM_CHECK(ids.size() == L.size() && ids.size() == stress.size(), "span sizes differ");
  for (const std::int64_t id : ids) ensure(id);
  const auto n = static_cast<std::int64_t>(ids.size());
  const common::Lame c{lambda_, mu_};
  for_each_index(n, [&](std::int64_t p) {
    const common::HughesWinget update(L[static_cast<std::size_t>(p)], dt, c);
    common::Mat3& s = stress_[static_cast<std::size_t>(ids[static_cast<std::size_t>(p)])];
    s = update.apply(s);
    stress[static_cast<std::size_t>(p)] = s;
  });
}

double LinearElastic::wave_speed() const { return std::sqrt((lambda_ + 2.0 * mu_) / density_); }

common::Mat3 LinearElastic::stress(std::int64_t id) const {
  if (id >= 0 && static_cast<std::size_t>(id) < stress_.size()) {
    return stress_[static_cast<std::size_t>(id)];
  }
  return initial_;
}

void LinearElastic::set_stress(std::int64_t id, const common::Mat3& s) {
  ensure(id);
  stress_[static_cast<std::size_t>(id)] = s;
}

void LinearElastic::save(common::StateWriter& writer, std::string_view prefix) const {
  std::vector<double> flat;
  flat.reserve(stress_.size() * 9);
  for (const common::Mat3& s : stress_) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) flat.push_back(s(i, j));
    }
  }
  writer.write(std::string(prefix) + "stress", flat);
}

void LinearElastic::load(const common::StateReader& reader, std::string_view prefix) {
  const std::string name = std::string(prefix) + "stress";
  const std::vector<double> flat = reader.read_f64(name);
  if (flat.size() % 9 != 0) {
    throw common::InputError("checkpoint field " + name + ": size " + std::to_string(flat.size()) +
                             " is not a multiple of 9");
  }
  common::require_finite(flat, "checkpoint field " + name + ":");
  stress_.resize(flat.size() / 9);
  for (std::size_t p = 0; p < stress_.size(); ++p) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        stress_[p](i, j) = flat[p * 9 + static_cast<std::size_t>(i * 3 + j)];
    }
  }
}

}  // namespace mpm
