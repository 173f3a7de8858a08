// Validation of the DEM parameter structs against their tables (params.hpp).
#include "dem/params.hpp"

namespace dem {

void Material::validate() const { common::check_ranges(kMaterial, *this); }

void Numerics::validate() const { common::check_ranges(kNumerics, *this); }

}  // namespace dem
