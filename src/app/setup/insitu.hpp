// In-situ initial states of the DEM points (issue 15): each point's target stress (the prepared
// sample's, a constant tensor, or geostatic from gravity, density and K0), a pressure floor, the
// grouping of points whose targets agree (one preparation per group and sample) and the pool of
// independently generated samples. docs/design/dem.md, "In-situ initial states".
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/choice_table.hpp"
#include "common/types.hpp"

namespace app {

class Job;

/// Cross-key rules of the in-situ keys (schema_insitu.cpp): one message per broken rule.
[[nodiscard]] std::vector<std::string> check_insitu_rules(const Job& job);

/// The initial state of a body's points (mpm.body[].initial_state; absent: prepared).
enum class InitialState {
  prepared,   ///< dem: every RVE a copy of the isotropic prepared sample
  uniform,    ///< dem: the RVEs' target is initial_stress
  geostatic,  ///< from gravity, density and k0
};
/// The job's names (mpm.body[].initial_state).
inline constexpr std::array<common::Named<InitialState>, 3> kInitialStateNames{
    {{"prepared", InitialState::prepared},
     {"uniform", InitialState::uniform},
     {"geostatic", InitialState::geostatic}}};

/// How a point draws its sample from the pool (dem.initial_state.sample_draw).
enum class SampleDraw {
  in_turn,    ///< id mod samples: on a row of points whose length is a multiple of samples, one
              ///< sample per vertical line of points
  scattered,  ///< a hash of (id, dem.sample.seed) mod samples: no pattern in space
};
/// The job's names (dem.initial_state.sample_draw).
inline constexpr std::array<common::Named<SampleDraw>, 2> kSampleDrawNames{
    {{"in_turn", SampleDraw::in_turn}, {"scattered", SampleDraw::scattered}}};

/// [dem.initial_state]: the knobs shared by every DEM body (defaults: the job defaults).
struct InsituOptions {
  double pressure_floor = 1e3;     ///< targets with p below this are scaled up to it [Pa], > 0
  double group_tolerance = 0.02;   ///< targets within this x max(p, floor) per component share
                                   ///< one preparation [-], >= 0
  double stress_tolerance = 0.01;  ///< servo tolerance (dem::stress_reached) [-]
  std::int64_t samples = 1;        ///< pool of independently generated samples [-], >= 1
  SampleDraw draw = SampleDraw::in_turn;  ///< how a point draws its sample
  std::int64_t draw_seed = 0;             ///< scattered: the hash's seed (dem.sample.seed)
};

/// Geostatic stress at `depth` below the free surface: sigma_v = -rho |g| depth along gravity,
/// sigma_h = k0 sigma_v across it (tension positive). @param rho bulk density [kg/m^3]
/// @param gravity [m/s^2], non-zero @param k0 [-] @param depth [m] @return Cauchy stress [Pa]
[[nodiscard]] common::Mat3 geostatic_stress(double rho, const common::Vec3& gravity, double k0,
                                            double depth);

/// Depth of x below the surface level `surface` along gravity: surface - x . (-g / |g|) [m].
[[nodiscard]] double depth_below(const common::Vec3& x, const common::Vec3& gravity,
                                 double surface);

/// Scales `target` up to p = floor when its p = -tr / 3 is below the floor (p must be > 0).
/// Returns true when it was floored.
bool apply_pressure_floor(common::Mat3& target, double floor);

/// Points whose targets agree, prepared once. Deterministic: targets are visited in ascending
/// (p, xx, yy, zz, yz, xz, xy, index) order; a target joins the last group made when every
/// component is within tolerance x max(p_rep, floor) of its representative (the group's first
/// target), else it starts a new group.
struct Grouping {
  std::vector<std::int32_t> group_of;  ///< group of each target, in input order
  std::vector<common::Mat3> target;    ///< representative target of each group [Pa]
  std::vector<std::int64_t> count;     ///< targets per group
};
[[nodiscard]] Grouping group_targets(const std::vector<common::Mat3>& targets, double tolerance,
                                     double floor);

/// Sample of the pool a point draws its RVE from: id mod samples.
[[nodiscard]] inline std::int64_t sample_of(std::int64_t id, std::int64_t samples) {
  return ((id % samples) + samples) % samples;
}

/// Sample of the pool point `id` draws as `o` says: in turn, id mod samples; scattered,
/// splitmix64(splitmix64(id) ^ draw_seed) mod samples. A pure function of the id and the options,
/// so the same on every rank and after a restart.
[[nodiscard]] std::int64_t sample_of(std::int64_t id, const InsituOptions& o);

struct MpmSetup;

/// The in-situ plan of a job: the target and preparation group of every DEM point. Built the
/// same on every rank (a pure function of the job and the points).
struct InsituPlan {
  InsituOptions options;
  std::vector<std::int64_t> ids;     ///< DEM point ids, ascending
  std::vector<std::int32_t> group;   ///< per id: group index; -1: the prepared sample as it is
  std::vector<common::Mat3> target;  ///< per id: target after the floor (prepared: zero) [Pa]
  Grouping groups;                   ///< of the points with a target
  std::int64_t floored = 0;          ///< targets scaled up to the pressure floor
  /// Group of DEM point `id` (-1: prepared). Throws InternalError for an id not in the plan.
  [[nodiscard]] std::int32_t group_of(std::int64_t id) const;
  /// Distinct (group, sample) pairs of the points: the preparations the run needs.
  [[nodiscard]] std::int64_t preparations() const;
};

/// The plan of the DEM points of `setup` (targets from each body's initial_state, the floor, the
/// grouping). Throws common::InputError naming the key of a body whose targets cannot be made.
[[nodiscard]] InsituPlan insitu_plan(const Job& job, const MpmSetup& setup);

/// The geostatic initial stress of every continuum (material = "elastic") point whose body has
/// initial_state = "geostatic", by point id [Pa]. Throws common::InputError as insitu_plan does.
[[nodiscard]] std::map<std::int64_t, common::Mat3> continuum_initial_stress(const Job& job,
                                                                            const MpmSetup& setup);

/// One line per target: "xx, yy, zz, yz, xz, xy" in kPa (logs).
[[nodiscard]] std::string stress_text(const common::Mat3& s);

}  // namespace app
