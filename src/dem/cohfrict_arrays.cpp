// Resizing of the per-pair history arrays.
#include "dem/cohfrict_arrays.hpp"

namespace dem {

void CohFrictHistoryArrays::resize(std::size_t n) {
  for (std::size_t a = 0; a < 3; ++a) {
    normal[a].resize(n, 0.0);
    shear[a].resize(n, 0.0);
    roll[a].resize(n, 0.0);
    twist[a].resize(n, 0.0);
  }
}

}  // namespace dem
