// Validation of the DEM parameter structs (InputError naming the entry, the value and the rule).
#include "dem/params.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace dem {

namespace {
void require(bool ok, const char* key, double value, const char* rule) {
  if (!ok) {
    std::ostringstream os;
    os << key << " = " << value << ": " << rule;
    throw common::InputError(os.str());
  }
}
}  // namespace

void Material::validate() const {
  require(density > 0.0 && std::isfinite(density), "dem.material.density", density,
          "must be > 0 [kg/m^3]");
  require(young > 0.0 && std::isfinite(young), "dem.material.young", young, "must be > 0 [Pa]");
  require(ks_over_kn >= 0.0, "dem.material.ks_over_kn", ks_over_kn, "must be >= 0");
  require(friction_deg >= 0.0 && friction_deg < 90.0, "dem.material.friction_deg", friction_deg,
          "must be in [0, 90) degrees");
  require(alpha_r >= 0.0, "dem.material.alpha_r", alpha_r, "must be >= 0");
  require(alpha_t >= 0.0, "dem.material.alpha_t", alpha_t, "must be >= 0");
}

void Numerics::validate() const {
  require(damping >= 0.0 && damping < 1.0, "dem.numerics.damping", damping, "must be in [0, 1)");
  require(dt_safety > 0.0 && dt_safety <= 1.0, "dem.numerics.dt_safety", dt_safety,
          "must be in (0, 1]");
  require(skin_factor > 0.0, "dem.numerics.skin_factor", skin_factor, "must be > 0");
  require(dt_refresh >= 1, "dem.numerics.dt_refresh", static_cast<double>(dt_refresh),
          "must be >= 1");
  require(max_skew >= 0.5, "dem.numerics.max_skew", max_skew, "must be >= 0.5");
}

}  // namespace dem
