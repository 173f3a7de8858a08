// Error tiers (docs/design/architecture.md): debug-only assertions for internal invariants,
// always-on checks that throw with context, and InputError for everything a user controls.
#pragma once

#include <stdexcept>
#include <string>

namespace common {

/// Anything a user controls is wrong: job file, CLI, packing file, checkpoint.
/// The message is complete and printed as is: "file:line: key = value: rule".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical failure (NaN, negative volume, unstable step); the message carries the context
/// (step, time, RVE or point id, the offending quantity).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The system failed to store a file: opening, writing, fsync or rename failed (disk full, quota,
/// I/O error, a read-only or vanished file system). Neither the user's input (InputError) nor a
/// bug (InternalError): the message names the file and the operating system's reason.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An internal invariant was broken: a bug, not a user error.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// The message of the exception being handled: what() of a std::exception, "unknown exception"
/// for anything else. @pre called inside a catch block.
[[nodiscard]] std::string current_error_text();

[[noreturn]] void throw_internal(const char* expr, const char* file, int line,
                                 const std::string& msg);

}  // namespace common

/// Always-on check of an internal invariant; throws common::InternalError with the location.
#define MPMXDEM_CHECK(cond, msg)                                           \
  do {                                                                     \
    if (!(cond)) ::common::throw_internal(#cond, __FILE__, __LINE__, msg); \
  } while (0)

/// Debug-only assertion (compiled out with NDEBUG): for invariants in hot loops.
#ifdef NDEBUG
#define MPMXDEM_ASSERT(cond) ((void)0)
#else
#define MPMXDEM_ASSERT(cond) MPMXDEM_CHECK(cond, "assertion failed")
#endif
