#include "laguerre/scenarios/Comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "laguerre/scenarios/Results.hpp"

namespace laguerre::scenarios {

double student_t_975(std::size_t dof) {
  static constexpr double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                     2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                     2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof == 0) return std::numeric_limits<double>::infinity();
  if (dof <= 30) return table[dof - 1];
  const double z = 1.959963984540054, v = static_cast<double>(dof);
  const double z3 = z * z * z, z5 = z3 * z * z;
  return z + (z3 + z) / (4 * v) + (5 * z5 + 16 * z3 + 3 * z) / (96 * v * v);
}

Interval wilson_interval(std::size_t successes, std::size_t trials, double z) {
  const double n = static_cast<double>(trials), p = static_cast<double>(successes) / n, z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

Interval t_interval(const std::vector<double>& samples) {
  const double r = static_cast<double>(samples.size());
  double m = 0;
  for (double x : samples) m += x;
  m /= r;
  double ss = 0;
  for (double x : samples) ss += (x - m) * (x - m);
  const double s = std::sqrt(ss / (r - 1));
  const double half = student_t_975(samples.size() - 1) * s / std::sqrt(r);
  return {m - half, m + half};
}

namespace {

/// Per-run delivery rates and stretch statistics of one pair population, summarized over the runs
/// (see the file comment of Comparison.hpp for the interval).
class PairAccumulator {
public:
  void add(std::size_t pairs, std::size_t delivered, double rate, double stretch_mean, double stretch_p95,
           double stretch_max) {
    if (pairs == 0) return;
    rates_.push_back(rate);
    delivered_ += delivered;
    pairs_ += pairs;
    if (delivered == 0) return;
    stretch_weighted_ += stretch_mean * static_cast<double>(delivered);
    stretch_weight_ += delivered;
    p95_ += stretch_p95;
    ++p95_count_;
    smax_ = std::isnan(smax_) ? stretch_max : std::max(smax_, stretch_max);
  }
  std::size_t runs() const { return rates_.size(); }
  PairSummary summary() const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PairSummary out;
    if (rates_.empty()) return out;
    double m = 0;
    for (double x : rates_) m += x;
    out.delivery_mean = m / static_cast<double>(rates_.size());
    if (rates_.size() >= 2) {
      const Interval ci = t_interval(rates_);
      out.delivery_ci = {std::max(0.0, ci.low), std::min(1.0, ci.high)};
      out.ci_method = "t";
    } else {
      out.delivery_ci = wilson_interval(delivered_, pairs_);
      out.ci_method = "wilson";
    }
    out.stretch_mean = stretch_weight_ ? stretch_weighted_ / static_cast<double>(stretch_weight_) : nan;
    out.stretch_p95 = p95_count_ ? p95_ / static_cast<double>(p95_count_) : nan;
    out.stretch_max = smax_;
    return out;
  }

private:
  std::vector<double> rates_;
  std::size_t delivered_ = 0, pairs_ = 0, stretch_weight_ = 0, p95_count_ = 0;
  double stretch_weighted_ = 0, p95_ = 0, smax_ = std::numeric_limits<double>::quiet_NaN();
};

/// The family of a point: its generator, then the values of its swept topology keys other than the
/// size (a file path by its stem), e.g. "field:one-large-hole:quasi-unit-disk"; sizes stay one column.
std::string family_label(const ScenarioPoint& p) {
  std::string label = p.config.topology.generator;
  for (const auto& [key, value] : p.values) {
    if (key.rfind("topology.", 0) != 0 || key == "topology.n") continue;
    std::string v = value;
    if (const auto slash = v.find_last_of('/'); slash != std::string::npos) {
      v = v.substr(slash + 1);
      if (const auto dot = v.find_last_of('.'); dot != std::string::npos && dot > 0) v.resize(dot);
    }
    label += ":" + v;
  }
  return label;
}

}  // namespace

std::vector<ComparisonRow> compare_runs(const Scenario& scenario, const std::vector<RunRecord>& records) {
  std::vector<ComparisonRow> rows;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const ScenarioPoint& p : scenario.points) {
    const ScenarioConfig& cfg = p.config;
    for (std::size_t k = 0; k < cfg.routing.schemes.size(); ++k) {
      ComparisonRow row;
      row.scenario = scenario.name;
      row.point = p.index;
      row.family = family_label(p);
      row.size = size_label(cfg);
      row.network = network_label(cfg.network);
      row.scheme = scheme_name(cfg.routing.schemes[k]);
      PairAccumulator core_pairs, all_pairs;
      double nodes = 0, sensors = 0, core_nodes = 0, disconnected = 0, iters = 0, rounds = 0, msgs = 0, simt = 0;
      double bytes = 0, state = 0;
      for (const RunRecord& r : records) {
        if (r.plan.point != p.index) continue;
        ++row.runs;
        if (k >= r.routing.size()) continue;
        const SchemeResult& s = r.routing[k];
        if (s.pairs == 0) continue;
        ++row.routed;
        core_pairs.add(s.pairs, s.delivered, s.delivery_rate, s.stretch_mean, s.stretch_p95, s.stretch_max);
        if (const auto& a = s.all_pairs) {
          all_pairs.add(a->pairs - a->disconnected, a->delivered, a->delivery_rate, a->stretch_mean, a->stretch_p95,
                        a->stretch_max);
          disconnected += a->pairs ? static_cast<double>(a->disconnected) / static_cast<double>(a->pairs) : 0.0;
        }
        nodes += static_cast<double>(r.nodes);
        sensors += static_cast<double>(r.sensors);
        core_nodes += static_cast<double>(r.core_nodes);
        iters += r.iterations;
        rounds += r.rounds;
        // A scheme with its own setup (hyperbolic) reports its messages; the others share the protocol's.
        msgs += std::isnan(s.setup_messages_per_node) ? r.messages_per_node : s.setup_messages_per_node;
        const double packed = r.core_nodes ? static_cast<double>(r.core_nodes) : 1.0;  // the protocol's nodes
        bytes += std::isnan(s.setup_bytes_per_node) ? static_cast<double>(r.bytes) / packed : s.setup_bytes_per_node;
        state += s.state_bytes_per_node;
        simt += r.simulated_seconds;
      }
      const PairSummary core = core_pairs.summary();
      row.delivery_mean = core.delivery_mean;
      row.delivery_ci = core.delivery_ci;
      row.ci_method = core.ci_method;
      row.stretch_mean = core.stretch_mean;
      row.stretch_p95 = core.stretch_p95;
      row.stretch_max = core.stretch_max;
      row.all_pairs = all_pairs.summary();
      row.all_pairs_runs = all_pairs.runs();
      const double routed = row.routed ? static_cast<double>(row.routed) : nan;
      row.nodes_mean = nodes / routed;
      row.sensors_mean = sensors / routed;
      row.core_nodes_mean = core_nodes / routed;
      row.disconnected_mean = row.all_pairs_runs ? disconnected / static_cast<double>(row.all_pairs_runs) : nan;
      row.iterations_mean = iters / routed;
      row.rounds_mean = rounds / routed;
      row.messages_per_node_mean = msgs / routed;
      row.bytes_per_node_mean = bytes / routed;
      row.state_bytes_per_node_mean = state / routed;
      row.simulated_seconds_mean = simt / routed;
      rows.push_back(row);
    }
  }
  return rows;
}

namespace {
std::string fmt(const char* f, double x) {
  if (std::isnan(x)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}
nlohmann::ordered_json num(double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); }
std::string csv_num(double x) { return std::isfinite(x) ? fmt("%.6g", x) : ""; }
}  // namespace

std::string comparison_table(const std::vector<ComparisonRow>& rows) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line,
                "%-40s %6s %-22s %-14s %5s %9s %17s %7s %7s %7s %8s %7s %9s %10s %8s %10s %8s %8s %8s %9s %17s %7s %7s %7s\n",
                "family", "n", "network", "scheme", "runs", "delivery", "95% CI", "stretch", "p95", "max", "iters",
                "rounds", "msgs/node", "bytes/node", "state B", "sim time", "sensors", "nodes", "packed", "all-pairs",
                "95% CI", "stretch", "p95", "discon");
  out += line;
  std::string last_group;
  for (const auto& r : rows) {
    const std::string group = r.scenario + "|" + std::to_string(r.point);
    if (!last_group.empty() && group != last_group && r.scheme == rows.front().scheme) out += "\n";
    last_group = group;
    const std::string ci = std::isnan(r.delivery_ci.low)
                               ? "-"
                               : "[" + fmt("%.1f", 100 * r.delivery_ci.low) + ", " + fmt("%.1f", 100 * r.delivery_ci.high) +
                                     "]" + (r.ci_method == "wilson" ? "w" : "");
    const PairSummary& a = r.all_pairs;
    const std::string all_ci = std::isnan(a.delivery_ci.low)
                                   ? "-"
                                   : "[" + fmt("%.1f", 100 * a.delivery_ci.low) + ", " +
                                         fmt("%.1f", 100 * a.delivery_ci.high) + "]" + (a.ci_method == "wilson" ? "w" : "");
    std::snprintf(line, sizeof line,
                  "%-40s %6s %-22s %-14s %2zu/%-2zu %8s%% %17s %7s %7s %7s %8s %7s %9s %10s %8s %9ss %8s %8s %8s %8s%% "
                  "%17s %7s %7s %6s%%\n",
                  r.family.c_str(), r.size.c_str(), r.network.substr(0, 22).c_str(), r.scheme.c_str(), r.routed, r.runs,
                  fmt("%.2f", 100 * r.delivery_mean).c_str(), ci.c_str(), fmt("%.3f", r.stretch_mean).c_str(),
                  fmt("%.3f", r.stretch_p95).c_str(), fmt("%.2f", r.stretch_max).c_str(),
                  fmt("%.1f", r.iterations_mean).c_str(), fmt("%.1f", r.rounds_mean).c_str(),
                  fmt("%.1f", r.messages_per_node_mean).c_str(), fmt("%.0f", r.bytes_per_node_mean).c_str(),
                  fmt("%.0f", r.state_bytes_per_node_mean).c_str(), fmt("%.4f", r.simulated_seconds_mean).c_str(),
                  fmt("%.1f", r.sensors_mean).c_str(), fmt("%.1f", r.nodes_mean).c_str(),
                  fmt("%.1f", r.core_nodes_mean).c_str(), fmt("%.2f", 100 * a.delivery_mean).c_str(), all_ci.c_str(), fmt("%.3f", a.stretch_mean).c_str(),
                  fmt("%.3f", a.stretch_p95).c_str(), fmt("%.2f", 100 * r.disconnected_mean).c_str());
    out += line;
  }
  out += "delivery = mean per-run delivery rate; 95% CI: Student t over repetitions (w: Wilson on the pairs of a single "
         "run); stretch = hop stretch (mean, mean per-run p95, max) against BFS in the routed graph.\n"
         "msgs/node, bytes/node: the scheme's own set-up (hyperbolic, simulated) or the packing protocol's (per packed "
         "node; 0 with protocol.mode central); state B = routing state per node (own and neighbours' coordinates).\n"
         "Fields with attach: sensors = deployed, nodes = routed (every sensor), packed = the 3-connected core; delivery/stretch above are over pairs "
         "of the packed core; all-pairs = delivery over pairs of all sensors in one link component (greedy power with "
         "the attachment, the others on the planarization of all sensors), stretch against BFS in the link graph; "
         "discon = share of the sampled pairs in different link components, excluded (no scheme can deliver them)\n";
  return out;
}

std::string comparison_csv(const std::vector<ComparisonRow>& rows) {
  std::string out =
      "scenario,point,family,n,network,scheme,runs,routed,nodes_mean,delivery_mean,delivery_ci_low,delivery_ci_high,"
      "ci_method,stretch_mean,stretch_p95,stretch_max,iterations_mean,rounds_mean,messages_per_node_mean,"
      "simulated_seconds_mean,bytes_per_node_mean,state_bytes_per_node_mean,sensors_mean,core_nodes_mean,all_pairs_delivery_mean,all_pairs_delivery_ci_low,all_pairs_delivery_ci_high,"
      "all_pairs_ci_method,all_pairs_stretch_mean,all_pairs_stretch_p95,all_pairs_stretch_max,disconnected_mean\n";
  auto q = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string o = "\"";
    for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
    return o + "\"";
  };
  for (const auto& r : rows)
    out += q(r.scenario) + "," + std::to_string(r.point) + "," + q(r.family) + "," + q(r.size) + "," + q(r.network) + "," +
           r.scheme + "," + std::to_string(r.runs) + "," + std::to_string(r.routed) + "," + csv_num(r.nodes_mean) + "," +
           csv_num(r.delivery_mean) + "," + csv_num(r.delivery_ci.low) + "," + csv_num(r.delivery_ci.high) + "," +
           r.ci_method + "," + csv_num(r.stretch_mean) + "," + csv_num(r.stretch_p95) + "," + csv_num(r.stretch_max) +
           "," + csv_num(r.iterations_mean) + "," + csv_num(r.rounds_mean) + "," + csv_num(r.messages_per_node_mean) +
           "," + csv_num(r.simulated_seconds_mean) + "," + csv_num(r.bytes_per_node_mean) + "," +
           csv_num(r.state_bytes_per_node_mean) + "," + csv_num(r.sensors_mean) + "," +
           csv_num(r.core_nodes_mean) + "," + csv_num(r.all_pairs.delivery_mean) + "," + csv_num(r.all_pairs.delivery_ci.low) + "," +
           csv_num(r.all_pairs.delivery_ci.high) + "," + r.all_pairs.ci_method + "," + csv_num(r.all_pairs.stretch_mean) +
           "," + csv_num(r.all_pairs.stretch_p95) + "," + csv_num(r.all_pairs.stretch_max) + "," +
           csv_num(r.disconnected_mean) + "\n";
  return out;
}

std::string comparison_json(const std::vector<ComparisonRow>& rows) {
  nlohmann::ordered_json arr = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    arr.push_back({{"scenario", r.scenario},
                   {"point", r.point},
                   {"family", r.family},
                   {"n", r.size},
                   {"network", r.network},
                   {"scheme", r.scheme},
                   {"runs", r.runs},
                   {"routed", r.routed},
                   {"nodes_mean", num(r.nodes_mean)},
                   {"delivery_mean", num(r.delivery_mean)},
                   {"delivery_ci", {num(r.delivery_ci.low), num(r.delivery_ci.high)}},
                   {"ci_method", r.ci_method},
                   {"stretch_mean", num(r.stretch_mean)},
                   {"stretch_p95", num(r.stretch_p95)},
                   {"stretch_max", num(r.stretch_max)},
                   {"iterations_mean", num(r.iterations_mean)},
                   {"rounds_mean", num(r.rounds_mean)},
                   {"messages_per_node_mean", num(r.messages_per_node_mean)},
                   {"simulated_seconds_mean", num(r.simulated_seconds_mean)},
                   {"bytes_per_node_mean", num(r.bytes_per_node_mean)},
                   {"state_bytes_per_node_mean", num(r.state_bytes_per_node_mean)},
                   {"sensors_mean", num(r.sensors_mean)},
                   {"core_nodes_mean", num(r.core_nodes_mean)}});
    if (r.all_pairs_runs > 0)
      arr.back()["all_pairs"] = {{"runs", r.all_pairs_runs},
                                 {"delivery_mean", num(r.all_pairs.delivery_mean)},
                                 {"delivery_ci", {num(r.all_pairs.delivery_ci.low), num(r.all_pairs.delivery_ci.high)}},
                                 {"ci_method", r.all_pairs.ci_method},
                                 {"stretch_mean", num(r.all_pairs.stretch_mean)},
                                 {"stretch_p95", num(r.all_pairs.stretch_p95)},
                                 {"stretch_max", num(r.all_pairs.stretch_max)},
                                 {"disconnected_mean", num(r.disconnected_mean)}};
  }
  nlohmann::ordered_json doc = {
      {"confidence_interval",
       "delivery_ci: 95% Student t-interval over repetitions (per-run delivery rates), clipped to [0, 1]; with a "
       "single routed repetition the Wilson score interval on its pairs (ci_method wilson)"},
      {"all_pairs",
       "fields with attach: delivery over sampled pairs of all sensors that lie in one link component (pairs in "
       "different components, disconnected_mean of them, are excluded: no scheme can deliver them); stretch = hops / "
       "BFS hops in the link graph of all sensors; delivery_mean, nodes_mean and the stretch outside all_pairs are "
       "over the packed core's pairs"},
      {"rows", arr}};
  return doc.dump(1) + "\n";
}

}  // namespace laguerre::scenarios
