#include "mpm/formulation.hpp"

#include <cstddef>
#include <string>

#include <Eigen/LU>

#include "common/errors.hpp"

namespace mpm {

Formulation formulation_from_string(std::string_view name) {
  if (const auto f = common::value_of(kFormulationNames, name)) return *f;
  throw common::InputError("mpm.formulation = \"" + std::string(name) + "\": must be one of " +
                           common::names_list(kFormulationNames));
}

std::string_view to_string(Formulation f) { return common::name_of(kFormulationNames, f); }

void to_spatial_gradient(const std::vector<common::Mat3>& F, std::vector<common::Mat3>& L) {
  for (std::size_t p = 0; p < L.size(); ++p) L[p] = L[p] * F[p].inverse();
}

void stress_for_reference_gradient(const std::vector<common::Mat3>& F,
                                   const std::vector<common::Mat3>& stress,
                                   std::vector<common::Mat3>& out) {
  out.resize(stress.size());
  for (std::size_t p = 0; p < stress.size(); ++p) out[p] = stress[p] * F[p].inverse().transpose();
}

}  // namespace mpm
