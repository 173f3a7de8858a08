// Point <-> grid transfers (see header). Kernels use location suffixes: _p point, _i node.
#include "mpm/transfers.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace mpm {

std::int64_t compute_stencils(ShapeKind kind, const Grid& grid, const MaterialPoints& points,
                              StencilCache& cache, int linear_axis) {
  const std::size_t n = points.size();
  std::array<ShapeKind, 3> kinds{kind, kind, kind};
  if (linear_axis >= 0 && linear_axis < 3) {
    kinds[static_cast<std::size_t>(linear_axis)] = ShapeKind::linear;
  }
  for (std::size_t d = 0; d < 3; ++d) cache.width[d] = stencil_width(kinds[d]);
  cache.base.resize(n);
  cache.w.resize(n * 9);
  cache.dw.resize(n * 9);
  const common::Vec3i cells = grid.cells;
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
  const auto nn = static_cast<std::int64_t>(n);
  // Weights of point q; false if its stencil leaves the grid.
  auto stencil = [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    bool inside = true;
    for (int d = 0; d < 3; ++d) {
      const double h = grid.spacing[d];
      const double s = (points.x[p][d] - grid.origin[d]) / h;
      const double lp = points.half_width0[p][d] / h;
      if (!std::isfinite(s) || s < -1.0 || s > cells[d] + 1.0) {
        inside = false;
        cache.base[p][d] = 0;
        continue;
      }
      const auto du = static_cast<std::size_t>(d);
      const Weights1D w1 = weights_1d(kinds[du], s, lp, h);
      cache.base[p][d] = w1.base;
      for (int a = 0; a < 3; ++a) {
        cache.w[p * 9 + static_cast<std::size_t>(d * 3 + a)] = w1.w[static_cast<std::size_t>(a)];
        cache.dw[p * 9 + static_cast<std::size_t>(d * 3 + a)] = w1.dw[static_cast<std::size_t>(a)];
      }
      if (w1.base < 0 || w1.base + cache.width[du] - 1 > cells[d]) inside = false;
    }
    return inside;
  };
  if (nn < kMinParallelPoints) {  // no parallel region for small problems (parallel.hpp)
    for (std::int64_t q = 0; q < nn; ++q) {
      if (!stencil(q)) bad = std::min(bad, q);
    }
  } else {
#pragma omp parallel for schedule(static) reduction(min : bad)
    for (std::int64_t q = 0; q < nn; ++q) {
      if (!stencil(q)) bad = std::min(bad, q);
    }
  }
  return bad == std::numeric_limits<std::int64_t>::max() ? -1 : bad;
}

void check_shape_domains(ShapeKind kind, const Grid& grid, const MaterialPoints& points,
                         int linear_axis) {
  if (kind != ShapeKind::ugimp) return;
  const auto num = [](double v) {
    std::ostringstream o;
    o << std::setprecision(17) << v;
    return o.str();
  };
  for (std::size_t p = 0; p < points.size(); ++p) {
    const std::string who = "mpm solver: point id " + std::to_string(points.id[p]);
    for (int d = 0; d < 3; ++d) {
      if (d == linear_axis) continue;
      if (points.half_width0[p][d] > 0.5 * grid.spacing[d]) {
        throw common::InputError(who + ": uGIMP needs half-widths <= spacing / 2");
      }
      const double lo = points.x[p][d] - points.half_width0[p][d];
      const double hi = points.x[p][d] + points.half_width0[p][d];
      const double g_lo = grid.origin[d];
      const double g_hi = grid.origin[d] + grid.cells[d] * grid.spacing[d];
      const double tol = 1e-9 * grid.spacing[d];
      if (lo <= g_lo + tol || hi >= g_hi - tol) {
        const char axis = static_cast<char>('x' + d);
        throw common::InputError(
            who + ": its uGIMP domain [" + num(lo) + ", " + num(hi) + "] m along " + axis +
            " reaches the grid's boundary at " + axis + " = " +
            num(lo <= g_lo + tol ? g_lo : g_hi) +
            " m: uGIMP needs one empty cell beyond the material (mpm.grid), its 3-node stencil "
            "reaches past the point's own cell; hold that node plane with the wall");
      }
    }
  }
}

namespace {

/// Sorts `keys`, distinct node indices each of which is marked in `marks` (marked(marks[i])),
/// ascending: where they are dense, one pass over the marks, which gives them in order, costs
/// less than sorting them (the same list either way).
template <class M, class Marked>
void sort_marked(std::vector<std::int64_t>& keys, const std::vector<M>& marks, Marked marked) {
  if (keys.size() * 8 > marks.size()) {
    keys.clear();
    for (std::size_t i = 0; i < marks.size(); ++i) {
      if (marked(marks[i])) keys.push_back(static_cast<std::int64_t>(i));
    }
  } else {
    std::sort(keys.begin(), keys.end());
  }
}

}  // namespace

void bin_points(const Grid& grid, const StencilCache& cache, PointBins& bins) {
  const std::size_t n = cache.base.size();
  const auto num_nodes = static_cast<std::size_t>(grid.num_nodes());
  if (bins.scratch.size() != num_nodes) bins.scratch.assign(num_nodes, -1);
  std::vector<std::int64_t> keys(n);
  bins.key.clear();
  // Count points per base node; scratch holds counts for used keys, -1 elsewhere.
  for (std::size_t p = 0; p < n; ++p) {
    const std::array<int, 3>& b = cache.base[p];
    keys[p] = grid.node_index(b[0], b[1], b[2]);
    std::int64_t& c = bins.scratch[static_cast<std::size_t>(keys[p])];
    if (c < 0) {
      c = 0;
      bins.key.push_back(keys[p]);
    }
    ++c;
  }
  sort_marked(bins.key, bins.scratch, [](std::int64_t c) { return c >= 0; });
  const std::size_t nb = bins.key.size();
  bins.offset.assign(nb + 1, 0);
  for (std::size_t b = 0; b < nb; ++b) {
    std::int64_t& c = bins.scratch[static_cast<std::size_t>(bins.key[b])];
    bins.offset[b + 1] = bins.offset[b] + c;
    c = bins.offset[b];  // scratch now holds the next write position of the bin
  }
  bins.order.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::int64_t& pos = bins.scratch[static_cast<std::size_t>(keys[p])];
    bins.order[static_cast<std::size_t>(pos++)] = static_cast<std::int64_t>(p);
  }
  // Two bins of one colour have bases that differ, on some axis, by a multiple of that axis's
  // width: their stencils are disjoint there.
  const std::array<int, 3> ns = cache.width;
  bins.by_colour.assign(static_cast<std::size_t>(ns[0] * ns[1] * ns[2]), {});
  for (std::size_t b = 0; b < nb; ++b) {
    bins.scratch[static_cast<std::size_t>(bins.key[b])] = -1;
    const common::Vec3i ijk = grid.node_ijk(bins.key[b]);
    const int colour = ijk[0] % ns[0] + ns[0] * (ijk[1] % ns[1] + ns[1] * (ijk[2] % ns[2]));
    bins.by_colour[static_cast<std::size_t>(colour)].push_back(static_cast<std::int64_t>(b));
  }
}

void activate_nodes(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                    GridFields& fields) {
  fields.clear_active();
  const std::array<int, 3> ns = cache.width;
  for (std::size_t b = 0; b + 1 < bins.offset.size(); ++b) {
    const auto p = static_cast<std::size_t>(bins.order[static_cast<std::size_t>(bins.offset[b])]);
    const std::array<int, 3>& base = cache.base[p];
    for (int k = 0; k < ns[2]; ++k) {
      for (int j = 0; j < ns[1]; ++j) {
        for (int i = 0; i < ns[0]; ++i) {
          const std::int64_t node_i = grid.node_index(base[0] + i, base[1] + j, base[2] + k);
          char& flag = fields.is_active[static_cast<std::size_t>(node_i)];
          if (!flag) {
            flag = 1;
            fields.active.push_back(node_i);
          }
        }
      }
    }
  }
  sort_marked(fields.active, fields.is_active, [](char flag) { return flag != 0; });
}

Transfer transfer_from_string(std::string_view name) {
  if (const auto t = common::value_of(kTransferNames, name)) return *t;
  throw common::InputError("mpm.transfer = \"" + std::string(name) + "\": must be one of " +
                           common::names_list(kTransferNames));
}

std::string_view to_string(Transfer t) { return common::name_of(kTransferNames, t); }

double pic_share(double flip, double pic_time, double dt) {
  return pic_time > 0.0 ? -std::expm1(-dt / pic_time) : 1.0 - flip;
}

void p2g_mass_momentum(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                       const MaterialPoints& points, const common::Vec3& gravity,
                       GridFields& fields, bool affine) {
  for_points_coloured(bins, [&](std::size_t p) {
    const double m_p = points.mass[p];
    const common::Vec3 mv_p = m_p * points.v[p];
    const common::Vec3 mg_p = m_p * gravity;
    const common::Mat3 mC_p = affine ? common::Mat3(m_p * points.C[p]) : common::Mat3::Zero();
    const common::Vec3 x_p = points.x[p];
    for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
      const auto i = static_cast<std::size_t>(node_i);
      fields.mass[i] += S * m_p;
      if (affine) {
        fields.momentum[i] += S * (mv_p + mC_p * (grid.node_position(node_i) - x_p));
      } else {
        fields.momentum[i] += S * mv_p;
      }
      fields.force[i] += S * mg_p;
    });
  });
}

void p2g_momentum(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                  const MaterialPoints& points, GridFields& fields, bool affine) {
  for (const std::int64_t i : fields.active) fields.momentum[static_cast<std::size_t>(i)].setZero();
  for_points_coloured(bins, [&](std::size_t p) {
    const common::Vec3 mv_p = points.mass[p] * points.v[p];
    const common::Mat3 mC_p =
        affine ? common::Mat3(points.mass[p] * points.C[p]) : common::Mat3::Zero();
    const common::Vec3 x_p = points.x[p];
    for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
      const auto i = static_cast<std::size_t>(node_i);
      if (affine) {
        fields.momentum[i] += S * (mv_p + mC_p * (grid.node_position(node_i) - x_p));
      } else {
        fields.momentum[i] += S * mv_p;
      }
    });
  });
}

void p2g_internal_force(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                        const MaterialPoints& points, GridFields& fields) {
  for_points_coloured(bins, [&](std::size_t p) {
    const common::Mat3 Vsigma_p = points.volume[p] * points.stress[p];
    for_each_node(grid, cache, p, [&](std::int64_t node_i, double, const common::Vec3& grad) {
      fields.force[static_cast<std::size_t>(node_i)] -= Vsigma_p * grad;
    });
  });
}

void g2p_velocity_gradient(const Grid& grid, const StencilCache& cache, const GridFields& fields,
                           double threshold, MaterialPoints& points) {
  const auto n = static_cast<std::int64_t>(points.size());
  for_each_index(n, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    common::Mat3 L_p = common::Mat3::Zero();
    const common::Vec3 v_p = points.v[p];
    for_each_node(grid, cache, p, [&](std::int64_t node_i, double, const common::Vec3& grad) {
      const auto i = static_cast<std::size_t>(node_i);
      if ((fields.mass[i] > 0.0 && fields.mass[i] >= threshold) || fields.fixed[i] == 7) {
        L_p += (fields.velocity[i] - v_p) * grad.transpose();
      }
    });
    points.L[p] = L_p;
  });
}

void g2p_update(const Grid& grid, const StencilCache& cache, const GridFields& fields,
                double pic_fraction, bool move_points, double dt, MaterialPoints& points,
                bool grid_positions, bool wall_impulse,
                const std::vector<common::Vec3>* pic_velocity) {
  const std::vector<common::Vec3>& V = pic_velocity != nullptr ? *pic_velocity : fields.velocity;
  const auto n = static_cast<std::int64_t>(points.size());
  for_each_index(n, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    common::Vec3 a_p = common::Vec3::Zero();
    common::Vec3 v_pic = common::Vec3::Zero();
    if (wall_impulse) {
      // The walls' momentum-stage correction, as an impulse over the step (zero elsewhere).
      for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
        const auto i = static_cast<std::size_t>(node_i);
        a_p += S * (fields.acceleration[i] + fields.wall_dv[i] / dt);
        v_pic += S * (V[i] + dt * fields.acceleration[i]);
      });
    } else if (pic_fraction == 0.0 && !grid_positions) {
      for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
        a_p += S * fields.acceleration[static_cast<std::size_t>(node_i)];
      });
    } else {
      for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
        const auto i = static_cast<std::size_t>(node_i);
        a_p += S * fields.acceleration[i];
        v_pic += S * (V[i] + dt * fields.acceleration[i]);
      });
    }
    const common::Vec3 v_flip = points.v[p] + dt * a_p;
    points.v[p] =
        pic_fraction == 0.0 ? v_flip : (1.0 - pic_fraction) * v_flip + pic_fraction * v_pic;
    // Grid positions: the end-of-step grid velocity, which the walls constrain (a point cannot
    // cross a held node plane within a CFL step); else the point's own (FLIP) velocity. With a
    // pic_velocity (XPIC's V*) the grid's own V, the field whose gradient deformed the material,
    // not V*.
    if (move_points && grid_positions && pic_velocity != nullptr) {
      common::Vec3 v_grid = common::Vec3::Zero();
      for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
        const auto i = static_cast<std::size_t>(node_i);
        v_grid += S * (fields.velocity[i] + dt * fields.acceleration[i]);
      });
      points.x[p] += dt * v_grid;
    } else if (move_points) {
      points.x[p] += dt * (grid_positions ? v_pic : points.v[p]);
    }
  });
}

void g2p_update_affine(const Grid& grid, const StencilCache& cache, const GridFields& fields,
                       double threshold, bool move_points, double dt, MaterialPoints& points) {
  const auto n = static_cast<std::int64_t>(points.size());
  for_each_index(n, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    common::Vec3 v_pic = common::Vec3::Zero();
    for_each_node(grid, cache, p, [&](std::int64_t node_i, double S, const common::Vec3&) {
      const auto i = static_cast<std::size_t>(node_i);
      v_pic += S * (fields.velocity[i] + dt * fields.acceleration[i]);
    });
    common::Mat3 C_p = common::Mat3::Zero();
    for_each_node(grid, cache, p, [&](std::int64_t node_i, double, const common::Vec3& grad) {
      const auto i = static_cast<std::size_t>(node_i);
      if ((fields.mass[i] > 0.0 && fields.mass[i] >= threshold) || fields.fixed[i] == 7) {
        C_p += (fields.velocity[i] + dt * fields.acceleration[i] - v_pic) * grad.transpose();
      }
    });
    points.v[p] = v_pic;
    points.C[p] = C_p;
    if (move_points) points.x[p] += dt * v_pic;
  });
}

}  // namespace mpm
