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

std::vector<ComparisonRow> compare_runs(const Scenario& scenario, const std::vector<RunRecord>& records) {
  std::vector<ComparisonRow> rows;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const ScenarioPoint& p : scenario.points) {
    const ScenarioConfig& cfg = p.config;
    for (std::size_t k = 0; k < cfg.routing.schemes.size(); ++k) {
      ComparisonRow row;
      row.scenario = scenario.name;
      row.point = p.index;
      row.family = cfg.topology.generator;
      row.size = size_label(cfg);
      row.network = network_label(cfg.network);
      row.scheme = scheme_name(cfg.routing.schemes[k]);
      std::vector<double> rates;
      std::size_t delivered = 0, pairs = 0;
      double stretch_weighted = 0, p95 = 0, smax = nan, nodes = 0, iters = 0, rounds = 0, msgs = 0, simt = 0;
      std::size_t stretch_weight = 0, p95_count = 0;
      for (const RunRecord& r : records) {
        if (r.plan.point != p.index) continue;
        ++row.runs;
        if (k >= r.routing.size()) continue;
        const SchemeResult& s = r.routing[k];
        if (s.pairs == 0) continue;
        ++row.routed;
        rates.push_back(s.delivery_rate);
        delivered += s.delivered;
        pairs += s.pairs;
        if (s.delivered > 0) {
          stretch_weighted += s.stretch_mean * static_cast<double>(s.delivered);
          stretch_weight += s.delivered;
          p95 += s.stretch_p95;
          ++p95_count;
          smax = std::isnan(smax) ? s.stretch_max : std::max(smax, s.stretch_max);
        }
        nodes += static_cast<double>(r.nodes);
        iters += r.iterations;
        rounds += r.rounds;
        // A scheme with its own setup (hyperbolic) reports its messages; the others share the protocol's.
        msgs += std::isnan(s.setup_messages_per_node) ? r.messages_per_node : s.setup_messages_per_node;
        simt += r.simulated_seconds;
      }
      const double routed = static_cast<double>(row.routed);
      if (row.routed == 0) {
        row.delivery_mean = row.stretch_mean = row.stretch_p95 = row.stretch_max = nan;
        row.delivery_ci = {nan, nan};
        row.nodes_mean = row.iterations_mean = row.rounds_mean = row.messages_per_node_mean =
            row.simulated_seconds_mean = nan;
      } else {
        double m = 0;
        for (double x : rates) m += x;
        row.delivery_mean = m / routed;
        if (row.routed >= 2) {
          const Interval ci = t_interval(rates);
          row.delivery_ci = {std::max(0.0, ci.low), std::min(1.0, ci.high)};
          row.ci_method = "t";
        } else {
          row.delivery_ci = wilson_interval(delivered, pairs);
          row.ci_method = "wilson";
        }
        row.stretch_mean = stretch_weight ? stretch_weighted / static_cast<double>(stretch_weight) : nan;
        row.stretch_p95 = p95_count ? p95 / static_cast<double>(p95_count) : nan;
        row.stretch_max = smax;
        row.nodes_mean = nodes / routed;
        row.iterations_mean = iters / routed;
        row.rounds_mean = rounds / routed;
        row.messages_per_node_mean = msgs / routed;
        row.simulated_seconds_mean = simt / routed;
      }
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
  std::snprintf(line, sizeof line, "%-24s %6s %-22s %-14s %5s %9s %17s %7s %7s %7s %8s %7s %9s %10s\n", "family", "n",
                "network", "scheme", "runs", "delivery", "95% CI", "stretch", "p95", "max", "iters", "rounds",
                "msgs/node", "sim time");
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
    std::snprintf(line, sizeof line, "%-24s %6s %-22s %-14s %2zu/%-2zu %8s%% %17s %7s %7s %7s %8s %7s %9s %9ss\n",
                  r.family.c_str(), r.size.c_str(), r.network.substr(0, 22).c_str(), r.scheme.c_str(), r.routed, r.runs,
                  fmt("%.2f", 100 * r.delivery_mean).c_str(), ci.c_str(), fmt("%.3f", r.stretch_mean).c_str(),
                  fmt("%.3f", r.stretch_p95).c_str(), fmt("%.2f", r.stretch_max).c_str(),
                  fmt("%.1f", r.iterations_mean).c_str(), fmt("%.1f", r.rounds_mean).c_str(),
                  fmt("%.1f", r.messages_per_node_mean).c_str(), fmt("%.4f", r.simulated_seconds_mean).c_str());
    out += line;
  }
  out += "delivery = mean per-run delivery rate; 95% CI: Student t over repetitions (w: Wilson on the pairs of a single "
         "run); stretch = hop stretch (mean, mean per-run p95, max)\n";
  return out;
}

std::string comparison_csv(const std::vector<ComparisonRow>& rows) {
  std::string out =
      "scenario,point,family,n,network,scheme,runs,routed,nodes_mean,delivery_mean,delivery_ci_low,delivery_ci_high,"
      "ci_method,stretch_mean,stretch_p95,stretch_max,iterations_mean,rounds_mean,messages_per_node_mean,"
      "simulated_seconds_mean\n";
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
           "," + csv_num(r.simulated_seconds_mean) + "\n";
  return out;
}

std::string comparison_json(const std::vector<ComparisonRow>& rows) {
  nlohmann::ordered_json arr = nlohmann::ordered_json::array();
  for (const auto& r : rows)
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
                   {"simulated_seconds_mean", num(r.simulated_seconds_mean)}});
  nlohmann::ordered_json doc = {
      {"confidence_interval",
       "delivery_ci: 95% Student t-interval over repetitions (per-run delivery rates), clipped to [0, 1]; with a "
       "single routed repetition the Wilson score interval on its pairs (ci_method wilson)"},
      {"rows", arr}};
  return doc.dump(1) + "\n";
}

}  // namespace laguerre::scenarios
