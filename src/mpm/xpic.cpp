// XPIC(m) grid velocity (see header). Location suffixes: _p point, _i node.
#include "mpm/xpic.hpp"

#include <cstdint>

#include "mpm/parallel.hpp"

namespace mpm {

void xpic_velocity(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                   const MaterialPoints& points, const GridFields& fields, double threshold,
                   int order, XpicScratch& scratch, std::vector<common::Vec3>& v_star) {
  const auto n_nodes = static_cast<std::size_t>(grid.num_nodes());
  v_star.resize(n_nodes, common::Vec3::Zero());
  scratch.w.resize(n_nodes, common::Vec3::Zero());
  scratch.sum.resize(n_nodes, common::Vec3::Zero());
  scratch.weight.resize(n_nodes, 0.0);
  scratch.w_point.resize(points.size());
  const std::vector<std::int64_t>& active = fields.active;
  const auto n_active = static_cast<std::int64_t>(active.size());
  auto node = [&](std::int64_t k) {
    return static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
  };
  // k = 1: C(m, 1) V = m V.
  for_each_index(n_active, [&](std::int64_t k) {
    const std::size_t i = node(k);
    scratch.w[i] = fields.velocity[i];
    v_star[i] = static_cast<double>(order) * fields.velocity[i];
  });
  double binomial = static_cast<double>(order);  // C(m, k - 1)
  for (int k = 2; k <= order; ++k) {
    binomial = binomial * static_cast<double>(order - k + 1) / static_cast<double>(k);  // C(m, k)
    const double coefficient = (k % 2 == 0) ? -binomial : binomial;  // (-1)^(k+1) C(m, k)
    // G2P: w_p = sum_i S w_i.
    for_each_index(static_cast<std::int64_t>(points.size()), [&](std::int64_t q) {
      const auto p = static_cast<std::size_t>(q);
      common::Vec3 w_p = common::Vec3::Zero();
      for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
        w_p += S * scratch.w[static_cast<std::size_t>(node_i)];
      });
      scratch.w_point[p] = w_p;
    });
    // P2G: w_i = sum_p m_p S w_p / sum_p m_p S.
    for_each_index(n_active, [&](std::int64_t k2) {
      const std::size_t i = node(k2);
      scratch.sum[i].setZero();
      scratch.weight[i] = 0.0;
    });
    for_points_coloured(bins, [&](std::size_t p) {
      const double m_p = points.mass[p];
      const common::Vec3 mw_p = m_p * scratch.w_point[p];
      for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
        const auto i = static_cast<std::size_t>(node_i);
        scratch.sum[i] += S * mw_p;
        scratch.weight[i] += S * m_p;
      });
    });
    for_each_index(n_active, [&](std::int64_t k2) {
      const std::size_t i = node(k2);
      const double m_i = fields.mass[i];
      common::Vec3 w_i = (m_i >= threshold && m_i > 0.0 && scratch.weight[i] > 0.0)
                             ? common::Vec3(scratch.sum[i] / scratch.weight[i])
                             : common::Vec3::Zero();
      for (int d = 0; d < 3; ++d) {
        if (fields.fixed[i] & (1u << d)) w_i[d] = fields.velocity[i][d];
      }
      scratch.w[i] = w_i;
      v_star[i] += coefficient * w_i;
    });
  }
}

}  // namespace mpm
