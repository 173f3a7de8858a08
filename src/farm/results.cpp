// results.h5 / points.xmf / means.csv writer (see header and docs/reference/outputs.md).
#include "farm/results.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/tensor.hpp"
#include "farm/placement.hpp"
#include "farm/results_layout.hpp"

namespace farm {

using h5::check;
using h5::Handle;
using results_detail::describe;
using results_detail::put_attr;
using results_detail::read_rows;
using results_detail::row_dims;
using results_detail::write_static;
using results_detail::writer_access;

struct ResultsWriter::Series {
  Handle dset;
  std::vector<hsize_t> row;
  hid_t type = H5T_NATIVE_DOUBLE;
  std::size_t row_bytes = 0;  ///< one row's values (8 bytes each)
  std::vector<char> pending;  ///< rows appended but not written yet, in order
  void set_layout(const SeriesSpec& spec, std::size_t n_rve, std::size_t n_pts,
                  std::size_t n_con = 0) {
    row = row_dims(spec, n_rve, n_pts, n_con);
    type = spec.integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
    row_bytes = 8;
    for (const hsize_t r : row) row_bytes *= static_cast<std::size_t>(r);
  }
};

SampleMeans sample_means(const mpm::MaterialPoints& points, const std::vector<MicroReport>& reports,
                         int axial_axis) {
  SampleMeans m;
  double faa = 0.0;
  double v = 0.0;
  double v0 = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    faa += points.F[p](axial_axis, axial_axis);
    v += points.volume[p];
    v0 += points.volume0[p];
  }
  if (points.size() > 0) {
    m.eps_ax = 1.0 - faa / static_cast<double>(points.size());
    m.eps_v = v0 > 0.0 ? 1.0 - v / v0 : 0.0;
  }
  for (const MicroReport& r : reports) {
    m.p += r.p;
    m.q += r.q;
  }
  if (!reports.empty()) {
    m.p /= static_cast<double>(reports.size());
    m.q /= static_cast<double>(reports.size());
  }
  return m;
}

ResultsWriter::ResultsWriter(const std::string& dir, const std::vector<std::int64_t>& rve_ids,
                             const mpm::MaterialPoints& points, std::int64_t restart_step,
                             std::vector<std::string> constraint_names,
                             const mpm::MaterialPoints* initial)
    : dir_(dir),
      rve_ids_(rve_ids),
      point_ids_(points.id),
      constraint_names_(std::move(constraint_names)) {
  h5::silence_errors();
  const PointIndex index(rve_ids_, point_ids_);  // every point has an RVE (checked)
  for (std::size_t p = 0; p < index.size(); ++p) rve_of_point_.push_back(index.rve_of(p));
  // x0 of /points/displacement by slot: the initial points' position of the same id (NaN for an
  // id they lack), or without them the positions now.
  x0_ = points.x;
  if (initial != nullptr) {
    std::map<std::int64_t, common::Vec3> at;
    for (std::size_t p = 0; p < initial->size(); ++p) at[initial->id[p]] = initial->x[p];
    for (std::size_t p = 0; p < x0_.size(); ++p) {
      const auto it = at.find(point_ids_[p]);
      x0_[p] = it != at.end() ? it->second
                              : common::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  const std::string path = (std::filesystem::path(dir) / "results.h5").string();
  const std::size_t n = rve_ids_.size();
  const std::size_t m = point_ids_.size();
  // HDF5 must not meet a full disk with metadata of its own to flush: a failed H5Fclose leaves a
  // file that HDF5's termination (at MPI_Finalize) crashes on (SIGSEGV instead of exit 4). So
  // room is reserved before the file is opened or created, and its metadata is on disk before
  // the first row (common::reserve_space; write_pending and flush do the same).
  common::reserve_space(path, kReserveSlack);
  if (restart_step >= 0 && std::filesystem::exists(path)) {
    file_ = Handle(H5Fopen(path.c_str(), H5F_ACC_RDWR, writer_access().get()), H5Fclose);
    if (!file_.valid()) throw common::InputError("output " + path + ": cannot reopen as HDF5");
    Handle sd(H5Dopen2(file_.get(), "/step", H5P_DEFAULT), H5Dclose);
    if (!sd.valid()) throw common::InputError("output " + path + ": dataset /step is missing");
    Handle ss(H5Dget_space(sd.get()), H5Sclose);
    hsize_t nt[1] = {0};
    H5Sget_simple_extent_dims(ss.get(), nt, nullptr);
    const auto steps = read_rows<std::int64_t>(file_.get(), "/step", nt[0]);
    hsize_t keep = 0;
    while (keep < nt[0] && steps[keep] <= restart_step) ++keep;
    for (const SeriesSpec& s : results_detail::series()) {
      auto se = std::make_unique<Series>();
      se->set_layout(s, n, m);
      if (results_detail::added_later(s.name) && H5Lexists(file_.get(), s.name, H5P_DEFAULT) <= 0) {
        create_nan_series(s, keep);  // added after format 1's first files (issues 15, 19)
        continue;
      }
      se->dset = Handle(H5Dopen2(file_.get(), s.name, H5P_DEFAULT), H5Dclose);
      if (!se->dset.valid()) {
        throw common::InputError("output " + path + ": dataset /" + std::string(s.name) +
                                 " is missing (not a results file of this program)");
      }
      std::vector<hsize_t> dims{keep};
      dims.insert(dims.end(), se->row.begin(), se->row.end());
      check(H5Dset_extent(se->dset.get(), dims.data()), std::string("truncate ") + s.name);
      series_[s.name] = std::move(se);
    }
    rows_ = static_cast<std::int64_t>(keep);
    steps_.assign(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(keep));
    times_ = read_rows<double>(file_.get(), "/time", keep);
    const auto ea = read_rows<double>(file_.get(), "/means/eps_ax", keep);
    const auto ev = read_rows<double>(file_.get(), "/means/eps_v", keep);
    const auto mp = read_rows<double>(file_.get(), "/means/p", keep);
    const auto mq = read_rows<double>(file_.get(), "/means/q", keep);
    for (hsize_t t = 0; t < keep; ++t) means_.push_back({ea[t], ev[t], mp[t], mq[t]});
    open_constraints(keep);
    describe(file_.get());  // a file of an earlier version gets them; software_version: this one
    describe_constraints();
    check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "H5Fflush " + path);
    return;
  }
  file_ =
      Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, writer_access().get()), H5Fclose);
  if (!file_.valid()) throw common::IoError("output " + path + ": HDF5 cannot create it");
  write_static(file_.get(), "/rve/id", rve_ids_);
  write_static(file_.get(), "/points/id", point_ids_);
  for (const SeriesSpec& s : results_detail::series()) create_series(s);
  if (!constraint_names_.empty()) {
    for (const SeriesSpec& s : results_detail::constraint_series()) create_series(s);
  }
  describe(file_.get());
  describe_constraints();
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "H5Fflush " + path);
}

void ResultsWriter::create_series(const SeriesSpec& s) {
  auto se = std::make_unique<Series>();
  se->set_layout(s, rve_ids_.size(), point_ids_.size(), constraint_names_.size());
  std::vector<hsize_t> dims{0};
  std::vector<hsize_t> maxd{H5S_UNLIMITED};
  // Chunks of many rows (up to kRowsPerWrite, at most ~1 MB): one chunk per row made every
  // block write and every H5Fflush touch thousands of chunks in a long run.
  const hsize_t rows_per_chunk =
      s.over == '-' ? 256
                    : std::clamp<hsize_t>((1u << 20) / std::max<std::size_t>(se->row_bytes, 1), 1,
                                          static_cast<hsize_t>(kRowsPerWrite));
  std::vector<hsize_t> chunk{rows_per_chunk};
  for (hsize_t r : se->row) {
    dims.push_back(r);
    maxd.push_back(r);
    chunk.push_back(std::max<hsize_t>(1, r));
  }
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxd.data()),
                     "H5Screate_simple"),
               H5Sclose);
  Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
  check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "H5Pset_chunk");
  Handle lcpl(check(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate"), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  se->dset =
      Handle(check(H5Dcreate2(file_.get(), s.name, s.integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE,
                              space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT),
                   std::string("create ") + s.name),
             H5Dclose);
  series_[s.name] = std::move(se);
}

void ResultsWriter::create_nan_series(const SeriesSpec& s, std::uint64_t keep) {
  create_series(s);
  Series& se = *series_.at(s.name);
  std::vector<hsize_t> dims{keep};
  dims.insert(dims.end(), se.row.begin(), se.row.end());
  check(H5Dset_extent(se.dset.get(), dims.data()), std::string("extend ") + s.name);
  if (keep == 0) return;
  const std::vector<double> nan(keep * se.row_bytes / 8, std::numeric_limits<double>::quiet_NaN());
  check(H5Dwrite(se.dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, nan.data()),
        std::string("write ") + s.name);
}

void ResultsWriter::open_constraints(std::uint64_t keep) {
  if (constraint_names_.empty()) return;
  const std::size_t nc = constraint_names_.size();
  for (const SeriesSpec& s : results_detail::constraint_series()) {
    if (H5Lexists(file_.get(), "constraints", H5P_DEFAULT) <= 0 ||
        H5Lexists(file_.get(), s.name, H5P_DEFAULT) <= 0) {
      // A file of an earlier version: the rows before the restart have no constraint data (NaN).
      create_nan_series(s, keep);
    } else {
      auto se = std::make_unique<Series>();
      se->set_layout(s, rve_ids_.size(), point_ids_.size(), nc);
      se->dset = Handle(H5Dopen2(file_.get(), s.name, H5P_DEFAULT), H5Dclose);
      Handle fs(H5Dget_space(se->dset.get()), H5Sclose);
      hsize_t d[3] = {0, 0, 0};
      if (H5Sget_simple_extent_ndims(fs.get()) != 3 ||
          (H5Sget_simple_extent_dims(fs.get(), d, nullptr), d[1] != nc)) {
        throw common::InputError("output results.h5: /" + std::string(s.name) + " does not hold " +
                                 std::to_string(nc) +
                                 " constraints (the job's [[mpm.velocity]] changed?)");
      }
      const std::vector<hsize_t> dims{keep, nc, 3};
      check(H5Dset_extent(se->dset.get(), dims.data()), std::string("truncate ") + s.name);
      series_[s.name] = std::move(se);
    }
  }
  // The kept rows, for reactions.csv.
  auto read = [&](const char* name) {
    std::vector<double> v(keep * nc * 3);
    if (keep > 0) {
      check(H5Dread(series_.at(name)->dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                    v.data()),
            std::string("read ") + name);
    }
    return v;
  };
  const std::vector<double> r = read("constraints/reaction");
  const std::vector<double> u = read("constraints/displacement");
  for (std::size_t t = 0; t < keep; ++t) {
    std::vector<double> row;
    for (std::size_t k = 0; k < nc; ++k) {
      for (std::size_t a = 0; a < 3; ++a) row.push_back(r[(t * nc + k) * 3 + a]);
      for (std::size_t a = 0; a < 3; ++a) row.push_back(u[(t * nc + k) * 3 + a]);
    }
    constraint_rows_.push_back(std::move(row));
  }
}

void ResultsWriter::describe_constraints() {
  if (constraint_names_.empty()) return;
  for (const SeriesSpec& s : results_detail::constraint_series()) {
    Handle d(check(H5Dopen2(file_.get(), s.name, H5P_DEFAULT), std::string("open ") + s.name),
             H5Dclose);
    put_attr(d.get(), "unit", std::string(s.unit));
    put_attr(d.get(), "description", std::string(s.description));
  }
  Handle g(check(H5Gopen2(file_.get(), "constraints", H5P_DEFAULT), "open /constraints"), H5Gclose);
  put_attr(g.get(), "names", fmt::format("{}", fmt::join(constraint_names_, ",")));
  put_attr(g.get(), "description",
           std::string("velocity constraints ([[mpm.velocity]] of the job, in order); names: "
                       "comma-separated, the columns of reactions.csv"));
}

ResultsWriter::~ResultsWriter() {
  // A run that stops on an error keeps the rows of the steps it completed, and its indexes
  // (points.xmf, means.csv, reactions.csv) list them: a user reads a failed run's last rows where
  // a finished run's are.
  try {
    write_pending();
  } catch (const std::exception& e) {
    std::cerr << "results.h5: " << pending_ << " row(s) could not be written: " << e.what() << "\n";
    return;
  }
  if (indexed_rows_ == rows()) return;
  try {
    write_xdmf();
    write_csv();
  } catch (const std::exception& e) {
    std::cerr << "results: the indexes of " << dir_ << " could not be rewritten: " << e.what()
              << "\n";
  }
}

void ResultsWriter::stage_row(const std::string& name, const void* data) {
  Series& s = *series_.at(name);
  const auto* b = static_cast<const char*>(data);
  s.pending.insert(s.pending.end(), b, b + s.row_bytes);
  pending_bytes_ += s.row_bytes;
}

void ResultsWriter::write_pending() {
  if (pending_ == 0) return;
  // HDF5 must not meet a full disk half-way (common::reserve_space): room for the rows as they
  // are (deflate hardly grows them) and for the chunk index and metadata they add.
  common::reserve_space(std::filesystem::path(dir_) / "results.h5", pending_bytes_ + kReserveSlack);
  const auto first = static_cast<hsize_t>(rows_);
  const auto count0 = static_cast<hsize_t>(pending_);
  for (auto& [name, sp] : series_) {
    Series& s = *sp;
    std::vector<hsize_t> dims{first + count0};
    dims.insert(dims.end(), s.row.begin(), s.row.end());
    check(H5Dset_extent(s.dset.get(), dims.data()), "extend " + name);
    Handle fs(H5Dget_space(s.dset.get()), H5Sclose);
    std::vector<hsize_t> start(dims.size(), 0);
    start[0] = first;
    std::vector<hsize_t> count = dims;
    count[0] = count0;
    check(
        H5Sselect_hyperslab(fs.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select " + name);
    Handle ms(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
    check(H5Dwrite(s.dset.get(), s.type, ms.get(), fs.get(), H5P_DEFAULT, s.pending.data()),
          "write " + name);
    s.pending.clear();
  }
  rows_ += pending_;
  pending_ = 0;
  pending_bytes_ = 0;
  // On disk after every block: a reader that opens the file now sees every row written so far.
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "H5Fflush " + dir_ + "/results.h5");
}

void ResultsWriter::stage_constraints(const std::vector<common::Vec3>& reactions,
                                      const std::vector<common::Vec3>& displacements) {
  if (constraint_names_.empty()) return;
  const std::size_t nc = constraint_names_.size();
  MPMXDEM_CHECK(reactions.size() == nc && displacements.size() == nc,
                "one reaction and one displacement per constraint");
  std::vector<double> r(3 * nc);
  std::vector<double> u(3 * nc);
  std::vector<double> row;
  for (std::size_t k = 0; k < nc; ++k) {
    for (int a = 0; a < 3; ++a) {
      r[3 * k + static_cast<std::size_t>(a)] = reactions[k][a];
      u[3 * k + static_cast<std::size_t>(a)] = displacements[k][a];
    }
    row.insert(row.end(), {reactions[k][0], reactions[k][1], reactions[k][2]});
    row.insert(row.end(), {displacements[k][0], displacements[k][1], displacements[k][2]});
  }
  stage_row("constraints/reaction", r.data());
  stage_row("constraints/displacement", u.data());
  constraint_rows_.push_back(std::move(row));
}

void ResultsWriter::stage_rves(const std::vector<common::Mat3>& rve_stress,
                               const std::vector<MicroReport>& reports,
                               const std::vector<MicroMeasures>& measures) {
  const std::size_t n = rve_ids_.size();
  const std::size_t m = point_ids_.size();
  auto mat9 = [](const common::Mat3& a, double* out) { common::row_major_out(out) = a; };
  std::vector<double> buf(9 * n);
  for (std::size_t k = 0; k < n; ++k) mat9(rve_stress[k], buf.data() + 9 * k);
  stage_row("rve/stress", buf.data());
  // The per-step fields (farm::kReportFields): /rve/<name>, and the points' copy where it has one.
  auto stage_report = [&](const ReportField& f, auto get) {
    std::vector<decltype(get(reports[0]))> v(n);
    for (std::size_t k = 0; k < n; ++k) v[k] = get(reports[k]);
    stage_row(std::string("rve/") + f.name, v.data());
    if (f.point_description == nullptr) return;
    decltype(v) w(m);
    for (std::size_t p = 0; p < m; ++p) w[p] = v[rve_of_point_[p]];
    stage_row(std::string("points/") + f.name, w.data());
  };
  for (const ReportField& f : kReportFields) {
    if (f.type == ReportType::real) {
      stage_report(f, [&f](const MicroReport& r) { return report_real(r, f); });
    } else {
      stage_report(f, [&f](const MicroReport& r) { return report_int(r, f); });
    }
  }
  // Grain-scale measures (RveFarm::measure, for output rows only); NaN when not given.
  MPMXDEM_CHECK(measures.empty() || measures.size() == n, "one MicroMeasures per RVE");
  for (const MeasureField& f : kMeasureFields) {
    const auto c = static_cast<std::size_t>(f.components);
    std::vector<double> v(c * n);
    for (std::size_t k = 0; k < n; ++k) {
      const MicroMeasures mm = measures.empty() ? MicroMeasures::none() : measures[k];
      const std::span<const double> src = values(mm, f);
      std::copy(src.begin(), src.end(), v.begin() + static_cast<std::ptrdiff_t>(c * k));
    }
    stage_row(std::string("rve/") + f.name, v.data());
  }
}

void ResultsWriter::stage_points(const mpm::MaterialPoints& points) {
  const std::size_t m = point_ids_.size();
  auto mat9 = [](const common::Mat3& a, double* out) { common::row_major_out(out) = a; };
  std::vector<double> buf(9 * m);
  std::vector<double> x(3 * m);
  for (std::size_t p = 0; p < m; ++p) {
    for (int a = 0; a < 3; ++a) x[3 * p + static_cast<std::size_t>(a)] = points.x[p][a];
  }
  stage_row("points/x", x.data());
  for (std::size_t p = 0; p < m; ++p) mat9(points.stress[p], buf.data() + 9 * p);
  stage_row("points/stress", buf.data());
  stage_row("points/volume", points.volume.data());
  for (std::size_t p = 0; p < m; ++p) {
    for (int a = 0; a < 3; ++a) x[3 * p + static_cast<std::size_t>(a)] = points.v[p][a];
  }
  stage_row("points/velocity", x.data());
  for (std::size_t p = 0; p < m; ++p) {
    for (int a = 0; a < 3; ++a) {
      x[3 * p + static_cast<std::size_t>(a)] = points.x[p][a] - x0_[p][a];
    }
  }
  stage_row("points/displacement", x.data());
  for (std::size_t p = 0; p < m; ++p) mat9(points.F[p], buf.data() + 9 * p);
  stage_row("points/F", buf.data());
}

void ResultsWriter::append(std::int64_t step, double time,
                           const std::vector<common::Mat3>& rve_stress,
                           const std::vector<MicroReport>& reports,
                           const mpm::MaterialPoints& points, const SampleMeans& means,
                           const std::vector<common::Vec3>& reactions,
                           const std::vector<common::Vec3>& displacements,
                           const std::vector<MicroMeasures>& measures) {
  MPMXDEM_CHECK(points.id == point_ids_, "material point ids or order changed during the run");
  stage_constraints(reactions, displacements);
  stage_row("time", &time);
  stage_row("step", &step);
  stage_rves(rve_stress, reports, measures);
  stage_points(points);
  stage_row("means/eps_ax", &means.eps_ax);
  stage_row("means/eps_v", &means.eps_v);
  stage_row("means/p", &means.p);
  stage_row("means/q", &means.q);
  ++pending_;
  steps_.push_back(step);
  times_.push_back(time);
  means_.push_back({means.eps_ax, means.eps_v, means.p, means.q});
  // Rows are written in blocks: one HDF5 extend + write per series for many rows (a row of its
  // own cost ~0.15-0.2 ms, 3 % of an MPM step of the paper's job at one row per 10 steps).
  if (pending_ >= kRowsPerWrite || pending_bytes_ >= kBytesPerWrite) write_pending();
}

void ResultsWriter::flush(bool indexes) {
  if (pending_ > 0) {
    write_pending();  // flushes results.h5
  } else {
    common::reserve_space(std::filesystem::path(dir_) / "results.h5", kReserveSlack);
    check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "H5Fflush " + dir_ + "/results.h5");
  }
  // points.xmf and means.csv are rewritten whole (atomic rename): O(rows), 0.4 s at 13,000 rows
  // on these machines. Unless asked for, at most 1 / kIndexShare times their last cost apart.
  const auto now = std::chrono::steady_clock::now();
  if (!indexes &&
      std::chrono::duration<double>(now - index_written_).count() * kIndexShare < index_cost_s_) {
    return;
  }
  write_xdmf();
  write_csv();
  indexed_rows_ = rows();
  index_written_ = std::chrono::steady_clock::now();
  index_cost_s_ = std::chrono::duration<double>(index_written_ - now).count();
}

void ResultsWriter::write_csv() const {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  // The first line is the header (pandas, csv.DictReader, numpy.genfromtxt(names=True) and
  // ParaView's CSV reader take it so); units are the names' suffixes (_s, _Pa; strains are [-]).
  // Definitions and sign conventions: the attributes of /means/* in results.h5,
  // docs/design/farm.md.
  fmt::format_to(it, "{}\n", kMeansCsvHeader);
  for (std::size_t t = 0; t < steps_.size(); ++t) {
    const std::array<double, 4>& m = means_[t];
    fmt::format_to(it, "{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", steps_[t], times_[t], m[0],
                   m[1], m[2], m[3]);
  }
  common::write_file_atomic(std::filesystem::path(dir_) / "means.csv", fmt::to_string(out));
  if (constraint_names_.empty()) return;
  // reactions.csv: the same rows; per constraint its reaction [N] and displacement [m].
  fmt::memory_buffer rc;
  auto ri = std::back_inserter(rc);
  fmt::format_to(ri, "step,time_s");
  for (const std::string& n : constraint_names_) {
    fmt::format_to(ri, ",{0}_rx_N,{0}_ry_N,{0}_rz_N,{0}_ux_m,{0}_uy_m,{0}_uz_m", n);
  }
  fmt::format_to(ri, "\n");
  for (std::size_t t = 0; t < steps_.size() && t < constraint_rows_.size(); ++t) {
    fmt::format_to(ri, "{},{:.17g}", steps_[t], times_[t]);
    for (const double v : constraint_rows_[t]) fmt::format_to(ri, ",{:.17g}", v);
    fmt::format_to(ri, "\n");
  }
  common::write_file_atomic(std::filesystem::path(dir_) / "reactions.csv", fmt::to_string(rc));
}

}  // namespace farm
