// HDF5 helpers (see header).
#include "farm/h5_util.hpp"

#include "common/errors.hpp"

namespace farm::h5 {

namespace {

/// H5Ewalk2 callback: keeps the system's reason of the first (innermost) error that has one.
/// HDF5's file drivers describe a failed system call as "... errno = 28, error message = 'No
/// space left on device', ..." (H5FDsec2.c, H5FDmpio.c).
herr_t find_reason(unsigned /*n*/, const H5E_error2_t* err, void* out) {
  auto& reason = *static_cast<std::string*>(out);
  if (!reason.empty() || err == nullptr || err->desc == nullptr) return 0;
  const std::string desc(err->desc);
  const std::string key = "error message = '";
  const std::size_t at = desc.find(key);
  if (at == std::string::npos) return 0;
  const std::size_t from = at + key.size();
  const std::size_t to = desc.find('\'', from);
  if (to != std::string::npos) reason = desc.substr(from, to - from);
  return 0;
}

}  // namespace

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

std::string system_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, find_reason, &reason);
  return reason;
}

hid_t check(hid_t status, const std::string& what) {
  if (status >= 0) return status;
  // A failed system call (disk full, quota, I/O error) is the storage's failure, not ours.
  const std::string reason = system_reason();
  if (!reason.empty()) throw common::IoError("HDF5: " + what + " failed: " + reason);
  throw common::InternalError("HDF5: " + what + " failed");
}

}  // namespace farm::h5
