// Nonlocal average (see nonlocal_average.hpp; docs/design/mpm.md "Regularisation"): Gaussian-
// weighted volume average over the points within 3 l, and its adjoint.
#include "mpm/nonlocal_average.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "mpm/parallel.hpp"

namespace mpm {

namespace {

void check_sizes(std::size_t n, std::size_t volume, std::size_t group) {
  if (volume != n || group != n) {
    throw common::NumericalError("NonlocalAverage: x, volume and group differ in size");
  }
}

}  // namespace

NonlocalAverage::NonlocalAverage(double length) : length_(length) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw common::InputError("mpm.regularisation.length = " + std::to_string(length) +
                             " m: the nonlocal average needs a finite length > 0");
  }
}

template <class Fn>
void NonlocalAverage::for_neighbours(std::size_t p, const std::vector<common::Vec3>& x,
                                     const std::vector<std::int32_t>& group, Fn&& fn) const {
  const double side = kNonlocalCutoff * length_;
  const double cutoff2 = side * side;
  const common::Vec3& xp = x[p];
  std::int64_t b[3];
  for (int d = 0; d < 3; ++d) {
    b[d] =
        std::clamp(static_cast<std::int64_t>((xp[d] - lo_[d]) / side), std::int64_t{0}, nb_[d] - 1);
  }
  for (std::int64_t k = std::max<std::int64_t>(b[2] - 1, 0); k <= std::min(b[2] + 1, nb_[2] - 1);
       ++k) {
    for (std::int64_t j = std::max<std::int64_t>(b[1] - 1, 0); j <= std::min(b[1] + 1, nb_[1] - 1);
         ++j) {
      for (std::int64_t i = std::max<std::int64_t>(b[0] - 1, 0);
           i <= std::min(b[0] + 1, nb_[0] - 1); ++i) {
        const std::int64_t key = i + nb_[0] * (j + nb_[1] * k);
        auto it = std::lower_bound(bins_.begin(), bins_.end(),
                                   std::pair<std::int64_t, std::int64_t>{key, -1});
        for (; it != bins_.end() && it->first == key; ++it) {
          const auto q = static_cast<std::size_t>(it->second);
          if (group[q] != group[p]) continue;
          // |x_q - x_p|^2 is |x_p - x_q|^2 bit for bit: w_pq = w_qp, the adjoint's symmetry.
          const double r2 = (x[q] - xp).squaredNorm();
          if (r2 < cutoff2) fn(q, r2);
        }
      }
    }
  }
}

void NonlocalAverage::prepare(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
                              const std::vector<std::int32_t>& group) {
  const std::size_t n = x.size();
  check_sizes(n, volume.size(), group.size());
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw common::NumericalError("NonlocalAverage: more than 2^31 points");
  }
  prepared_ = false;
  x_ = x;
  volume_ = volume;
  offset_.assign(n + 1, 0);
  weight_sum_.assign(n, 0.0);
  if (n == 0) {
    index_.clear();
    weight_.clear();
    prepared_ = true;
    return;
  }
  // Bins of side 3 l over the points' bounding box: a point's neighbours lie in its own bin and
  // the 26 around it. Keys are found by binary search in the sorted (key, point) list, so the
  // memory is that of the points, however far they spread.
  const double side = kNonlocalCutoff * length_;
  lo_ = x[0];
  common::Vec3 hi = x[0];
  for (const auto& xp : x) {
    lo_ = lo_.cwiseMin(xp);
    hi = hi.cwiseMax(xp);
  }
  for (int d = 0; d < 3; ++d) nb_[d] = static_cast<std::int64_t>((hi[d] - lo_[d]) / side) + 1;
  bins_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::int64_t b[3];
    for (int d = 0; d < 3; ++d) {
      b[d] = std::clamp(static_cast<std::int64_t>((x[p][d] - lo_[d]) / side), std::int64_t{0},
                        nb_[d] - 1);
    }
    bins_[p] = {b[0] + nb_[0] * (b[1] + nb_[1] * b[2]), static_cast<std::int64_t>(p)};
  }
  std::sort(bins_.begin(), bins_.end());
  // Two passes: count the pairs of each point, then fill them (compressed rows in point order).
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    std::int64_t count = 0;
    for_neighbours(p, x, group, [&](std::size_t, double) { ++count; });
    offset_[p + 1] = count;
  });
  for (std::size_t p = 0; p < n; ++p) offset_[p + 1] += offset_[p];
  index_.resize(static_cast<std::size_t>(offset_[n]));
  weight_.resize(static_cast<std::size_t>(offset_[n]));
  const double inv_two_l2 = 1.0 / (2.0 * length_ * length_);
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    auto k = static_cast<std::size_t>(offset_[p]);
    double sum = 0.0;
    for_neighbours(p, x, group, [&](std::size_t q, double r2) {
      const double w = std::exp(-r2 * inv_two_l2) * volume[q];
      index_[k] = static_cast<std::int32_t>(q);
      weight_[k] = w;
      sum += w;
      ++k;
    });
    weight_sum_[p] = sum;  // > 0: the point itself is in it (w = V_p > 0)
  });
  prepared_ = true;
}

void NonlocalAverage::apply(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) {
  const std::size_t n = in.size();
  if (!prepared_ || n != weight_sum_.size()) {
    throw common::NumericalError("NonlocalAverage::apply: not prepared for these points");
  }
  out.resize(n);
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    common::Mat3 sum = common::Mat3::Zero();
    for (auto k = static_cast<std::size_t>(offset_[p]);
         k < static_cast<std::size_t>(offset_[p + 1]); ++k) {
      sum += weight_[k] * in[static_cast<std::size_t>(index_[k])];
    }
    out[p] = sum / weight_sum_[p];
  });
}

void NonlocalAverage::apply_adjoint(const std::vector<common::Mat3>& in,
                                    std::vector<common::Mat3>& out) {
  const std::size_t n = in.size();
  if (!prepared_ || n != weight_sum_.size()) {
    throw common::NumericalError("NonlocalAverage::apply_adjoint: not prepared for these points");
  }
  out.resize(n);
  // w_pq = w_qp: q's own row lists its p's with w_qp V_p, the weight the adjoint needs.
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t iq) {
    const auto q = static_cast<std::size_t>(iq);
    common::Mat3 sum = common::Mat3::Zero();
    for (auto k = static_cast<std::size_t>(offset_[q]);
         k < static_cast<std::size_t>(offset_[q + 1]); ++k) {
      const auto p = static_cast<std::size_t>(index_[k]);
      sum += (weight_[k] / weight_sum_[p]) * in[p];
    }
    out[q] = sum;
  });
}

}  // namespace mpm
