#pragma once
/// @file
/// The simulator: delivers byte messages between node handlers over a Network, with timers, link
/// models, crashes, per-node random streams, traffic metrics and an optional trace.
///
/// Semantics (all times in simulated nanoseconds):
///  - Every node is started at time 0, in index order (NodeHandler::on_start).
///  - `send` draws the message's fate from a stream keyed by (seed, link, index of the message on
///    that link): loss, latency, duplication. A delivered copy reaches the receiver's handler at
///    now + latency. Messages only travel on links; sending to a non-neighbour throws.
///  - Crashes come from the Network's schedule. While a node is down, its sends, the copies that
///    reach it, and its timers that fire are dropped and counted. Copies already in flight when their
///    sender crashes are still delivered (they are on the air). A node down at time 0 is started when
///    it first recovers; a node that recovers after having started gets NodeHandler::on_recover (its
///    state survives the outage; timers that fell inside it are lost).
///  - Order at equal times: every event carries a key (Kernel::schedule_keyed_at) that depends only
///    on the node or link that caused it, never on the order in which events were scheduled:
///        kind (2 bits) · field (32 bits) · counter (30 bits), most significant first,
///    kind 0 a crash or recovery (field: node; counter: 2·(index in the failure schedule) + 1 for the
///    recovery), 1 a start (node; 0), 2 a delivered copy (directed link; 2·(index of the message on
///    the link) + copy), 3 a timer (node; index of the timer among the node's timers). So at equal
///    times a crash or recovery precedes every start, message and timer due at that instant (a crash
///    at time 0 means the node never starts before it recovers), copies precede timers, copies come
///    by (sender, receiver, message index) and a node's timers in the order it set them. Because
///    the key is a function of the causing node's own history, a partitioned run (sim/mpi) processes
///    every node's events in the same order as this one. Past 2^29 messages on one link or 2^30
///    timers at one node, send/schedule_timer throw std::length_error.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "laguerre/sim/Kernel.hpp"
#include "laguerre/sim/Metrics.hpp"
#include "laguerre/sim/Network.hpp"
#include "laguerre/sim/Random.hpp"
#include "laguerre/sim/Trace.hpp"

namespace laguerre::sim {

class Simulator;

/// Identifies a pending timer (a kernel event handle); value 0 is never a live timer.
using TimerHandle = EventHandle;

/// The callbacks a simulator invokes for the nodes it runs (one object serves every node).
class NodeHandler {
public:
  virtual ~NodeHandler() = default;
  /// Node `v` starts (once, before any other callback for `v`).
  virtual void on_start(Simulator& sim, NodeIndex v) = 0;
  /// A copy of a message from neighbour `from` reached `v`; `bytes` is valid during the call only.
  virtual void on_message(Simulator& sim, NodeIndex v, NodeIndex from, Phase phase,
                          std::span<const std::byte> bytes) = 0;
  /// A timer that `v` scheduled fired.
  virtual void on_timer(Simulator& sim, NodeIndex v, std::uint64_t timer) = 0;
  /// Node `v` came back after a crash (only if it had started before).
  virtual void on_recover(Simulator& /*sim*/, NodeIndex /*v*/) {}
  /// A hint: a message for `v` is a few events ahead; start loading (__builtin_prefetch) the state
  /// on_message will touch. Must not change anything. The default does nothing.
  virtual void prefetch(NodeIndex /*v*/) const {}
  /// The second stage of the hint, about two events after prefetch(v) for the same message, when
  /// what prefetch(v) loaded has likely arrived: start loading the state found through it (e.g. a
  /// node's arrays behind pointers in its object). Must not change anything. Default: nothing.
  virtual void prefetch_state(NodeIndex /*v*/) const {}
};

/// Receives the copies that a partitioned Simulator addresses to nodes it does not own (see
/// Simulator::partition); the parallel kernel implements it.
class RemoteOutbox {
public:
  virtual ~RemoteOutbox() = default;
  /// A copy of `bytes` from `from` to `to` (a node another part owns), due at `at` with event key
  /// `key` (see the file comment); `bytes` is valid during the call only.
  virtual void post(Time at, std::uint64_t key, NodeIndex from, NodeIndex to, Phase phase,
                    std::span<const std::byte> bytes) = 0;
};

/// Run-wide settings.
struct SimConfig {
  std::uint64_t seed = 1;              ///< the root of every random stream
  TraceMode trace = TraceMode::off;    ///< what to keep of delivered messages
};

/// A discrete-event simulation of one network. Not copyable (the kernel's handlers point at it).
class Simulator {
public:
  /// A simulator of `network` whose nodes are served by `handler` (which must outlive it).
  /// With `held` (one flag per node; empty: every node), it is built for one part of a partitioned
  /// run: it holds the state of the nodes v with held[v] != 0 only (random streams, timer counts,
  /// crash state, traffic counters) and of their outgoing links (message counters, random link
  /// keys), each keyed as in the whole simulator; it must then be partition()ed with the same flags
  /// before it runs (flags that hold every node build the whole simulator). Throws
  /// core::InternalError (a broken precondition) if the network is inconsistent (Network::validate)
  /// or `held` has the wrong size.
  Simulator(Network network, SimConfig config, NodeHandler& handler, std::vector<std::uint8_t> held = {});
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// Runs until the limits (see Kernel::run); the first call starts the nodes and the failure
  /// schedule. May be called again to continue.
  RunReport run(const RunLimits& limits = {});
  /// Asks run() to return after the current event.
  void request_stop() { kernel_.request_stop(); }
  /// Calls `observer` between events during run(), each time `every` ≥ 1 more events have been
  /// processed (e.g. to draw progress); it may read anything but must not send, schedule or stop.
  /// An empty observer (the default) removes it: run() is then the kernel's loop alone, at no cost.
  /// The run is the same with or without an observer (a kernel run stopped and resumed between events
  /// equals one never stopped).
  void set_observer(std::uint64_t every, std::function<void()> observer);

  /// Current simulated time.
  Time now() const { return kernel_.now(); }
  /// Sends `bytes` from `from` to its neighbour `to`, tagged with `phase`. Throws
  /// core::InternalError (a broken precondition) if `to` is not a neighbour of `from`.
  void send(NodeIndex from, NodeIndex to, std::span<const std::byte> bytes, Phase phase = 0);
  /// Sends `bytes` on the directed link `link` (from its source to its target), tagged with `phase`:
  /// `send` without the neighbour lookup, for hosts that resolved the link once. Requires
  /// `link` < network().link_count().
  void send_on_link(LinkIndex link, std::span<const std::byte> bytes, Phase phase = 0);
  /// Sends `bytes` from `from` to each of its neighbours (one copy of the bytes is stored).
  void broadcast(NodeIndex from, std::span<const std::byte> bytes, Phase phase = 0);
  /// Schedules NodeHandler::on_timer(v, timer) after `after` ≥ 0 ns. Throws core::InternalError (a broken precondition)
  /// for a negative delay.
  TimerHandle schedule_timer(NodeIndex v, Duration after, std::uint64_t timer);
  /// Cancels a pending timer; false if it already fired, was cancelled, or is unknown.
  bool cancel_timer(TimerHandle handle) {
    return kernel_.cancel(handle) == CancelResult::cancelled;
  }
  /// The random stream of node `v` (a held node), keyed by (seed, node, id(v)).
  RandomStream& node_stream(NodeIndex v) { return node_streams_[local_index(v)]; }
  /// Whether `v` (a held node) is up (not crashed) now.
  bool is_up(NodeIndex v) const { return down_[local_index(v)] == 0; }

  /// The number of nodes whose state this simulator holds (node_count() unless built for a part).
  std::size_t local_count() const { return local_.empty() ? network_.node_count() : held_.size(); }
  /// The position of held node `v` among the held nodes, by increasing index (v itself unless built
  /// for a part): per-node tables of the simulator and its hosts are indexed by it.
  NodeIndex local_index(NodeIndex v) const { return local_.empty() ? v : local_[v]; }
  /// The held node at position `i` < local_count() (the inverse of local_index).
  NodeIndex local_node(std::size_t i) const { return local_.empty() ? static_cast<NodeIndex>(i) : held_[i]; }
  /// The position of held node `v`'s first outgoing link among the held nodes' links (in network
  /// order; its i-th link comes i later): per-link tables of hosts are indexed by it.
  std::size_t local_link_start(NodeIndex v) const { return local_link(network_.link_at(v, 0), local_index(v)); }

  /// The network.
  const Network& network() const { return network_; }
  /// The settings.
  const SimConfig& config() const { return config_; }
  /// Traffic counters per held node (by local_index) and phase.
  const TrafficMetrics& traffic() const { return traffic_; }
  /// The trace of delivered messages.
  const Trace& trace() const { return trace_; }
  /// Timers dropped because their node was down when they fired.
  std::uint64_t timers_dropped() const { return timers_dropped_; }
  /// Makes this simulator one part of a partitioned run; call before the first run. It then starts
  /// and fails only the nodes v with owned[v] != 0, hands every copy addressed to another node to
  /// `outbox` (which must outlive it) instead of scheduling it, and keeps every trace record (a
  /// hash_only trace becomes a records trace) with its event key (trace_keys), for the merge. Throws
  /// core::InternalError (a broken precondition) if called after the first run, with
  /// owned.size() != node_count(), or, for a simulator built for a part, with other flags than it was
  /// built with.
  void partition(std::vector<std::uint8_t> owned, RemoteOutbox& outbox);
  /// Schedules the delivery of a copy another part posted (RemoteOutbox::post's arguments); `to`
  /// must be owned. Throws core::InternalError (a broken precondition) if `at` lies in the past.
  void deliver_remote(Time at, std::uint64_t key, NodeIndex from, NodeIndex to, Phase phase,
                      std::span<const std::byte> bytes);
  /// The event key of each trace record, in trace order (partitioned runs only; empty otherwise).
  std::span<const std::uint64_t> trace_keys() const { return trace_keys_; }

  /// The underlying kernel (to schedule extra model events with handlers of one's own).
  Kernel& kernel() { return kernel_; }
  /// The underlying kernel, read-only.
  const Kernel& kernel() const { return kernel_; }

private:
  /// Bytes a message slot holds inline; longer messages spill to a per-slot buffer.
  static constexpr std::size_t inline_bytes = 54;
  /// Slots per chunk of the message pool (chunks never move, so a delivered span stays valid while
  /// its handler sends and the pool grows).
  static constexpr std::size_t chunk_slots = 1024;
  /// One stored message, shared by every copy in flight (reference-counted, recycled): one cache
  /// line, with the bytes inline when they fit (the sender travels in each delivery event's payload,
  /// so that the packing protocol's largest frequent message, a 54-byte PlacedMsg, fits).
  struct alignas(64) Message {
    std::uint32_t size = 0;
    std::uint32_t refs = 0;
    Phase phase = 0;
    std::byte bytes[inline_bytes];
  };
  static_assert(sizeof(Message) == 64, "A message slot is one cache line.");
  /// What a random link model needs per directed link (only kept when some link is not
  /// deterministic, LinkModel::is_deterministic).
  struct LinkRandom {
    std::uint64_t key = 0;  // stream key of the link
    double length = 0;      // distance between its endpoints
  };
  /// The payload of a delivery event: the message slot (low half) and the sender (high half).
  static std::uint64_t delivery_payload(NodeIndex from, std::uint32_t message) {
    return (std::uint64_t{from} << 32) | message;
  }

  static void prefetch_delivery(const void* self, const Event& event);
  void on_start_event(Kernel& kernel, const Event& event);
  void on_deliver_event(Kernel& kernel, const Event& event);
  void on_timer_event(Kernel& kernel, const Event& event);
  void on_crash_event(Kernel& kernel, const Event& event);
  void on_recover_event(Kernel& kernel, const Event& event);
  Message& slot(std::uint32_t message) { return chunks_[message / chunk_slots][message % chunk_slots]; }
  std::span<const std::byte> bytes_of(std::uint32_t message);
  std::uint32_t store(std::span<const std::byte> bytes, Phase phase);
  void release(std::uint32_t message);
  /// Puts one message on link `link` from `from` to `to` (the message is already stored; adds its
  /// references).
  void transmit(LinkIndex link, NodeIndex from, NodeIndex to, std::uint32_t message);
  /// The position of link `l` among the held nodes' links; `from` is local_index of its source.
  std::size_t local_link(LinkIndex l, NodeIndex from) const { return local_.empty() ? l : l - link_shift_[from]; }
  /// Whether copies to `v` go to the outbox (a partitioned run, another part's node).
  bool foreign(NodeIndex v) const {
    return outbox_ != nullptr && (local_.empty() ? owned_[v] == 0 : local_[v] == not_held);
  }
  static constexpr NodeIndex not_held = 0xffffffffu;

  Network network_;
  SimConfig config_;
  NodeHandler* handler_;
  Kernel kernel_;
  HandlerId start_id_, deliver_id_, timer_id_, crash_id_, recover_id_;
  // Built for a part (held flags given): local_[v] is v's position among the held nodes (not_held
  // for the others), held_ the held nodes by increasing index, link_shift_[i] what to subtract from
  // a link index of held node i to get its position among the held nodes' links. All three are
  // empty in a whole simulator, where positions are the indices.
  std::vector<NodeIndex> local_;
  std::vector<NodeIndex> held_;
  std::vector<LinkIndex> link_shift_;
  // Per held node (by local_index) and per link of a held node (by local_link):
  std::vector<RandomStream> node_streams_;
  std::vector<std::uint32_t> link_sent_;     // messages sent so far on each directed link (< 2^29)
  std::vector<LinkRandom> link_random_;      // per directed link; empty if every link is deterministic
  std::vector<std::uint32_t> node_timers_;    // timers set so far by each node (their event keys)
  std::vector<std::uint32_t> down_;  // outages in progress per node
  std::vector<std::uint8_t> started_;
  std::vector<std::unique_ptr<Message[]>> chunks_;
  std::uint32_t slots_used_ = 0;                  // slots ever handed out
  std::vector<std::uint32_t> free_messages_;
  std::vector<std::vector<std::byte>> spill_;     // bytes of slot i when longer than inline_bytes
  TrafficMetrics traffic_;
  Trace trace_;
  std::uint64_t timers_dropped_ = 0;
  bool launched_ = false;
  std::uint64_t observe_every_ = 0;     // set_observer
  std::function<void()> observer_;
  RemoteOutbox* outbox_ = nullptr;      // set by partition()
  std::vector<std::uint8_t> owned_;     // partitioned whole simulators: owned_[v] != 0 if v is this part's
  // Receivers of the last prefetch_delivery calls (a ring): the one of two calls ago gets the second
  // stage of the hint (NodeHandler::prefetch_state). A hint only: a stale entry wastes a prefetch.
  mutable NodeIndex prefetched_[2] = {0, 0};
  mutable std::uint32_t prefetch_turn_ = 0;
  std::vector<std::uint64_t> trace_keys_;
};

}  // namespace laguerre::sim
