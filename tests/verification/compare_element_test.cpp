// compare_element_test: the coupled element test (`mpmxdem run`, means.csv) against pure DEM
// (`mpmxdem dem`, dem_series.csv) on the same sample; a helper of the CTest test
// verification.coupled.element_test.np2 (element_test.cmake).
// Usage: compare_element_test MEANS_CSV DEM_SERIES_CSV EPS_FROM EPS_TO TOL_Q TOL_EPS_V
// Strains are logarithmic, compression positive (means.csv holds 1 - F_zz and 1 - V/V0: converted).
// At every MPM row with eps_a in [EPS_FROM, EPS_TO] the DEM's q and eps_v are interpolated linearly
// in eps_a. Passes (exit 0) when
//   RMS over the rows of (q_mpm - q_dem) / q_dem <= TOL_Q  (the measure of docs/validation/triaxial.md)
//   and max |eps_v,mpm - eps_v,dem| <= TOL_EPS_V;
// exit 1 when not, 2 on unreadable input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Table = std::map<std::string, std::vector<double>>;

// A CSV with a header line; lines starting with '#' are comments.
Table read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  std::vector<std::string> names;
  Table t;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    if (names.empty()) {
      while (std::getline(ss, cell, ',')) names.push_back(cell);
      continue;
    }
    std::size_t k = 0;
    while (std::getline(ss, cell, ',') && k < names.size())
      t[names[k++]].push_back(std::stod(cell));
    if (k != names.size()) throw std::runtime_error(path + ": short row: " + line);
  }
  return t;
}

const std::vector<double>& column(const Table& t, const std::string& name,
                                  const std::string& path) {
  const auto it = t.find(name);
  if (it == t.end() || it->second.empty()) throw std::runtime_error(path + ": no column " + name);
  return it->second;
}

// y(x) by linear interpolation in a series with non-decreasing x; x must lie in its range.
double interp(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  if (it == xs.begin() || it == xs.end()) throw std::runtime_error("strain outside the DEM series");
  const auto k = static_cast<std::size_t>(it - xs.begin());
  const double t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + t * (ys[k] - ys[k - 1]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr,
                 "usage: compare_element_test MEANS_CSV DEM_SERIES_CSV EPS_FROM EPS_TO TOL_Q "
                 "TOL_EPS_V\n");
    return 2;
  }
  try {
    const std::string mpm_path = argv[1];
    const std::string dem_path = argv[2];
    const double from = std::stod(argv[3]);
    const double to = std::stod(argv[4]);
    const double tol_q = std::stod(argv[5]);
    const double tol_ev = std::stod(argv[6]);
    const Table mpm = read_csv(mpm_path);
    const Table dem = read_csv(dem_path);
    const auto& m_ea = column(mpm, "eps_ax", mpm_path);
    const auto& m_ev = column(mpm, "eps_v", mpm_path);
    const auto& m_q = column(mpm, "q_mean_Pa", mpm_path);
    const auto& d_ea = column(dem, "eps_a", dem_path);
    const auto& d_ev = column(dem, "eps_v", dem_path);
    const auto& d_q = column(dem, "q", dem_path);

    double sum_rel2 = 0.0;
    double worst_ev = 0.0;
    double worst_ev_at = 0.0;
    int n = 0;
    double next = from;
    for (std::size_t k = 0; k < m_ea.size(); ++k) {
      const double ea = -std::log1p(-m_ea[k]);
      if (ea < from || ea > to) continue;
      const double ev = -std::log1p(-m_ev[k]);
      const double q_dem = interp(d_ea, d_q, ea);
      const double ev_dem = interp(d_ea, d_ev, ea);
      sum_rel2 += (m_q[k] - q_dem) * (m_q[k] - q_dem) / (q_dem * q_dem);
      if (std::abs(ev - ev_dem) > worst_ev) {
        worst_ev = std::abs(ev - ev_dem);
        worst_ev_at = ea;
      }
      ++n;
      if (ea >= next) {  // one line per 0.1 % of axial strain
        std::printf("  eps_a %.5f: q %.1f / %.1f kPa, eps_v %.3e / %.3e (MPM x DEM / DEM)\n", ea,
                    m_q[k] / 1e3, q_dem / 1e3, ev, ev_dem);
        next = ea + 0.001;
      }
    }
    if (n < 10) {
      std::fprintf(stderr, "only %d MPM rows in eps_a [%g, %g]: nothing to compare\n", n, from, to);
      return 2;
    }
    const double rms_q = std::sqrt(sum_rel2 / n);
    std::printf(
        "%d rows in eps_a [%g, %g]: RMS relative error of q %.4f (tolerance %g), "
        "max |eps_v,mpm - eps_v,dem| %.3e at eps_a %.4f (tolerance %g)\n",
        n, from, to, rms_q, tol_q, worst_ev, worst_ev_at, tol_ev);
    return (rms_q <= tol_q && worst_ev <= tol_ev) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_element_test: %s\n", e.what());
    return 2;
  }
}
