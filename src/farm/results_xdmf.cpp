// points.xmf of ResultsWriter: the XDMF 3 index of results.h5's point series for ParaView (see
// results.hpp and docs/reference/outputs.md).
#include <fmt/format.h>

#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "farm/results.hpp"

namespace farm {

namespace {

/// One row's DataItem of a point series, split around the row index.
struct Slab {
  std::string head;  ///< text before the row index
  std::string tail;  ///< text after it
};

/// The DataItem of row t of results.h5's dataset `ds` (m points of `per` values, nt rows), in
/// Xdmf3's hyperslab form "file:/dataset|start:stride:count:dims", which ParaView's default
/// reader (Xdmf3) reads; a HyperSlab DataItem with an XML selection (XDMF 2's form) gave it
/// empty grids (ParaView 5.11, issue 19). ParaView's legacy "XDMF Reader" does not read it.
Slab hyperslab(const char* ds, int per, std::size_t m, std::int64_t nt) {
  const std::string dims = per > 1 ? fmt::format("{} {}", m, per) : fmt::format("{}", m);
  Slab s;
  s.head = fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"8\" "
      "Format=\"HDF\">results.h5:/{}|",
      dims, ds);
  s.tail = per > 1 ? fmt::format(" 0 0:1 1 1:1 {0} {1}:{2} {0} {1}</DataItem>", m, per, nt)
                   : fmt::format(" 0:1 1:1 {0}:{1} {0}</DataItem>", m, nt);
  return s;
}

}  // namespace

void ResultsWriter::write_xdmf() const {
  // Formatted with fmt and the row-invariant text prepared once: rewriting the index of a long
  // run (13,000 rows) with iostreams took 0.4 s per flush.
  const std::size_t m = point_ids_.size();
  const std::int64_t nt = rows_;
  auto slab = [&](const char* ds, int per) { return hyperslab(ds, per, m, nt); };
  const Slab x = slab("points/x", 3);
  // Every attribute of a row, in the index's order: name in ParaView = the dataset's name.
  struct Attr {
    std::string name;
    const char* type;
    Slab slab;
  };
  std::vector<Attr> attrs;
  attrs.push_back({"stress", "Tensor", slab("points/stress", 9)});
  for (const char* a : {"velocity", "displacement"}) {
    attrs.push_back({a, "Vector", slab((std::string("points/") + a).c_str(), 3)});
  }
  attrs.push_back({"F", "Tensor", slab("points/F", 9)});
  // The points' copies of the RVEs' per-step fields (farm::kReportFields), then their volume.
  for (const ReportField& f : kReportFields) {
    if (f.point_description != nullptr) {
      attrs.push_back({f.name, "Scalar", slab((std::string("points/") + f.name).c_str(), 1)});
    }
  }
  attrs.push_back({"volume", "Scalar", slab("points/volume", 1)});
  // The RVEs' grain-scale measures, where points and RVEs are one to one (the same ids in the
  // same order: every point a DEM point): ParaView colours the points by them.
  bool one_to_one = rve_ids_.size() == m;
  for (std::size_t k = 0; one_to_one && k < m; ++k) one_to_one = rve_of_point_[k] == k;
  if (one_to_one) {
    for (const MeasureField& f : kMeasureFields) {
      const char* type = f.components == 9 ? "Tensor" : f.components == 3 ? "Vector" : "Scalar";
      attrs.push_back({f.name, type, slab((std::string("rve/") + f.name).c_str(), f.components)});
    }
  }
  const std::string id_attr = fmt::format(
      "<Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\"><DataItem "
      "Dimensions=\"{}\" NumberType=\"Int\" Precision=\"8\" "
      "Format=\"HDF\">results.h5:/points/id</DataItem></Attribute>\n",
      m);
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it,
                 "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
                 "<Grid Name=\"points\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (std::int64_t t = 0; t < nt; ++t) {
    const auto tu = static_cast<std::size_t>(t);
    fmt::format_to(it,
                   "<Grid Name=\"step_{}\" GridType=\"Uniform\">\n<Time Value=\"{:.17g}\"/>\n"
                   "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\"/>\n"
                   "<Geometry GeometryType=\"XYZ\">{}{}{}</Geometry>\n",
                   steps_[tu], times_[tu], m, x.head, t, x.tail);
    for (const Attr& a : attrs) {
      fmt::format_to(it,
                     "<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">{}{}{}"
                     "</Attribute>\n",
                     a.name, a.type, a.slab.head, t, a.slab.tail);
    }
    fmt::format_to(it, "{}</Grid>\n", id_attr);
  }
  fmt::format_to(it, "</Grid>\n</Domain>\n</Xdmf>\n");
  common::write_file_atomic(std::filesystem::path(dir_) / "points.xmf", fmt::to_string(out));
}

}  // namespace farm
