// The protocols on the simulator: the one wiring of `laguerre simulate` and the scenario runner.
#include "laguerre/scenarios/ProtocolRun.hpp"

#include <algorithm>
#include <chrono>
#include <memory>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/Scenario.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/sim/LiveCluster.hpp"
#include "laguerre/sim/SimHost.hpp"

namespace laguerre::scenarios {

sim::Network make_network(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                          const sim::LinkModel& link) {
  sim::Network net = sim::network_of(g, link);
  if (!positions.empty()) {
    std::vector<protocols::Position> pos;
    pos.reserve(positions.size());
    for (const auto& p : positions) pos.push_back({p.x, p.y});
    net.set_positions(std::move(pos));
  }
  return net;
}

namespace {
// The longest one-way latency the link model can produce on this network.
sim::Duration max_latency(const sim::Network& net, const sim::LinkModel& link) {
  sim::Duration m = link.latency.max_latency(0);
  for (sim::LinkIndex l = 0; l < net.link_count(); ++l) m = std::max(m, link.latency.max_latency(net.link_length(l)));
  return m;
}

}  // namespace

// Traffic is counted under the message type; a frame of the reliability layer under the type of the
// message it carries (retransmissions included), a probe (empty frame) and an ack under their own.
sim::Phase traffic_phase(std::span<const std::byte> bytes) {
  static const std::size_t frame_header = protocols::encoded_size(protocols::MessageType::frame);  // once
  if (bytes.size() > frame_header + 1 && bytes[1] == static_cast<std::byte>(protocols::MessageType::frame))
    return static_cast<sim::Phase>(bytes[frame_header + 1]);
  return bytes.size() >= 2 ? static_cast<sim::Phase>(bytes[1]) : 0;
}

protocols::PackingParams packing_params(const ProtocolSetup& setup) {
  protocols::PackingParams params;
  params.steps_per_check = setup.steps_per_round;
  params.max_iterations = setup.max_iterations;
  params.root = setup.root;
  params.asynchronous = setup.asynchronous;
  params.acceleration = setup.acceleration;
  params.termination = setup.termination;
  return params;
}

namespace {
std::string crash_text(const CrashSpec& c) {
  return std::to_string(c.node) + "@" + format_duration(c.at) + (c.recover_at ? "-" + format_duration(*c.recover_at) : "");
}

}  // namespace

std::vector<std::vector<std::uint32_t>> hop_distances_from_sources(
    const core::PlanarGraph& g, const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs) {
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

PackingNodeSummary summarize(const protocols::PackingNode& node) {
  return {node.placement().circle, node.local_condition(), node.outcome(), node.is_final(), node.steps(),
          node.round(),           node.counters(),        node.finished_at(), node.suspect()};
}

void collect_packing_summaries(const core::PlanarGraph& g, std::span<const PackingNodeSummary> nodes,
                               const std::vector<bool>& down, ProtocolOutcome& out) {
  const std::size_t n = g.num_vertices();
  LAGUERRE_PRECONDITION(nodes.size() == n, "collect_packing_summaries needs one summary per vertex.");
  out.circles.resize(n);
  out.local.resize(n);
  for (core::Vertex v = 0; v < n; ++v) {
    const PackingNodeSummary& node = nodes[v];
    out.circles[v] = node.circle;
    out.local[v] = node.local;
    out.converged_nodes += node.outcome == protocols::PackingOutcome::converged;
    out.holds_nodes += node.local == core::LocalCondition::holds;
    out.iterations = std::max(out.iterations, node.steps);
    out.rounds = std::max(out.rounds, node.round);
    out.reliability += node.counters;
    if (node.finished_at >= 0) out.finished_at = std::max(out.finished_at, node.finished_at);
    // A node down for good is no survivor; a node that came back counts as one.
    if (!down.empty() && down[v]) {
      ++out.crashed_nodes;
      continue;
    }
    if (node.outcome == protocols::PackingOutcome::neighbour_failed) {
      ++out.failed_nodes;
      ++out.suspects[node.suspect];
    }
  }
  for (OutageOutcome& o : out.outages) {
    o.outcome = nodes[o.node].outcome;
    o.final = nodes[o.node].final;
  }
}

void collect_packing_nodes(const core::PlanarGraph& g,
                           const std::function<const protocols::PackingNode&(core::Vertex)>& node_of,
                           const std::vector<bool>& down, ProtocolOutcome& out) {
  std::vector<PackingNodeSummary> nodes;
  nodes.reserve(g.num_vertices());
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) nodes.push_back(summarize(node_of(v)));
  collect_packing_summaries(g, nodes, down, out);
}

void collect_traffic(const sim::TrafficMetrics& traffic, ProtocolOutcome& out) {
  const sim::TrafficCounters total = traffic.total();
  out.messages = total.messages_sent;
  out.bytes = total.bytes_sent;
  for (std::size_t v = 0; v < traffic.node_count(); ++v) {
    const auto t = traffic.node_total(static_cast<std::uint32_t>(v));
    out.max_node_messages = std::max(out.max_node_messages, t.messages_sent);
    out.max_node_bytes = std::max(out.max_node_bytes, t.bytes_sent);
  }
  out.by_phase.clear();
  for (std::size_t p = 0; p < traffic.phase_count(); ++p) out.by_phase.push_back(traffic.phase_total(static_cast<sim::Phase>(p)));
}

namespace {
// Observes `host` between events and reports its progress to `report` every `period` seconds: the
// clock is read every 2^16 events (a few microseconds per ~50 ms of simulation), the nodes scanned
// only when a report is due.
void watch_progress(sim::SimHost& host, const std::function<void(const ProtocolProgress&)>& report, double period) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto every = std::chrono::duration<double>(period);
  host.simulator().set_observer(std::uint64_t{1} << 16, [&host, report, start, every, last = start]() mutable {
    const auto now = clock::now();
    if (now - last < every) return;
    last = now;
    const sim::Simulator& sim = host.simulator();
    ProtocolProgress p;
    p.nodes = sim.network().node_count();
    p.phase = protocols::PackingPhase::finished;
    p.rounds = p.iterations = std::numeric_limits<std::uint32_t>::max();
    for (sim::NodeIndex v = 0; v < p.nodes; ++v) {
      const auto& node = static_cast<const protocols::PackingNode&>(host.node(v));
      p.phase = std::min(p.phase, node.phase());
      p.rounds = std::min(p.rounds, node.round());
      p.iterations = std::min(p.iterations, node.steps());
      p.holds_nodes += node.local_condition() == core::LocalCondition::holds;
      p.final_nodes += node.is_final();
    }
    if (p.nodes == 0) p.rounds = p.iterations = 0;
    p.events = sim.kernel().events_processed();
    p.wall_seconds = std::chrono::duration<double>(now - start).count();
    p.simulated_time = sim.now();
    report(p);
  });
}
}  // namespace

HyperbolicSetupOutcome run_hyperbolic_setup(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                                            const sim::LinkModel& link, std::uint64_t seed, core::Vertex root) {
  link.validate();
  if (link.loss > 0 || link.duplication > 0)
    throw core::InputError("network", 0, "the hyperbolic set-up runs on reliable links only (found loss or duplication)");
  if (link.latency.kind == sim::LatencyKind::distance && positions.empty())
    throw core::InputError("a distance latency needs node positions, and this topology has none");
  const std::size_t n = g.num_vertices();
  protocols::HyperbolicSetupParams params;
  if (n > 0) params.initiator = g.id(0);
  if (root != core::none) params.root = g.id(root);
  sim::SimConfig config;
  config.seed = seed;
  sim::SimHost host(
      make_network(g, positions, link), config,
      [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        std::vector<protocols::NodeId> nb;
        for (const core::Vertex u : g.neighbours(v)) nb.push_back(g.id(u));
        return std::make_unique<protocols::HyperbolicSetupNode>(rt, g.id(v), std::move(nb), params);
      },
      traffic_phase);
  const sim::RunReport report = host.run({});
  HyperbolicSetupOutcome out;
  ProtocolOutcome traffic;
  collect_traffic(host.simulator().traffic(), traffic);
  out.messages = traffic.messages;
  out.bytes = traffic.bytes;
  out.max_node_messages = traffic.max_node_messages;
  out.by_phase = std::move(traffic.by_phase);
  out.simulated_time = report.simulated_time;
  out.wall_seconds = report.wall_seconds;
  out.parents.assign(n, core::none);
  out.depths.assign(n, 0);
  out.addresses.resize(n);
  for (core::Vertex v = 0; v < n; ++v) {
    const auto& node = static_cast<const protocols::HyperbolicSetupNode&>(host.node(v));
    out.done_nodes += node.done();
    out.rejected += node.counters().rejected;
    const std::size_t state = node.state_bytes();
    out.state_bytes += state;
    out.max_state_bytes = std::max(out.max_state_bytes, state);
    out.depths[v] = node.depth();
    out.addresses[v] = node.address();
    if (node.is_root()) {
      out.root = v;
      out.tiling_degree = node.tiling_degree();
    } else if (const auto p = host.simulator().network().index_of(node.parent())) {
      out.parents[v] = *p;
    }
  }
  for (core::Vertex v = 0; v < n; ++v) {
    const auto& node = static_cast<const protocols::HyperbolicSetupNode&>(host.node(v));
    for (std::size_t i = 0; i < g.degree(v); ++i)
      out.inconsistent_tables += node.neighbour_address(i) != out.addresses[g.neighbours(v)[i]];
  }
  return out;
}

ProtocolOutcome run_packing_protocol(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                                     const ProtocolSetup& setup) {
  const std::size_t n = g.num_vertices();
  setup.link.validate();
  if (setup.link.latency.kind == sim::LatencyKind::distance && positions.empty())
    throw core::InputError("a distance latency needs node positions, and this topology has none");
  protocols::PackingParams params = packing_params(setup);
  sim::Network network = make_network(g, positions, setup.link);
  ProtocolOutcome out;
  std::vector<bool> down(n, false);  // down for good
  for (const CrashSpec& c : setup.crashes) {
    const auto v = network.index_of(c.node);
    if (!v)
      throw core::InputError("crash " + crash_text(c), 0, "the graph has no node with id " + std::to_string(c.node));
    network.add_crash(*v, c.at, c.recover_at);
    out.outages.push_back({c, *v, protocols::PackingOutcome::running, false});
    if (!c.recover_at) down[*v] = true;
  }
  // Loss, duplication and crashes need the reliability layer (PackingNode.hpp, "Loss, duplication and
  // crashes"); on reliable links it stays off and the wire traffic is the synchronous protocol's.
  out.lossy = setup.lossy();
  if (out.lossy) {
    protocols::enable_lossy_links(params, max_latency(network, setup.link));
    if (setup.retransmit_after) params.retransmit_after = std::max<sim::Duration>(1, *setup.retransmit_after);
    params.adaptive_rto = setup.adaptive_rto;
  }
  out.retransmit_after = params.retransmit_after;
  out.adaptive_rto = params.adaptive_rto;
  sim::SimConfig config;
  config.seed = setup.seed;
  // The nodes' results, read where each node lives (every node here, or its MPI rank's, which builds
  // only its own nodes).
  sim::InPlaceRunner in_place;
  sim::HostRunner& runner = setup.runner != nullptr ? *setup.runner : in_place;
  std::vector<std::uint8_t> held = runner.ownership(network);
  sim::SimHost host(
      std::move(network), config,
      [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        return std::make_unique<protocols::PackingNode>(rt, protocols::local_knowledge(g, v), params);
      },
      traffic_phase, std::move(held));
  if (setup.on_progress && setup.runner == nullptr) watch_progress(host, setup.on_progress, setup.progress_period);
  const sim::RunReport report = runner.run(host, {});
  std::vector<PackingNodeSummary> nodes(n);
  const auto summary_of = [&](sim::NodeIndex v) { return summarize(static_cast<const protocols::PackingNode&>(host.node(v))); };
  if (setup.runner == nullptr) {  // every node is here: no byte copies of the summaries
    for (core::Vertex v = 0; v < n; ++v) nodes[v] = summary_of(v);
  } else {
    const std::vector<std::vector<std::byte>> described = runner.gather([&](sim::NodeIndex v) {
      std::vector<std::byte> bytes;
      sim::append_bytes(bytes, summary_of(v));
      return bytes;
    });
    for (core::Vertex v = 0; v < n; ++v) {
      std::size_t at = 0;
      nodes[v] = sim::read_bytes<PackingNodeSummary>(described[v], at);
    }
  }
  collect_packing_summaries(g, nodes, down, out);
  collect_traffic(runner.traffic(), out);
  out.simulated_time = report.simulated_time;
  out.wall_seconds = report.wall_seconds;
  out.events = report.events_processed;
  out.events_per_second = report.events_per_second;
  out.peak_memory_bytes = report.peak_memory_bytes;
  return out;
}


std::string verify_against_core(const core::PlanarGraph& g, core::GraphKind kind, const ProtocolSetup& setup,
                                const ProtocolOutcome& outcome) {
  const std::size_t n = g.num_vertices();
  if (outcome.failed_nodes > 0) return "not applicable: the run was abandoned after a node failure";
  if (setup.asynchronous) {
    // The asynchronous iterates depend on timing: check the nodes' embedding with core's own checks.
    const auto checks = core::check_all(g, outcome.circles);
    const auto ok = static_cast<std::size_t>(std::count(checks.begin(), checks.end(), core::LocalCondition::holds));
    return "asynchronous mode (not bit for bit by design): core's " +
           std::string(kind == core::GraphKind::triangulated_disc ? "LPD" : "GLPD") + " check holds at " +
           std::to_string(ok) + "/" + std::to_string(n) + " nodes";
  }
  const core::PackResult r = core::pack(g, protocols::reference_options(packing_params(setup)));
  const core::CircleEmbedding& phi = outcome.circles;
  bool same = r.iterations == static_cast<int>(outcome.iterations);
  for (core::Vertex v = 0; v < n && same; ++v)
    same = r.circles[v].x == phi[v].x && r.circles[v].y == phi[v].y && r.circles[v].r == phi[v].r;
  return same ? "identical to core::pack, bit for bit" : "DIFFERS from core::pack";
}

std::unique_ptr<protocols::Node> make_forwarding_node(protocols::Runtime& rt, protocols::PacketSink& sink,
                                                      const core::PlanarGraph& g, core::Vertex v,
                                                      const core::CircleEmbedding& circles,
                                                      const std::vector<core::Point2>& positions,
                                                      const std::optional<protocols::ReliableParams>& reliable) {
  if (reliable) {
    std::vector<protocols::NodeId> ids;
    for (const core::Vertex w : g.neighbours(v)) ids.push_back(g.id(w));
    return std::make_unique<protocols::ReliableNode>(rt, std::move(ids), *reliable, [&](protocols::Runtime& inner) {
      return make_forwarding_node(inner, sink, g, v, circles, positions);
    });
  }
  std::vector<protocols::NodeId> nb;
  std::vector<core::Circle> nb_circles;
  std::vector<core::Point2> nb_points;
  for (core::Vertex w : g.neighbours(v)) {
    nb.push_back(g.id(w));
    nb_circles.push_back(circles[w]);
    nb_points.push_back(positions[w]);
  }
  return std::make_unique<protocols::ForwardingNode>(rt, sink, g.id(v), nb, circles[v], nb_circles, positions[v],
                                                     nb_points);
}

protocols::ForwardingNode& forwarding_node(protocols::Node& node) {
  auto* layer = dynamic_cast<protocols::ReliableNode*>(&node);
  return static_cast<protocols::ForwardingNode&>(layer ? layer->inner() : node);
}

std::vector<core::Point2> forwarding_positions(const core::CircleEmbedding& circles,
                                               const std::vector<core::Point2>& positions) {
  if (!positions.empty()) return positions;
  std::vector<core::Point2> pos(circles.size());
  for (std::size_t v = 0; v < circles.size(); ++v) pos[v] = core::centre(circles[v]);
  return pos;
}

protocols::DataPacket forwarding_packet(const core::PlanarGraph& g, const core::CircleEmbedding& circles,
                                        const std::vector<core::Point2>& positions, core::Scheme scheme,
                                        const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs, std::size_t i) {
  // core::route's default hop limit, so that the hop-by-hop outcomes are core's.
  const auto ttl = static_cast<std::uint32_t>(std::min<std::size_t>(core::default_ttl(g, scheme), 0xffffffffu));
  const core::Vertex t = pairs[i].second;
  return {i, g.id(t), circles[t], ttl, scheme, positions[t]};
}

ForwardingResult summarize_forwarding(core::Scheme scheme, const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs,
                                      const std::vector<std::vector<std::uint32_t>>& hop_distance,
                                      const std::vector<protocols::PacketReport>& reports) {
  ForwardingResult res;
  res.scheme = scheme;
  res.packets = pairs.size();
  // In packet order, not in the order the packets ended: the sums (hence the means, to the last bit)
  // depend on the packets' outcomes only, not on the host's timing.
  std::vector<const protocols::PacketReport*> by_packet;
  by_packet.reserve(reports.size());
  for (const auto& r : reports) by_packet.push_back(&r);
  std::sort(by_packet.begin(), by_packet.end(), [](const auto* a, const auto* b) { return a->packet < b->packet; });
  std::vector<double> stretch;
  double hops = 0;
  for (const protocols::PacketReport* report : by_packet) {
    const protocols::PacketReport& r = *report;
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
  return res;
}

protocols::ReliableParams forwarding_reliable_params(sim::Duration max_latency) {
  protocols::ReliableParams reliable = protocols::lossy_link_params(max_latency);
  reliable.probes = false;
  return reliable;
}

void require_forwarding_schemes(const std::vector<core::Scheme>& schemes) {
  for (const core::Scheme s : schemes)
    if (std::find(core::all_schemes.begin(), core::all_schemes.end(), s) == core::all_schemes.end())
      throw core::InputError("--scheme", 0,
                             "found '" + scheme_name(s) +
                                 "', expected a scheme of the per-node forwarding protocol (greedy-power, greedy-euclid, "
                                 "compass or gfg); the hyperbolic baseline is routed centrally by `laguerre route`, "
                                 "`run` and `compare`");
}

std::string forwarding_blocker(const ProtocolOutcome& outcome) {
  if (outcome.failed_nodes > 0) return "the packing run was abandoned";
  if (!std::all_of(outcome.circles.begin(), outcome.circles.end(), protocols::forwardable))
    return "some final circles are not finite (the run stopped before its layout was representable in doubles)";
  return {};
}

std::vector<ForwardingResult> run_forwarding(const core::PlanarGraph& g, const core::CircleEmbedding& circles,
                                             const std::vector<core::Point2>& positions, const sim::LinkModel& link,
                                             std::uint64_t seed, const std::vector<core::Scheme>& schemes,
                                             const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs) {
  require_forwarding_schemes(schemes);
  if (pairs.empty()) return {};  // nothing to forward: no node is built (a blocked run's circles may not be finite)
  const std::size_t n = g.num_vertices();
  const std::vector<core::Point2> pos = forwarding_positions(circles, positions);
  const std::vector<std::vector<std::uint32_t>> hop_distance = hop_distances_from_sources(g, pairs);
  // On lossy links every node runs the reliability layer under its forwarding node: each hop is
  // delivered exactly once, so the packets take core::route's paths.
  const bool lossy = link.loss > 0 || link.duplication > 0;
  std::optional<protocols::ReliableParams> reliable;
  if (lossy) reliable = forwarding_reliable_params(max_latency(make_network(g, positions, link), link));
  sim::SimConfig config;
  config.seed = seed;
  std::vector<ForwardingResult> results;
  for (const core::Scheme scheme : schemes) {
    PacketCollector sink;
    sim::SimHost fwd(
        make_network(g, positions, link), config,
        [&](protocols::Runtime& rt, sim::NodeIndex v) {
          return make_forwarding_node(rt, sink, g, v, circles, pos, reliable);
        },
        traffic_phase);
    for (std::size_t i = 0; i < pairs.size(); ++i)
      forwarding_node(fwd.node(pairs[i].first)).originate(forwarding_packet(g, circles, pos, scheme, pairs, i));
    const sim::RunReport fwd_report = fwd.run();
    std::uint64_t retransmissions = 0;
    for (sim::NodeIndex v = 0; lossy && v < n; ++v)
      retransmissions += static_cast<const protocols::ReliableNode&>(fwd.node(v)).counters().retransmissions;
    ForwardingResult res = summarize_forwarding(scheme, pairs, hop_distance, sink.reports);
    res.retransmissions = retransmissions;
    res.simulated_seconds = sim::to_seconds(fwd_report.simulated_time);
    results.push_back(res);
  }
  return results;
}

}  // namespace laguerre::scenarios
