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

void ResultsWriter::write_xdmf() const {
  // Formatted with fmt and the row-invariant text prepared once: rewriting the index of a long
  // run (13,000 rows) with iostreams took 0.4 s per flush.
  const std::size_t m = point_ids_.size();
  const std::int64_t nt = rows_;
  struct Slab {
    std::string head;  ///< text before the row index
    std::string tail;  ///< text after it
  };
  // Xdmf3's hyperslab form "file:/dataset|start:stride:count:dims", which ParaView's default
  // reader (Xdmf3) reads; a HyperSlab DataItem with an XML selection (XDMF 2's form) gave it
  // empty grids (ParaView 5.11, issue 19). ParaView's legacy "XDMF Reader" does not read it.
  auto slab = [&](const char* ds, int per) {
    const std::string dims = per > 1 ? fmt::format("{} {}", m, per) : fmt::format("{}", m);
    Slab s;
    s.head = fmt::format(
        "<DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"8\" "
        "Format=\"HDF\">results.h5:/{}|",
        dims, ds);
    s.tail = per > 1 ? fmt::format(" 0 0:1 1 1:1 {0} {1}:{2} {0} {1}</DataItem>", m, per, nt)
                     : fmt::format(" 0:1 1:1 {0}:{1} {0}</DataItem>", m, nt);
    return s;
  };
  const Slab x = slab("points/x", 3);
  const Slab stress = slab("points/stress", 9);
  // Attributes by type: name in ParaView = the dataset's name under /points.
  const char* vectors[] = {"velocity", "displacement"};
  const char* tensors[] = {"F"};
  std::vector<Slab> vec;
  for (const char* a : vectors) vec.push_back(slab((std::string("points/") + a).c_str(), 3));
  std::vector<Slab> ten;
  for (const char* a : tensors) ten.push_back(slab((std::string("points/") + a).c_str(), 9));
  // The points' copies of the RVEs' per-step fields (farm::kReportFields), then their volume.
  std::vector<std::string> scalars;
  for (const ReportField& f : kReportFields) {
    if (f.point_description != nullptr) scalars.emplace_back(f.name);
  }
  scalars.emplace_back("volume");
  std::vector<Slab> sc;
  for (const std::string& a : scalars) sc.push_back(slab(("points/" + a).c_str(), 1));
  // The RVEs' grain-scale measures, where points and RVEs are one to one (the same ids in the
  // same order: every point a DEM point): ParaView colours the points by them.
  bool one_to_one = rve_ids_.size() == m;
  for (std::size_t k = 0; one_to_one && k < m; ++k) one_to_one = rve_of_point_[k] == k;
  std::vector<Slab> measures;  // one per farm::kMeasureFields row
  if (one_to_one) {
    for (const MeasureField& f : kMeasureFields) {
      measures.push_back(slab((std::string("rve/") + f.name).c_str(), f.components));
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
                   "<Geometry GeometryType=\"XYZ\">{}{}{}</Geometry>\n"
                   "<Attribute Name=\"stress\" AttributeType=\"Tensor\" Center=\"Node\">{}{}{}"
                   "</Attribute>\n",
                   steps_[tu], times_[tu], m, x.head, t, x.tail, stress.head, t, stress.tail);
    for (std::size_t a = 0; a < vec.size(); ++a) {
      fmt::format_to(it,
                     "<Attribute Name=\"{}\" AttributeType=\"Vector\" Center=\"Node\">{}{}{}"
                     "</Attribute>\n",
                     vectors[a], vec[a].head, t, vec[a].tail);
    }
    for (std::size_t a = 0; a < ten.size(); ++a) {
      fmt::format_to(it,
                     "<Attribute Name=\"{}\" AttributeType=\"Tensor\" Center=\"Node\">{}{}{}"
                     "</Attribute>\n",
                     tensors[a], ten[a].head, t, ten[a].tail);
    }
    for (std::size_t a = 0; a < sc.size(); ++a) {
      fmt::format_to(it,
                     "<Attribute Name=\"{}\" AttributeType=\"Scalar\" Center=\"Node\">{}{}{}"
                     "</Attribute>\n",
                     scalars[a], sc[a].head, t, sc[a].tail);
    }
    for (std::size_t a = 0; a < measures.size(); ++a) {
      const MeasureField& f = kMeasureFields[a];
      const char* type = f.components == 9 ? "Tensor" : f.components == 3 ? "Vector" : "Scalar";
      fmt::format_to(it,
                     "<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">{}{}{}"
                     "</Attribute>\n",
                     f.name, type, measures[a].head, t, measures[a].tail);
    }
    fmt::format_to(it, "{}</Grid>\n", id_attr);
  }
  fmt::format_to(it, "</Grid>\n</Domain>\n</Xdmf>\n");
  common::write_file_atomic(std::filesystem::path(dir_) / "points.xmf", fmt::to_string(out));
}

}  // namespace farm
