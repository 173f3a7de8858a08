// Thin RAII and error-checking helpers over the HDF5 C API, private to the farm.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>

namespace farm::h5 {

/// Owns one HDF5 identifier and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      closer_ = o.closer_;
      o.id_ = -1;
    }
    return *this;
  }
  ~Handle() { reset(); }
  void reset() { (void)close(); }
  /// Closes now; returns the closer's status (a failed flush of what the object held), which
  /// reset() and the destructor ignore.
  herr_t close() {
    herr_t status = 0;
    if (id_ >= 0 && closer_ != nullptr) status = closer_(id_);
    id_ = -1;
    return status;
  }
  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// Turns off HDF5's own error printing (our messages name the file and the dataset).
void silence_errors();
/// The system's reason of the latest HDF5 failure on this thread's error stack ("No space left
/// on device"), or "" when the failure was not a system call's.
[[nodiscard]] std::string system_reason();
/// When status < 0 throws common::IoError("HDF5: <what> failed: <system's reason>") if a system
/// call failed, else common::InternalError("HDF5: <what> failed"); returns status.
hid_t check(hid_t status, const std::string& what);

template <class T>
hid_t native_type();
template <>
inline hid_t native_type<double>() {
  return H5T_NATIVE_DOUBLE;
}
template <>
inline hid_t native_type<std::int64_t>() {
  return H5T_NATIVE_INT64;
}
template <>
inline hid_t native_type<std::uint8_t>() {
  return H5T_NATIVE_UINT8;
}

}  // namespace farm::h5
