// Packing text format reader/writer and n x n x n tiling.
#include "dem/packing_io.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
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

}  // namespace

Packing read_packing(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw common::InputError(path + ": cannot open packing file");
  Packing pk;
  bool have_h = false;
  bool have_cell = false;
  std::string line;
  long ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    if (line.compare(first, 4, "CELL") == 0) {
      const auto v = numbers(path, ln, line.substr(first + 4), 3);
      for (double d : v) {
        if (!(d > 0.0)) fail(path, ln, "CELL sizes must be > 0");
      }
      if (!have_h) pk.cell.h = common::Vec3(v[0], v[1], v[2]).asDiagonal();
      have_cell = true;
    } else if (line.compare(first, 5, "HSIZE") == 0) {
      const auto v = numbers(path, ln, line.substr(first + 5), 9);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) pk.cell.h(a, b) = v[3 * a + b];
      }
      if (!(pk.cell.h.determinant() > 0.0)) fail(path, ln, "HSIZE must have det > 0");
      have_h = true;
    } else {
      if (!have_h && !have_cell) fail(path, ln, "sphere line before CELL/HSIZE");
      const auto v = numbers(path, ln, line, 4);
      if (!(v[3] > 0.0)) fail(path, ln, "radius must be > 0");
      pk.x.emplace_back(v[0], v[1], v[2]);
      pk.r.push_back(v[3]);
    }
  }
  if (!have_h && !have_cell) throw common::InputError(path + ": no CELL or HSIZE line");
  if (pk.r.empty()) throw common::InputError(path + ": no spheres");
  return pk;
}

void write_packing(const std::string& path, const Packing& pk, const std::string& comment) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw common::InputError(path + ": cannot write packing file");
  std::fprintf(f, "# mpmxdem packing, N %zu\n", pk.r.size());
  if (!comment.empty()) std::fprintf(f, "# %s\n", comment.c_str());
  const auto& h = pk.cell.h;
  std::fprintf(f, "CELL %.17g %.17g %.17g\n", h.col(0).norm(), h.col(1).norm(), h.col(2).norm());
  std::fprintf(f, "HSIZE");
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
