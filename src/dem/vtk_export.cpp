// VTK XML (ASCII) views of a periodic cell: see vtk_export.hpp and docs/design/dem.md.
#include "dem/vtk_export.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <type_traits>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "dem/measures.hpp"

namespace dem {

using common::Mat3;
using common::Vec3;

namespace {

/// The XML prolog and the opening VTKFile tag of a file of `type`.
std::string header(std::string_view type) {
  std::string h = "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  h += type;
  h += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  return h;
}

/// Appends a double with 17 significant digits (round trip exact).
void put(std::string& out, double v) {
  std::array<char, 32> buf{};
  const auto res =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  out.append(buf.data(), res.ptr);
}
void put(std::string& out, std::int64_t v) {
  std::array<char, 24> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  out.append(buf.data(), res.ptr);
}

/// One <DataArray> of n tuples of `comps` values; value(t, c) gives component c of tuple t.
template <class T, class F>
void data_array(std::string& out, const char* name, std::size_t n, int comps, F value) {
  out += "        <DataArray type=\"";
  out +=
      std::is_same_v<T, double> ? "Float64" : (std::is_same_v<T, std::uint8_t> ? "UInt8" : "Int64");
  out += "\"";
  if (name != nullptr) {
    out += " Name=\"";
    out += name;
    out += "\"";
  }
  if (comps > 1) {
    out += " NumberOfComponents=\"";
    put(out, std::int64_t{comps});
    out += "\"";
  }
  out += " format=\"ascii\">\n";
  for (std::size_t t = 0; t < n; ++t) {
    out += "         ";
    for (int c = 0; c < comps; ++c) {
      out += ' ';
      if constexpr (std::is_same_v<T, double>) {
        put(out, static_cast<double>(value(t, c)));
      } else {
        put(out, static_cast<std::int64_t>(value(t, c)));
      }
    }
    out += '\n';
  }
  out += "        </DataArray>\n";
}

void vec3_array(std::string& out, const char* name, const std::vector<Vec3>& v) {
  data_array<double>(out, name, v.size(), 3, [&v](std::size_t t, int c) { return v[t][c]; });
}
void scalar_array(std::string& out, const char* name, const std::vector<double>& v) {
  data_array<double>(out, name, v.size(), 1, [&v](std::size_t t, int) { return v[t]; });
}
void tensor_array(std::string& out, const char* name, const Mat3& m) {
  // Row-major, as VTK's 9-component tensors.
  data_array<double>(out, name, 1, 9, [&m](std::size_t, int c) { return m(c / 3, c % 3); });
}

/// Position x wrapped into the cell: fractional coordinates in [0, 1).
Vec3 wrapped(const Mat3& h, const Mat3& hinv, const Vec3& x) {
  const Vec3 s = hinv * x;
  const Vec3 m(std::floor(s[0]), std::floor(s[1]), std::floor(s[2]));
  return x - h * m;
}

std::string spheres_file(const Simulation& sim, const std::vector<Vec3>& xw) {
  const Spheres& s = sim.spheres();
  const Contacts& c = sim.contacts();
  const std::size_t n = s.size();
  const Mat3& l = sim.cell().l;
  std::vector<Vec3> velocity(n);
  for (std::size_t q = 0; q < n; ++q) velocity[q] = s.u[q] + l * xw[q];
  std::vector<std::int64_t> degree(n, 0);
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (!c.active[p]) continue;
    ++degree[static_cast<std::size_t>(c.i[p])];
    ++degree[static_cast<std::size_t>(c.j[p])];
  }
  std::string out = header("PolyData");
  out += "  <PolyData>\n    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfVerts=\"" +
         std::to_string(n) + "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  out += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  data_array<std::int64_t>(out, "id", n, 1, [](std::size_t t, int) { return t; });
  scalar_array(out, "radius", s.r);
  vec3_array(out, "velocity", velocity);
  vec3_array(out, "fluctuating_velocity", s.u);
  vec3_array(out, "spin", s.w);
  vec3_array(out, "force", s.force);
  vec3_array(out, "torque", s.torque);
  data_array<std::int64_t>(out, "contacts", n, 1,
                           [&degree](std::size_t t, int) { return degree[t]; });
  out += "      </PointData>\n      <Points>\n";
  vec3_array(out, nullptr, xw);
  out += "      </Points>\n      <Verts>\n";
  data_array<std::int64_t>(out, "connectivity", n, 1, [](std::size_t t, int) { return t; });
  data_array<std::int64_t>(out, "offsets", n, 1, [](std::size_t t, int) { return t + 1; });
  out += "      </Verts>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  return out;
}

std::string contacts_file(const Simulation& sim, const std::vector<Vec3>& xw) {
  const Spheres& s = sim.spheres();
  const Contacts& c = sim.contacts();
  const Mat3& h = sim.cell().h;
  std::vector<std::size_t> act;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (c.active[p]) act.push_back(p);
  }
  const std::size_t nc = act.size();
  std::vector<Vec3> ends(2 * nc);
  std::vector<Vec3> fn_vec(nc);
  std::vector<Vec3> shear(nc);
  std::vector<Vec3> force(nc);
  std::vector<Vec3> normal(nc);
  std::vector<Vec3> roll(nc);
  std::vector<Vec3> twist(nc);
  std::vector<double> fn(nc);
  std::vector<double> fs(nc);
  std::vector<double> overlap(nc);
  for (std::size_t k = 0; k < nc; ++k) {
    const std::size_t p = act[k];
    const auto i = static_cast<std::size_t>(c.i[p]);
    const auto j = static_cast<std::size_t>(c.j[p]);
    // The branch of the current positions (the image k carries the periodicity).
    const Vec3 d = s.x[j] + h * c.k[p].cast<double>() - s.x[i];
    ends[2 * k] = xw[i];
    ends[2 * k + 1] = xw[i] + d;
    const CohFrictHistory hist = c.hist.get(p);
    fn[k] = sim.normal_force(p);
    fn_vec[k] = fn[k] * hist.normal;
    shear[k] = hist.shear;
    fs[k] = hist.shear.norm();
    force[k] = c.force[p];
    normal[k] = hist.normal;
    roll[k] = hist.roll;
    twist[k] = hist.twist;
    overlap[k] = s.r[i] + s.r[j] - d.norm();
  }
  std::string out = header("PolyData");
  out += "  <PolyData>\n    <Piece NumberOfPoints=\"" + std::to_string(2 * nc) +
         "\" NumberOfVerts=\"0\" NumberOfLines=\"" + std::to_string(nc) +
         "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  out += "      <CellData Scalars=\"normal_force\" Vectors=\"normal_force_vector\">\n";
  data_array<std::int64_t>(out, "sphere1", nc, 1, [&](std::size_t t, int) { return c.i[act[t]]; });
  data_array<std::int64_t>(out, "sphere2", nc, 1, [&](std::size_t t, int) { return c.j[act[t]]; });
  scalar_array(out, "normal_force", fn);
  vec3_array(out, "normal_force_vector", fn_vec);
  vec3_array(out, "shear_force", shear);
  scalar_array(out, "shear_force_magnitude", fs);
  vec3_array(out, "force", force);
  vec3_array(out, "normal", normal);
  vec3_array(out, "rolling_moment", roll);
  vec3_array(out, "twisting_moment", twist);
  scalar_array(out, "overlap", overlap);
  out += "      </CellData>\n      <Points>\n";
  vec3_array(out, nullptr, ends);
  out += "      </Points>\n      <Lines>\n";
  data_array<std::int64_t>(out, "connectivity", 2 * nc, 1, [](std::size_t t, int) { return t; });
  data_array<std::int64_t>(out, "offsets", nc, 1, [](std::size_t t, int) { return 2 * (t + 1); });
  out += "      </Lines>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  return out;
}

std::string cell_file(const Simulation& sim) {
  const Mat3& h = sim.cell().h;
  const Measures m = measure(sim);
  // VTK_HEXAHEDRON (12) corner order: bottom face (z = 0) counter-clockwise, then the top face.
  constexpr std::array<std::array<int, 3>, 8> kCorners = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  std::vector<Vec3> corners(8);
  for (std::size_t a = 0; a < 8; ++a) {
    corners[a] = h * Vec3(kCorners[a][0], kCorners[a][1], kCorners[a][2]);
  }
  const auto one = [](double v) { return std::vector<double>{v}; };
  std::string out = header("UnstructuredGrid");
  out += "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n";
  out += "      <CellData Tensors=\"stress\">\n";
  tensor_array(out, "stress", m.stress);
  scalar_array(out, "p", one(m.p));
  scalar_array(out, "q", one(m.q));
  scalar_array(out, "void_ratio", one(m.void_ratio));
  scalar_array(out, "z", one(m.z));
  scalar_array(out, "z_mech", one(m.z_mech));
  tensor_array(out, "fabric", m.fabric);
  scalar_array(out, "unbalanced", one(m.unbalanced));
  scalar_array(out, "kinetic_energy", one(m.kinetic));
  scalar_array(out, "volume", one(sim.cell().volume()));
  out += "      </CellData>\n      <Points>\n";
  vec3_array(out, nullptr, corners);
  out += "      </Points>\n      <Cells>\n";
  data_array<std::int64_t>(out, "connectivity", 8, 1, [](std::size_t t, int) { return t; });
  data_array<std::int64_t>(out, "offsets", 1, 1, [](std::size_t, int) { return 8; });
  data_array<std::uint8_t>(out, "types", 1, 1, [](std::size_t, int) { return 12; });
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

std::string multiblock_file(const std::string& stem) {
  std::string out = header("vtkMultiBlockDataSet");
  out += "  <vtkMultiBlockDataSet>\n";
  const std::array<std::pair<const char*, const char*>, 3> blocks = {
      {{"spheres", "_spheres.vtp"}, {"contacts", "_contacts.vtp"}, {"cell", "_cell.vtu"}}};
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    out += "    <DataSet index=\"" + std::to_string(b) + "\" name=\"" + blocks[b].first +
           "\" file=\"" + stem + blocks[b].second + "\"/>\n";
  }
  out += "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
  return out;
}

}  // namespace

std::vector<VtkFile> vtk_view(const Simulation& sim, const std::string& stem) {
  MPMXDEM_CHECK(!stem.empty() && stem.find_first_of("/\"<>&") == std::string::npos,
                "vtk_view: stem '" + stem + "' must be a plain file name");
  const Mat3& h = sim.cell().h;
  const Mat3 hinv = h.inverse();
  const Spheres& s = sim.spheres();
  std::vector<Vec3> xw(s.size());
  for (std::size_t q = 0; q < s.size(); ++q) xw[q] = wrapped(h, hinv, s.x[q]);
  return {{stem + "_spheres.vtp", spheres_file(sim, xw)},
          {stem + "_contacts.vtp", contacts_file(sim, xw)},
          {stem + "_cell.vtu", cell_file(sim)},
          {stem + ".vtm", multiblock_file(stem)}};
}

std::string vtk_series(const std::vector<VtkSeriesEntry>& entries) {
  std::string out = header("Collection");
  out += "  <Collection>\n";
  for (const VtkSeriesEntry& e : entries) {
    MPMXDEM_CHECK(e.file.find_first_of("\"<>&") == std::string::npos,
                  "vtk_series: file name '" + e.file + "'");
    out += "    <DataSet timestep=\"";
    put(out, e.time);
    out += "\" part=\"0\" file=\"" + e.file + "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

std::vector<VtkSeriesEntry> read_vtk_series(const std::string& text, const std::string& what) {
  const auto bad = [&what](const std::string& why) {
    return common::InputError(what + ": not a time series written by mpmxdem inspect (" + why +
                              "); remove it or choose another directory");
  };
  if (text.find("<VTKFile type=\"Collection\"") == std::string::npos ||
      text.find("</Collection>") == std::string::npos) {
    throw bad("no VTKFile of type Collection");
  }
  const auto attribute = [&](std::size_t from, std::size_t to, const std::string& name) {
    const std::size_t a = text.find(" " + name + "=\"", from);
    if (a == std::string::npos || a > to) throw bad("a DataSet without " + name);
    const std::size_t b = a + name.size() + 3;
    const std::size_t e = text.find('"', b);
    if (e == std::string::npos || e > to) throw bad("a DataSet without " + name);
    return text.substr(b, e - b);
  };
  std::vector<VtkSeriesEntry> out;
  for (std::size_t at = text.find("<DataSet"); at != std::string::npos;
       at = text.find("<DataSet", at + 1)) {
    const std::size_t end = text.find("/>", at);
    if (end == std::string::npos) throw bad("an unterminated DataSet");
    VtkSeriesEntry e;
    const std::string t = attribute(at, end, "timestep");
    const auto res = std::from_chars(t.data(), t.data() + t.size(), e.time);
    if (res.ec != std::errc() || res.ptr != t.data() + t.size()) throw bad("timestep '" + t + "'");
    e.file = attribute(at, end, "file");
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<VtkSeriesEntry> read_vtk_series_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return {};
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) {
    throw common::InputError("cannot read the time series '" + path.string() +
                             "': " + std::strerror(errno));
  }
  return read_vtk_series(text, path.string());
}

std::string rve_view_stem(std::int64_t id, std::int64_t step) {
  return "rve_" + std::to_string(id) + "_step_" + std::to_string(step);
}

std::string rve_series_name(std::int64_t id) { return "rve_" + std::to_string(id) + ".pvd"; }

std::vector<VtkSeriesEntry> merge_vtk_series(std::vector<VtkSeriesEntry> entries,
                                             const VtkSeriesEntry& add) {
  std::erase_if(entries, [&add](const VtkSeriesEntry& e) { return e.file == add.file; });
  entries.push_back(add);
  std::sort(entries.begin(), entries.end(), [](const VtkSeriesEntry& a, const VtkSeriesEntry& b) {
    return a.time != b.time ? a.time < b.time : a.file < b.file;
  });
  return entries;
}

void write_vtk_files(const std::filesystem::path& dir, const std::vector<VtkFile>& files) {
  std::vector<std::filesystem::path> staged;
  try {
    for (const VtkFile& f : files) {
      const std::filesystem::path tmp = common::staging_path(dir / f.name);
      staged.push_back(tmp);
      std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
      if (os) os.write(f.text.data(), static_cast<std::streamsize>(f.text.size()));
      if (os) os.close();
      if (!os) {
        throw common::IoError("cannot write '" + tmp.string() + "': " + std::strerror(errno));
      }
    }
  } catch (...) {
    std::error_code ec;
    for (const auto& t : staged) std::filesystem::remove(t, ec);
    throw;
  }
  for (std::size_t k = 0; k < files.size(); ++k)
    common::publish_file(staged[k], dir / files[k].name);
}

}  // namespace dem
