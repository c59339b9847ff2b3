#pragma once
/// @file
/// The protocols of `laguerre simulate` on the live host: P processes on 127.0.0.1 (sim::LiveCluster),
/// each hosting a contiguous block of the nodes over UDP (sim::UdpHost), run the packing protocol
/// (phase 0) and then hop-by-hop forwarding, one phase per scheme, with the wiring of ProtocolRun.
/// In sync mode the outcome's circles, iterations and per-node outcomes are core::pack's bit for bit
/// whatever the real timing; with loss the reliability layer keeps them so.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "laguerre/core/EnumNames.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
#include "laguerre/sim/LiveCluster.hpp"

namespace laguerre::scenarios {

/// How to run live (the protocol itself is described by a ProtocolSetup).
/// How `laguerre live` spreads the nodes over its workers.
enum class LivePartition {
  blocks,  ///< contiguous blocks of vertex indices (sim::LiveCluster::partition_blocks)
  metis,   ///< METIS k-way, as the MPI kernel partitions (fewer links between workers)
};
inline constexpr core::EnumNames<LivePartition, 2> live_partition_names{
    {{LivePartition::blocks, "blocks"}, {LivePartition::metis, "metis"}}};

struct LiveSetup {
  std::size_t processes = 1;              ///< worker processes
  std::vector<std::size_t> process_of;    ///< worker of each vertex (sim::LiveConfig::process_of); empty: blocks
  std::uint16_t base_port = 0;            ///< worker k binds base_port + k; 0: free ports
  double timeout_seconds = 60;            ///< bound on the whole run
  int socket_buffer = 4 << 20;            ///< SO_RCVBUF / SO_SNDBUF requested
  std::size_t max_datagram = sim::max_udp_payload;  ///< largest datagram, header included
  /// One-way latency the reliability layer's periods are fitted to (protocols::enable_lossy_links).
  sim::Duration assumed_latency = 1'000'000;
  std::optional<std::size_t> fail_worker;  ///< failure injection (sim::LiveConfig::fail_worker)
};

/// What a live run produced.
struct LiveOutcome {
  ProtocolOutcome packing;                   ///< as run_packing_protocol's (times are wall-clock)
  std::vector<ForwardingResult> forwarding;  ///< one per scheme (simulated_seconds: wall seconds)
  std::vector<sim::WorkerReport> workers;    ///< per worker process
  sim::UdpCounters total;                    ///< the workers' counters, summed
  std::vector<double> phase_seconds;         ///< wall seconds of each phase (packing, then each scheme)
};

/// Runs the packing protocol on `g` (prepared for packing) live, then forwards one packet per pair
/// of `pairs` per scheme (none if a node failed). Throws core::InputError for what the live host
/// cannot do (duplication, outages, a distance latency: real links have their own timing) or bad live
/// settings, and what sim::LiveCluster throws.
LiveOutcome run_live(const core::PlanarGraph& g, const std::vector<core::Point2>& positions, const ProtocolSetup& setup,
                     const LiveSetup& live, const std::vector<core::Scheme>& schemes,
                     const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs);

}  // namespace laguerre::scenarios
