// balance_replay: the farm's balancing replayed offline on a recorded cost trace (a program that
// prints figures, never a test). Record a trace with
//   MPMXDEM_COST_TRACE=/tmp/trace.csv mpmxdem run JOB --out DIR
// (any number of ranks: the RVE costs are thread CPU times), then
//   balance_replay /tmp/trace.csv [--ranks 2,4,8,16] [--threads 1] [--threshold 1.2] [--check-every
//   20]
//       [--settled 3] [--move-s 2e-4] [--jitter 0] [--jitter-seeds 5] [--checks 0|1]
//       [--partition spread|cells]
// prints, for each number of virtual ranks, the balance (mean/max of the ranks' step times
// summed over the steps, as the farm logs it) that the partition policy achieves with these
// costs, before and after its first migration. --jitter adds a normal noise of that coefficient
// of variation to every rank's step time (the median over --jitter-seeds seeds is printed).
// docs/design/farm.md, "Balancing", has the figures and what they mean.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "farm/balance_replay.hpp"
#include "farm/cost_trace.hpp"

namespace {

std::vector<int> int_list(const std::string& s) {
  std::vector<int> out;
  std::stringstream ss(s);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(std::stoi(f));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

/// How an RVE's step cost swings (the steps after the first 5, whose start-up costs differ):
/// the median over RVEs of its coefficient of variation, and the mean correlation of the swings
/// of graph neighbours (the partition's concern, docs/design/farm.md "Grouping").
void print_swings(const farm::CostTraceData& t) {
  const std::size_t skip = std::min<std::size_t>(5, t.cpu_s.size() / 2);
  const std::size_t m = t.cpu_s.size() - skip;
  const std::size_t n = t.cpu_s.front().size();
  if (m < 3) return;
  std::vector<double> mean(n, 0.0);
  std::vector<double> sd(n, 0.0);
  for (std::size_t s = skip; s < t.cpu_s.size(); ++s)
    for (std::size_t k = 0; k < n; ++k) mean[k] += t.cpu_s[s][k] / static_cast<double>(m);
  for (std::size_t s = skip; s < t.cpu_s.size(); ++s)
    for (std::size_t k = 0; k < n; ++k) {
      const double d = t.cpu_s[s][k] - mean[k];
      sd[k] += d * d / static_cast<double>(m - 1);
    }
  std::vector<double> cv;
  for (std::size_t k = 0; k < n; ++k) {
    sd[k] = std::sqrt(sd[k]);
    if (mean[k] > 0.0) cv.push_back(sd[k] / mean[k]);
  }
  double corr = 0.0;
  std::size_t pairs = 0;
  for (std::size_t a = 0; a < t.graph.size(); ++a) {
    for (auto e = t.graph.xadj[a]; e < t.graph.xadj[a + 1]; ++e) {
      const auto b = static_cast<std::size_t>(t.graph.adjncy[static_cast<std::size_t>(e)]);
      if (!(sd[a] > 0.0 && sd[b] > 0.0)) continue;
      double c = 0.0;
      for (std::size_t s = skip; s < t.cpu_s.size(); ++s)
        c += (t.cpu_s[s][a] - mean[a]) * (t.cpu_s[s][b] - mean[b]);
      corr += c / (static_cast<double>(m - 1) * sd[a] * sd[b]);
      ++pairs;
    }
  }
  double sum = 0.0;
  for (const double v : mean) sum += v;
  std::printf(
      "RVE step cost: mean %.3g ms; swings (steps %zu on): median coefficient of variation %.3f, "
      "correlation of graph neighbours %s\n",
      1e3 * sum / static_cast<double>(n), skip + 1, cv.empty() ? 0.0 : median(cv),
      pairs > 0 ? std::to_string(corr / static_cast<double>(pairs)).c_str() : "(no edges)");
}

// Prints the trace's size, its RVEs' CPU time in all and the recorded run's own balance.
void print_recorded(const farm::CostTraceData& trace, const char* path) {
  const std::size_t n = trace.cpu_s.front().size();
  double total = 0.0;
  for (const auto& row : trace.cpu_s)
    for (const double c : row) total += c;
  // The recorded run's own balance (its ranks' wall times, noise and all).
  double rec_mean = 0.0;
  double rec_max = 0.0;
  std::size_t rec_ranks = 0;
  for (const auto& row : trace.busy_s) {
    double mx = 0.0;
    double sum = 0.0;
    std::size_t used = 0;
    for (const double b : row) {
      if (b <= 0.0) continue;  // rank 0 left to the MPM
      mx = std::max(mx, b);
      sum += b;
      ++used;
    }
    rec_ranks = std::max(rec_ranks, used);
    if (used > 0) rec_mean += sum / static_cast<double>(used);
    rec_max += mx;
  }
  std::printf("trace %s: %zu RVEs, %zu steps (%lld..%lld), RVE CPU time %.3f s in all\n", path, n,
              trace.steps.size(), static_cast<long long>(trace.steps.front()),
              static_cast<long long>(trace.steps.back()), total);
  std::printf("recorded on %zu rank(s): balance (mean/max busy, wall) %.3f\n", rec_ranks,
              rec_max > 0.0 ? rec_mean / rec_max : 1.0);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: balance_replay TRACE.csv [--option value ...]\n");
    return 2;
  }
  std::map<std::string, std::string> opt;
  for (int i = 2; i + 1 < argc; i += 2) {
    std::string k = argv[i];
    if (k.rfind("--", 0) == 0) k = k.substr(2);
    opt[k] = argv[i + 1];
  }
  const auto get = [&](const std::string& k, const std::string& d) {
    const auto it = opt.find(k);
    return it == opt.end() ? d : it->second;
  };
  try {
    const farm::CostTraceData trace = farm::read_cost_trace(argv[1]);
    print_recorded(trace, argv[1]);
    print_swings(trace);
    farm::ReplayOptions o;
    o.threshold = std::stod(get("threshold", "1.2"));
    o.check_every = std::stoll(get("check-every", "20"));
    o.settled_windows = std::stoi(get("settled", "3"));
    o.move_s_per_rve = std::stod(get("move-s", "2e-4"));
    o.rank_jitter = std::stod(get("jitter", "0"));
    const int seeds = o.rank_jitter > 0.0 ? std::stoi(get("jitter-seeds", "5")) : 1;
    const bool show_checks = get("checks", "0") == "1";
    o.style = farm::parse_partition_style(get("partition", "spread"));
    o.threads = std::stoi(get("threads", "1"));
    std::printf(
        "policy: threshold %.3g, check every %lld steps, settled after %d window(s), move %.3g s "
        "per RVE, rank jitter %.3g (median of %d seed(s)), partition %s\n",
        o.threshold, static_cast<long long>(o.check_every), o.settled_windows, o.move_s_per_rve,
        o.rank_jitter, seeds, farm::to_string(o.style));
    std::printf("%6s %8s %9s %9s %14s %13s %8s %8s %s\n", "ranks", "threads", "balance", "of cores",
                "before first", "after first", "start-up", "moved", "migrations at steps");
    for (const int P : int_list(get("ranks", "2,4,8,16"))) {
      o.parts = P;
      std::vector<double> bal;
      std::vector<double> b0;
      std::vector<double> b1;
      std::vector<double> eff;
      farm::ReplayResult last;
      for (int s = 0; s < seeds; ++s) {
        o.jitter_seed = static_cast<std::uint64_t>(s + 1);
        last = farm::replay_balance(trace, o);
        bal.push_back(last.balance);
        b0.push_back(last.balance_before_first);
        b1.push_back(last.balance_after_first);
        eff.push_back(last.core_efficiency);
      }
      std::string at;
      for (const auto& c : last.checks) {
        if (c.migrated) at += (at.empty() ? "" : ", ") + std::to_string(c.step);
      }
      std::printf("%6d %8d %9.3f %9.3f %14.3f %13.3f %8lld %8lld %s\n", P, o.threads, median(bal),
                  median(eff), median(b0), median(b1), static_cast<long long>(last.startup_moves),
                  static_cast<long long>(last.moved), at.empty() ? "-" : at.c_str());
      if (show_checks) {
        for (const auto& c : last.checks)
          std::printf("         step %lld: imbalance %.3f -> %.3f (%s, %lld moves)%s\n",
                      static_cast<long long>(c.step), c.imbalance_now, c.imbalance_new,
                      c.method == farm::RebalanceMethod::metis ? farm::fresh_name(o.style)
                                                               : farm::to_string(c.method),
                      static_cast<long long>(c.moves), c.migrated ? ", migrated" : "");
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "balance_replay: %s\n", e.what());
    return 1;
  }
  return 0;
}
