#pragma once
/// @file
/// The reliability layer as a decorator: a `ReliableNode` wraps any `Node` and serves it a `Runtime`
/// whose links deliver every message exactly once (no loss, no duplicate; not necessarily in order),
/// over a host whose links lose, duplicate, delay and reorder messages, and whose nodes may crash.
/// docs/protocol.md ("Loss, duplication and crashes") describes the frames, acknowledgements,
/// retransmission with backoff, adaptive timeout, probes and the failure flood.
///
/// Wire: everything the layer sends is a LinkMessage (Codec.hpp): the inner node's messages travel as
/// FrameMsg payloads, a FailureMsg (type 15) payload is the layer's failure notice. An inner node must
/// therefore never send a message whose type byte (byte 1) is MessageType::failure.
///
/// Guarantees, given a host that keeps the Runtime contract and neighbours that run ReliableNode with
/// the same ReliableParams: a message the inner node sends to a live neighbour reaches that
/// neighbour's inner node exactly once, unless the link is given up. A link is given up after
/// `max_retransmissions` retransmissions without progress (or a neighbour silent while probed); the
/// layer then floods a failure notice, every layer that gets it stops delivering to its inner node and
/// calls `Node::on_failure(suspect)` once, and every node goes quiet (the host's queue drains).

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols {

/// The layer's parameters (all nodes of a run must agree on them).
struct ReliableParams {
  Duration retransmit_after = 0;  ///< first retransmission period (ns; a ReliableNode needs > 0)
  int backoff_cap = 8;            ///< longest retransmission period, in multiples of retransmit_after (≥ 1)
  int max_retransmissions = 24;   ///< retransmissions without progress before a neighbour is suspected (≥ 1)
  Duration ack_delay = 0;         ///< wait before a standalone ack (ns), in case a frame can carry it
  Duration probe_after = 0;       ///< silence before a node probes a neighbour (ns); 0 = 32 × retransmit_after
  bool probes = true;             ///< probe silent neighbours until the inner node is final (Node::is_final)
  bool adaptive_rto = true;       ///< adapt each link's retransmission timeout to measured round trips
  Duration rto_min = 0;           ///< lower clamp of the adaptive timeout (ns); 0 = retransmit_after / 4
  std::uint32_t initial_seq = 0;  ///< first sequence number of every link
};

/// Throws core::InternalError (a broken precondition) if a parameter is out of range (retransmit_after, ack_delay,
/// probe_after or rto_min negative; backoff_cap or max_retransmissions below 1).
void validate(const ReliableParams& params);

/// Parameters fitted to links whose one-way latency is at most `max_latency` ns: ack_delay =
/// max_latency / 2, retransmit_after = 3 × max_latency (above the longest round trip plus the ack
/// delay), the rest default.
ReliableParams lossy_link_params(Duration max_latency);

/// The layer's message statistics (physical messages; a broadcast counts once per neighbour).
struct ReliableCounters {
  std::uint64_t sent = 0;                                   ///< messages handed to the host's runtime
  std::uint64_t bytes_sent = 0;                             ///< their bytes
  std::uint64_t received = 0;                               ///< messages received from the host
  std::array<std::uint64_t, decode_status_count> decode{};  ///< received messages per DecodeStatus (as LinkMessage)
  std::uint64_t not_a_neighbour = 0;                        ///< from an id that is not a neighbour
  std::uint64_t unexpected = 0;                             ///< timers that fit no link
  std::uint64_t bad_payload = 0;                            ///< frame payloads that did not decode (failure notices)
  std::uint64_t frames = 0;                                 ///< frames sent for the first time
  std::uint64_t retransmissions = 0;                        ///< frames sent again after a timeout
  std::uint64_t acks = 0;                                   ///< standalone acks sent
  std::uint64_t duplicates = 0;                             ///< frames received again (never delivered twice)
  std::uint64_t out_of_window = 0;                          ///< frames too far ahead, dropped unacknowledged
  std::uint64_t probes = 0;                                 ///< empty frames sent to silent neighbours
  std::uint64_t links_failed = 0;                           ///< links given up after max_retransmissions

  /// Adds `o` field by field (totals over nodes).
  ReliableCounters& operator+=(const ReliableCounters& o);
};

/// A node that runs an inner node over the reliability layer.
class ReliableNode final : public Node, private Runtime {
public:
  /// Builds the inner node, given the runtime it must use (the layer; valid as long as the layer).
  using InnerFactory = std::function<std::unique_ptr<Node>(Runtime&)>;

  /// The layer on `runtime` (which must outlive it) for a node whose neighbours are `neighbours`
  /// (distinct, not the node itself), wrapping the node `make_inner` builds. Throws
  /// core::InternalError (a broken precondition) on bad neighbours or parameters out of range, or a null inner node.
  /// Inner timer ids must stay below 2^56 (the layer's own use the top byte).
  ReliableNode(Runtime& runtime, std::vector<NodeId> neighbours, ReliableParams params, const InnerFactory& make_inner);
  ~ReliableNode() override;
  ReliableNode(const ReliableNode&) = delete;
  ReliableNode& operator=(const ReliableNode&) = delete;

  /// Starts the inner node, then the probes.
  void on_start() override;
  /// A LinkMessage from the host: acknowledgements, and a fresh frame's payload to the inner node.
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  /// The layer's timers (retransmission, delayed ack, probe); the inner node's go to it.
  void on_timer(TimerId timer) override;
  /// Back from an outage: re-arms retransmissions, owed acks and probes, then the inner node's on_recover.
  void on_recover() override;
  /// Whether the inner node is final or the layer has abandoned the run after a failure.
  bool is_final() const override { return failed_ || inner_->is_final(); }

  /// The wrapped node.
  Node& inner() { return *inner_; }
  /// The wrapped node, read-only.
  const Node& inner() const { return *inner_; }
  /// Whether a failure was detected here or announced by a notice.
  bool failed() const { return failed_; }
  /// The node suspected of having failed (meaningful when failed()).
  NodeId suspect() const { return suspect_; }
  /// The current retransmission timeout towards neighbour i (in `neighbours` order).
  Duration rto(std::size_t i) const;
  /// Message statistics.
  const ReliableCounters& counters() const { return counters_; }

private:
  struct Link;

  NodeId self() const override { return rt_.self(); }
  Time now() const override { return rt_.now(); }
  void send(NodeId to, std::span<const std::byte> bytes) override;
  void broadcast(std::span<const std::byte> bytes) override;
  TimerHandle schedule(Duration after, TimerId timer) override;
  bool cancel(TimerHandle handle) override { return rt_.cancel(handle); }
  std::uint64_t random_u64() override { return rt_.random_u64(); }

  std::size_t index_of(NodeId id) const;
  void raw_send(std::size_t i, std::span<const std::byte> bytes);
  void send_ack(std::size_t i);
  void send_frame(std::size_t i, std::span<const std::byte> payload);
  void put_frame(std::size_t i, std::uint32_t seq, std::span<const std::byte> payload);
  void handle_frame(std::size_t i, FrameMsg& f);
  void handle_ack(std::size_t i, const AckInfo& a);
  void sample_rtt(Link& l, Duration r);
  void deliver(std::size_t i, std::span<const std::byte> payload);
  void flush_acks();
  void arm_retransmit(std::size_t i);
  void on_retransmit(std::size_t i);
  void on_probe();
  void give_up(std::size_t i);
  void declare_failure(NodeId suspect, std::size_t except);

  Runtime& rt_;
  ReliableParams params_;
  std::vector<NodeId> neighbours_;
  std::vector<std::pair<NodeId, std::uint32_t>> sorted_ids_;  // (id, index) for lookup
  std::vector<Link> links_;
  std::vector<std::size_t> ack_owed_;  // links with ack_pending, to flush
  std::vector<std::byte> buffer_;
  TimerHandle probe_timer_ = 0;
  bool failed_ = false;
  NodeId suspect_ = 0;
  ReliableCounters counters_;
  std::unique_ptr<Node> inner_;
};

}  // namespace laguerre::protocols
