// Nonlocal strain-gradient regularisation (see gradient_regularisation.hpp; docs/design/mpm.md
// "Regularisation").
#include "mpm/gradient_regularisation.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "mpm/parallel.hpp"

namespace mpm {

GradientRegularisation::GradientRegularisation(double length, double modulus, AverageKind average)
    : average_(make_point_average(average, length)), modulus_(modulus) {
  if (!(modulus > 0.0) || !std::isfinite(modulus)) {
    throw common::InputError("mpm.regularisation.modulus = " + std::to_string(modulus) +
                             " Pa: the regularisation needs a finite modulus > 0");
  }
}

double GradientRegularisation::update(const std::vector<common::Vec3>& x,
                                      const std::vector<double>& volume,
                                      const std::vector<std::int32_t>& material,
                                      const std::vector<common::Mat3>& L, double dt) {
  const std::size_t n = x.size();
  if (strain_.empty()) strain_.assign(n, common::Mat3::Zero());
  if (strain_.size() != n || L.size() != n) {
    throw common::NumericalError("GradientRegularisation: the points changed in number");
  }
  rate_.resize(n);
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    rate_[p] = 0.5 * (L[p] + L[p].transpose());
  });
  average_->prepare(x, volume, material);
  average_->apply(rate_, average_rate_);
  thread_local std::vector<double> terms;
  compute_terms(static_cast<std::int64_t>(n), terms, [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    const common::Mat3 W = 0.5 * (L[p] - L[p].transpose());
    const common::Mat3 de = rate_[p] - average_rate_[p];
    const common::Mat3 before = strain_[p];
    strain_[p] += dt * (de + W * before - before * W);
    return volume[p] * modulus_ * (0.5 * (before + strain_[p])).cwiseProduct(de).sum();
  });
  double power = 0.0;
  for (const double t : terms) power += t;
  return dt * power;
}

void GradientRegularisation::add_force_stress(const std::vector<common::Vec3>& x,
                                              const std::vector<double>& volume,
                                              const std::vector<std::int32_t>& material,
                                              std::vector<common::Mat3>& stress) {
  const std::size_t n = x.size();
  if (strain_.empty()) return;  // before the first update: no strain, no stress
  if (strain_.size() != n || stress.size() != n) {
    throw common::NumericalError("GradientRegularisation: the points changed in number");
  }
  tau_.resize(n);
  for (std::size_t p = 0; p < n; ++p) tau_[p] = modulus_ * strain_[p];
  // The neighbours of the last update when the points have not moved since (USF: the same step;
  // MUSL: the previous step's end), found again otherwise (after a restart: the same bits).
  if (!average_->prepared_for(x, volume)) average_->prepare(x, volume, material);
  average_->apply_adjoint(tau_, smoothed_);
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    stress[p] += tau_[p] - smoothed_[p];
  });
}

}  // namespace mpm
