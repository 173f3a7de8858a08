// Program version (kept in step with CMakeLists.txt's project version by a test).
#pragma once

namespace app {
inline constexpr const char* kVersion = "0.1.0";
}
