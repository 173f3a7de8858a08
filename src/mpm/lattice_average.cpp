// Nonlocal average through a lattice (see lattice_average.hpp; docs/design/mpm.md
// "Regularisation").
#include "mpm/lattice_average.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "mpm/messages.hpp"
#include "mpm/nonlocal_average.hpp"
#include "mpm/parallel.hpp"

namespace mpm {

namespace {

constexpr int kTensor = 9;  // components of a Mat3

/// The lattice node of corner c (bits: x, y, z) of the cell whose lower corner is node base.
std::int64_t corner_node(std::int64_t base, int c, const std::array<std::int64_t, 3>& n) {
  return base + (c & 1) + n[0] * (((c >> 1) & 1) + n[1] * ((c >> 2) & 1));
}

/// The tent weight of corner c for a point at f (its position in the cell, each in [0, 1]).
double corner_weight(const common::Vec3& f, int c) {
  return ((c & 1) ? f[0] : 1.0 - f[0]) * (((c >> 1) & 1) ? f[1] : 1.0 - f[1]) *
         (((c >> 2) & 1) ? f[2] : 1.0 - f[2]);
}

}  // namespace

LatticeAverage::LatticeAverage(double length) : length_(length) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw common::InputError("mpm.regularisation.length = " + std::to_string(length) +
                             " m: the nonlocal average needs a finite length > 0");
  }
  spacing_ = length / kLatticePerLength;
  const double lg2 = length * length - spacing_ * spacing_ / 3.0;
  const auto K = static_cast<int>(std::floor(kNonlocalCutoff * kLatticePerLength + 1e-9));
  for (int k = 0; k <= K; ++k) {
    const double r = k * spacing_;
    taps_.push_back(std::exp(-r * r / (2.0 * lg2)));
  }
}

void LatticeAverage::prepare(const std::vector<common::Vec3>& x, const std::vector<double>& volume,
                             const std::vector<std::int32_t>& group) {
  const std::size_t n = x.size();
  if (volume.size() != n || group.size() != n) {
    throw common::NumericalError("LatticeAverage: x, volume and group differ in size");
  }
  prepared_ = false;
  x_ = x;
  volume_ = volume;
  weight_sum_.assign(n, 0.0);
  corner_.resize(n);
  frac_.resize(n);
  slot_.resize(n);
  // Groups as dense slots in the order of their ids.
  std::vector<std::int32_t> ids(group);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  groups_ = ids.size();
  for (std::size_t p = 0; p < n; ++p) {
    slot_[p] = static_cast<std::int32_t>(std::lower_bound(ids.begin(), ids.end(), group[p]) -
                                         ids.begin());
  }
  if (n == 0) {
    prepared_ = true;
    return;
  }
  lo_ = x[0];
  common::Vec3 hi = x[0];
  for (const auto& xp : x) {
    lo_ = lo_.cwiseMin(xp);
    hi = hi.cwiseMax(xp);
  }
  double nodes = 1.0;
  for (int d = 0; d < 3; ++d) {
    const double cells = std::floor((hi[d] - lo_[d]) / spacing_);
    nodes *= cells + 2.0;
    if (!(nodes <= static_cast<double>(kMaxLatticeNodes))) {
      throw common::NumericalError(
          "mpm.regularisation.average = \"lattice\": the points span " +
          messages::num_str(hi[0] - lo_[0]) + " x " + messages::num_str(hi[1] - lo_[1]) + " x " +
          messages::num_str(hi[2] - lo_[2]) + " m, more than " + std::to_string(kMaxLatticeNodes) +
          " lattice nodes of l / 3 = " + messages::num_str(spacing_) +
          " m (use average = \"pairs\", whose memory is that of the points)");
    }
    n_[static_cast<std::size_t>(d)] = static_cast<std::int64_t>(cells) + 2;
  }
  for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    std::int64_t idx[3];
    for (int d = 0; d < 3; ++d) {
      const double u = (x[p][d] - lo_[d]) / spacing_;
      idx[d] = std::clamp(static_cast<std::int64_t>(std::floor(u)), std::int64_t{0},
                          n_[static_cast<std::size_t>(d)] - 2);
      frac_[p][d] = std::clamp(u - static_cast<double>(idx[d]), 0.0, 1.0);
    }
    corner_[p] = idx[0] + n_[0] * (idx[1] + n_[1] * idx[2]);
  });
  // W_p: the smoothing of the volumes.
  smooth<1>([&](std::size_t p, double* v) { v[0] = volume[p]; },
            [&](std::size_t p, const double* sum) { weight_sum_[p] = sum[0]; });  // > 0: p's own
  prepared_ = true;
}

void LatticeAverage::convolve(std::vector<double>& f, int components) {
  const auto C = static_cast<std::int64_t>(components);
  const auto K = static_cast<std::int64_t>(taps_.size()) - 1;
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t len = n_[static_cast<std::size_t>(axis)];
    const std::int64_t stride = axis == 0 ? 1 : (axis == 1 ? n_[0] : n_[0] * n_[1]);
    const std::int64_t lines = n_[0] * n_[1] * n_[2] / len;
    line_.resize(static_cast<std::size_t>(len * C));
    for (std::int64_t l = 0; l < lines; ++l) {
      // The first node of line l: l's index over the two other axes.
      const std::int64_t start = axis == 0 ? l * n_[0]
                                 : axis == 1 ? (l % n_[0]) + (l / n_[0]) * n_[0] * n_[1]
                                             : l;
      bool empty = true;
      for (std::int64_t i = 0; i < len; ++i) {
        const double* src = &f[static_cast<std::size_t>((start + i * stride) * C)];
        double* dst = &line_[static_cast<std::size_t>(i * C)];
        for (std::int64_t c = 0; c < C; ++c) {
          dst[c] = src[c];
          if (src[c] != 0.0) empty = false;
        }
      }
      if (empty) continue;
      for (std::int64_t i = 0; i < len; ++i) {
        double* dst = &f[static_cast<std::size_t>((start + i * stride) * C)];
        const std::int64_t a = std::max<std::int64_t>(i - K, 0);
        const std::int64_t b = std::min<std::int64_t>(i + K, len - 1);
        for (std::int64_t c = 0; c < C; ++c) dst[c] = 0.0;
        for (std::int64_t j = a; j <= b; ++j) {
          const double g = taps_[static_cast<std::size_t>(std::abs(j - i))];
          const double* src = &line_[static_cast<std::size_t>(j * C)];
          for (std::int64_t c = 0; c < C; ++c) dst[c] += g * src[c];
        }
      }
    }
  }
}

template <int C, class Value, class Store>
void LatticeAverage::smooth(Value&& value, Store&& store) {
  const std::size_t n = corner_.size();
  const std::int64_t nodes = n_[0] * n_[1] * n_[2];
  for (std::size_t g = 0; g < groups_; ++g) {
    field_.assign(static_cast<std::size_t>(nodes * C), 0.0);
    // Onto the lattice in point order (a fixed order: the same bits on any thread count).
    for (std::size_t p = 0; p < n; ++p) {
      if (static_cast<std::size_t>(slot_[p]) != g) continue;
      double v[C];
      value(p, v);
      for (int c = 0; c < 8; ++c) {
        const double w = corner_weight(frac_[p], c);
        if (w == 0.0) continue;
        double* dst = &field_[static_cast<std::size_t>(corner_node(corner_[p], c, n_) * C)];
        for (int k = 0; k < C; ++k) dst[k] += w * v[k];
      }
    }
    convolve(field_, C);
    for_each_index(static_cast<std::int64_t>(n), [&](std::int64_t ip) {
      const auto p = static_cast<std::size_t>(ip);
      if (static_cast<std::size_t>(slot_[p]) != g) return;
      double sum[C] = {};
      for (int c = 0; c < 8; ++c) {
        const double w = corner_weight(frac_[p], c);
        if (w == 0.0) continue;
        const double* src = &field_[static_cast<std::size_t>(corner_node(corner_[p], c, n_) * C)];
        for (int k = 0; k < C; ++k) sum[k] += w * src[k];
      }
      store(p, sum);
    });
  }
}

void LatticeAverage::apply(const std::vector<common::Mat3>& in, std::vector<common::Mat3>& out) {
  const std::size_t n = in.size();
  if (!prepared_ || n != weight_sum_.size()) {
    throw common::NumericalError("LatticeAverage::apply: not prepared for these points");
  }
  out.resize(n);
  smooth<kTensor>(
      [&](std::size_t p, double* v) {
        for (int k = 0; k < kTensor; ++k) v[k] = volume_[p] * in[p].data()[k];
      },
      [&](std::size_t p, const double* sum) {
        for (int k = 0; k < kTensor; ++k) out[p].data()[k] = sum[k] / weight_sum_[p];
      });
}

void LatticeAverage::apply_adjoint(const std::vector<common::Mat3>& in,
                                   std::vector<common::Mat3>& out) {
  const std::size_t n = in.size();
  if (!prepared_ || n != weight_sum_.size()) {
    throw common::NumericalError("LatticeAverage::apply_adjoint: not prepared for these points");
  }
  out.resize(n);
  smooth<kTensor>(
      [&](std::size_t p, double* v) {
        const double a = volume_[p] / weight_sum_[p];
        for (int k = 0; k < kTensor; ++k) v[k] = a * in[p].data()[k];
      },
      [&](std::size_t p, const double* sum) {
        for (int k = 0; k < kTensor; ++k) out[p].data()[k] = sum[k];
      });
}

std::unique_ptr<PointAverage> make_point_average(AverageKind kind, double length) {
  if (kind == AverageKind::lattice) return std::make_unique<LatticeAverage>(length);
  return std::make_unique<NonlocalAverage>(length);
}

}  // namespace mpm
