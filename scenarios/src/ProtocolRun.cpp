// The packing protocol on the simulator (what `laguerre simulate` does, as a library function).
#include "laguerre/scenarios/ProtocolRun.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/PackingNode.hpp"
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

// Traffic is counted under the message type; a frame of the reliability layer under the type of the
// message it carries, a probe (empty frame) and an ack under their own.
sim::Phase phase_of(std::span<const std::byte> bytes) {
  const std::size_t frame_header = protocols::encoded_size(protocols::MessageType::frame);
  if (bytes.size() > frame_header + 1 && bytes[1] == static_cast<std::byte>(protocols::MessageType::frame))
    return static_cast<sim::Phase>(bytes[frame_header + 1]);
  return bytes.size() >= 2 ? static_cast<sim::Phase>(bytes[1]) : 0;
}
}  // namespace

ProtocolOutcome run_packing_protocol(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                                     const ProtocolSetup& setup) {
  const std::size_t n = g.num_vertices();
  setup.link.validate();
  if (setup.link.latency.kind == sim::LatencyKind::distance && positions.empty())
    throw std::invalid_argument("a distance latency needs node positions, and this topology has none");
  protocols::PackingParams params;
  params.steps_per_check = setup.steps_per_round;
  params.max_iterations = setup.max_iterations;
  params.root = setup.root;
  params.asynchronous = setup.asynchronous;
  sim::Network network = make_network(g, positions, setup.link);
  std::vector<sim::NodeIndex> crashed;
  for (const CrashSpec& c : setup.crashes) {
    const auto v = network.index_of(c.node);
    if (!v) throw std::invalid_argument("crash " + std::to_string(c.node) + "@" + format_duration(c.at) +
                                        ": the graph has no node with id " + std::to_string(c.node));
    network.add_crash(*v, c.at);
    crashed.push_back(*v);
  }
  const bool lossy = setup.link.loss > 0 || setup.link.duplication > 0 || !setup.crashes.empty() ||
                     setup.retransmit_after.has_value();
  if (lossy) {
    protocols::enable_lossy_links(params, max_latency(network, setup.link));
    if (setup.retransmit_after) params.retransmit_after = std::max<sim::Duration>(1, *setup.retransmit_after);
  }
  sim::SimConfig config;
  config.seed = setup.seed;
  sim::SimHost host(
      std::move(network), config,
      [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        return std::make_unique<protocols::PackingNode>(rt, protocols::local_knowledge(g, v), params);
      },
      phase_of);
  const sim::RunReport report = host.run();

  ProtocolOutcome out;
  out.circles.resize(n);
  out.local.resize(n);
  for (core::Vertex v = 0; v < n; ++v) {
    const auto& node = static_cast<const protocols::PackingNode&>(host.node(v));
    out.circles[v] = node.placement().circle;
    out.local[v] = node.local_condition();
    out.converged_nodes += node.outcome() == protocols::PackingOutcome::converged;
    out.holds_nodes += node.local_condition() == core::LocalCondition::holds;
    out.iterations = std::max(out.iterations, node.steps());
    out.rounds = std::max(out.rounds, node.round());
    out.retransmissions += node.counters().retransmissions;
    if (std::find(crashed.begin(), crashed.end(), v) != crashed.end()) continue;
    out.failed_nodes += node.outcome() == protocols::PackingOutcome::neighbour_failed;
  }
  std::sort(crashed.begin(), crashed.end());
  out.crashed_nodes = static_cast<std::size_t>(std::unique(crashed.begin(), crashed.end()) - crashed.begin());
  const auto& traffic = host.simulator().traffic();
  const sim::TrafficCounters total = traffic.total();
  out.messages = total.messages_sent;
  out.bytes = total.bytes_sent;
  for (sim::NodeIndex v = 0; v < n; ++v) out.max_node_messages = std::max(out.max_node_messages, traffic.node_total(v).messages_sent);
  out.simulated_seconds = sim::to_seconds(report.simulated_time);
  out.wall_seconds = report.wall_seconds;
  out.events = report.events_processed;
  return out;
}

}  // namespace laguerre::scenarios
