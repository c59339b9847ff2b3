// The worked example of embedding laguerre in another simulator: the packing protocol and greedy
// forwarding on ns-3 (Debian's ns-3 3.37), one laguerre::ns3host::NodeApplication per ns-3 node.
//
//   ns3_example GRAPH [--link point-to-point|wifi] [--delay 1ms] [--data-rate 100Mbps] [--pairs all|K]
//               [--scheme greedy-power|…|all] [--seed S] [--wifi-latency 20ms] [--time-limit 600s]
//               [--verify] [--compare-simulator]
//
// It prints the summary of `laguerre simulate` (tools::print_protocol_summary, also --json), then what
// ns-3 carried.
// Point-to-point links never lose a datagram, so the nodes run the synchronous protocol bare and its
// result is core::pack's bit for bit (--verify) and the simulator's (--compare-simulator: radii,
// iterations, rounds, local conditions, outcomes and forwarding outcomes). Wi-Fi loses frames (hidden
// terminals, ARP), so there every node runs the reliability layer (protocols::ReliableNode) under
// its protocol; the result is still exact, only the traffic and the time differ.
//
// This file is C++20 and owns the laguerre nodes; Ns3Network.cpp (C++17) builds the ns-3 world.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../../laguerre/Common.hpp"
#include "../../laguerre/ProtocolSummary.hpp"
#include "Ns3Network.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/ns3/HostedProtocolNode.hpp"
#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"

namespace {

namespace lc = laguerre::core;
namespace lp = laguerre::protocols;
namespace ls = laguerre::scenarios;
namespace lh = laguerre::ns3host;
namespace le = laguerre::ns3example;
namespace lt = laguerre::tools;

struct Args {
  lt::GraphArgs graph;
  std::string link = "point-to-point";
  std::string delay = "1ms";
  std::string data_rate = "100Mbps";
  std::string pairs = "all";
  std::string scheme = "greedy-power";
  std::string wifi_latency = "20ms";
  std::string time_limit = "600s";
  std::uint64_t seed = 1;
  int steps = 1;
  bool verify = false;
  bool compare = false;
  bool dynamic_arp = false;
  bool json = false;
};

// Counts every message a node sends under its phase, as the simulator does.
lh::SendObserver count_into(laguerre::sim::TrafficMetrics& traffic, lc::Vertex v) {
  return [&traffic, v](lp::NodeId, std::span<const std::byte> bytes) {
    traffic.add_sent(static_cast<std::uint32_t>(v), ls::traffic_phase(bytes), bytes.size());
  };
}

bool same_circles(const lc::CircleEmbedding& a, const lc::CircleEmbedding& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t v = 0; v < a.size(); ++v)
    if (!(a[v].x == b[v].x && a[v].y == b[v].y && a[v].r == b[v].r)) return false;
  return true;
}

bool same_forwarding(const ls::ForwardingResult& a, const ls::ForwardingResult& b) {
  auto same = [](double x, double y) { return x == y || (x != x && y != y); };  // NaN = NaN here
  return a.scheme == b.scheme && a.packets == b.packets && a.delivered == b.delivered && a.dead_ends == b.dead_ends &&
         a.loops == b.loops && a.ttl_exceeded == b.ttl_exceeded && same(a.hops_mean, b.hops_mean) &&
         same(a.stretch_mean, b.stretch_mean) && same(a.stretch_p95, b.stretch_p95) && same(a.stretch_max, b.stretch_max);
}

int run(const Args& a) {
  const std::vector<lc::Scheme> schemes = lt::parse_schemes(a.scheme, "--scheme");
  const lc::PairSelection selection = lt::parse_pairs(a.pairs, a.seed, "--pairs");
  const bool wifi = a.link == "wifi";
  const laguerre::sim::Duration delay = ls::parse_duration(a.delay, "--delay");
  const laguerre::sim::Duration wifi_latency = ls::parse_duration(a.wifi_latency, "--wifi-latency");
  const laguerre::sim::Duration limit = ls::parse_duration(a.time_limit, "--time-limit");
  if (delay <= 0 || wifi_latency <= 0 || limit <= 0)
    throw lc::InputError("--delay/--wifi-latency/--time-limit", 0, "found a zero duration, expected a positive one");
  const lt::LoadedGraph loaded = lt::load_graph(a.graph);
  const lc::PlanarGraph& g = loaded.input.graph;
  const std::vector<lc::Point2>& positions = loaded.input.positions;
  const std::size_t n = g.num_vertices();

  ls::ProtocolSetup setup;  // synchronous, N steps per round; the simulator's twin has the same delay
  setup.steps_per_round = a.steps;
  setup.link.latency = ls::parse_latency("constant:" + a.delay, "--delay");
  setup.seed = a.seed;

  le::NetworkSpec spec;
  spec.link = wifi ? le::LinkKind::wifi : le::LinkKind::point_to_point;
  spec.delay_ns = delay;
  spec.data_rate = a.data_rate;
  spec.seed = a.seed;
  spec.dynamic_arp = a.dynamic_arp;
  spec.ids.resize(n);
  spec.neighbours.resize(n);
  for (lc::Vertex v = 0; v < n; ++v) {
    spec.ids[v] = g.id(v);
    for (const lc::Vertex w : g.neighbours(v)) spec.neighbours[v].push_back(w);
  }
  for (const lc::Point2& p : positions) spec.positions.push_back({p.x, p.y});
  le::Ns3Network net(spec);

  // Packing: one PackingNode per ns-3 node, over the reliability layer on Wi-Fi.
  lp::PackingParams params = ls::packing_params(setup);
  if (wifi) lp::enable_lossy_links(params, wifi_latency);
  laguerre::sim::TrafficMetrics traffic(n);
  net.host([&](std::size_t i) {
    const auto v = static_cast<lc::Vertex>(i);
    return lh::hosted(
        [&g, &params, v](lp::Runtime& rt) { return std::make_unique<lp::PackingNode>(rt, lp::local_knowledge(g, v), params); },
        count_into(traffic, v));
  });
  const le::PhaseReport packing = net.run(limit);
  ls::ProtocolOutcome po;
  ls::collect_packing_nodes(
      g, [&](lc::Vertex v) -> const lp::PackingNode& { return static_cast<const lp::PackingNode&>(lh::protocol_node(net.hosted(v))); },
      {}, po);
  ls::collect_traffic(traffic, po);
  po.lossy = wifi;
  po.retransmit_after = params.retransmit_after;
  po.adaptive_rto = params.adaptive_rto;
  po.simulated_time = packing.last_activity_ns;
  po.wall_seconds = packing.wall_seconds;
  po.events = packing.events;
  po.events_per_second = packing.wall_seconds > 0 ? static_cast<double>(packing.events) / packing.wall_seconds : 0;
  po.peak_memory_bytes = laguerre::sim::peak_memory_bytes();
  const std::string verify = a.verify ? ls::verify_against_core(g, loaded.kind, setup, po) : "";

  // Forwarding: one ForwardingNode per ns-3 node (over the reliability layer on Wi-Fi), one run per
  // scheme; each packet starts in an event of its source's ns-3 node.
  const auto pairs = po.failed_nodes > 0 ? std::vector<std::pair<lc::Vertex, lc::Vertex>>{} : lc::select_pairs(n, selection);
  const std::vector<lc::Point2> pos = ls::forwarding_positions(po.circles, positions);
  const std::vector<std::vector<std::uint32_t>> hop_distance = ls::hop_distances_from_sources(g, pairs);
  std::optional<lp::ReliableParams> reliable;
  if (wifi) reliable = ls::forwarding_reliable_params(wifi_latency);
  std::vector<ls::ForwardingResult> results;
  double forwarding_wall = 0;
  for (const lc::Scheme scheme : schemes) {
    ls::PacketCollector sink;
    net.host([&](std::size_t i) {
      return lh::hosted([&, v = static_cast<lc::Vertex>(i)](lp::Runtime& rt) { return ls::make_forwarding_node(rt, sink, g, v, po.circles, pos, reliable); });
    });
    for (std::size_t i = 0; i < pairs.size(); ++i)
      net.at_node(pairs[i].first, [&net, source = pairs[i].first, packet = ls::forwarding_packet(g, po.circles, pos, scheme, pairs, i)] {
        ls::forwarding_node(lh::protocol_node(net.hosted(source))).originate(packet);
      });
    const le::PhaseReport phase = net.run(limit);
    ls::ForwardingResult res = ls::summarize_forwarding(scheme, pairs, hop_distance, sink.reports);
    for (lc::Vertex v = 0; reliable && v < n; ++v)
      res.retransmissions += static_cast<const lp::ReliableNode&>(lh::protocol_node(net.hosted(v))).counters().retransmissions;
    res.simulated_seconds = static_cast<double>(phase.last_activity_ns - phase.started_ns) * 1e-9;
    forwarding_wall += phase.wall_seconds;
    results.push_back(res);
  }

  const lh::HostCounters c = net.counters();
  std::size_t packets = 0, delivered = 0;
  std::uint64_t retransmissions = 0;
  double forwarding_simulated = 0;
  for (const auto& r : results) {
    packets += r.packets;
    delivered += r.delivered;
    retransmissions += r.retransmissions;
    forwarding_simulated += r.simulated_seconds;
  }
  nlohmann::json ns3 = {{"network", net.description()},
                        {"link", a.link},
                        {"datagrams_sent", c.datagrams_sent},
                        {"payload_bytes_sent", c.bytes_sent},
                        {"datagrams_received", c.datagrams_received},
                        {"send_failures", c.send_failures},
                        {"unknown_sources", c.unknown_sources},
                        {"forwarding_wall_seconds", forwarding_wall}};
  std::vector<std::string> lines{"ns-3         " + net.description()};
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "datagrams    %llu sent (%llu payload bytes), %llu received, %llu refused by the socket, %llu from "
                "unknown addresses; forwarding took %.3f s wall",
                static_cast<unsigned long long>(c.datagrams_sent), static_cast<unsigned long long>(c.bytes_sent),
                static_cast<unsigned long long>(c.datagrams_received), static_cast<unsigned long long>(c.send_failures),
                static_cast<unsigned long long>(c.unknown_sources), forwarding_wall);
  lines.emplace_back(buf);
  if (wifi) {
    std::snprintf(buf, sizeof buf,
                  "wifi         delivery %zu/%zu packets (forwarding over the reliability layer); retransmissions: "
                  "packing %llu, forwarding %llu; simulated time: packing %.6f s, forwarding %.6f s",
                  delivered, packets, static_cast<unsigned long long>(po.reliability.retransmissions),
                  static_cast<unsigned long long>(retransmissions), laguerre::sim::to_seconds(po.simulated_time),
                  forwarding_simulated);
    lines.emplace_back(buf);
    ns3["wifi"] = {{"packets", packets},
                   {"delivered", delivered},
                   {"packing_retransmissions", po.reliability.retransmissions},
                   {"forwarding_retransmissions", retransmissions},
                   {"packing_simulated_seconds", laguerre::sim::to_seconds(po.simulated_time)},
                   {"forwarding_simulated_seconds", forwarding_simulated}};
  }
  bool ok = verify.empty() || verify == "identical to core::pack, bit for bit";
  if (a.compare) {
    // The simulator's run of the same protocol (synchronous, loss-free, the same constant delay).
    const ls::ProtocolOutcome twin = ls::run_packing_protocol(g, positions, setup);
    const std::vector<ls::ForwardingResult> twin_results =
        ls::run_forwarding(g, twin.circles, positions, setup.link, a.seed, schemes, pairs);
    std::string diff;
    if (!same_circles(po.circles, twin.circles)) diff += " radii/centres";
    if (po.iterations != twin.iterations) diff += " iterations";
    if (po.rounds != twin.rounds) diff += " rounds";
    if (po.local != twin.local) diff += " local-conditions";
    if (po.converged_nodes != twin.converged_nodes || po.failed_nodes != twin.failed_nodes) diff += " outcomes";
    for (std::size_t i = 0; i < results.size(); ++i)
      if (!same_forwarding(results[i], twin_results[i])) diff += " forwarding:" + std::string(lc::to_string(results[i].scheme));
    const std::string verdict = diff.empty() ? "identical to the simulator's sync run (circles, iterations, rounds, local "
                                               "conditions, outcomes, forwarding), bit for bit"
                                             : "DIFFERS from the simulator's sync run:" + diff;
    std::snprintf(buf, sizeof buf, "simulator    %s; messages %llu here, %llu in the simulator", verdict.c_str(),
                  static_cast<unsigned long long>(po.messages), static_cast<unsigned long long>(twin.messages));
    lines.emplace_back(buf);
    ns3["simulator"] = verdict;
    ns3["simulator_messages"] = twin.messages;
    ok = ok && diff.empty();
  }
  const int status = lt::print_protocol_summary(
      {loaded, setup, "sync", a.graph.outer, po, results, schemes, a.verify ? &verify : nullptr, "", {{"ns3", ns3}},
       ls::forwarding_blocker(po)}, a.json);
  if (!a.json)
    for (const std::string& line : lines) std::printf("%s\n", line.c_str());
  if (status != 0) return status;
  return ok ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The packing protocol and greedy forwarding on ns-3, one laguerre node per ns-3 node "
               "(README, \"Embedding laguerre in another simulator\")."};
  Args a;
  lt::add_graph_options(app, a.graph, "graph", "Graph file (edge list, coords or planar_code)");
  lt::add_outer_option(app, a.graph);
  app.add_option("--link", a.link, "point-to-point (one link per edge) or wifi (one ad-hoc channel)")
      ->check(CLI::IsMember({"point-to-point", "wifi"}))
      ->capture_default_str();
  app.add_option("--delay", a.delay, "Point-to-point: every link's delay (and the simulator twin's latency)")->capture_default_str();
  app.add_option("--data-rate", a.data_rate, "Point-to-point: every link's rate")->capture_default_str();
  app.add_option("--wifi-latency", a.wifi_latency, "Wi-Fi: the one-way latency the reliability layer is tuned for")
      ->capture_default_str();
  app.add_flag("--dynamic-arp", a.dynamic_arp, "Wi-Fi: resolve neighbours with ARP instead of filling the caches up front");
  app.add_option("--time-limit", a.time_limit, "Simulated-time bound of each ns-3 run")->capture_default_str();
  app.add_option("--pairs", a.pairs, "'all' ordered pairs, or a number sampled with --seed")->capture_default_str();
  app.add_option("--scheme", a.scheme, "greedy-power, greedy-euclid, compass, gfg or all")->capture_default_str();
  app.add_option("--seed", a.seed, "Seed of the random streams and of the pair sample")
      ->check(lt::seed_validator())
      ->capture_default_str();
  app.add_option("--steps-per-round,-N", a.steps, "Thurston steps per round")->check(CLI::Range(1, 10000))->capture_default_str();
  app.add_flag("--verify", a.verify, "Also run core::pack and check the nodes' circles are identical");
  app.add_flag("--json", a.json, "Machine-readable output (simulate's document with an \"ns3\" object)");
  app.add_flag("--compare-simulator", a.compare, "Also run laguerre's simulator (sync mode) and check the results are identical");
  return lt::run_program(app, argc, argv, "ns3_example", [&] { return run(a); });
}
