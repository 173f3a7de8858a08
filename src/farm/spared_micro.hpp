// farm::SparedMicro: a MicroModel decorator that spares an RVE whose accumulated strain increment
// since its last update is small: the stress is predicted with a tangent taken at that update,
// and the accumulated increment is handed to the inner model (the DEM) in one step when it passes
// the tolerance, after max_spared_steps, or at once where the prediction drifted (docs/design/sparing.md).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "common/param_table.hpp"
#include "dem/tangent.hpp"
#include "farm/micro_model.hpp"

namespace farm {

/// Guard bit of MicroReport::guards (above dem::RveGuard's bits): the step was spared, the
/// stress is the tangent's prediction and no DEM step ran.
inline constexpr std::uint32_t kGuardSpared = 1u << 16;

/// Version of SparedMicro's fields (spare/version; docs/reference/checkpoint.md).
inline constexpr std::int64_t kSparedStateVersion = 1;

/// How a spared step predicts the stress.
enum class SparingTangent : std::int64_t {
  contact = 0,  ///< the affine contact-stiffness tangent C (dem::contact_stiffness_tangent)
  scaled = 1,   ///< alpha C, alpha in [0, 1] fitted to the DEM's response at the last catch-up,
                ///< for increments that continue that one (E : E_fit >= 0); C on a reversal
};

/// [dem.sparing]. The member initializers are the job keys' defaults.
struct SparingOptions {
  double tolerance = 0.0;  ///< ||sym(sum L dt)|| (Frobenius) that triggers a DEM update [-]; 0: off
  std::int64_t max_spared_steps = 20;  ///< DEM update at the latest after this many spared steps
  double drift_tolerance = 0.02;       ///< |sigma_DEM - sigma_predicted| / max(p, pressure_floor)
                                  ///< at a DEM update above which the RVE's allowance halves [-]
  double pressure_floor = 1e3;  ///< floor of p in the drift measure [Pa]
  std::int64_t tangent = static_cast<std::int64_t>(SparingTangent::scaled);  ///< SparingTangent

  /// Throws common::InputError naming the job key of the first invalid entry.
  void validate() const;
};

inline constexpr auto kSparingOptions = common::make_table<SparingOptions>(
    "farm::SparingOptions", "dem.sparing",
    {{"tolerance", &SparingOptions::tolerance, common::Unit::Dimensionless, common::in_co(0, 1),
      common::Source::job_default,
      "Sparing of idle RVEs: an RVE whose strain increment accumulated since its last DEM update "
      "(Frobenius norm of the symmetric part of sum L dt) stays at or below this is not stepped; "
      "its stress is predicted with a tangent (docs/design/sparing.md). 0: off, every RVE is stepped "
      "every MPM step."},
     {"max_spared_steps", &SparingOptions::max_spared_steps, common::Unit::Dimensionless,
      common::in_cc(1, 1e6), common::Source::job_default,
      "Sparing: an RVE is brought up to date by the DEM after at most this many spared MPM "
      "steps."},
     {"drift_tolerance", &SparingOptions::drift_tolerance, common::Unit::Dimensionless,
      common::gt(0), common::Source::job_default,
      "Sparing: when the DEM's stress after spared steps differs from the prediction by more than "
      "this fraction of p (Frobenius norm), that RVE's own tolerance and maximum of spared steps "
      "halve (down to 1/64 of `tolerance` and 1 step); a good prediction doubles them back."},
     {"pressure_floor", &SparingOptions::pressure_floor, common::Unit::Pressure, common::gt(0),
      common::Source::cpp_only, "Floor of p in the drift measure (dem.coupling.pressure_floor)."},
     {"tangent", &SparingOptions::tangent, common::Unit::Dimensionless, common::in_cc(0, 1),
      common::Source::cpp_only, "SparingTangent: 0 contact stiffness, 1 scaled (default)."}});

/// The tangent of an inner model's current state (e.g. dem::contact_stiffness_tangent of a
/// DemMicro's simulation) [Pa].
using TangentFn = std::function<dem::Tangent(const MicroModel&)>;

class SparedMicro final : public MicroModel {
 public:
  /// @pre inner != nullptr, options valid, tangent callable on inner
  SparedMicro(std::unique_ptr<MicroModel> inner, const SparingOptions& options, TangentFn tangent);

  /// Spares the step (predicted stress, report with kGuardSpared, dem_steps 0) or steps the
  /// inner model with the accumulated increment: inner.step(L, dt) itself when nothing was
  /// spared (bit for bit the undecorated model), else inner.step(G / T, T) with G = sum L dt and
  /// T = sum dt.
  MicroReport step(const common::Mat3& L, double dt) override;
  /// The prediction while spared, else the inner model's stress [Pa].
  [[nodiscard]] common::Mat3 stress() const override;
  [[nodiscard]] MicroReport report() const override;
  [[nodiscard]] MicroMeasures measures() const override { return inner_->measures(); }
  /// The inner model's view: the grains as of its last DEM update (a spared step moves no grain;
  /// the cell's stress there is the DEM's, not the tangent's prediction).
  [[nodiscard]] std::vector<ViewFile> grain_view(const std::string& stem) const override {
    return inner_->grain_view(stem);
  }
  /// The inner model's fields and spare/* (docs/reference/checkpoint.md).
  void save(common::StateWriter& writer) const override;
  [[nodiscard]] double cost_estimate() const override { return inner_->cost_estimate(); }
  [[nodiscard]] double wave_speed() const override { return inner_->wave_speed(); }
  /// The wrapped model's state as of its last DEM step (kept: a spared step leaves it as it is,
  /// and the farm asks every step).
  [[nodiscard]] bool dilute() const override { return dilute_; }

  /// Rebuilds a SparedMicro around inner_load(reader) with the spare/* fields of the reader
  /// (options from the caller: a restart may change them).
  static std::unique_ptr<MicroModel> load(const common::StateReader& reader,
                                          std::unique_ptr<MicroModel> inner,
                                          const SparingOptions& options, TangentFn tangent);

  [[nodiscard]] const MicroModel& inner() const { return *inner_; }
  [[nodiscard]] std::int64_t spared_now() const { return n_spared_; }  ///< pending spared steps
  [[nodiscard]] double allowance() const { return allowance_; }        ///< current tolerance [-]
  [[nodiscard]] std::int64_t cap() const { return cap_; }  ///< current max_spared_steps [-]
  [[nodiscard]] double alpha() const { return alpha_; }    ///< scale of the tangent [-]
  /// Relative error |sigma_DEM - sigma_pred| / max(p, floor) of the last update after spared
  /// steps; -1 before any [-].
  [[nodiscard]] double last_drift() const { return last_drift_; }

 private:
  /// Q (sigma0 + a C : sym(g)) Q^T, Q the rotation of g, a = 1 (contact, or a reversal of the
  /// increment alpha was fitted on) or alpha (scaled).
  [[nodiscard]] common::Mat3 predict(const common::Mat3& sigma0, const common::Mat3& g) const;
  void after_update(const common::Mat3& g_applied, const common::Mat3& sigma_before,
                    bool had_spared);

  std::unique_ptr<MicroModel> inner_;
  SparingOptions options_;
  TangentFn tangent_fn_;
  // State (saved): the accumulated increment since the last update, its duration and count, the
  // stress and report of the last update, its tangent (computed on the first spared step), the
  // RVE's allowance, the tangent's scale and the last drift.
  common::Mat3 g_acc_ = common::Mat3::Zero();
  double dt_acc_ = 0.0;
  std::int64_t n_spared_ = 0;
  MicroReport base_;  ///< report of the last update (p, q, e, Z, guards)
  dem::Tangent c_ = dem::Tangent::Zero();
  bool have_c_ = false;
  double allowance_ = 0.0;
  std::int64_t cap_ = 1;  ///< the RVE's own max_spared_steps, halved and doubled with allowance_
  double alpha_ = 1.0;
  common::Mat3 e_fit_ = common::Mat3::Zero();  ///< strain increment alpha was fitted on [-]
  double last_drift_ = -1.0;
  common::Mat3 sigma_ = common::Mat3::Zero();  ///< the prediction while spared (not saved)
  bool dilute_ = false;                        ///< inner_->dilute() since its last step (not saved)
};

/// Which models a kind spares (e.g. the DEM ones: is_dem_micro).
using SparePredicate = std::function<bool(const MicroModel&)>;

/// A MicroKind whose models for which `spare` holds are wrapped in SparedMicro when
/// options.tolerance > 0 (created, or loaded from a state without spare/* fields); with
/// tolerance 0 `inner` unchanged, except that a state with spare/* fields (a checkpoint written
/// with sparing on) loads as a SparedMicro that hands its pending increment to the inner model
/// at its next step and spares nothing after.
[[nodiscard]] MicroKind spared_kind(MicroKind inner, const SparingOptions& options,
                                    SparePredicate spare, TangentFn tangent);

/// Whether m is a DemMicro.
[[nodiscard]] bool is_dem_micro(const MicroModel& m);

/// The TangentFn of a DemMicro: dem::contact_stiffness_tangent of its simulation (zero for any
/// other model).
[[nodiscard]] dem::Tangent dem_micro_tangent(const MicroModel& m);

}  // namespace farm
