// Per-step cost trace (see header).
#include "farm/cost_trace.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <utility>

#include "common/errors.hpp"

namespace farm {

namespace {

constexpr const char* kHeader = "step,rve,id,rank,cpu_s,busy_s,dem_steps,rebuilds";

std::string reason() { return errno != 0 ? std::strerror(errno) : "unknown reason"; }

/// The fields of one CSV line; false if a field is not a number.
bool split_numbers(const std::string& line, std::vector<double>& out) {
  out.clear();
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) {
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0') return false;
    out.push_back(v);
  }
  return true;
}

common::InputError bad_row(const std::string& file, std::size_t line_no, const std::string& rule) {
  return common::InputError(fmt::format("cost trace {}, line {}: {}", file, line_no, rule));
}

/// `path`.graph.csv: rows for every RVE up to the largest index seen (RVEs without neighbours
/// have none).
RveGraph read_trace_graph(const std::string& gpath) {
  std::ifstream g(gpath);
  if (!g) throw common::IoError("cost trace " + gpath + ": cannot read: " + reason());
  std::map<std::size_t, std::vector<std::int64_t>> adj;
  std::vector<double> f;
  std::string line;
  std::size_t no = 0;
  while (std::getline(g, line)) {
    if (++no == 1) continue;
    if (!split_numbers(line, f) || f.size() != 2 || f[0] < 0 || f[1] < 0)
      throw bad_row(gpath, no, "expected 'rve,neighbour' (two indices >= 0)");
    adj[static_cast<std::size_t>(f[0])].push_back(static_cast<std::int64_t>(f[1]));
  }
  RveGraph graph;
  graph.xadj.push_back(0);
  const std::size_t n_graph = adj.empty() ? 0 : adj.rbegin()->first + 1;
  for (std::size_t k = 0; k < n_graph; ++k) {
    const auto it = adj.find(k);
    if (it != adj.end())
      graph.adjncy.insert(graph.adjncy.end(), it->second.begin(), it->second.end());
    graph.xadj.push_back(static_cast<std::int64_t>(graph.adjncy.size()));
  }
  return graph;
}

/// `path`.start.csv: the start-up weights by RVE index.
std::vector<double> read_trace_start(const std::string& spath) {
  std::ifstream w(spath);
  if (!w) throw common::IoError("cost trace " + spath + ": cannot read: " + reason());
  std::vector<double> weight;
  std::vector<double> f;
  std::string line;
  std::size_t no = 0;
  while (std::getline(w, line)) {
    if (++no == 1) continue;
    if (!split_numbers(line, f) || f.size() != 3 || f[0] != static_cast<double>(no - 2) ||
        !(f[2] >= 0))
      throw bad_row(spath, no, "expected 'rve,id,weight' with rve = 0, 1, ... and weight >= 0");
    weight.push_back(f[2]);
  }
  return weight;
}

}  // namespace

std::string cost_trace_path_from_env() {
  const char* env = std::getenv("MPMXDEM_COST_TRACE");
  return env == nullptr ? std::string() : std::string(env);
}

CostTrace::CostTrace(std::string path, const RveGraph& graph, std::vector<std::int64_t> ids,
                     const std::vector<double>& start_weight)
    : path_(std::move(path)), ids_(std::move(ids)) {
  MPMXDEM_CHECK(start_weight.size() == ids_.size(), "one start-up weight per RVE");
  const std::string start_path = path_ + ".start.csv";
  {
    errno = 0;
    std::ofstream w(start_path, std::ios::trunc);
    if (!w) throw common::IoError("cost trace " + start_path + ": cannot create: " + reason());
    w << "rve,id,weight\n";
    for (std::size_t k = 0; k < ids_.size(); ++k)
      w << fmt::format("{},{},{:.17g}\n", k, ids_[k], start_weight[k]);
    w.flush();
    if (!w) throw common::IoError("cost trace " + start_path + ": write failed: " + reason());
  }
  const std::string graph_path = path_ + ".graph.csv";
  {
    errno = 0;
    std::ofstream g(graph_path, std::ios::trunc);
    if (!g) throw common::IoError("cost trace " + graph_path + ": cannot create: " + reason());
    g << "rve,neighbour\n";
    for (std::size_t k = 0; k < graph.size(); ++k) {
      for (auto e = graph.xadj[k]; e < graph.xadj[k + 1]; ++e)
        g << k << ',' << graph.adjncy[static_cast<std::size_t>(e)] << '\n';
    }
    g.flush();
    if (!g) throw common::IoError("cost trace " + graph_path + ": write failed: " + reason());
  }
  errno = 0;
  out_.open(path_, std::ios::trunc);
  if (!out_) throw common::IoError("cost trace " + path_ + ": cannot create: " + reason());
  out_ << kHeader << '\n';
}

void CostTrace::record(std::int64_t step, std::span<const int> owner, std::span<const double> cpu_s,
                       std::span<const double> busy_s, std::span<const std::int64_t> dem_steps,
                       std::span<const std::int64_t> rebuilds) {
  const std::size_t n = ids_.size();
  MPMXDEM_CHECK(
      owner.size() == n && cpu_s.size() == n && dem_steps.size() == n && rebuilds.size() == n,
      "one owner, cost, DEM step count and rebuild count per RVE");
  std::string rows;
  for (std::size_t k = 0; k < ids_.size(); ++k) {
    const auto r = static_cast<std::size_t>(owner[k]);
    MPMXDEM_CHECK(r < busy_s.size(), "owner rank out of range");
    rows += fmt::format("{},{},{},{},{:.9g},{:.9g},{},{}\n", step, k, ids_[k], owner[k], cpu_s[k],
                        busy_s[r], dem_steps[k], rebuilds[k]);
  }
  errno = 0;
  out_ << rows;
  out_.flush();
  if (!out_) throw common::IoError("cost trace " + path_ + ": write failed: " + reason());
}

CostTraceData read_cost_trace(const std::string& path) {
  CostTraceData d;
  d.graph = read_trace_graph(path + ".graph.csv");
  d.start_weight = read_trace_start(path + ".start.csv");
  std::vector<double> f;
  std::string line;
  std::ifstream in(path);
  if (!in) throw common::IoError("cost trace " + path + ": cannot read: " + reason());
  std::size_t no = 0;
  std::int64_t current = -1;
  // The header says whether the rows carry the work columns (traces of before them do not).
  std::size_t fields = 6;
  std::string expected = "expected 'step,rve,id,rank,cpu_s,busy_s' with rve, rank, cpu_s >= 0";
  while (std::getline(in, line)) {
    if (++no == 1) {
      if (line == kHeader) {
        fields = 8;
        expected = fmt::format("expected '{}' with rve, rank, cpu_s and the counts >= 0", kHeader);
      }
      continue;
    }
    if (!split_numbers(line, f) || f.size() != fields || f[1] < 0 || f[3] < 0 || f[4] < 0 ||
        (fields == 8 && (f[6] < 0 || f[7] < 0)))
      throw bad_row(path, no, expected);
    const auto step = static_cast<std::int64_t>(f[0]);
    const auto k = static_cast<std::size_t>(f[1]);
    const auto r = static_cast<std::size_t>(f[3]);
    if (step != current) {
      if (!d.steps.empty() && step <= current)
        throw bad_row(path, no, "steps must increase (a restarted run: trace each part apart)");
      if (!d.cpu_s.empty() && d.cpu_s.back().size() != d.cpu_s.front().size())
        throw bad_row(path, no, "every step must list the same RVEs");
      current = step;
      d.steps.push_back(step);
      d.cpu_s.emplace_back();
      d.busy_s.emplace_back();
      if (fields == 8) {
        d.dem_steps.emplace_back();
        d.rebuilds.emplace_back();
      }
    }
    if (k != d.cpu_s.back().size())
      throw bad_row(path, no, "RVE indices must run 0, 1, ... per step");
    d.cpu_s.back().push_back(f[4]);
    if (fields == 8) {
      d.dem_steps.back().push_back(static_cast<std::int64_t>(f[6]));
      d.rebuilds.back().push_back(static_cast<std::int64_t>(f[7]));
    }
    if (d.busy_s.back().size() <= r) d.busy_s.back().resize(r + 1, 0.0);
    d.busy_s.back()[r] = f[5];
  }
  if (d.steps.empty()) throw bad_row(path, no, "no step rows");
  const std::size_t n = d.cpu_s.front().size();
  if (d.cpu_s.back().size() != n) throw bad_row(path, no, "every step must list the same RVEs");
  if (d.start_weight.size() != n)
    throw bad_row(path + ".start.csv", d.start_weight.size() + 1,
                  "one weight per RVE of the trace");
  // The graph file lists RVEs up to the last one with a neighbour: pad to n.
  if (d.graph.size() > n) throw bad_row(path + ".graph.csv", 0, "more RVEs than the trace");
  while (d.graph.size() < n) d.graph.xadj.push_back(d.graph.xadj.back());
  return d;
}

}  // namespace farm
