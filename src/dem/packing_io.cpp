// Packing text format reader/writer and n x n x n tiling.
#include "dem/packing_io.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "common/errors.hpp"

namespace dem {

namespace {

[[noreturn]] void fail(const std::string& path, long line, const std::string& what) {
  throw common::InputError(path + ":" + std::to_string(line) + ": " + what);
}

std::vector<double> numbers(const std::string& path, long line, const std::string& text,
                            std::size_t expected) {
  std::vector<double> v;
  std::istringstream is(text);
  std::string tok;
  while (is >> tok) {
    double d = 0.0;
    const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), d);
    if (res.ec != std::errc() || res.ptr != tok.data() + tok.size() || !std::isfinite(d)) {
      fail(path, line, "'" + tok + "' is not a finite number");
    }
    v.push_back(d);
  }
  if (v.size() != expected) {
    fail(path, line,
         "expected " + std::to_string(expected) + " numbers, found " + std::to_string(v.size()));
  }
  return v;
}

/// Where the cell directive of `line` starts: "CELL ..." / "HSIZE ..." as they are, or written as
/// a comment ("# CELL ...", the form write_packing uses, so that YADE's ymport.text reads the
/// spheres and skips the cell) when the rest is a number list. npos for a comment or a sphere.
std::size_t cell_directive(const std::string& line, std::size_t first) {
  auto keyword_at = [&](std::size_t at) {
    return line.compare(at, 4, "CELL") == 0 || line.compare(at, 5, "HSIZE") == 0;
  };
  if (line[first] != '#') return keyword_at(first) ? first : std::string::npos;
  const auto at = line.find_first_not_of(" \t", first + 1);
  if (at == std::string::npos || !keyword_at(at)) return std::string::npos;
  // A comment that happens to start with the word (e.g. "# CELL sizes in m") stays a comment.
  std::istringstream is(line.substr(at + (line.compare(at, 4, "CELL") == 0 ? 4 : 5)));
  std::string tok;
  std::size_t n = 0;
  while (is >> tok) {
    double d = 0.0;
    const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), d);
    if (res.ec != std::errc() || res.ptr != tok.data() + tok.size()) return std::string::npos;
    ++n;
  }
  return n == 3 || n == 9 ? at : std::string::npos;
}

}  // namespace

Packing read_packing(const std::string& path) { return read_packing(path, std::nullopt); }

namespace {

// Each cell line of a packing file (CELL, or HSIZE) against the job's cell (the same cell to
// 1e-9 or refused) and against the file's first cell line: every later cell line must give the
// same side lengths (YADE dumps carry both CELL and HSIZE).
class CellLines {
 public:
  CellLines(const std::string& path, const std::optional<common::Vec3>& cell)
      : path_(path), cell_(cell) {}

  void check(long at, const common::Mat3& h) {
    const common::Vec3 sizes(h.col(0).norm(), h.col(1).norm(), h.col(2).norm());
    if (cell_) {
      const common::Mat3 given = cell_->asDiagonal();
      if ((h - given).cwiseAbs().maxCoeff() > 1e-9 * given.cwiseAbs().maxCoeff()) {
        fail(path_, at,
             "this cell line disagrees with the job's cell (dem.sample.cell = [" + g((*cell_)[0]) +
                 ", " + g((*cell_)[1]) + ", " + g((*cell_)[2]) +
                 "] m): give the cell in one place only");
      }
    }
    if (first_line_ == 0) {
      first_line_ = at;
      first_sizes_ = sizes;
      return;
    }
    if ((sizes - first_sizes_).cwiseAbs().maxCoeff() > 1e-9 * first_sizes_.cwiseAbs().maxCoeff()) {
      fail(path_, at,
           "this cell line (side lengths " + g(sizes[0]) + ", " + g(sizes[1]) + ", " + g(sizes[2]) +
               " m) disagrees with the cell of line " + std::to_string(first_line_) + " (" +
               g(first_sizes_[0]) + ", " + g(first_sizes_[1]) + ", " + g(first_sizes_[2]) +
               " m): one cell per packing file");
    }
  }

 private:
  static std::string g(double v) {
    std::ostringstream os;
    os.precision(9);
    os << v;
    return os.str();
  }

  const std::string& path_;
  const std::optional<common::Vec3>& cell_;
  long first_line_ = 0;
  common::Vec3 first_sizes_ = common::Vec3::Zero();
};

// A sphere line came before any cell line (and the job gives none); yade_format: the line of
// YADE's "#format" header, 0 if none.
std::string no_cell_message(long yade_format) {
  std::string msg =
      "sphere line before any cell line: a packing file needs 'CELL Lx Ly Lz' (or 'HSIZE' + 9 "
      "numbers, the cell matrix row-major; both may be written as '# CELL ...' comments) before "
      "its spheres";
  if (yade_format > 0) {
    // YADE's text export (yade.export.text) writes the spheres only, never the cell.
    msg +=
        "; line " + std::to_string(yade_format) +
        " says this is a YADE text export (yade.export.text), which carries no cell: add the "
        "line '# CELL' + O.cell.size (or '# HSIZE' + O.cell.hSize) before the spheres, give the "
        "cell sizes in the job (dem.sample.cell = [Lx, Ly, Lz]), or export with "
        "tools/mpmxdem_tools/references/yade_export_packing.py (docs/validation/yade_reference.md)";
  }
  return msg;
}

}  // namespace

Packing read_packing(const std::string& path, const std::optional<common::Vec3>& cell) {
  std::ifstream in(path);
  if (!in) throw common::InputError(path + ": cannot open packing file");
  Packing pk;
  std::vector<long> lines;  // packing line of each sphere
  bool have_h = false;
  bool have_cell = false;
  if (cell) pk.cell.h = cell->asDiagonal();
  CellLines cell_lines(path, cell);
  long yade_format = 0;  // line of YADE's "#format x_y_z_r" (yade.export.text), 0: none
  std::string line;
  long ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line.compare(first, 7, "#format") == 0) yade_format = ln;
    if (line[first] == '#') {
      first = cell_directive(line, first);
      if (first == std::string::npos) continue;
    }
    if (line.compare(first, 4, "CELL") == 0) {
      const auto v = numbers(path, ln, line.substr(first + 4), 3);
      for (double d : v) {
        if (!(d > 0.0)) fail(path, ln, "CELL sizes must be > 0");
      }
      cell_lines.check(ln, common::Vec3(v[0], v[1], v[2]).asDiagonal());
      if (!have_h) pk.cell.h = common::Vec3(v[0], v[1], v[2]).asDiagonal();
      have_cell = true;
    } else if (line.compare(first, 5, "HSIZE") == 0) {
      const auto v = numbers(path, ln, line.substr(first + 5), 9);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) pk.cell.h(a, b) = v[3 * a + b];
      }
      if (!(pk.cell.h.determinant() > 0.0)) fail(path, ln, "HSIZE must have det > 0");
      cell_lines.check(ln, pk.cell.h);
      have_h = true;
    } else {
      if (!have_h && !have_cell && !cell) fail(path, ln, no_cell_message(yade_format));
      const auto v = numbers(path, ln, line, 4);
      if (!(v[3] > 0.0)) fail(path, ln, "radius must be > 0");
      pk.x.emplace_back(v[0], v[1], v[2]);
      pk.r.push_back(v[3]);
      lines.push_back(ln);
    }
  }
  if (!have_h && !have_cell && !cell) {
    throw common::InputError(path +
                             ": no CELL or HSIZE line (or give the cell in the job: "
                             "dem.sample.cell = [Lx, Ly, Lz])");
  }
  if (pk.r.empty()) throw common::InputError(path + ": no spheres");
  check_packing(pk, path, lines);
  return pk;
}

namespace {

std::string where(const std::string& source, const std::vector<long>& lines, std::size_t i) {
  return i < lines.size() ? source + ":" + std::to_string(lines[i])
                          : source + ": sphere " + std::to_string(i);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Two centres closer than half the sum of their radii (overlap beyond anything a packing at rest
// holds), found with bins of 2 r_max over the fractional coordinates (periodic images ignored: a
// check for degenerate input, not a contact search). Returns the pair, or n, n.
std::pair<std::size_t, std::size_t> coincident_pair(const Packing& pk, const common::Mat3& hinv) {
  const std::size_t n = pk.r.size();
  const double r_max = *std::max_element(pk.r.begin(), pk.r.end());
  std::array<long, 3> nb{};
  for (int a = 0; a < 3; ++a) {
    nb[static_cast<std::size_t>(a)] =
        std::clamp(static_cast<long>(pk.cell.width(a) / (2.0 * r_max)), 1L,
                   std::max(1L, static_cast<long>(std::cbrt(static_cast<double>(n))) + 1));
  }
  std::map<std::array<long, 3>, std::vector<std::size_t>> bins;
  std::vector<std::array<long, 3>> bin_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    const common::Vec3 s = hinv * pk.x[i];
    for (std::size_t a = 0; a < 3; ++a) {
      bin_of[i][a] = static_cast<long>(
          std::floor(s[static_cast<Eigen::Index>(a)] * static_cast<double>(nb[a])));
    }
    bins[bin_of[i]].push_back(i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (long dx = -1; dx <= 1; ++dx) {
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = bins.find({bin_of[i][0] + dx, bin_of[i][1] + dy, bin_of[i][2] + dz});
          if (it == bins.end()) continue;
          for (const std::size_t j : it->second) {
            if (j <= i) continue;
            if ((pk.x[i] - pk.x[j]).norm() < 0.5 * (pk.r[i] + pk.r[j])) return {i, j};
          }
        }
      }
    }
  }
  return {n, n};
}

}  // namespace

void check_packing(const Packing& pk, const std::string& source, const std::vector<long>& lines) {
  const std::size_t n = pk.r.size();
  auto bad = [&](std::size_t i, const std::string& what) {
    throw common::InputError(where(source, lines, i) + ": " + what);
  };
  if (n < 2) {
    throw common::InputError(source + ": " + std::to_string(n) +
                             " sphere(s): a packing needs at least 2 spheres");
  }
  const double det = pk.cell.h.determinant();
  if (!pk.cell.h.allFinite() || !(det > 0.0) || !std::isfinite(det)) {
    throw common::InputError(
        source + ": the cell matrix must be finite with a finite det > 0 (det " + num(det) + ")");
  }
  double w_min = pk.cell.width(0);
  for (int a = 1; a < 3; ++a) w_min = std::min(w_min, pk.cell.width(a));
  if (!(w_min > 0.0) || !std::isfinite(w_min)) {
    throw common::InputError(source + ": the cell's smallest width is " + num(w_min) +
                             " m: the cell matrix is too large or too small for double precision");
  }
  // A sphere far smaller than the largest is below the round-off of the contact geometry (the
  // overlap is a difference of lengths of the largest spheres' size) and would set the time step.
  constexpr double kMinRadiusRatio = 1e-6;
  double r_max = 0.0;
  for (const double r : pk.r) r_max = std::max(r_max, std::isfinite(r) ? r : 0.0);
  const common::Mat3 hinv = pk.cell.h.inverse();
  double solid = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!pk.x[i].allFinite()) bad(i, "the centre must be finite");
    if (!(std::isfinite(pk.r[i]) && pk.r[i] > 0.0))
      bad(i, "radius " + num(pk.r[i]) + " must be > 0 and finite");
    if (!(pk.r[i] >= kMinRadiusRatio * r_max)) {
      bad(i, "radius " + num(pk.r[i]) + " m is below 1e-6 times the largest radius (" + num(r_max) +
                 " m): a size ratio above 1e6 is below the round-off of the "
                 "contact geometry (radii in one unit?)");
    }
    if (!(2.0 * pk.r[i] < w_min)) {
      bad(i, "radius " + num(pk.r[i]) +
                 " m: the diameter must be below the cell's smallest width " + num(w_min) +
                 " m (a larger sphere touches its own periodic image; radii and cell "
                 "in the same unit?)");
    }
    const common::Vec3 s = hinv * pk.x[i];
    if ((s.array() < -1.0).any() || (s.array() > 2.0).any()) {
      bad(i, "centre (" + num(pk.x[i].x()) + ", " + num(pk.x[i].y()) + ", " + num(pk.x[i].z()) +
                 ") is " + num(std::max((-s.array()).maxCoeff(), s.array().maxCoeff() - 1.0)) +
                 " cell lengths outside the cell: centres must lie within one cell length of it "
                 "(not wrapped silently; centres and cell in the same unit?)");
    }
    solid += 4.0 / 3.0 * std::numbers::pi * pk.r[i] * pk.r[i] * pk.r[i];
  }
  const auto [a, b] = coincident_pair(pk, hinv);
  if (a < n) {
    bad(b, "the centre is " + num((pk.x[a] - pk.x[b]).norm()) +
               " m from the centre of the sphere at " + where(source, lines, a) +
               ": closer than half the sum of their radii (" + num(0.5 * (pk.r[a] + pk.r[b])) +
               " m): a degenerate packing (spheres at one point?)");
  }
  const double fraction = solid / pk.cell.volume();
  if (!(fraction >= 0.01 && fraction <= 1.0)) {
    throw common::InputError(source + ": solid volume fraction " + num(fraction) +
                             " (spheres over cell volume) must be in [0.01, 1]: radii and cell in "
                             "different units?");
  }
}

void write_packing(const std::string& path, const Packing& pk, const std::string& comment) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw common::InputError(path + ": cannot write packing file");
  std::fprintf(f, "# mpmxdem packing, N %zu\n", pk.r.size());
  if (!comment.empty()) std::fprintf(f, "# %s\n", comment.c_str());
  const auto& h = pk.cell.h;
  // The cell lines are written as comments: YADE's ymport.text reads the file as it is.
  std::fprintf(f, "# CELL %.17g %.17g %.17g\n", h.col(0).norm(), h.col(1).norm(), h.col(2).norm());
  std::fprintf(f, "# HSIZE");
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) std::fprintf(f, " %.17g", h(a, b));
  }
  std::fprintf(f, "\n# x y z r\n");
  for (std::size_t i = 0; i < pk.r.size(); ++i) {
    std::fprintf(f, "%.17g %.17g %.17g %.17g\n", pk.x[i].x(), pk.x[i].y(), pk.x[i].z(), pk.r[i]);
  }
  std::fclose(f);
}

Packing tile_packing(const Packing& pk, int n) { return tile_packing(pk, {n, n, n}); }

Packing tile_packing(const Packing& pk, const std::array<int, 3>& n) {
  for (const int k : n) {
    if (k < 1) throw common::InputError("dem: tile counts must be >= 1, got " + std::to_string(k));
  }
  Packing out;
  out.cell.h = pk.cell.h * common::Vec3(n[0], n[1], n[2]).asDiagonal();
  for (int c = 0; c < n[2]; ++c) {
    for (int b = 0; b < n[1]; ++b) {
      for (int a = 0; a < n[0]; ++a) {
        const common::Vec3 shift = pk.cell.h * common::Vec3(a, b, c);
        for (std::size_t i = 0; i < pk.r.size(); ++i) {
          out.x.push_back(pk.x[i] + shift);
          out.r.push_back(pk.r[i]);
        }
      }
    }
  }
  return out;
}

}  // namespace dem
