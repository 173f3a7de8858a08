// SparedMicro: sparing of idle RVEs with a tangent prediction and error control (see header and
// docs/design/sparing.md).
#include "farm/spared_micro.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "dem/rve.hpp"
#include "farm/dem_micro.hpp"

namespace farm {

using common::Mat3;

namespace {

/// Smallest allowance, as a fraction of the tolerance: 6 halvings.
constexpr double kMinAllowance = 1.0 / 64.0;

Mat3 sym(const Mat3& g) { return 0.5 * (g + g.transpose()); }

/// Rotation of an increment g: the Cayley transform of its skew part, exactly orthogonal and
/// second-order accurate (the Hughes-Winget rotation of common/tensor.hpp over one step).
Mat3 rotation(const Mat3& g) {
  const Mat3 w = 0.5 * (g - g.transpose());
  const Mat3 i = Mat3::Identity();
  return (i - 0.5 * w).inverse() * (i + 0.5 * w);
}

std::vector<double> nine(const Mat3& m) {
  std::vector<double> v(9);
  common::to_row_major(m, std::span<double, 9>(v.data(), 9));
  return v;
}

/// A field of finite numbers (a NaN would pass every comparison that decides whether to step
/// the RVE).
std::vector<double> read_finite(const common::StateReader& r, const char* name) {
  std::vector<double> v = r.read_f64(name);
  common::require_finite(v, std::string("spared micro state: field '") + name + "'");
  return v;
}
double read_finite_scalar(const common::StateReader& r, const char* name) {
  const std::vector<double> v = read_finite(r, name);
  if (v.size() != 1) {
    throw common::InputError(std::string("spared micro state: field '") + name +
                             "' must hold 1 value, has " + std::to_string(v.size()));
  }
  return v[0];
}

Mat3 read_nine(const common::StateReader& r, const char* name) {
  const std::vector<double> v = read_finite(r, name);
  if (v.size() != 9) {
    throw common::InputError(std::string("spared micro state: field '") + name +
                             "' must hold 9 values, has " + std::to_string(v.size()));
  }
  return common::row_major(v.data());
}

}  // namespace

void SparingOptions::validate() const { common::check_ranges(kSparingOptions, *this); }

SparedMicro::SparedMicro(std::unique_ptr<MicroModel> inner, const SparingOptions& options,
                         TangentFn tangent)
    : inner_(std::move(inner)), options_(options), tangent_fn_(std::move(tangent)) {
  MPMXDEM_CHECK(inner_ != nullptr, "SparedMicro: no inner model");
  options_.validate();
  base_ = inner_->report();
  dilute_ = inner_->dilute();
  allowance_ = options_.tolerance;
  cap_ = options_.max_spared_steps;
}

Mat3 SparedMicro::predict(const Mat3& sigma0, const Mat3& g) const {
  const Mat3 e = sym(g);
  // The fitted scale holds while the loading goes on; a reversal unloads elastically, which the
  // (stiffer) contact tangent describes better (measured: docs/design/sparing.md).
  const bool scaled = options_.tangent == static_cast<std::int64_t>(SparingTangent::scaled) &&
                      (e.array() * e_fit_.array()).sum() >= 0.0;
  const Mat3 q = rotation(g);
  return q * (sigma0 + (scaled ? alpha_ : 1.0) * dem::apply_tangent(c_, e)) * q.transpose();
}

MicroReport SparedMicro::step(const Mat3& L, double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (options_.tolerance > 0.0 && n_spared_ < cap_ && L.allFinite() && dt >= 0.0) {
    const Mat3 g = g_acc_ + L * dt;
    if (sym(g).norm() <= allowance_) {
      if (!have_c_) {
        c_ = tangent_fn_(*inner_);  // of the state of the last update: the inner is untouched
        have_c_ = true;
      }
      g_acc_ = g;
      dt_acc_ += dt;
      ++n_spared_;
      sigma_ = predict(inner_->stress(), g_acc_);
      MicroReport r = report();
      r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return r;
    }
  }
  const Mat3 sigma_before = inner_->stress();
  const bool had_spared = n_spared_ > 0;
  MicroReport r;
  Mat3 g_applied;
  if (!had_spared) {
    g_applied = L * dt;
    r = inner_->step(L, dt);  // exactly the undecorated call
  } else {
    g_applied = g_acc_ + L * dt;
    const double t = dt_acc_ + dt;
    // The DEM needs only the increment G (its T_p follows from G, eq. 11): it gets (G / t) t,
    // which is G to the last bit, deterministically.
    r = inner_->step(t > 0.0 ? Mat3(g_applied / t) : Mat3::Zero(), t > 0.0 ? t : 0.0);
  }
  after_update(g_applied, sigma_before, had_spared);
  base_ = r;
  dilute_ = inner_->dilute();
  return r;
}

void SparedMicro::after_update(const Mat3& g, const Mat3& sigma_before, bool had_spared) {
  if (had_spared) {
    const Mat3 sigma = inner_->stress();
    const double p = std::max(common::pressure(sigma), options_.pressure_floor);
    last_drift_ = (sigma - predict(sigma_before, g)).norm() / p;
    const double tol = options_.tolerance;
    // A drifting prediction shortens both the strain and the time it may run: an RVE that keeps
    // straining below the tolerance but not as predicted (e.g. oscillating) is updated sooner.
    if (last_drift_ > options_.drift_tolerance) {
      allowance_ = std::max(0.5 * allowance_, kMinAllowance * tol);
      cap_ = std::max<std::int64_t>(1, cap_ / 2);
    } else if (last_drift_ < 0.25 * options_.drift_tolerance) {
      allowance_ = std::min(2.0 * allowance_, tol);
      cap_ = std::min(2 * cap_, options_.max_spared_steps);
    }
    // Scale of the tangent: least-squares fit of alpha C : E to the DEM's increment (rotation
    // removed), in [0, 1] (C is an upper bound).
    const Mat3 q = rotation(g);
    const Mat3 ds = q.transpose() * sigma * q - sigma_before;
    const Mat3 ce = dem::apply_tangent(c_, sym(g));
    const double den = (ce.array() * ce.array()).sum();
    if (den > 0.0) {
      alpha_ = std::clamp((ds.array() * ce.array()).sum() / den, 0.0, 1.0);
      e_fit_ = sym(g);
    }
  }
  g_acc_.setZero();
  dt_acc_ = 0.0;
  n_spared_ = 0;
  have_c_ = false;
  c_.setZero();
}

Mat3 SparedMicro::stress() const { return n_spared_ > 0 ? sigma_ : inner_->stress(); }

MicroReport SparedMicro::report() const {
  if (n_spared_ == 0) return inner_->report();
  MicroReport r;
  r.p = common::pressure(sigma_);
  r.q = common::deviatoric(sigma_);
  r.void_ratio = (1.0 + base_.void_ratio) * (Mat3::Identity() + g_acc_).determinant() - 1.0;
  r.z = base_.z;
  r.guards = kGuardSpared | (base_.guards & dem::kGuardNoContacts);
  return r;
}

void SparedMicro::save(common::StateWriter& w) const {
  inner_->save(w);
  common::write_scalar(w, "spare/version", kSparedStateVersion);
  w.write("spare/g_acc", nine(g_acc_));
  common::write_scalar(w, "spare/dt_acc", dt_acc_);
  common::write_scalar(w, "spare/n_spared", n_spared_);
  w.write("spare/base", std::vector<double>{base_.p, base_.q, base_.void_ratio, base_.z});
  common::write_scalar(w, "spare/base_guards", static_cast<std::int64_t>(base_.guards));
  common::write_scalar(w, "spare/have_tangent", std::int64_t{have_c_ ? 1 : 0});
  w.write("spare/tangent", std::span<const double>(c_.data(), 81));
  common::write_scalar(w, "spare/allowance", allowance_);
  common::write_scalar(w, "spare/cap", cap_);
  common::write_scalar(w, "spare/alpha", alpha_);
  w.write("spare/alpha_strain", nine(e_fit_));
  common::write_scalar(w, "spare/last_drift", last_drift_);
}

std::unique_ptr<MicroModel> SparedMicro::load(const common::StateReader& r,
                                              std::unique_ptr<MicroModel> inner,
                                              const SparingOptions& options, TangentFn tangent) {
  const std::int64_t version = common::read_scalar_i64(r, "spare/version");
  if (version != kSparedStateVersion) {
    throw common::InputError("spared micro state: spare/version = " + std::to_string(version) +
                             ", this build reads " + std::to_string(kSparedStateVersion));
  }
  auto m = std::make_unique<SparedMicro>(std::move(inner), options, std::move(tangent));
  m->g_acc_ = read_nine(r, "spare/g_acc");
  m->dt_acc_ = read_finite_scalar(r, "spare/dt_acc");
  m->n_spared_ = common::read_scalar_i64(r, "spare/n_spared");
  const std::vector<double> b = read_finite(r, "spare/base");
  const std::vector<double> c = read_finite(r, "spare/tangent");
  const std::int64_t have_c = common::read_scalar_i64(r, "spare/have_tangent");
  if (b.size() != 4 || c.size() != 81 || m->n_spared_ < 0 || m->dt_acc_ < 0.0 ||
      (have_c != 0 && have_c != 1)) {
    throw common::InputError(
        "spared micro state: spare/base must hold 4 values, spare/tangent 81, spare/n_spared "
        "and spare/dt_acc must be >= 0 and spare/have_tangent 0 or 1 (n_spared " +
        std::to_string(m->n_spared_) + ", dt_acc " + std::to_string(m->dt_acc_) +
        ", have_tangent " + std::to_string(have_c) + ")");
  }
  m->base_.p = b[0];
  m->base_.q = b[1];
  m->base_.void_ratio = b[2];
  m->base_.z = b[3];
  m->base_.guards = static_cast<std::uint32_t>(common::read_scalar_i64(r, "spare/base_guards"));
  m->have_c_ = have_c != 0;
  std::copy(c.begin(), c.end(), m->c_.data());
  // A restart may change the tolerance: the RVE's allowance stays within the new bounds.
  const double tol = options.tolerance;
  m->allowance_ = std::clamp(read_finite_scalar(r, "spare/allowance"), kMinAllowance * tol, tol);
  m->cap_ = std::clamp<std::int64_t>(common::read_scalar_i64(r, "spare/cap"), 1,
                                     options.max_spared_steps);
  m->alpha_ = read_finite_scalar(r, "spare/alpha");
  m->e_fit_ = read_nine(r, "spare/alpha_strain");
  m->last_drift_ = read_finite_scalar(r, "spare/last_drift");
  if (m->n_spared_ > 0) m->sigma_ = m->predict(m->inner_->stress(), m->g_acc_);
  return m;
}

bool is_dem_micro(const MicroModel& m) { return dynamic_cast<const DemMicro*>(&m) != nullptr; }

dem::Tangent dem_micro_tangent(const MicroModel& m) {
  if (const auto* d = dynamic_cast<const DemMicro*>(&m))
    return dem::contact_stiffness_tangent(d->rve().simulation());
  return dem::Tangent::Zero();
}

MicroKind spared_kind(MicroKind inner, const SparingOptions& options, SparePredicate spare,
                      TangentFn tangent) {
  options.validate();
  MicroKind k;
  if (options.tolerance > 0.0) {
    k.create = [create = inner.create, options, spare,
                tangent](std::int64_t id) -> std::unique_ptr<MicroModel> {
      std::unique_ptr<MicroModel> m = create(id);
      if (spare(*m)) return std::make_unique<SparedMicro>(std::move(m), options, tangent);
      return m;
    };
  } else {
    k.create = inner.create;
  }
  k.load = [load = inner.load, options, spare,
            tangent](const common::StateReader& r) -> std::unique_ptr<MicroModel> {
    std::unique_ptr<MicroModel> m = load(r);
    if (r.has("spare/version")) return SparedMicro::load(r, std::move(m), options, tangent);
    if (options.tolerance > 0.0 && spare(*m))
      return std::make_unique<SparedMicro>(std::move(m), options, tangent);
    return m;
  };
  k.prepare = inner.prepare;
  return k;
}

}  // namespace farm
