// Validation of the DEM parameter structs against their tables (params.hpp).
#include "dem/params.hpp"

#include <string>

#include "common/errors.hpp"

namespace dem {

void Material::validate() const {
  common::check_ranges(kMaterial, *this);
  switch (law) {
    case ContactLawKind::cohfrict:
      common::check_ranges(kCohFrict, *this);
      return;
    case ContactLawKind::hertz_mindlin:
      common::check_ranges(kHertzMindlin, hm);
      return;
  }
  throw common::InputError("dem.material.contact_law: unknown law " +
                           std::to_string(static_cast<int>(law)));
}

void Numerics::validate() const {
  common::check_ranges(kNumerics, *this);
  if (skin_min_factor > skin_factor) {
    throw common::InputError("dem.numerics.verlet_skin_min = " + std::to_string(skin_min_factor) +
                             ": must be <= dem.numerics.verlet_skin (" +
                             std::to_string(skin_factor) + "), the widest skin");
  }
}

}  // namespace dem
