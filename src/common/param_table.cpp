// Parameter tables: range rules in words and the out-of-range error (see param_table.hpp).
#include "common/param_table.hpp"

#include <sstream>

#include "common/errors.hpp"

namespace common {

std::string_view unit_symbol(Unit u) {
  switch (u) {
    case Unit::none:
      return "";
    case Unit::length:
      return "m";
    case Unit::pressure:
      return "Pa";
    case Unit::angle:
      return "deg";
    case Unit::time:
      return "s";
    case Unit::density:
      return "kg/m^3";
    case Unit::velocity:
      return "m/s";
    case Unit::acceleration:
      return "m/s^2";
    case Unit::rate:
      return "1/s";
  }
  return "";
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
