// ElasticMaterial: validation against its table and the rules between its angles; the degrees of
// an older state's radians (see elastic_material.hpp).
#include "farm/elastic_material.hpp"

#include <array>
#include <charconv>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace farm {

namespace {

// "mpm.elastic.<key> = <value>: <rule>", the values as the tables' range errors write them.
[[noreturn]] void fail(const char* key, double value, const std::string& rule) {
  std::ostringstream os;
  os << kElasticMaterial.section << '.' << key << " = " << value << ": " << rule;
  throw common::InputError(os.str());
}

// The length of v's shortest round-trip decimal form.
std::size_t shortest_digits(double v) {
  std::array<char, 32> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return static_cast<std::size_t>(res.ptr - buf.data());
}

std::string deg(double v) {
  std::ostringstream os;
  os << v << " deg";
  return os.str();
}

}  // namespace

void ElasticMaterial::validate() const {
  common::check_ranges(kElasticMaterial, *this);
  if (dilatancy_deg > friction_deg) {
    fail("dilatancy_angle", dilatancy_deg,
         "must be <= mpm.elastic.friction_angle (" + deg(friction_deg) + ")");
  }
  if (dilatancy_cutoff > 0.0 && !(dilatancy_deg > 0.0)) {
    fail("dilatancy_cutoff", dilatancy_cutoff, "needs mpm.elastic.dilatancy_angle > 0");
  }
  if (softening_strain > 0.0) {
    if (!(friction_deg > 0.0))
      fail("softening_strain", softening_strain, "needs mpm.elastic.friction_angle > 0");
    if (dilatancy_deg != 0.0) {
      fail("dilatancy_angle", dilatancy_deg, "must be 0 with mpm.elastic.softening_strain");
    }
    if (residual_friction_deg > friction_deg) {
      fail("residual_friction_angle", residual_friction_deg,
           "must be <= mpm.elastic.friction_angle (" + deg(friction_deg) + ")");
    }
  }
}

double degrees_of_radians(double rad) {
  const double guess = rad * 180.0 / M_PI;
  // to_radians is monotone and rounds twice: the degrees giving rad exactly, if any, lie within a
  // few ulps of guess. Of those, the one written with the fewest digits is the job's (11.7, not
  // 11.699999999999998); a tie goes to the nearest to guess.
  constexpr int kUlps = 16;
  double best = guess;
  std::size_t best_digits = std::numeric_limits<std::size_t>::max();
  double below = guess;
  double above = guess;
  for (int k = 0; k <= kUlps; ++k) {
    for (const double d : {below, above}) {
      if (to_radians(d) != rad) continue;
      const std::size_t n = shortest_digits(d);
      if (n < best_digits) {
        best = d;
        best_digits = n;
      }
    }
    below = std::nextafter(below, -std::numeric_limits<double>::infinity());
    above = std::nextafter(above, std::numeric_limits<double>::infinity());
  }
  return best;
}

}  // namespace farm
