// Point <-> grid transfers as free functions over the SoA: stencils, binning, P2G (eqs. 5-7),
// G2P of the velocity gradient and the NFLIP/PIC point update (eqs. 9-10).
// Determinism: points are binned by stencil base node; P2G runs over bins in colour order.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "common/choice_table.hpp"
#include "mpm/grid.hpp"
#include "mpm/material_points.hpp"
#include "mpm/parallel.hpp"
#include "mpm/shape_function.hpp"

namespace mpm {

/// How velocities go between points and grid (docs/design/mpm.md, "Transfers").
enum class Transfer {
  flip,  ///< v_p blended FLIP/PIC (eqs. 9-10, SolverConfig::flip); P2G of m_p v_p
  /// Affine PIC (Jiang et al. 2015): each point also carries C_p, the grid's velocity gradient at
  /// it, and P2G sends m_p (v_p + C_p (x_v - x_p)): an affine velocity field goes through a
  /// G2P-P2G round trip exactly, even with one point per cell (FLIP/PIC then loses it: a cell's
  /// 8 nodes get the one point's velocity)
  apic,
};
/// The job's names of the transfers (mpm.transfer).
inline constexpr std::array<common::Named<Transfer>, 2> kTransferNames{
    {{"flip", Transfer::flip}, {"apic", Transfer::apic}}};
[[nodiscard]] Transfer transfer_from_string(std::string_view name);  ///< "flip" | "apic"

/// PIC share of a FLIP/PIC step of length dt [s]: 1 - exp(-dt / pic_time) when pic_time > 0 (a
/// relaxation in time: n steps of dt leave exp(-n dt / pic_time) of the FLIP part, whatever dt),
/// else 1 - flip (a share per step).
[[nodiscard]] double pic_share(double flip, double pic_time, double dt);
[[nodiscard]] std::string_view to_string(Transfer t);

/// Per-step cache of each point's 1D weights (positions do not change between P2G and G2P).
struct StencilCache {
  std::array<int, 3> width{2, 2, 2};     ///< nodes per axis (the thickness of plane strain: 2)
  std::vector<std::array<int, 3>> base;  ///< stencil base node (i, j, k) per point
  std::vector<double> w;                 ///< S, [(p * 3 + axis) * 3 + a] [-]
  std::vector<double> dw;                ///< dS/dx, same layout [1/m]
};

/// Calls f(node_i, S, grad S) for the width[0] x width[1] x width[2] nodes of point p (the
/// cache's weights; node_i the grid's linear node index).
template <class Fn>
inline void for_each_node(const Grid& grid, const StencilCache& c, std::size_t p, Fn&& f) {
  const std::array<int, 3> ns = c.width;
  const std::array<int, 3>& b = c.base[p];
  const double* w = &c.w[p * 9];
  const double* dw = &c.dw[p * 9];
  for (int k = 0; k < ns[2]; ++k) {
    for (int j = 0; j < ns[1]; ++j) {
      const double wyz = w[3 + j] * w[6 + k];
      for (int i = 0; i < ns[0]; ++i) {
        const std::int64_t node_i = grid.node_index(b[0] + i, b[1] + j, b[2] + k);
        const double S = w[i] * wyz;
        const common::Vec3 grad(dw[i] * wyz, w[i] * dw[3 + j] * w[6 + k],
                                w[i] * w[3 + j] * dw[6 + k]);
        f(node_i, S, grad);
      }
    }
  }
}

/// Points sorted by stencil base node (stable: ties keep slot order), grouped into bins, bins
/// grouped into width[0] width[1] width[2] colours. Two bins of one colour touch disjoint nodes.
struct PointBins {
  std::vector<std::int64_t> order;                   ///< point slots, sorted by bin
  std::vector<std::int64_t> offset;                  ///< bin b: order[offset[b] .. offset[b+1])
  std::vector<std::int64_t> key;                     ///< base node index of bin b (ascending)
  std::vector<std::vector<std::int64_t>> by_colour;  ///< bins of each colour, ascending
  std::vector<std::int64_t> scratch;                 ///< dense per-node counter, kept all -1
};

/// Runs kernel(p) for every point, colour by colour; bins of one colour in parallel. One
/// parallel region per call; small problems run a plain loop in the same order, without a region
/// (parallel.hpp: a region with a false if-clause still costs ~10 us here).
template <class Fn>
inline void for_points_coloured(const PointBins& bins, Fn&& kernel) {
  const bool parallel = static_cast<std::int64_t>(bins.order.size()) >= kMinParallelPoints;
  if (!parallel) {
    for (const std::vector<std::int64_t>& colour : bins.by_colour) {
      for (const std::int64_t b : colour) {
        const auto bu = static_cast<std::size_t>(b);
        for (std::int64_t o = bins.offset[bu]; o < bins.offset[bu + 1]; ++o) {
          kernel(static_cast<std::size_t>(bins.order[static_cast<std::size_t>(o)]));
        }
      }
    }
    return;
  }
#pragma omp parallel
  for (const std::vector<std::int64_t>& colour : bins.by_colour) {
    const auto nb = static_cast<std::int64_t>(colour.size());
#pragma omp for schedule(static)
    for (std::int64_t q = 0; q < nb; ++q) {
      const auto b = static_cast<std::size_t>(colour[static_cast<std::size_t>(q)]);
      for (std::int64_t o = bins.offset[b]; o < bins.offset[b + 1]; ++o) {
        kernel(static_cast<std::size_t>(bins.order[static_cast<std::size_t>(o)]));
      }
    }
  }
}

/// Fills `cache` for every point. Returns the smallest slot whose stencil leaves the grid or
/// whose position is not finite, or -1 when all are inside. uGIMP uses half_width0 / h.
/// `linear_axis` (0-2, or -1 for none) uses the linear shape along that axis whatever `kind`:
/// the thickness of plane strain, whose one-cell grid has 2 node planes.
std::int64_t compute_stencils(ShapeKind kind, const Grid& grid, const MaterialPoints& points,
                              StencilCache& cache, int linear_axis = -1);

/// Throws common::InputError naming the point when `kind` cannot serve it: uGIMP needs
/// half-widths <= spacing / 2, and a domain clear of the grid's boundary (one that reaches it has
/// a stencil node beyond it as soon as its point moves outward: refused when the solver is built,
/// with the remedy, not at step 1). Not along `linear_axis`, where the shape is linear.
void check_shape_domains(ShapeKind kind, const Grid& grid, const MaterialPoints& points,
                         int linear_axis = -1);

/// Sorts points into bins and colours (counting sort; cost O(points + bins)).
void bin_points(const Grid& grid, const StencilCache& cache, PointBins& bins);

/// Clears the previous step's nodes and marks every node of every non-empty bin active.
void activate_nodes(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                    GridFields& fields);

/// Eq. 7 and the gravity part of eq. 6: m_v += m_p S, momentum_v += m_p S v_p,
/// force_v += m_p S g. Bit-for-bit independent of the number of threads.
/// `affine` (Transfer::apic): momentum_v += m_p S (v_p + C_p (x_v - x_p)).
void p2g_mass_momentum(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                       const MaterialPoints& points, const common::Vec3& gravity,
                       GridFields& fields, bool affine = false);

/// Re-projects momentum only (MUSL's second transfer): momentum_v = sum_p m_p S v_p (with
/// `affine`, v_p + C_p (x_v - x_p)).
void p2g_momentum(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                  const MaterialPoints& points, GridFields& fields, bool affine = false);

/// Eq. 5 with the point integration of classical MPM / GIMP: force_v -= V_p sigma_p grad S_v.
void p2g_internal_force(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                        const MaterialPoints& points, GridFields& fields);

/// L_p = sum_v (V_v - v_p) (x) grad S_v(x_p) over the nodes with m_v >= threshold [kg] or a
/// fully prescribed velocity
/// (eq. 3 in difference form: equal to it where every stencil node holds mass, since the
/// gradients sum to zero). Nodes without mass are left out instead of counting with V = 0,
/// which would strain a point sitting on the material's edge (e.g. exactly on a node plane,
/// where the empty neighbour still has a non-zero gradient): a rigid translation stays
/// strain-free.
void g2p_velocity_gradient(const Grid& grid, const StencilCache& cache, const GridFields& fields,
                           double threshold, MaterialPoints& points);

/// Eqs. 9-10 blended with PIC: a_p = sum_v S a_v; v_flip = v_p + dt a_p;
/// v_pic = sum_v S (V_v + dt a_v); v_p <- (1 - pic) v_flip + pic v_pic; x_p <- x_p + dt v_p
/// (only when `move_points`: otherwise the points keep their positions, see SolverConfig).
/// `grid_positions`: x_p <- x_p + dt v_pic instead (the walls' held nodes then stop the points:
/// a FLIP velocity does not see them and can carry a point through a rigid base).
/// `wall_impulse`: a_v also counts the walls' momentum-stage correction, a_v + wall_dv_v / dt,
/// in the FLIP increment (not in v_pic, whose V_v already has it): v_flip then changes by
/// sum_v S (V_v(t + dt) - V_v projected), and a point's velocity into a wall is taken away
/// (SolverConfig::wall_impulse_on_points).
/// `pic_velocity` (sized to the grid): the V_v of v_pic instead of fields.velocity, e.g. XPIC's
/// V* (xpic.hpp); the FLIP increment is unchanged, and `grid_positions` still moves the points
/// with the grid's own sum_v S (V_v + dt a_v).
void g2p_update(const Grid& grid, const StencilCache& cache, const GridFields& fields,
                double pic_fraction, bool move_points, double dt, MaterialPoints& points,
                bool grid_positions = false, bool wall_impulse = false,
                const std::vector<common::Vec3>* pic_velocity = nullptr);

/// The APIC point update: v_p <- sum_v S V'_v and C_p <- sum_v (V'_v - v_p) (x) grad S_v(x_p)
/// with V'_v = V_v + dt a_v the end-of-step grid velocity, over the nodes that count in
/// g2p_velocity_gradient (mass >= threshold, or a fully prescribed velocity; the difference form
/// keeps a rigid translation free of C); x_p <- x_p + dt v_p when `move_points` (the PIC velocity
/// is the grid's, so a held node plane holds the points too).
void g2p_update_affine(const Grid& grid, const StencilCache& cache, const GridFields& fields,
                       double threshold, bool move_points, double dt, MaterialPoints& points);

}  // namespace mpm
