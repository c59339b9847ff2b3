#include "laguerre/scenarios/Results.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include <nlohmann/json.hpp>

namespace laguerre::scenarios {

namespace {
nlohmann::ordered_json num(double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); }
std::string g6(double x) {
  if (!std::isfinite(x)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}
std::string quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}
std::string fmt(const char* f, double x) {
  if (!std::isfinite(x)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}
}  // namespace

std::string network_label(const NetworkSpec& network) {
  std::string s = network.latency_text;
  if (network.loss > 0) s += " loss=" + g6(network.loss);
  if (network.duplication > 0) s += " dup=" + g6(network.duplication);
  if (!network.crashes.empty()) s += " crashes=" + std::to_string(network.crashes.size());
  return s;
}

std::string size_label(const ScenarioConfig& config) {
  return config.topology.params.has("n") ? config.topology.params.describe("n") : "-";
}

std::string results_json(const Scenario& scenario, const std::vector<RunRecord>& records) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const RunRecord& r : records) {
    const ScenarioPoint& p = scenario.points.at(r.plan.point);
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const auto& [k, v] : p.values) values[k] = v;
    nlohmann::ordered_json routing = nlohmann::ordered_json::object();
    for (const SchemeResult& s : r.routing) {
      nlohmann::ordered_json& entry = routing[scheme_name(s.scheme)];
      entry = {{"pairs", s.pairs},
               {"delivered", s.delivered},
               {"delivery_rate", num(s.delivery_rate)},
               {"stretch_mean", num(s.stretch_mean)},
               {"stretch_p95", num(s.stretch_p95)},
               {"stretch_max", num(s.stretch_max)},
               {"hops_mean", num(s.hops_mean)},
               {"positions", s.positions},
               {"setup_messages_per_node", num(s.setup_messages_per_node)},
               {"setup_bytes_per_node", num(s.setup_bytes_per_node)},
               {"state_bytes_per_node", num(s.state_bytes_per_node)},
               {"coordinate_bits_mean", num(s.coordinate_bits_mean)},
               {"coordinate_bits_max", num(s.coordinate_bits_max)}};
      if (s.all_pairs) {
        const AllPairsStats& a = *s.all_pairs;
        entry["all_pairs"] = {{"pairs", a.pairs},
                              {"disconnected", a.disconnected},
                              {"delivered", a.delivered},
                              {"delivery_rate", num(a.delivery_rate)},
                              {"delivery_over", "pairs in one link component (disconnected pairs excluded)"},
                              {"stretch_mean", num(a.stretch_mean)},
                              {"stretch_p95", num(a.stretch_p95)},
                              {"stretch_max", num(a.stretch_max)},
                              {"stretch_reference", "BFS hops in the link graph of all sensors"},
                              {"hops_mean", num(a.hops_mean)},
                              {"invalid_routes", a.invalid_routes}};
      }
    }
    nlohmann::ordered_json run = {{"point", r.plan.point},
                          {"repetition", r.plan.repetition},
                          {"seed", r.plan.seed},
                          {"topology_seed", r.plan.topology_seed},
                          {"values", values},
                          {"status", std::string(to_string(r.status))},
                          {"message", r.message},
                          {"family", r.family},
                          {"topology", r.topology},
                          {"topology_note", r.topology_note},
                          {"kind", r.kind},
                          {"network", network_label(p.config.network)},
                          {"sensors", r.sensors},
                          {"nodes", r.nodes},
                          {"core_nodes", r.core_nodes},
                          {"unreachable_sensors", r.unreachable_sensors},
                          {"edges", r.edges},
                          {"iterations", r.iterations},
                          {"rounds", r.rounds},
                          {"local_condition_holds", r.holds_nodes},
                          {"messages", r.messages},
                          {"bytes", r.bytes},
                          {"messages_per_node", r.messages_per_node},
                          {"max_node_messages", r.max_node_messages},
                          {"retransmissions", r.retransmissions},
                          {"simulated_seconds", r.simulated_seconds},
                          {"events", r.events},
                          {"routing", routing},
                          {"wall_seconds", r.wall_seconds}};
    if (r.exact_iterations >= 0 || r.core_lpd_iterations >= 0) {
      run["exact_iterations"] = r.exact_iterations >= 0 ? nlohmann::ordered_json(r.exact_iterations) : nlohmann::ordered_json(nullptr);
      run["core_lpd_iterations"] = r.core_lpd_iterations;
    }
    runs.push_back(run);
  }
  nlohmann::ordered_json doc = {{"scenario", scenario.name},
                        {"source", scenario.source},
                        {"seed", scenario.seed},
                        {"repetitions", scenario.repetitions},
                        {"points", scenario.points.size()},
                        {"sweep", scenario.sweep_keys},
                        {"seed_rule",
                         "run seed = mix(mix(mix(seed) ^ point) ^ repetition); topology seed = "
                         "mix(mix(mix(seed) ^ fnv1a64(canonical topology)) ^ repetition); mix = SplitMix64"},
                        {"runs", runs}};
  return doc.dump(1) + "\n";
}

std::string results_csv(const Scenario& scenario, const std::vector<RunRecord>& records) {
  std::string out = "point,repetition,seed";
  for (const auto& k : scenario.sweep_keys) out += "," + quote(k);
  out += ",status,family,topology,kind,network,nodes,edges,iterations,rounds,local_condition_holds,messages,"
         "messages_per_node,max_node_messages,retransmissions,simulated_seconds,exact_iterations,scheme,positions,"
         "pairs,delivered,delivery_rate,stretch_mean,stretch_p95,stretch_max,hops_mean,sensors,core_nodes,all_pairs,"
         "all_pairs_disconnected,all_pairs_delivered,all_pairs_delivery_rate,all_pairs_stretch_mean,"
         "all_pairs_stretch_p95,all_pairs_stretch_max\n";
  for (const RunRecord& r : records) {
    const ScenarioPoint& p = scenario.points.at(r.plan.point);
    std::string head = std::to_string(r.plan.point) + "," + std::to_string(r.plan.repetition) + "," +
                       std::to_string(r.plan.seed);
    for (const auto& [k, v] : p.values) head += "," + quote(v);
    head += "," + std::string(to_string(r.status)) + "," + quote(r.family) + "," + quote(r.topology) + "," + r.kind + "," +
            quote(network_label(p.config.network)) + "," + std::to_string(r.nodes) + "," + std::to_string(r.edges) + "," +
            std::to_string(r.iterations) + "," + std::to_string(r.rounds) + "," + std::to_string(r.holds_nodes) + "," +
            std::to_string(r.messages) + "," + g6(r.messages_per_node) + "," + std::to_string(r.max_node_messages) +
            "," + std::to_string(r.retransmissions) + "," + g6(r.simulated_seconds) + "," +
            (r.exact_iterations >= 0 ? std::to_string(r.exact_iterations) : "");
    const std::string sizes = "," + std::to_string(r.sensors) + "," + std::to_string(r.core_nodes);
    if (r.routing.empty()) out += head + ",,,,,,,,," + sizes + ",,,,,,,\n";
    for (const SchemeResult& s : r.routing) {
      std::string all = ",,,,,,,";
      if (s.all_pairs) {
        const AllPairsStats& a = *s.all_pairs;
        all = "," + std::to_string(a.pairs) + "," + std::to_string(a.disconnected) + "," + std::to_string(a.delivered) +
              "," + g6(a.delivery_rate) + "," + g6(a.stretch_mean) + "," + g6(a.stretch_p95) + "," + g6(a.stretch_max);
      }
      out += head + "," + scheme_name(s.scheme) + "," + s.positions + "," + std::to_string(s.pairs) + "," +
             std::to_string(s.delivered) + "," + g6(s.delivery_rate) + "," + g6(s.stretch_mean) + "," +
             g6(s.stretch_p95) + "," + g6(s.stretch_max) + "," + g6(s.hops_mean) + sizes + all + "\n";
    }
  }
  return out;
}

std::string summary_table(const Scenario& scenario, const std::vector<RunRecord>& records) {
  std::string out;
  char line[512];
  for (const ScenarioPoint& p : scenario.points) {
    std::string title = "point " + std::to_string(p.index);
    for (const auto& [k, v] : p.values) title += "  " + k + "=" + v;
    if (p.values.empty()) title = scenario.name;
    std::size_t runs = 0, ok = 0;
    std::map<std::string, std::size_t> other;
    double nodes = 0, sensors = 0, core_nodes = 0, iters = 0, rounds = 0, msgs = 0, simt = 0;
    std::size_t measured = 0;
    std::string first_problem;
    for (const RunRecord& r : records) {
      if (r.plan.point != p.index) continue;
      ++runs;
      if (r.status == RunStatus::ok) ++ok;
      else {
        ++other[std::string(to_string(r.status))];
        if (first_problem.empty()) first_problem = r.message;
      }
      if (r.nodes == 0 || r.status == RunStatus::unsupported || r.status == RunStatus::error) continue;
      ++measured;
      nodes += static_cast<double>(r.nodes);
      sensors += static_cast<double>(r.sensors);
      core_nodes += static_cast<double>(r.core_nodes);
      iters += r.iterations;
      rounds += r.rounds;
      msgs += r.messages_per_node;
      simt += r.simulated_seconds;
    }
    const double m = measured ? static_cast<double>(measured) : std::numeric_limits<double>::quiet_NaN();
    std::string status = std::to_string(ok) + "/" + std::to_string(runs) + " ok";
    for (const auto& [k, v] : other) status += ", " + std::to_string(v) + " " + k;
    out += title + "\n";
    std::snprintf(line, sizeof line,
                  "  %s: %s, %s sensors, %s nodes routed, %s packed; %s iterations, %s rounds, %s messages/packed node, "
                  "%s s simulated (means)\n",
                  p.config.topology.generator.c_str(), status.c_str(), fmt("%.0f", sensors / m).c_str(),
                  fmt("%.0f", nodes / m).c_str(), fmt("%.0f", core_nodes / m).c_str(),
                  fmt("%.1f", iters / m).c_str(), fmt("%.1f", rounds / m).c_str(), fmt("%.1f", msgs / m).c_str(),
                  fmt("%.4f", simt / m).c_str());
    out += line;
    if (!first_problem.empty()) out += "  first problem: " + first_problem + "\n";
    for (std::size_t k = 0; k < p.config.routing.schemes.size(); ++k) {
      std::size_t pairs = 0, delivered = 0, w = 0, all_pairs = 0, all_connected = 0, all_delivered = 0, all_w = 0;
      double stretch = 0, smax = std::numeric_limits<double>::quiet_NaN(), all_stretch = 0;
      double setup_msgs = 0, setup_bytes = 0, state = 0;
      std::size_t runs_k = 0;
      std::string where;
      for (const RunRecord& r : records) {
        if (r.plan.point != p.index || k >= r.routing.size()) continue;
        const SchemeResult& s = r.routing[k];
        if (s.all_pairs) {
          all_pairs += s.all_pairs->pairs;
          all_connected += s.all_pairs->pairs - s.all_pairs->disconnected;
          all_delivered += s.all_pairs->delivered;
          if (s.all_pairs->delivered) {
            all_stretch += s.all_pairs->stretch_mean * static_cast<double>(s.all_pairs->delivered);
            all_w += s.all_pairs->delivered;
          }
        }
        pairs += s.pairs;
        delivered += s.delivered;
        where = s.positions;
        // The scheme's own set-up, or the packing protocol's (per packed node), as in compare.
        const double packed = r.core_nodes ? static_cast<double>(r.core_nodes) : 1.0;
        ++runs_k;
        setup_msgs += std::isnan(s.setup_messages_per_node) ? r.messages_per_node : s.setup_messages_per_node;
        setup_bytes += std::isnan(s.setup_bytes_per_node) ? static_cast<double>(r.bytes) / packed : s.setup_bytes_per_node;
        state += s.state_bytes_per_node;
        if (s.delivered) {
          stretch += s.stretch_mean * static_cast<double>(s.delivered);
          w += s.delivered;
          smax = std::isnan(smax) ? s.stretch_max : std::max(smax, s.stretch_max);
        }
      }
      if (pairs == 0) continue;
      const double rk = static_cast<double>(runs_k);
      std::snprintf(line, sizeof line,
                    "    %-14s %9zu/%-9zu delivered (%6.2f%%)  stretch mean %s, max %s  [%s positions]  set-up %s msgs, "
                    "%s B per node; state %s B per node\n",
                    scheme_name(p.config.routing.schemes[k]).c_str(), delivered, pairs,
                    100.0 * static_cast<double>(delivered) / static_cast<double>(pairs),
                    fmt("%.3f", w ? stretch / static_cast<double>(w) : std::nan("")).c_str(), fmt("%.2f", smax).c_str(),
                    where.c_str(), fmt("%.1f", setup_msgs / rk).c_str(), fmt("%.0f", setup_bytes / rk).c_str(),
                    fmt("%.0f", state / rk).c_str());
      out += line;
      if (all_pairs == 0) continue;
      std::snprintf(line, sizeof line,
                    "    %-14s %9zu/%-9zu all sensor pairs delivered (%6.2f%% of %zu connected; %zu disconnected "
                    "excluded)  stretch vs links %s\n",
                    "", all_delivered, all_connected,
                    all_connected ? 100.0 * static_cast<double>(all_delivered) / static_cast<double>(all_connected) : 0.0,
                    all_connected, all_pairs - all_connected,
                    fmt("%.3f", all_w ? all_stretch / static_cast<double>(all_w) : std::nan("")).c_str());
      out += line;
    }
  }
  // Thesis §5.4.1 comparison, when iterations to an exact packing were measured.
  std::map<std::string, std::vector<const RunRecord*>> by_family;
  std::map<std::string, std::size_t> unreached;
  for (const RunRecord& r : records) {
    if (r.status != RunStatus::ok || r.core_lpd_iterations < 0) continue;
    const std::string fam = r.family + " (" + r.kind + ")";
    if (r.exact_iterations >= 0) by_family[fam].push_back(&r);
    else ++unreached[fam];
  }
  if (!by_family.empty() || !unreached.empty()) {
    out += "\nIterations to LPD/GLPD (protocol, synchronous rounds of N steps) vs to an exact packing (core::pack):\n";
    std::snprintf(line, sizeof line, "  %-40s %6s %6s %16s %16s %12s %14s\n", "family", "graphs", "n", "to LPD/GLPD",
                  "to exact", "ratio(mean)", "ratio(means)");
    out += line;
    for (const auto& [fam, rs] : by_family) {
      double l = 0, e = 0, ratio = 0, nn = 0, l2 = 0, e2 = 0;
      for (const RunRecord* r : rs) {
        l += r->iterations;
        e += r->exact_iterations;
        l2 += static_cast<double>(r->iterations) * r->iterations;
        e2 += static_cast<double>(r->exact_iterations) * r->exact_iterations;
        ratio += static_cast<double>(r->exact_iterations) / std::max<double>(1, r->iterations);
        nn += static_cast<double>(r->nodes);
      }
      const double k = static_cast<double>(rs.size());
      const double sl = k > 1 ? std::sqrt(std::max(0.0, (l2 - l * l / k) / (k - 1))) : 0;
      const double se = k > 1 ? std::sqrt(std::max(0.0, (e2 - e * e / k) / (k - 1))) : 0;
      const std::string a = fmt("%.1f", l / k) + "±" + fmt("%.1f", sl), b = fmt("%.1f", e / k) + "±" + fmt("%.1f", se);
      std::snprintf(line, sizeof line, "  %-40s %6zu %6.1f %16s %16s %12.2f %14.2f\n", fam.c_str(), rs.size(), nn / k,
                    a.c_str(), b.c_str(), ratio / k, l > 0 ? e / l : 0.0);
      out += line;
    }
    for (const auto& [fam, k] : unreached)
      out += "  " + fam + ": " + std::to_string(k) +
             " graph(s) reached LPD/GLPD but no exact packing within protocol.max_iterations (left out above)\n";
    out += "  Thesis (uniform graphs, ~50 vertices): triangulations < 100 iterations, exact/LPD ratio 3.8; 3-connected "
           "100-500 iterations, ratio 1.8.\n";
  }
  return out;
}

}  // namespace laguerre::scenarios
