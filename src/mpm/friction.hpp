// Coulomb friction of a rigid wall on one grid node: the standard MPM frictional boundary, i.e.
// the contact algorithm of Bardenhagen et al. (2001, CMES 2(4):509-522) with a rigid body as the
// other side. docs/design/mpm.md, "Frictional boundaries and reactions".
#pragma once

#include <array>

#include "common/choice_table.hpp"
#include "common/types.hpp"

namespace mpm {

/// What a wall does along its normal.
enum class WallContact {
  fixed,           ///< the normal velocity is the wall's, pushing or pulling
  no_penetration,  ///< only approach is stopped: the node may separate from the wall
};
/// The job's names (mpm.velocity[].contact).
inline constexpr std::array<common::Named<WallContact>, 2> kWallContactNames{
    {{"fixed", WallContact::fixed}, {"no_penetration", WallContact::no_penetration}}};

/// A rigid wall with an axis-aligned normal. `side` is the side of the material the wall lies on
/// (-1: the wall is below the material along `axis`, like the grid face "z-"), so the unit normal
/// pointing from the wall into the material is n = -side e_axis.
struct WallFriction {
  int axis = 2;     ///< normal axis, 0..2
  int side = -1;    ///< -1 or +1
  double mu = 0.0;  ///< Coulomb coefficient [-], >= 0 (0: smooth)
  WallContact contact = WallContact::fixed;
};

/// Result of the friction law on one node.
struct WallCorrection {
  common::Vec3 velocity;    ///< corrected nodal velocity [m/s]
  bool in_contact = false;  ///< false: the node was left as it was (separating, no_penetration)
};

/// Applies the wall to a trial nodal velocity v_trial [m/s] given the wall velocity v_wall [m/s]:
/// with v = v_trial - v_wall, v_n = v . n and v_t = v - v_n n, the node is in contact when the
/// contact is fixed or v_n < 0 (approaching). In contact the normal correction is dv_n = -v_n
/// (the relative normal velocity becomes zero) and the tangential slip is reduced by
/// min(|v_t|, mu max(dv_n, 0)) along -v_t / |v_t|: Coulomb's |f_t| <= mu f_n on the impulse
/// m dv the wall applies, with no friction when the wall pulls (dv_n < 0, fixed contact only).
/// A large mu makes the wall rough (no slip while it pushes).
[[nodiscard]] WallCorrection apply_wall_friction(const common::Vec3& v_trial,
                                                 const common::Vec3& v_wall,
                                                 const WallFriction& wall);

}  // namespace mpm
