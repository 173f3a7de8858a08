// Boundary conditions on the grid: velocity constraints on node sets (e.g. the moving top platen,
// Duverger et al. 2022 eq. 13) and pressures/tractions on the material's current faces (the
// 100 kPa confinement of section 3), turned into nodal forces (eq. 6, f^trac).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/choice_table.hpp"
#include "mpm/friction.hpp"
#include "mpm/grid.hpp"
#include "mpm/material_points.hpp"
#include "mpm/shape_function.hpp"

namespace mpm {

/// A face of an axis-aligned box (the grid, the material): its normal axis and side, in the order
/// axis-major, lower side first (axis_of, side_of).
enum class Face { x_lower, x_upper, y_lower, y_upper, z_lower, z_upper };
/// The job's names (mpm.velocity[].face and .normal, mpm.traction[].face).
inline constexpr std::array<common::Named<Face>, 6> kFaceNames{{{"x-", Face::x_lower},
                                                                {"x+", Face::x_upper},
                                                                {"y-", Face::y_lower},
                                                                {"y+", Face::y_upper},
                                                                {"z-", Face::z_lower},
                                                                {"z+", Face::z_upper}}};
/// Normal axis of face f, 0..2.
[[nodiscard]] constexpr int axis_of(Face f) { return static_cast<int>(f) / 2; }
/// Side of face f: -1 at the lowest coordinate along its axis, +1 at the highest.
[[nodiscard]] constexpr int side_of(Face f) { return static_cast<int>(f) % 2 == 0 ? -1 : 1; }

/// Prescribed velocity components on the nodes whose position lies in the box [lo, hi]
/// (tolerance 1e-9 cell). Applied to the nodal velocity before the velocity gradient is taken,
/// and to the nodal acceleration before G2P (a = (V(t + dt) - V(t)) / dt, zero for a constant
/// velocity), so the points next to these nodes follow them.
struct VelocityConstraint {
  common::Vec3 lo;                               ///< box lower corner [m]
  common::Vec3 hi;                               ///< box upper corner [m]
  std::array<bool, 3> fixed{};                   ///< which components are prescribed
  common::Vec3 velocity = common::Vec3::Zero();  ///< prescribed velocity [m/s]
  /// Optional: velocity as a function of the node position [m] and time [s]; replaces
  /// `velocity` when set (e.g. a rigid rotation field for verification).
  std::function<common::Vec3(const common::Vec3&, double)> field;
  /// Optional antisymmetric (mirror) condition for non-interpolating shapes (B-splines): when
  /// mirror_axis is 0..2, a selected node at distance d beyond the plane x[mirror_axis] =
  /// mirror_plane [m] (which must be a node plane) gets 2 V - V(mirror node), the node on the
  /// plane gets V, for the prescribed components (same for accelerations). The interpolated
  /// velocity on the plane is then exactly V.
  int mirror_axis = -1;
  double mirror_plane = 0.0;  ///< [m]
  /// Optional frictional wall (docs/design/mpm.md, "Frictional boundaries and reactions"): when
  /// wall.axis is 0..2 (see has_wall), the nodes are on a rigid wall moving at `velocity` (all
  /// three components; `fixed` is not used) with Coulomb friction (apply_wall_friction).
  /// No mirror.
  WallFriction wall{-1, -1, 0.0, WallContact::fixed};
  /// Active for from <= t < until, t the start time of a step [s] (defaults: always). An
  /// inactive constraint leaves its nodes free (e.g. a gate removed at `until`).
  double from = -std::numeric_limits<double>::infinity();
  double until = std::numeric_limits<double>::infinity();
  std::string name{};  ///< name in the outputs; empty: "constraint_<k>" (k: add_constraint order)

  [[nodiscard]] bool has_wall() const { return wall.axis >= 0; }
  [[nodiscard]] bool active_at(double t) const { return from <= t && t < until; }
  [[nodiscard]] bool has_window() const {
    return from > -std::numeric_limits<double>::infinity() ||
           until < std::numeric_limits<double>::infinity();
  }
};

/// The grid's boundary node plane on one side: a box selecting those nodes.
/// axis in {0, 1, 2}, side -1 (lower) or +1 (upper).
VelocityConstraint face_constraint(const Grid& grid, int axis, int side, std::array<bool, 3> fixed,
                                   const common::Vec3& velocity = common::Vec3::Zero());
/// One grid node at `node` [m] (a box of +/- spacing / 4 around it).
VelocityConstraint node_constraint(const Grid& grid, const common::Vec3& node,
                                   std::array<bool, 3> fixed,
                                   const common::Vec3& velocity = common::Vec3::Zero());

/// A constraint with its node list resolved (sorted), built once by the solver.
struct ResolvedConstraint {
  VelocityConstraint spec;
  std::vector<std::int64_t> nodes;
  std::vector<std::int64_t> mirror;  ///< mirror node per node (-1: on the plane); mirror only
};
ResolvedConstraint resolve(const Grid& grid, const VelocityConstraint& c);

/// Sets the prescribed components of the active constrained nodes' velocity at time t [s], for
/// the constraints active at t. A wall applies its friction law to the projected velocity
/// V(t) (Bardenhagen's momentum-stage correction) and flags its normal component as prescribed
/// where the node is in contact; the correction V_corrected - V_projected is added to
/// `fields.wall_dv`.
void apply_velocity_constraints(const Grid& grid, const std::vector<ResolvedConstraint>& cs,
                                double t, GridFields& fields);
/// Sets the prescribed components of the active constrained nodes' acceleration:
/// (V(t + dt) - V(t)) / dt [m/s^2], for the constraints active at t. A wall applies its friction
/// law to the trial velocity V(t) + a dt and sets a = (v_corrected - V(t)) / dt.
/// When `reactions` is given it is resized to cs.size() and holds, per constraint, the force it
/// exerts on the material sum_i m_i (a_i after - a_i before) [N] over its nodes, constraints
/// applied in order (a node in several constraints counts in each for what that one changed).
void apply_acceleration_constraints(const Grid& grid, const std::vector<ResolvedConstraint>& cs,
                                    double t, double dt, GridFields& fields,
                                    std::vector<common::Vec3>* reactions = nullptr);
/// The velocity a constraint prescribes at time t [s], for its displacement: `velocity`, or the
/// field at the centre of its box; plain constraints: zero on the free components [m/s].
[[nodiscard]] common::Vec3 prescribed_velocity(const VelocityConstraint& c, double t);

/// A load on one face of the material: pressure and/or traction over the face's CURRENT area.
/// The face is made of the facets of the points whose initial domain touched the material's
/// initial bounding face (normal `axis`, `side`); each facet is carried by its point and deforms
/// with it (Nanson: a_p = J_p F_p^-T N A0_p), so a pressure stays a pressure on the deformed
/// face, whatever the points' drift inside the grid (docs/design/mpm.md, "Tractions").
struct TractionLoad {
  int axis = 0;           ///< normal axis of the face, 0..2
  int side = -1;          ///< -1: the face at the material's lowest coordinate, +1 the highest
  double pressure = 0.0;  ///< [Pa], positive pushes into the material (force -p a)
  common::Vec3 traction = common::Vec3::Zero();  ///< additional traction vector [Pa] (times |a|)
};

/// Axis-aligned box of the material's current domains: each point spans x_p +- e_p with
/// e_p,d = sum_k |F_dk| hw0_k (the bounding box of its deformed parallelepiped).
struct MaterialExtent {
  common::Vec3 lo;  ///< [m]
  common::Vec3 hi;  ///< [m]
};
MaterialExtent material_extent(const MaterialPoints& points);

/// Slots of the points whose domain face lies on the bounding face (axis, side) of the
/// material's current extent (within 1e-6 of the smallest half-width). Call on the initial state.
std::vector<std::int64_t> face_points(const MaterialPoints& points, int axis, int side);

/// Adds the nodal forces of one load carried by the facets of `facet_points` (slots): facet
/// force f_p = -p a_p + t |a_p|, spread over its 2 x 2 Gauss points on the deformed facet with
/// the grid basis (linear hat for linear and uGIMP, the B-spline for bspline2), positions clipped
/// to the grid, each Gauss point's weights renormalised over the active nodes, so the nodal
/// forces sum exactly to sum_p f_p. A Gauss point that touches no active node (a facet deformed
/// far from its point) gives its share to the nodes of the point's own position; throws
/// common::NumericalError if those are not active either. Returns the current loaded area
/// sum_p |a_p| [m^2]. `reference_geometry` (total Lagrangian, the grid being the reference
/// configuration): the Gauss points lie on the facet's initial position (the force is still
/// Nanson's, on the deformed area).
double apply_traction(const Grid& grid, ShapeKind kind, const TractionLoad& load,
                      const MaterialPoints& points, const std::vector<std::int64_t>& facet_points,
                      GridFields& fields, bool reference_geometry = false);

}  // namespace mpm
