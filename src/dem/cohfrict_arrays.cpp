// Resizing of the per-pair property and history arrays.
#include "dem/cohfrict_arrays.hpp"

namespace dem {

void CohFrictPropsArrays::resize(std::size_t n) {
  const CohFrictProps fresh;
  kn.resize(n, fresh.kn);
  ks.resize(n, fresh.ks);
  kr.resize(n, fresh.kr);
  kt.resize(n, fresh.kt);
  tan_phi.resize(n, fresh.tan_phi);
  roll_cap.resize(n, fresh.roll_cap);
  twist_cap.resize(n, fresh.twist_cap);
}

void CohFrictHistoryArrays::resize(std::size_t n) {
  for (std::size_t a = 0; a < 3; ++a) {
    normal[a].resize(n, 0.0);
    shear[a].resize(n, 0.0);
    roll[a].resize(n, 0.0);
    twist[a].resize(n, 0.0);
  }
}

}  // namespace dem
