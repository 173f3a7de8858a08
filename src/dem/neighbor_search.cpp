// Verlet lists over fractional-coordinate bins; lattice re-mapping of skewed cells; rebuild test.
#include "dem/neighbor_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <tuple>

#include "common/errors.hpp"
#include "dem/threads.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;
using common::Vec3i;

namespace {

using Key = std::tuple<std::int32_t, std::int32_t, int, int, int>;
Key key_of(const Contacts& c, std::size_t p) {
  return {c.i[p], c.j[p], c.k[p][0], c.k[p][1], c.k[p][2]};
}

}  // namespace

bool remap_and_wrap(Spheres& s, PeriodicCell& cell, Contacts& c, double max_skew) {
  // Lattice reduction: c_b <- c_b - round(c_b . c_a / |c_a|^2) c_a, i.e. H <- H U.
  Eigen::Matrix3i u = Eigen::Matrix3i::Identity();
  bool remapped = false;
  for (int pass = 0; pass < 4; ++pass) {
    bool changed = false;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        if (a == b) continue;
        const Vec3 ca = cell.h.col(a);
        const double ratio = cell.h.col(b).dot(ca) / ca.squaredNorm();
        if (std::abs(ratio) > max_skew) {
          const double n = std::round(ratio);
          if (n == 0.0) continue;
          cell.h.col(b) -= n * ca;
          u.col(b) -= static_cast<int>(n) * u.col(a);
          changed = true;
        }
      }
    }
    if (!changed) break;
    remapped = true;
  }
  if (remapped) {
    // branch = x_j - x_i + H_old k = x_j - x_i + H_new U^-1 k.
    const Eigen::Matrix3d uinv_d = u.cast<double>().inverse();
    const Eigen::Matrix3i uinv = uinv_d.array().round().cast<int>().matrix();
    for (std::size_t p = 0; p < c.size(); ++p) c.k[p] = uinv * c.k[p];
  }
  // Wrap positions into [0,1)^3 in fractional coordinates, shifting pair images accordingly. A
  // position that is not finite (a blow-up) would make the image shift an undefined conversion.
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.x[i].allFinite()) {
      throw common::NumericalError("dem: sphere " + std::to_string(i) + " (radius " +
                                   std::to_string(s.r[i]) +
                                   " m) has a position that is not finite: the DEM blew up");
    }
  }
  const Mat3 hinv = cell.h.inverse();
  std::vector<Vec3i> shift(s.size(), Vec3i::Zero());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3 xi = hinv * s.x[i];
    Vec3i m(static_cast<int>(std::floor(xi[0])), static_cast<int>(std::floor(xi[1])),
            static_cast<int>(std::floor(xi[2])));
    if (m != Vec3i::Zero()) {
      s.x[i] -= cell.h * m.cast<double>();
      shift[i] = m;
    }
  }
  for (std::size_t p = 0; p < c.size(); ++p) c.k[p] += shift[c.j[p]] - shift[c.i[p]];
  return remapped;
}

namespace {

// Spheres sorted into bins of fractional coordinates at least `cutoff` wide (at most about n
// bins): each sphere's bin, and each bin's members (ids ascending) at start[b]..start[b + 1].
struct Bins {
  std::array<int, 3> nb{};
  std::vector<std::array<int, 3>> bin3;
  std::vector<std::int64_t> start;
  std::vector<std::int32_t> members;

  [[nodiscard]] std::int64_t index(const std::array<int, 3>& b) const {
    return (static_cast<std::int64_t>(b[2]) * nb[1] + b[1]) * nb[0] + b[0];
  }
};

Bins bin_spheres(const Spheres& s, const PeriodicCell& cell, const Mat3& hinv, double cutoff) {
  const std::size_t n = s.size();
  Bins bins;
  std::size_t nbins_total = 1;
  // Keep the bin count comparable to the sphere count (a huge cell must not make huge grids).
  const int nb_cap = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(n))) + 1);
  for (int a = 0; a < 3; ++a) {
    const double w = cell.width(a);
    if (w < cutoff) {
      throw common::NumericalError("dem: periodic cell width " + std::to_string(w) +
                                   " m is below 2 r_max + skin = " + std::to_string(cutoff) +
                                   " m (cell too small or too flat for its spheres)");
    }
    bins.nb[a] = std::clamp(static_cast<int>(w / cutoff), 1, nb_cap);
    nbins_total *= static_cast<std::size_t>(bins.nb[a]);
  }
  bins.bin3.resize(n);
  std::vector<std::int64_t> bin_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 frac = hinv * s.x[i];
    for (int a = 0; a < 3; ++a) {
      bins.bin3[i][a] =
          std::clamp(static_cast<int>(std::floor(frac[a] * bins.nb[a])), 0, bins.nb[a] - 1);
    }
    bin_of[i] = bins.index(bins.bin3[i]);
  }
  // Counting sort of spheres into bins (stable: ids ascending inside a bin).
  bins.start.assign(nbins_total + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++bins.start[bin_of[i] + 1];
  std::partial_sum(bins.start.begin(), bins.start.end(), bins.start.begin());
  bins.members.resize(n);
  std::vector<std::int64_t> fill(bins.start.begin(), bins.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    bins.members[fill[bin_of[i]]++] = static_cast<std::int32_t>(i);
  }
  return bins;
}

struct Candidate {
  std::int32_t j;
  Vec3i k;
  bool shell;  // not touching: within the skin only
};

// For each sphere i, the pairs (i, j > i, image k) closer than r_i + r_j + skin, sorted by (j, k).
std::vector<std::vector<Candidate>> candidates(const Spheres& s, const PeriodicCell& cell,
                                               const Bins& bins, double skin) {
  const std::size_t n = s.size();
  const auto& nb = bins.nb;
  std::vector<std::vector<Candidate>> per_sphere(n);
#pragma omp parallel for schedule(dynamic, 64) if (!one_thread(static_cast <std::int64_t>(n))) \
    num_threads(team_size(static_cast <std::int64_t>(n)))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    auto& out = per_sphere[i];
    for (int oz = -1; oz <= 1; ++oz) {
      for (int oy = -1; oy <= 1; ++oy) {
        for (int ox = -1; ox <= 1; ++ox) {
          const std::array<int, 3> o{ox, oy, oz};
          std::array<int, 3> b{};
          Vec3i k;
          for (int a = 0; a < 3; ++a) {
            const int raw = bins.bin3[i][a] + o[a];
            // With fewer than 3 bins an offset can revisit a bin under another image; distinct
            // offsets always give distinct (bin, image) pairs, and nb == 1 needs only offset 0 and
            // the two images, which ox = -1, 0, 1 provide.
            const int q = static_cast<int>(std::floor(static_cast<double>(raw) / nb[a]));
            b[a] = raw - q * nb[a];
            k[a] = q;
          }
          const std::int64_t bin = bins.index(b);
          const Vec3 shift = cell.h * k.cast<double>();
          for (std::int64_t q = bins.start[bin]; q < bins.start[bin + 1]; ++q) {
            const std::int32_t j = bins.members[q];
            if (static_cast<std::size_t>(j) <= i) continue;
            const Vec3 d = s.x[j] + shift - s.x[i];
            const double rc = s.r[i] + s.r[j] + skin;
            const double d2 = d.squaredNorm();
            if (d2 < rc * rc) {
              const double rs = s.r[i] + s.r[j];
              out.push_back({j, k, d2 >= rs * rs});
            }
          }
        }
      }
    }
    std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
      return std::tie(a.j, a.k[0], a.k[1], a.k[2]) < std::tie(b.j, b.k[0], b.k[1], b.k[2]);
    });
  }
  return per_sphere;
}

// The new list from the candidates, the active contacts of the old list `c` carrying their
// history over; the number of shell pairs (within the skin, not touching).
std::int64_t merge_lists(const Spheres& s, const PeriodicCell& cell,
                         const std::vector<std::vector<Candidate>>& per_sphere, double limit,
                         Contacts& c) {
  // Active contacts of the old list, sorted by key, to carry their history over.
  std::vector<std::size_t> old_active;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p]) old_active.push_back(p);
  }
  std::sort(old_active.begin(), old_active.end(),
            [&](std::size_t a, std::size_t b) { return key_of(c, a) < key_of(c, b); });

  // An active contact of the old list that the new one lacks is farther than r_i + r_j + skin:
  // no longer touching, it ends (the force pass would end it). Beyond r_i + r_j + `limit` (the
  // widest skin, the fixed skin's own) the spheres jumped farther in one list's life than any
  // list allows: a strain increment or a time step too large for the packing.
  const auto lost = [&](std::size_t o) {
    const auto i = static_cast<std::size_t>(c.i[o]);
    const auto j = static_cast<std::size_t>(c.j[o]);
    const Vec3i& k = c.k[o];
    const Vec3 d = s.x[j] + cell.h * k.cast<double>() - s.x[i];
    const double rl = s.r[i] + s.r[j] + limit;
    if (!(d.squaredNorm() < rl * rl)) {
      throw common::NumericalError(
          "dem: active contact lost by the neighbour search (pair " + std::to_string(i) + "-" +
          std::to_string(j) +
          "): spheres moved farther than the Verlet skin between two list builds (a strain "
          "increment or a time step too large for the packing)");
    }
  };
  Contacts fresh;
  std::size_t total = 0;
  for (const auto& v : per_sphere) total += v.size();
  fresh.resize(total);
  std::size_t p = 0;
  std::size_t q = 0;
  std::int64_t shell = 0;
  for (std::size_t i = 0; i < per_sphere.size(); ++i) {
    for (const Candidate& cd : per_sphere[i]) {
      shell += cd.shell ? 1 : 0;
      fresh.i[p] = static_cast<std::int32_t>(i);
      fresh.j[p] = cd.j;
      fresh.k[p] = cd.k;
      const Key kp = key_of(fresh, p);
      while (q < old_active.size() && key_of(c, old_active[q]) < kp) lost(old_active[q++]);
      if (q < old_active.size() && key_of(c, old_active[q]) == kp) {
        const std::size_t o = old_active[q++];
        fresh.active[p] = 1;
        fresh.tan_phi[p] = c.tan_phi[o];
        fresh.hist.set(p, c.hist.get(o));
        fresh.force[p] = c.force[o];
        fresh.torque_i[p] = c.torque_i[o];
        fresh.torque_j[p] = c.torque_j[o];
        fresh.branch[p] = c.branch[o];
      }
      ++p;
    }
  }
  while (q < old_active.size()) lost(old_active[q++]);
  fresh.build_sphere_lists(per_sphere.size());
  c = std::move(fresh);
  return shell;
}

}  // namespace

void build_pairs(const Spheres& s, const PeriodicCell& cell, Contacts& c, VerletState& vs) {
  vs.r_max = s.size() > 0 ? *std::max_element(s.r.begin(), s.r.end()) : 0.0;
  const Mat3 hinv = cell.h.inverse();
  const Bins bins = bin_spheres(s, cell, hinv, 2.0 * vs.r_max + vs.skin);
  const auto per_sphere = candidates(s, cell, bins, vs.skin);
  vs.shell_pairs = merge_lists(s, cell, per_sphere, std::max(vs.skin, vs.skin_max), c);
  vs.x_ref = s.x;
  vs.h_ref_inv = hinv;
  ++vs.builds;
}

bool needs_rebuild(const Spheres& s, const PeriodicCell& cell, const VerletState& vs) {
  return drift_measure(s, cell, vs) >= vs.skin;
}

double rebuild_measure(double amax2, const Mat3& f, double r_max, double skin) {
  const double eps = (f - Mat3::Identity()).norm();  // Frobenius >= spectral norm
  return 2.0 * std::sqrt(amax2) + eps * (2.0 * r_max + skin);
}

double drift_measure(const Spheres& s, const PeriodicCell& cell, const VerletState& vs) {
  if (vs.x_ref.size() != s.size()) return std::numeric_limits<double>::infinity();
  // Branch change of any pair: d = F d0 + (a_j - a_i), F = H H0^-1, a = x - F x0. A pair outside
  // the list had |d0| >= R_i + R_j + skin; it cannot touch while
  // 2 max|a| + ||F - I|| (2 r_max + skin) < skin.
  const Mat3 f = rebuild_deformation(cell, vs);
  return rebuild_measure(max_drift2_region(s, f, vs), f, vs.r_max, vs.skin);
}

double max_drift2_region(const Spheres& s, const Mat3& f, const VerletState& vs) {
  const auto n = static_cast<std::int64_t>(s.size());
  if (one_thread(n)) return max_drift2(s, f, vs);
  double amax2 = 0.0;
#pragma omp parallel for reduction(max : amax2) schedule(static) num_threads(team_size(n))
  for (std::int64_t i = 0; i < n; ++i) {
    amax2 = std::max(amax2, rebuild_drift2(s, f, vs, static_cast<std::size_t>(i)));
  }
  return amax2;
}

}  // namespace dem
