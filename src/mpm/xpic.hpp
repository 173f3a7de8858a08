// XPIC(m), the extended PIC update of Hammerquist & Nairn (2017): the PIC share of a point update
// takes the grid velocity V* = sum_{k=1..m} (-1)^(k+1) C(m, k) Q^(k-1) V instead of V, where
// Q = S+ S is the grid -> points -> grid round trip of PIC (mass-weighted). On the points this is
// (I - (I - P)^m) v_p with P = S S+ the PIC round trip: a mode that P keeps to a factor lambda
// (a smooth one, lambda near 1) is kept to 1 - (1 - lambda)^m, a mode in P's null space (the
// sub-cell noise FLIP carries) is removed as by PIC. m = 1 is PIC.
// docs/design/mpm.md, "Transfers" (XPIC).
#pragma once

#include <vector>

#include "mpm/grid.hpp"
#include "mpm/material_points.hpp"
#include "mpm/transfers.hpp"

namespace mpm {

/// Per-step work arrays of xpic_velocity (kept between steps to avoid reallocations).
struct XpicScratch {
  std::vector<common::Vec3> w;        ///< Q^(k-1) V on the grid [m/s]
  std::vector<common::Vec3> sum;      ///< sum_p m_p S w_p [kg m/s]
  std::vector<double> weight;         ///< sum_p m_p S [kg]
  std::vector<common::Vec3> w_point;  ///< S w at each point [m/s]
};

/// V* of order `order` (>= 1) on the active nodes of `fields`, from their start-of-step velocity
/// V (fields.velocity, with its constraints applied), into `v_star` (sized to the grid; inactive
/// nodes untouched). Each iterate Q w keeps the components that fields.fixed prescribes at V's
/// value (the coefficients sum to 1, so V* keeps them too) and is zero at nodes below
/// `threshold` [kg] (as compute_nodal_velocity). Costs order - 1 G2P + P2G passes over the
/// points; the P2G runs in colour order: the same bits on any number of threads.
void xpic_velocity(const Grid& grid, const StencilCache& cache, const PointBins& bins,
                   const MaterialPoints& points, const GridFields& fields, double threshold,
                   int order, XpicScratch& scratch, std::vector<common::Vec3>& v_star);

}  // namespace mpm
