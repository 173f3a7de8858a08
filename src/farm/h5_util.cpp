// HDF5 helpers (see header).
#include "farm/h5_util.hpp"

#include "common/errors.hpp"

namespace farm::h5 {

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

hid_t check(hid_t status, const std::string& what) {
  if (status < 0) throw common::InternalError("HDF5: " + what + " failed");
  return status;
}

}  // namespace farm::h5
