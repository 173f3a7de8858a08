// Parameter tables: range rules in words and the out-of-range error (see param_table.hpp).
#include "common/param_table.hpp"

#include <array>
#include <sstream>

#include "common/errors.hpp"

namespace common {

std::string_view unit_symbol(Unit u) {
  // Indexed by Unit, in its order.
  constexpr std::array<std::string_view, 10> kSymbols{"",       "m",   "Pa",    "deg", "s",
                                                      "kg/m^3", "m/s", "m/s^2", "1/s", "N m/rad"};
  return kSymbols.at(static_cast<std::size_t>(u));
}

namespace {
// Numbers as the app's "{:g}" writes them: 6 significant digits, shortest form.
std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

std::string Range::rule(Unit u) const {
  const std::string sym(unit_symbol(u));
  const std::string unit = sym.empty() ? "" : " " + sym;
  if (lo && hi) {
    return "must be in " + std::string(lo_open ? "(" : "[") + num(*lo) + ", " + num(*hi) +
           (hi_open ? ")" : "]") + unit;
  }
  if (lo) return "must be " + std::string(lo_open ? "> " : ">= ") + num(*lo) + unit;
  if (hi) return "must be " + std::string(hi_open ? "< " : "<= ") + num(*hi) + unit;
  return "must be a finite number";
}

void throw_out_of_range(const std::string& name, double value, bool integer, const Range& range,
                        Unit unit) {
  std::ostringstream os;
  os << name << " = ";
  if (integer) {
    os << static_cast<long long>(value);
  } else {
    os << value;
  }
  os << ": " << range.rule(unit);
  throw InputError(os.str());
}

}  // namespace common
