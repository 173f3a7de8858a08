// Validation of the DEM parameter structs against their tables (params.hpp).
#include "dem/params.hpp"

#include <string>

#include "common/errors.hpp"

namespace dem {

void Material::validate() const {
  common::check_ranges(kMaterial, *this);
  if (law == ContactLawKind::cohfrict) {
    common::check_ranges(kCohFrict, *this);
    return;
  }
  bool known = false;
  for_each_table_law([&](const auto& d) {
    if (d.kind != law) return;
    common::check_ranges(d.table, this->*d.params);
    known = true;
  });
  if (!known) {
    throw common::InputError("dem.material.contact_law: unknown law " +
                             std::to_string(static_cast<int>(law)));
  }
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
