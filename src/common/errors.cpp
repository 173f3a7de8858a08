// Error helpers: see errors.hpp.
#include "common/errors.hpp"

namespace common {

void throw_internal(const char* expr, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": check '" + expr +
                      "' failed: " + msg);
}

}  // namespace common
