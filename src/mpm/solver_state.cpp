// MPM state save/load: the named fields of a checkpoint (see solver.hpp, docs/design/mpm.md
// "Checkpoint").
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "mpm/solver.hpp"

namespace mpm {

namespace {

std::vector<double> flatten(const std::vector<common::Vec3>& v) {
  std::vector<double> out;
  out.reserve(v.size() * 3);
  for (const common::Vec3& a : v) out.insert(out.end(), {a[0], a[1], a[2]});
  return out;
}

std::vector<double> flatten(const std::vector<common::Mat3>& v) {
  std::vector<double> out(v.size() * 9);
  for (std::size_t p = 0; p < v.size(); ++p) common::row_major_out(out.data() + 9 * p) = v[p];
  return out;
}

std::vector<double> read_sized(const common::StateReader& r, const std::string& name,
                               std::size_t expected) {
  std::vector<double> d = r.read_f64(name);
  if (d.size() != expected) {
    throw common::InputError("mpm checkpoint: field " + name + " has " + std::to_string(d.size()) +
                             " values, expected " + std::to_string(expected));
  }
  common::require_finite(d, "mpm checkpoint: field " + name);  // a NaN passes the grid's bounds
  return d;
}

void unflatten(const std::vector<double>& d, std::vector<common::Vec3>& v) {
  for (std::size_t p = 0; p < v.size(); ++p)
    v[p] = common::Vec3(d[3 * p], d[3 * p + 1], d[3 * p + 2]);
}

void unflatten(const std::vector<double>& d, std::vector<common::Mat3>& v) {
  for (std::size_t p = 0; p < v.size(); ++p) v[p] = common::row_major(d.data() + 9 * p);
}

/// The point slots of each of `loads` traction loads' facets, each checked to lie in [0, n).
std::vector<std::vector<std::int64_t>> read_facet_slots(const common::StateReader& r,
                                                        std::size_t loads, std::size_t n) {
  std::vector<std::vector<std::int64_t>> facets(loads);
  for (std::size_t k = 0; k < loads; ++k) {
    const std::string name = "loads/traction_" + std::to_string(k) + "/point_slots";
    facets[k] = r.read_i64(name);
    for (const std::int64_t slot : facets[k]) {
      if (slot < 0 || static_cast<std::size_t>(slot) >= n) {
        throw common::InputError("mpm checkpoint: " + name + " holds slot " + std::to_string(slot) +
                                 " outside [0, " + std::to_string(n) + ")");
      }
    }
  }
  return facets;
}

}  // namespace

void Solver::save(common::StateWriter& w) const {
  w.write("solver/step", std::vector<std::int64_t>{step_});
  w.write("solver/time", std::vector<double>{time_});
  w.write("solver/internal_work", std::vector<double>{internal_work_});
  w.write("points/id", points_.id);
  w.write("points/x", flatten(points_.x));
  w.write("points/v", flatten(points_.v));
  w.write("points/mass", points_.mass);
  w.write("points/volume", points_.volume);
  w.write("points/volume0", points_.volume0);
  w.write("points/half_width0", flatten(points_.half_width0));
  w.write("points/stress", flatten(points_.stress));
  w.write("points/F", flatten(points_.F));
  w.write("points/L", flatten(points_.L));
  if (config_.transfer == Transfer::apic) w.write("points/C", flatten(points_.C));
  if (regularisation_ && !regularisation_->strain().empty()) {
    w.write("points/regularisation_strain", flatten(regularisation_->strain()));
  }
  std::vector<std::int64_t> mat(points_.material.begin(), points_.material.end());
  w.write("points/material", mat);
  for (std::size_t k = 0; k < traction_points_.size(); ++k) {
    w.write("loads/traction_" + std::to_string(k) + "/point_slots", traction_points_[k]);
  }
  // Only what cannot be recomputed: the displacements of windowed or field constraints.
  const bool windows = std::any_of(constraints_.begin(), constraints_.end(), [](const auto& c) {
    return c.spec.has_window() || c.spec.field;
  });
  if (windows) w.write("constraints/displacement", flatten(displacements_));
}

void Solver::load(const common::StateReader& r) {
  const std::vector<std::int64_t> step = r.read_i64("solver/step");
  if (step.size() != 1 || r.read_f64("solver/time").size() != 1) {
    throw common::InputError("mpm checkpoint: solver/step and solver/time must hold one value");
  }
  const std::vector<double> time = read_sized(r, "solver/time", 1);
  if (step[0] < 0) {
    throw common::InputError("mpm checkpoint: solver/step = " + std::to_string(step[0]) +
                             ": must be >= 0");
  }
  // Absent from checkpoints written before the energy accounting: the work restarts from 0.
  double work = 0.0;
  if (r.has("solver/internal_work")) {
    work = read_sized(r, "solver/internal_work", 1)[0];
  }
  MaterialPoints pts;
  const std::vector<std::int64_t> ids = r.read_i64("points/id");
  const std::size_t n = ids.size();
  pts.resize(n);
  pts.id = ids;
  unflatten(read_sized(r, "points/x", 3 * n), pts.x);
  unflatten(read_sized(r, "points/v", 3 * n), pts.v);
  pts.mass = read_sized(r, "points/mass", n);
  pts.volume = read_sized(r, "points/volume", n);
  pts.volume0 = read_sized(r, "points/volume0", n);
  unflatten(read_sized(r, "points/half_width0", 3 * n), pts.half_width0);
  unflatten(read_sized(r, "points/stress", 9 * n), pts.stress);
  unflatten(read_sized(r, "points/F", 9 * n), pts.F);
  unflatten(read_sized(r, "points/L", 9 * n), pts.L);
  // APIC's affine velocities; absent from the state of a FLIP run (zero: a FLIP state continued
  // with APIC starts from a PIC step).
  if (r.has("points/C")) {
    unflatten(read_sized(r, "points/C", 9 * n), pts.C);
  } else {
    pts.C.assign(n, common::Mat3::Zero());
  }
  const std::vector<std::int64_t> mat = r.read_i64("points/material");
  if (mat.size() != n)
    throw common::InputError("mpm checkpoint: points/material has the wrong size");
  for (std::size_t p = 0; p < n; ++p) {
    if (mat[p] < 0 || static_cast<std::size_t>(mat[p]) >= materials_.size()) {
      throw common::InputError("mpm checkpoint: points/material of point id " +
                               std::to_string(ids[p]) + " = " + std::to_string(mat[p]) +
                               ": no such material model");
    }
    pts.material[p] = static_cast<std::int32_t>(mat[p]);
  }
  pts.validate();
  std::vector<std::vector<std::int64_t>> facets = read_facet_slots(r, tractions_.size(), n);
  // Constraint displacements: saved for windowed or field constraints; absent (an older
  // checkpoint, or none of those), each is v t of its constant velocity.
  std::vector<common::Vec3> disp(constraints_.size(), common::Vec3::Zero());
  if (r.has("constraints/displacement")) {
    unflatten(read_sized(r, "constraints/displacement", 3 * constraints_.size()), disp);
  } else {
    for (std::size_t k = 0; k < constraints_.size(); ++k) {
      const VelocityConstraint& c = constraints_[k].spec;
      if (!c.has_window() && !c.field) disp[k] = prescribed_velocity(c, time[0]) * time[0];
    }
  }
  // The regularisation's strain; absent: saved before the first step (zero).
  std::vector<common::Mat3> reg_strain;
  if (regularisation_ && r.has("points/regularisation_strain")) {
    reg_strain.resize(n);
    unflatten(read_sized(r, "points/regularisation_strain", 9 * n), reg_strain);
  }
  traction_points_ = std::move(facets);
  if (regularisation_) regularisation_->set_strain(std::move(reg_strain));
  points_ = std::move(pts);
  step_ = step[0];
  kinetic_step_ = -1;
  time_ = time[0];
  internal_work_ = work;
  displacements_ = std::move(disp);
}

}  // namespace mpm
