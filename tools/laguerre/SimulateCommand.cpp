// `laguerre simulate`: run the distributed packing protocol on one actor per node in the
// discrete-event simulator, then forward packets hop by hop over the simulated network.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <iostream>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "Common.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/sim/SimHost.hpp"

namespace laguerre::tools {

namespace {
struct SimulateArgs {
  std::string graph;
  std::string format = "automatic";
  std::size_t index = 1;
  std::string mode = "sync";
  std::string latency = "constant:1ms";
  double loss = 0;
  double dup = 0;
  std::uint64_t seed = 1;
  int steps = 1;
  int max_iterations = 100000;
  std::string root = "deepest";
  std::string pairs = "all";
  std::string scheme = "greedy-power";
  std::vector<std::string> crashes;
  std::vector<std::string> recoveries;
  std::string retransmit_after;
  bool fixed_rto = false;
  bool verify = false;
  bool json = false;
};

// "250us", "1ms", "2s", "100" (nanoseconds) → nanoseconds.
sim::Duration parse_duration(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const std::string unit = text.substr(used);
  double scale = 0;
  if (unit.empty() || unit == "ns") scale = 1;
  else if (unit == "us") scale = 1e3;
  else if (unit == "ms") scale = 1e6;
  else if (unit == "s") scale = 1e9;
  if (used == 0 || scale == 0 || !(value >= 0))
    throw std::invalid_argument("--latency: expected a non-negative duration such as 250us, 1ms or 2s, found '" +
                                text + "'.");
  return static_cast<sim::Duration>(value * scale + 0.5);
}

// constant:D | uniform:LO:HI | distance:BASE:NS_PER_UNIT[:JITTER]
sim::LatencyModel parse_latency(const std::string& spec) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= spec.size(); ++i)
    if (i == spec.size() || spec[i] == ':') {
      parts.push_back(spec.substr(start, i - start));
      start = i + 1;
    }
  const std::string expected =
      "expected constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER] (durations like 1ms)";
  if (parts[0] == "constant" && parts.size() == 2) return sim::LatencyModel::constant(parse_duration(parts[1]));
  if (parts[0] == "uniform" && parts.size() == 3)
    return sim::LatencyModel::uniform(parse_duration(parts[1]), parse_duration(parts[2]));
  if (parts[0] == "distance" && (parts.size() == 3 || parts.size() == 4)) {
    double per_unit = 0;
    try {
      per_unit = std::stod(parts[2]);
    } catch (const std::exception&) {
      throw std::invalid_argument("--latency: NS_PER_UNIT must be a number, found '" + parts[2] + "'.");
    }
    return sim::LatencyModel::distance(parse_duration(parts[1]), per_unit,
                                       parts.size() == 4 ? parse_duration(parts[3]) : 0);
  }
  throw std::invalid_argument("--latency '" + spec + "': " + expected + ".");
}

sim::Network make_network(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                          const sim::LinkModel& link) {
  sim::Network net = sim::network_of(g, link);
  if (!positions.empty()) {
    std::vector<protocols::Position> pos;
    for (const auto& p : positions) pos.push_back({p.x, p.y});
    net.set_positions(std::move(pos));
  }
  return net;
}

// One outage of --crash / --recover.
struct Outage {
  sim::NodeIndex node = 0;
  sim::Time at = 0;
  std::optional<sim::Time> recover_at;
};

// ID@TIME for `option` (TIME a duration from the start, as for --latency) → (node index, TIME text).
std::pair<sim::NodeIndex, std::string> parse_node_at(const std::string& option, const std::string& spec,
                                                    const sim::Network& net) {
  const std::size_t at = spec.find('@');
  std::uint64_t id = 0;
  std::size_t used = 0;
  try {
    id = std::stoull(spec.substr(0, at), &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (at == std::string::npos || used == 0 || used != at)
    throw std::invalid_argument(option + ": expected ID@TIME such as 17@40ms" +
                                (option == "--crash" ? std::string(" or ID@T1-T2 such as 17@40ms-90ms") : "") +
                                ", found '" + spec + "'.");
  const auto v = net.index_of(id);
  if (!v)
    throw std::invalid_argument(option + " " + spec + ": the graph has no node with id " + std::to_string(id) + ".");
  return {*v, spec.substr(at + 1)};
}

// --crash ID@T (for good) or ID@T1-T2 (back at T2), then --recover ID@T attached to the latest earlier
// outage of that node that has no recovery yet.
std::vector<Outage> parse_outages(const std::vector<std::string>& crashes, const std::vector<std::string>& recoveries,
                                  const sim::Network& net) {
  std::vector<Outage> out;
  for (const std::string& c : crashes) {
    const auto [v, when] = parse_node_at("--crash", c, net);
    const std::size_t dash = when.find('-');
    Outage o{v, parse_duration(when.substr(0, dash)), std::nullopt};
    if (dash != std::string::npos) o.recover_at = parse_duration(when.substr(dash + 1));
    if (o.recover_at && *o.recover_at <= o.at)
      throw std::invalid_argument("--crash " + c + ": the recovery time must come after the crash time.");
    out.push_back(o);
  }
  for (const std::string& r : recoveries) {
    const auto [v, when] = parse_node_at("--recover", r, net);
    const sim::Time t = parse_duration(when);
    Outage* best = nullptr;
    for (Outage& o : out)
      if (o.node == v && !o.recover_at && o.at < t && (!best || o.at > best->at)) best = &o;
    if (!best)
      throw std::invalid_argument("--recover " + r + ": node " + std::to_string(net.id(v)) +
                                  " has no --crash before that time without a recovery.");
    best->recover_at = t;
  }
  return out;
}

// The longest one-way latency the link model can produce on this network.
sim::Duration max_latency(const sim::Network& net, const sim::LinkModel& link) {
  sim::Duration m = link.latency.max_latency(0);
  for (sim::LinkIndex l = 0; l < net.link_count(); ++l) m = std::max(m, link.latency.max_latency(net.link_length(l)));
  return m;
}

// --scheme: one scheme by name (dashes or underscores), or all of them.
std::vector<core::Scheme> parse_schemes(const std::string& text) {
  if (text == "all") return {core::all_schemes.begin(), core::all_schemes.end()};
  std::string name = text;
  std::replace(name.begin(), name.end(), '-', '_');
  if (const auto s = core::parse_scheme(name)) return {*s};
  throw std::invalid_argument("--scheme: expected greedy-power, greedy-euclid, compass, gfg or all, found '" + text + "'.");
}

// Hop distances (breadth-first search) from every source that appears in `pairs`; other rows empty.
std::vector<std::vector<std::uint32_t>> bfs_from_sources(const core::PlanarGraph& g,
                                                          const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs) {
  const std::size_t n = g.num_vertices();
  constexpr std::uint32_t unreached = 0xffffffffu;
  std::vector<std::vector<std::uint32_t>> dist(n);
  std::vector<core::Vertex> queue;
  for (const auto& [s, t] : pairs) {
    if (!dist[s].empty()) continue;
    dist[s].assign(n, unreached);
    dist[s][s] = 0;
    queue.assign(1, s);
    for (std::size_t head = 0; head < queue.size(); ++head)
      for (const core::Vertex w : g.neighbours(queue[head]))
        if (dist[s][w] == unreached) {
          dist[s][w] = dist[s][queue[head]] + 1;
          queue.push_back(w);
        }
  }
  return dist;
}

// Hop-by-hop forwarding of one scheme: outcomes and hop stretch against BFS shortest paths.
struct SchemeResult {
  core::Scheme scheme = core::Scheme::greedy_power;
  std::size_t packets = 0, delivered = 0, dead_ends = 0, loops = 0, ttl_exceeded = 0;
  double hops_mean = 0;
  double stretch_mean = std::numeric_limits<double>::quiet_NaN();
  double stretch_p95 = std::numeric_limits<double>::quiet_NaN();
  double stretch_max = std::numeric_limits<double>::quiet_NaN();
  double simulated_seconds = 0;
};

std::string_view outcome_name(protocols::PackingOutcome o) {
  switch (o) {
    case protocols::PackingOutcome::running: return "running";
    case protocols::PackingOutcome::converged: return "converged";
    case protocols::PackingOutcome::cap: return "cap";
    case protocols::PackingOutcome::neighbour_failed: return "neighbour_failed";
  }
  return "?";
}

class Collector : public protocols::PacketSink {
public:
  void on_packet_end(const protocols::PacketReport& r) override { reports.push_back(r); }
  std::vector<protocols::PacketReport> reports;
};

int run_simulate(const SimulateArgs& a) {
  if (a.mode != "sync" && a.mode != "async")
    throw std::invalid_argument("--mode: expected sync or async, found '" + a.mode + "'.");
  const std::vector<core::Scheme> schemes = parse_schemes(a.scheme);
  const LoadedGraph loaded = load_graph(a.graph, a.format, a.index);
  const core::PlanarGraph& g = loaded.input.graph;
  const std::size_t n = g.num_vertices();
  sim::LinkModel link;
  link.latency = parse_latency(a.latency);
  link.loss = a.loss;
  link.duplication = a.dup;
  link.validate();
  if (link.latency.kind == sim::LatencyKind::distance && loaded.input.positions.empty())
    throw std::invalid_argument("--latency distance:… needs node positions; " + a.graph +
                                " has none (use the coords format).");

  protocols::PackingParams params;
  params.steps_per_check = a.steps;
  params.max_iterations = a.max_iterations;
  params.root = a.root == "smallest-id" ? core::RootRule::smallest_id : core::RootRule::deepest;
  params.asynchronous = a.mode == "async";
  sim::Network network = make_network(g, loaded.input.positions, link);
  const std::vector<Outage> crashes = parse_outages(a.crashes, a.recoveries, network);
  for (const Outage& o : crashes) network.add_crash(o.node, o.at, o.recover_at);
  // Loss, duplication and crashes need the reliability layer (PackingNode.hpp, "Loss, duplication and
  // crashes"); on reliable links it stays off and the wire traffic is the synchronous protocol's.
  const bool lossy = a.loss > 0 || a.dup > 0 || !crashes.empty() || !a.retransmit_after.empty();
  if (lossy) {
    protocols::enable_lossy_links(params, max_latency(network, link));
    if (!a.retransmit_after.empty()) params.retransmit_after = std::max<sim::Duration>(1, parse_duration(a.retransmit_after));
    params.adaptive_rto = !a.fixed_rto;
  }
  sim::SimConfig config;
  config.seed = a.seed;
  // Traffic is counted under the message type; a frame of the reliability layer under the type of the
  // message it carries (retransmissions included), a probe (empty frame) and an ack under their own.
  auto phase_of = [](std::span<const std::byte> bytes) -> sim::Phase {
    const std::size_t frame_header = protocols::encoded_size(protocols::MessageType::frame);
    if (bytes.size() > frame_header + 1 && bytes[1] == static_cast<std::byte>(protocols::MessageType::frame))
      return static_cast<sim::Phase>(bytes[frame_header + 1]);
    return bytes.size() >= 2 ? static_cast<sim::Phase>(bytes[1]) : 0;
  };
  sim::SimHost host(
      std::move(network), config,
      [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        return std::make_unique<protocols::PackingNode>(rt, protocols::local_knowledge(g, v), params);
      },
      phase_of);
  const sim::RunReport report = host.run();

  // Gather the outcome and the embedding the nodes hold.
  core::CircleEmbedding phi(n);
  std::size_t converged = 0, holds = 0, failed = 0, survivors = 0;
  std::uint32_t steps = 0, rounds = 0;
  sim::Time finished_at = 0;  // when the last node reached its final outcome
  protocols::PackingCounters rel;  // reliability-layer totals
  std::map<protocols::NodeId, std::size_t> suspects;
  for (core::Vertex v = 0; v < n; ++v) {
    const auto& node = static_cast<const protocols::PackingNode&>(host.node(v));
    phi[v] = node.placement().circle;
    converged += node.outcome() == protocols::PackingOutcome::converged;
    holds += node.local_condition() == core::LocalCondition::holds;
    steps = std::max(steps, node.steps());
    rounds = std::max(rounds, node.round());
    const auto& c = node.counters();
    rel += c;
    if (node.finished_at() >= 0) finished_at = std::max(finished_at, node.finished_at());
    // A node down for good is no survivor; a node that came back counts as one.
    const bool crashed =
        std::any_of(crashes.begin(), crashes.end(), [&](const Outage& o) { return o.node == v && !o.recover_at; });
    if (crashed) continue;
    ++survivors;
    if (node.outcome() == protocols::PackingOutcome::neighbour_failed) {
      ++failed;
      ++suspects[node.suspect()];
    }
  }
  std::string suspect_list;
  for (const auto& [id, count] : suspects)
    suspect_list += (suspect_list.empty() ? "" : ", ") + std::to_string(id) + " (" + std::to_string(count) + " nodes)";
  const auto& traffic = host.simulator().traffic();
  const sim::TrafficCounters total = traffic.total();
  std::uint64_t max_msgs = 0, max_bytes = 0;
  for (sim::NodeIndex v = 0; v < n; ++v) {
    const auto t = traffic.node_total(v);
    max_msgs = std::max(max_msgs, t.messages_sent);
    max_bytes = std::max(max_bytes, t.bytes_sent);
  }
  std::string verify;
  if (a.verify && failed > 0) {
    verify = "not applicable: the run was abandoned after a node failure";
  } else if (a.verify && params.asynchronous) {
    // The asynchronous iterates depend on timing: check the nodes' embedding with core's own checks.
    const auto checks = core::check_all(g, phi);
    const auto ok = static_cast<std::size_t>(std::count(checks.begin(), checks.end(), core::LocalCondition::holds));
    verify = "asynchronous mode (not bit for bit by design): core's " +
             std::string(loaded.kind == core::GraphKind::triangulated_disc ? "LPD" : "GLPD") + " check holds at " +
             std::to_string(ok) + "/" + std::to_string(n) + " nodes";
  } else if (a.verify) {
    core::PackOptions opt;
    opt.steps_per_check = a.steps;
    opt.max_iterations = a.max_iterations;
    opt.root = params.root;
    const core::PackResult r = core::pack(g, opt);
    bool same = r.iterations == static_cast<int>(steps);
    for (core::Vertex v = 0; v < n && same; ++v)
      same = r.circles[v].x == phi[v].x && r.circles[v].y == phi[v].y && r.circles[v].r == phi[v].r;
    verify = same ? "identical to core::pack, bit for bit" : "DIFFERS from core::pack";
  }

  // Forward packets hop by hop on the final embedding, one simulation per scheme. Greedy power uses
  // the circles; the geometric schemes use the graph's coordinates when the file has them, else the
  // packing's centres (as `laguerre route` does with one embedding).
  core::PairSelection selection{0, a.seed};
  if (a.pairs != "all") {
    try {
      selection.sample = std::stoull(a.pairs);
    } catch (const std::exception&) {
      throw std::invalid_argument("--pairs expects 'all' or a positive number, found '" + a.pairs + "'.");
    }
  }
  const auto pairs = failed > 0 ? std::vector<std::pair<core::Vertex, core::Vertex>>{} : core::select_pairs(n, selection);
  const bool input_positions = !loaded.input.positions.empty();
  std::vector<core::Point2> pos(n);
  core::CircleEmbedding geo(n);
  for (core::Vertex v = 0; v < n; ++v) {
    pos[v] = input_positions ? loaded.input.positions[v] : core::centre(phi[v]);
    geo[v] = {pos[v].x, pos[v].y, 0.0};
  }
  const std::vector<std::vector<std::uint32_t>> hop_distance = bfs_from_sources(g, pairs);
  std::vector<SchemeResult> results;
  for (const core::Scheme scheme : schemes) {
    SchemeResult res;
    res.scheme = scheme;
    res.packets = pairs.size();
    Collector sink;
    // Forwarding has no retransmission: packets travel over the same latencies without loss/duplication.
    sim::LinkModel fwd_link = link;
    fwd_link.loss = 0;
    fwd_link.duplication = 0;
    sim::SimHost fwd(
        make_network(g, loaded.input.positions, fwd_link), config,
        [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
          std::vector<protocols::NodeId> nb;
          std::vector<core::Circle> circles;
          std::vector<core::Point2> points;
          for (core::Vertex w : g.neighbours(v)) {
            nb.push_back(g.id(w));
            circles.push_back(phi[w]);
            points.push_back(pos[w]);
          }
          return std::make_unique<protocols::ForwardingNode>(rt, sink, g.id(v), nb, phi[v], circles, pos[v], points);
        },
        phase_of);
    // core::route's default hop limit, so that the hop-by-hop outcomes are core's.
    const auto ttl = static_cast<std::uint32_t>(std::min<std::size_t>(core::default_ttl(g, scheme), 0xffffffffu));
    if (!pairs.empty() && failed == 0) {
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const auto [s, t] = pairs[i];
        static_cast<protocols::ForwardingNode&>(fwd.node(s)).originate({i, g.id(t), phi[t], ttl, scheme, pos[t]});
      }
    }
    const sim::RunReport fwd_report = fwd.run();
    res.simulated_seconds = static_cast<double>(fwd_report.simulated_time) * 1e-9;
    std::vector<double> stretch;
    double hops = 0;
    for (const auto& r : sink.reports) {
      switch (r.outcome) {
        case protocols::PacketOutcome::delivered: {
          ++res.delivered;
          hops += r.hops;
          const auto [s, t] = pairs[r.packet];
          const std::uint32_t d = hop_distance[s][t];
          if (d > 0) stretch.push_back(static_cast<double>(r.hops) / static_cast<double>(d));
          break;
        }
        case protocols::PacketOutcome::dead_end: ++res.dead_ends; break;
        case protocols::PacketOutcome::loop: ++res.loops; break;
        case protocols::PacketOutcome::ttl_exceeded: ++res.ttl_exceeded; break;
      }
    }
    res.hops_mean = res.delivered ? hops / static_cast<double>(res.delivered) : 0.0;
    if (!stretch.empty()) {
      double sum = 0;
      for (double x : stretch) sum += x;
      res.stretch_mean = sum / static_cast<double>(stretch.size());
      res.stretch_max = *std::max_element(stretch.begin(), stretch.end());
      res.stretch_p95 = core::nearest_rank_percentile(stretch, 95);
    }
    results.push_back(res);
  }
  std::size_t packets = 0, delivered = 0;
  double hops_total = 0, fwd_seconds = 0;
  for (const SchemeResult& r : results) {
    packets += r.packets;
    delivered += r.delivered;
    hops_total += r.hops_mean * static_cast<double>(r.delivered);
    fwd_seconds += r.simulated_seconds;
  }

  const double msgs_mean = static_cast<double>(total.messages_sent) / static_cast<double>(n);
  const double bytes_mean = static_cast<double>(total.bytes_sent) / static_cast<double>(n);
  if (a.json) {
    nlohmann::json phases = nlohmann::json::object();
    for (std::size_t p = 1; p < traffic.phase_count(); ++p) {
      const auto t = traffic.phase_total(static_cast<sim::Phase>(p));
      if (t.messages_sent == 0) continue;
      phases[std::string(protocols::to_string(static_cast<protocols::MessageType>(p)))] = {
          {"messages", t.messages_sent}, {"bytes", t.bytes_sent}};
    }
    nlohmann::json doc = {{"graph", loaded.input.name},
                          {"nodes", n},
                          {"edges", g.num_edges()},
                          {"kind", std::string(core::to_string(loaded.kind))},
                          {"converged_nodes", converged},
                          {"local_condition_holds", holds},
                          {"iterations", steps},
                          {"mode", a.mode},
                          {"rounds", rounds},
                          {"messages", total.messages_sent},
                          {"bytes", total.bytes_sent},
                          {"messages_per_node_mean", msgs_mean},
                          {"messages_per_node_max", max_msgs},
                          {"bytes_per_node_mean", bytes_mean},
                          {"bytes_per_node_max", max_bytes},
                          {"by_phase", phases},
                          {"simulated_seconds", static_cast<double>(report.simulated_time) * 1e-9},
                          {"finished_seconds", static_cast<double>(finished_at) * 1e-9},
                          {"wall_seconds", report.wall_seconds},
                          {"events", report.events_processed},
                          {"events_per_second", report.events_per_second},
                          {"peak_memory_bytes", report.peak_memory_bytes},
                          {"packets", packets},
                          {"delivered", delivered},
                          {"hops_mean", delivered ? hops_total / static_cast<double>(delivered) : 0.0},
                          {"forwarding_simulated_seconds", fwd_seconds},
                          {"forwarding_positions", input_positions ? "input coordinates" : "packing centres"}};
    nlohmann::json fwd_json = nlohmann::json::array();
    auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
    for (const SchemeResult& r : results)
      fwd_json.push_back({{"scheme", std::string(core::to_string(r.scheme))},
                          {"packets", r.packets},
                          {"delivered", r.delivered},
                          {"dead_ends", r.dead_ends},
                          {"loops", r.loops},
                          {"ttl_exceeded", r.ttl_exceeded},
                          {"hops_mean", r.hops_mean},
                          {"stretch_mean", number(r.stretch_mean)},
                          {"stretch_p95", number(r.stretch_p95)},
                          {"stretch_max", number(r.stretch_max)},
                          {"simulated_seconds", r.simulated_seconds}});
    doc["forwarding"] = fwd_json;
    if (a.verify) doc["verify"] = verify;
    if (lossy) {
      doc["reliability"] = {{"frames", rel.frames},
                            {"retransmissions", rel.retransmissions},
                            {"acks", rel.acks},
                            {"duplicates", rel.duplicates},
                            {"probes", rel.probes},
                            {"links_given_up", rel.links_failed},
                            {"retransmit_after_seconds", static_cast<double>(params.retransmit_after) * 1e-9},
                            {"adaptive_rto", params.adaptive_rto}};
      doc["failed_nodes"] = failed;
      doc["survivors"] = survivors;
      nlohmann::json sus = nlohmann::json::object();
      for (const auto& [id, count] : suspects) sus[std::to_string(id)] = count;
      doc["suspects"] = sus;
      nlohmann::json outages = nlohmann::json::array();
      for (const Outage& o : crashes) {
        const auto& node = static_cast<const protocols::PackingNode&>(host.node(o.node));
        outages.push_back({{"node", g.id(o.node)},
                           {"crash_seconds", static_cast<double>(o.at) * 1e-9},
                           {"recover_seconds", o.recover_at ? nlohmann::json(static_cast<double>(*o.recover_at) * 1e-9)
                                                            : nlohmann::json()},
                           {"outcome", std::string(outcome_name(node.outcome()))},
                           {"final", node.is_final()}});
      }
      doc["outages"] = outages;
    }
    std::cout << doc.dump(1) << '\n';
  } else {
    std::printf("graph        %s: %zu nodes, %zu edges, %s\n", loaded.input.name.c_str(), n, g.num_edges(),
                std::string(core::to_string(loaded.kind)).c_str());
    std::printf("protocol     %s after %u %s in %u rounds (N = %d); %zu/%zu nodes report %s\n",
                converged == n ? "converged" : "did not converge", steps,
                params.asynchronous ? "iteration-equivalents (asynchronous)" : "iterations", rounds, a.steps, holds, n,
                loaded.kind == core::GraphKind::triangulated_disc ? "LPD" : "GLPD");
    if (failed > 0)
      std::printf("failure      %zu/%zu surviving nodes ended with neighbour_failed; suspected: %s\n", failed, survivors,
                  suspect_list.c_str());
    for (const Outage& o : crashes) {
      const auto& node = static_cast<const protocols::PackingNode&>(host.node(o.node));
      if (o.recover_at)
        std::printf("outage       node %llu down from %.3f ms to %.3f ms, then ended %s\n",
                    static_cast<unsigned long long>(g.id(o.node)), static_cast<double>(o.at) * 1e-6,
                    static_cast<double>(*o.recover_at) * 1e-6, std::string(outcome_name(node.outcome())).c_str());
    }
    if (lossy)
      std::printf("reliability  %llu frames, %llu retransmissions, %llu acks, %llu duplicates detected, %llu probes, "
                  "%llu links given up (retransmit after %.3f ms, %s)\n",
                  static_cast<unsigned long long>(rel.frames), static_cast<unsigned long long>(rel.retransmissions),
                  static_cast<unsigned long long>(rel.acks), static_cast<unsigned long long>(rel.duplicates),
                  static_cast<unsigned long long>(rel.probes), static_cast<unsigned long long>(rel.links_failed),
                  static_cast<double>(params.retransmit_after) * 1e-6,
                  params.adaptive_rto ? "then adaptive" : "fixed");
    std::printf("messages     %llu (%.1f per node, max %llu); bytes %llu (%.0f per node, max %llu)\n",
                static_cast<unsigned long long>(total.messages_sent), msgs_mean,
                static_cast<unsigned long long>(max_msgs), static_cast<unsigned long long>(total.bytes_sent),
                bytes_mean, static_cast<unsigned long long>(max_bytes));
    std::printf("by phase    ");
    for (std::size_t p = 1; p < traffic.phase_count(); ++p) {
      const auto t = traffic.phase_total(static_cast<sim::Phase>(p));
      if (t.messages_sent)
        std::printf(" %s %llu", std::string(protocols::to_string(static_cast<protocols::MessageType>(p))).c_str(),
                    static_cast<unsigned long long>(t.messages_sent));
    }
    std::printf("\ntime         %.6f s simulated (every node final at %.6f s), %.3f s wall, %llu events (%.3g events/s), "
                "peak memory %.1f MiB\n",
                static_cast<double>(report.simulated_time) * 1e-9, static_cast<double>(finished_at) * 1e-9,
                report.wall_seconds,
                static_cast<unsigned long long>(report.events_processed), report.events_per_second,
                static_cast<double>(report.peak_memory_bytes) / (1024.0 * 1024.0));
    if (a.verify) std::printf("verify       %s\n", verify.c_str());
    if (failed > 0)
      std::printf("forwarding   skipped: the packing run was abandoned\n");
    else
      for (const SchemeResult& r : results)
        std::printf("forwarding   %-13s %zu/%zu packets delivered hop by hop%s, %.2f hops on average; %zu dead ends, "
                    "%zu loops, %zu TTL exceeded; hop stretch mean %.3f, p95 %.3f, max %.3f\n",
                    std::string(core::to_string(r.scheme)).c_str(), r.delivered, r.packets,
                    lossy ? " (over loss-free links)" : "", r.hops_mean, r.dead_ends, r.loops, r.ttl_exceeded,
                    r.stretch_mean, r.stretch_p95, r.stretch_max);
    if (failed == 0 && std::any_of(schemes.begin(), schemes.end(), [](core::Scheme sc) { return sc != core::Scheme::greedy_power; }))
      std::printf("positions    %s (greedy Euclidean, compass, gfg)\n",
                  input_positions ? "the graph's coordinates" : "the packing's centres");
  }
  return converged == n ? 0 : 3;
}
}  // namespace

Action add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Run the distributed packing protocol, one actor per node, in the discrete-event simulator.");
  cmd->footer("Then every selected pair sends a packet, forwarded hop by hop by the --scheme(s); the geometric\n"
              "schemes use the file's coordinates, or the packing's centres when it has none.\n"
              "With --loss, --dup or --crash the nodes run the reliability layer (acks, retransmissions,\n"
              "duplicate detection, crash detection); a detected crash ends every survivor with neighbour_failed.\n"
              "A recovering node keeps its state: an outage shorter than the detection time is masked (the run\n"
              "converges); after a longer one it ends with neighbour_failed as well.\n"
              "Exit status: 0 converged, 3 not converged or a node failed, 2 bad input.");
  cmd->add_option("graph", args->graph, "Graph file (edge list, coords or planar_code)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--format", args->format, "Input format: automatic, edges, coords, planar_code")->capture_default_str();
  cmd->add_option("--index", args->index, "Which graph of a multi-graph file (from 1)")->capture_default_str();
  cmd->add_option("--mode", args->mode, "Protocol mode: sync (bit for bit with core::pack) or async (chaotic updates)")
      ->check(CLI::IsMember({"sync", "async"}))
      ->capture_default_str();
  cmd->add_option("--latency", args->latency, "constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER]")
      ->capture_default_str();
  cmd->add_option("--loss", args->loss, "Loss probability per copy (turns the reliability layer on)")->capture_default_str();
  cmd->add_option("--dup", args->dup, "Duplication probability per message (turns the reliability layer on)")
      ->capture_default_str();
  cmd->add_option("--crash", args->crashes,
                  "Crash node ID at TIME for good (17@40ms) or until T2 (17@40ms-90ms); repeatable");
  cmd->add_option("--recover", args->recoveries,
                  "Bring a crashed node back, e.g. 17@90ms (its state survives; repeatable)");
  cmd->add_option("--retransmit-after", args->retransmit_after,
                  "First retransmission period of the reliability layer (default: 3 × the longest latency)");
  cmd->add_flag("--fixed-rto", args->fixed_rto,
                "Keep the retransmission timeout at --retransmit-after (no round-trip estimation)");
  cmd->add_option("--seed", args->seed, "Seed of every random stream (and of the pair sample)")->capture_default_str();
  cmd->add_option("--steps-per-round,-N", args->steps, "Thurston steps per round")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations, "Cap on Thurston steps")->capture_default_str();
  cmd->add_option("--root", args->root, "Layout root election: deepest or smallest-id")
      ->check(CLI::IsMember({"deepest", "smallest-id"}))->capture_default_str();
  cmd->add_option("--pairs", args->pairs, "'all' ordered pairs, or a number sampled with --seed")->capture_default_str();
  cmd->add_option("--scheme", args->scheme, "Forwarding scheme: greedy-power, greedy-euclid, compass, gfg or all")
      ->capture_default_str();
  cmd->add_flag("--verify", args->verify, "Also run core::pack and check the nodes' circles are identical");
  cmd->add_flag("--json", args->json, "Machine-readable output");
  return [args] { return run_simulate(*args); };
}

}  // namespace laguerre::tools
