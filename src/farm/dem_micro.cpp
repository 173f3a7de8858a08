// DemMicro: dem::Rve behind the MicroModel contract (see header).
#include "farm/dem_micro.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "dem/measures.hpp"
#include "dem/vtk_export.hpp"

namespace farm {

namespace {

MicroReport to_micro(const dem::StepReport& s) {
  MicroReport r;
  r.p = s.p;
  r.q = s.q;
  r.void_ratio = s.void_ratio;
  r.z = s.z;
  r.dem_steps = s.dem_steps;
  r.t_p = s.t_p;
  r.guards = s.guards;
  r.rebuilds = s.rebuilds;
  r.wall_s = s.wall_s;
  return r;
}

}  // namespace

DemMicro::DemMicro(dem::Rve rve, std::uint32_t fail_guards)
    : rve_(std::move(rve)), fail_guards_(fail_guards) {}

MicroReport DemMicro::step(const common::Mat3& L, double dt) {
  const dem::StepReport s = rve_.step(L, dt);
  if ((s.guards & fail_guards_) != 0U) {
    throw common::NumericalError("DEM RVE guard exhausted (guards = " + std::to_string(s.guards) +
                                 ", failing set = " + std::to_string(fail_guards_) + "): " +
                                 ((s.guards & dem::kGuardStepCap) != 0U
                                      ? "T_p needed more than max_steps_per_call = " +
                                            std::to_string(rve_.params().max_steps_per_call) +
                                            " DEM steps"
                                      : std::string("see dem::RveGuard")));
  }
  return to_micro(s);
}

MicroReport DemMicro::report() const { return to_micro(rve_.measure()); }

MicroMeasures DemMicro::measures() const {
  const dem::Measures d = dem::measure(rve_.simulation());
  MicroMeasures m;
  common::row_major_out(m.fabric) = d.fabric;
  m.z_mech = d.z_mech;
  m.unbalanced = d.unbalanced;
  m.kinetic = d.kinetic;
  return m;
}

std::vector<ViewFile> DemMicro::grain_view(const std::string& stem) const {
  std::vector<ViewFile> out;
  for (dem::VtkFile& f : dem::vtk_view(rve_.simulation(), stem)) {
    out.push_back({std::move(f.name), std::move(f.text)});
  }
  return out;
}

void DemMicro::save(common::StateWriter& w) const {
  rve_.save(w);
  w.write("farm/dem_fail_guards",
          std::vector<std::int64_t>{static_cast<std::int64_t>(fail_guards_)});
}

double DemMicro::wave_speed() const {
  const dem::Material& m = rve_.params().material;
  return std::sqrt(m.young / m.density);
}

std::unique_ptr<MicroModel> DemMicro::load(const common::StateReader& r) {
  const auto g = r.read_i64("farm/dem_fail_guards");
  if (g.size() != 1 || g[0] < 0) {
    throw common::InputError(
        "DEM micro state: field 'farm/dem_fail_guards' must hold one value >= 0");
  }
  return std::make_unique<DemMicro>(dem::Rve::load(r), static_cast<std::uint32_t>(g[0]));
}

MicroKind DemMicro::kind(const DemMicroParams& params,
                         std::function<dem::Packing(std::int64_t id)> packing_of) {
  params.rve.validate();
  MicroKind k;
  k.create = [params, packing_of = std::move(packing_of)](std::int64_t id) {
    return std::make_unique<DemMicro>(dem::Rve(packing_of(id), params.rve), params.fail_guards);
  };
  k.load = [](const common::StateReader& r) { return DemMicro::load(r); };
  return k;
}

}  // namespace farm
