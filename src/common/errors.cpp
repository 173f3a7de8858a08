// Error helpers: see errors.hpp.
#include "common/errors.hpp"

namespace common {

std::string current_error_text() {
  try {
    throw;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
}

void throw_internal(const char* expr, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": check '" + expr +
                      "' failed: " + msg);
}

}  // namespace common
