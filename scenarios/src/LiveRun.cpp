// The protocols on the live host: the worker program (packing, then one forwarding phase per scheme)
// and the launcher's merge of the workers' results into ProtocolRun's outcome types.
#include "laguerre/scenarios/LiveRun.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <type_traits>

#include "laguerre/core/Error.hpp"
#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/protocols/PackingNode.hpp"

namespace laguerre::scenarios {

namespace {
using sim::append_bytes;
using sim::read_bytes;

// One packing node's result, as a worker sends it.
struct NodeRecord {
  std::uint32_t v = 0;
  PackingNodeSummary node;
  std::uint64_t messages_sent = 0;
  std::uint64_t bytes_sent = 0;
};

// What runs in every worker: the packing phase, then one forwarding phase per scheme.
class LiveProtocols final : public sim::LiveProgram, public protocols::PacketSink {
public:
  LiveProtocols(const core::PlanarGraph& g, const std::vector<core::Point2>& positions, protocols::PackingParams params,
                std::optional<protocols::ReliableParams> reliable, const std::vector<core::Scheme>& schemes,
                const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs)
      : g_(g), positions_(positions), params_(params), reliable_(reliable), schemes_(schemes), pairs_(pairs) {}

  void start_phase(std::uint8_t phase, std::span<const std::byte> input, sim::UdpHost& host) override {
    if (phase == 0) {
      host.start_phase(0, [&](protocols::Runtime& rt, core::Vertex v) -> std::unique_ptr<protocols::Node> {
        return std::make_unique<protocols::PackingNode>(rt, protocols::local_knowledge(g_, v), params_);
      });
      pending_ = host.local_vertices();
      return;
    }
    std::size_t at = 0;
    circles_.resize(g_.num_vertices());
    for (core::Circle& c : circles_) c = read_bytes<core::Circle>(input, at);
    const std::vector<core::Point2> pos = forwarding_positions(circles_, positions_);
    const core::Scheme scheme = schemes_[phase - 1];
    reports_.clear();
    host.start_phase(phase, [&](protocols::Runtime& rt, core::Vertex v) {
      return make_forwarding_node(rt, *this, g_, v, circles_, pos, reliable_);
    });
    const auto& local = host.local_vertices();
    for (std::size_t i = 0; i < pairs_.size(); ++i)
      if (std::binary_search(local.begin(), local.end(), pairs_[i].first))
        forwarding_node(host.node(pairs_[i].first)).originate(forwarding_packet(g_, circles_, pos, scheme, pairs_, i));
    host.run_queue();
  }

  std::uint64_t progress(sim::UdpHost& host) override {
    if (!forwarding_) {
      std::erase_if(pending_, [&](core::Vertex v) { return host.node(v).is_final(); });
      return host.local_vertices().size() - pending_.size();
    }
    return reports_.size();
  }

  std::vector<std::byte> finish_phase(std::uint8_t phase, sim::UdpHost& host) override {
    std::vector<std::byte> out;
    if (phase == 0) {
      append_bytes(out, static_cast<std::uint32_t>(host.local_vertices().size()));
      for (const core::Vertex v : host.local_vertices()) {
        const auto& node = static_cast<const protocols::PackingNode&>(host.node(v));
        const sim::TrafficCounters t = host.traffic().node_total(static_cast<std::uint32_t>(v));
        append_bytes(out, NodeRecord{static_cast<std::uint32_t>(v), summarize(node), t.messages_sent, t.bytes_sent});
      }
      const auto& traffic = host.traffic();
      append_bytes(out, static_cast<std::uint32_t>(traffic.phase_count()));
      for (std::size_t p = 0; p < traffic.phase_count(); ++p) {
        sim::TrafficCounters sum;
        for (const core::Vertex v : host.local_vertices())
          sum += traffic.get(static_cast<std::uint32_t>(v), static_cast<sim::Phase>(p));
        append_bytes(out, sum);
      }
      forwarding_ = true;
      return out;
    }
    std::uint64_t retransmissions = 0;
    if (reliable_)
      for (const core::Vertex v : host.local_vertices())
        retransmissions += static_cast<const protocols::ReliableNode&>(host.node(v)).counters().retransmissions;
    append_bytes(out, retransmissions);
    for (const protocols::PacketReport& r : reports_) append_bytes(out, r);
    return out;
  }

  void on_packet_end(const protocols::PacketReport& r) override { reports_.push_back(r); }

private:
  const core::PlanarGraph& g_;
  const std::vector<core::Point2>& positions_;
  protocols::PackingParams params_;
  std::optional<protocols::ReliableParams> reliable_;
  const std::vector<core::Scheme>& schemes_;
  const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs_;
  std::vector<core::Vertex> pending_;
  core::CircleEmbedding circles_;
  std::vector<protocols::PacketReport> reports_;
  bool forwarding_ = false;
};

// The launcher's side of phase 0: the workers' node records merged as run_packing_protocol merges nodes.
void merge_packing(const std::vector<std::vector<std::byte>>& results, const core::PlanarGraph& g, ProtocolOutcome& out) {
  std::vector<PackingNodeSummary> nodes(g.num_vertices());
  for (const auto& blob : results) {
    std::size_t at = 0;
    const auto count = read_bytes<std::uint32_t>(blob, at);
    for (std::uint32_t i = 0; i < count; ++i) {
      const auto r = read_bytes<NodeRecord>(blob, at);
      nodes[r.v] = r.node;
      out.messages += r.messages_sent;
      out.bytes += r.bytes_sent;
      out.max_node_messages = std::max(out.max_node_messages, r.messages_sent);
      out.max_node_bytes = std::max(out.max_node_bytes, r.bytes_sent);
    }
    const auto phases = read_bytes<std::uint32_t>(blob, at);
    if (out.by_phase.size() < phases) out.by_phase.resize(phases);
    for (std::uint32_t p = 0; p < phases; ++p) out.by_phase[p] += read_bytes<sim::TrafficCounters>(blob, at);
  }
  collect_packing_summaries(g, nodes, {}, out);
}
}  // namespace

LiveOutcome run_live(const core::PlanarGraph& g, const std::vector<core::Point2>& positions, const ProtocolSetup& setup,
                     const LiveSetup& live, const std::vector<core::Scheme>& schemes,
                     const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs) {
  require_forwarding_schemes(schemes);
  if (setup.link.duplication > 0)
    throw core::InputError("--dup", 0, "0 on the live host (real links duplicate nothing on loopback)");
  if (!setup.crashes.empty())
    throw core::InputError("--crash", 0, "no outage on the live host (kill a worker process instead)");
  const std::size_t n = g.num_vertices();
  protocols::PackingParams params = packing_params(setup);
  std::optional<protocols::ReliableParams> reliable;
  LiveOutcome result;
  ProtocolOutcome& out = result.packing;
  out.lossy = setup.lossy();
  if (out.lossy) {
    protocols::enable_lossy_links(params, live.assumed_latency);
    if (setup.retransmit_after) params.retransmit_after = std::max<sim::Duration>(1, *setup.retransmit_after);
    params.adaptive_rto = setup.adaptive_rto;
    reliable = forwarding_reliable_params(live.assumed_latency);
  }
  out.retransmit_after = params.retransmit_after;
  out.adaptive_rto = params.adaptive_rto;

  sim::LiveConfig config;
  config.processes = live.processes;
  config.process_of = live.process_of;
  config.base_port = live.base_port;
  config.timeout_seconds = live.timeout_seconds;
  config.fail_worker = live.fail_worker;
  config.lossless = !out.lossy;
  config.host.seed = setup.seed;
  config.host.loss = setup.link.loss;
  config.host.socket_buffer = live.socket_buffer;
  config.host.max_datagram = live.max_datagram;
  LiveProtocols program(g, positions, params, reliable, schemes, pairs);
  sim::LiveCluster cluster(g, config, program, traffic_phase);

  merge_packing(cluster.run_phase({}, n), g, out);
  if (forwarding_blocker(out).empty() && !pairs.empty()) {
    std::vector<std::byte> circles;
    for (const core::Circle& c : out.circles) append_bytes(circles, c);
    const auto hop_distance = hop_distances_from_sources(g, pairs);
    for (const core::Scheme scheme : schemes) {
      std::uint64_t retransmissions = 0;
      std::vector<protocols::PacketReport> reports;
      for (const auto& blob : cluster.run_phase(circles, pairs.size())) {
        std::size_t at = 0;
        retransmissions += read_bytes<std::uint64_t>(blob, at);
        while (at < blob.size()) reports.push_back(read_bytes<protocols::PacketReport>(blob, at));
      }
      ForwardingResult r = summarize_forwarding(scheme, pairs, hop_distance, reports);
      r.retransmissions = retransmissions;
      r.simulated_seconds = cluster.phase_seconds().back();
      result.forwarding.push_back(r);
    }
  }
  result.phase_seconds = cluster.phase_seconds();
  result.workers = cluster.finish();
  for (const sim::WorkerReport& w : result.workers) {
    result.total += w.counters;
    out.peak_memory_bytes = std::max<std::size_t>(out.peak_memory_bytes, w.peak_memory_bytes);
  }
  out.wall_seconds = result.phase_seconds.front();
  out.simulated_time = static_cast<sim::Time>(out.wall_seconds * 1e9);
  double wall = 0;
  for (const double t : result.phase_seconds) wall += t;
  out.events = result.total.datagrams_sent;
  out.events_per_second = wall > 0 ? static_cast<double>(out.events) / wall : 0;
  return result;
}

}  // namespace laguerre::scenarios
