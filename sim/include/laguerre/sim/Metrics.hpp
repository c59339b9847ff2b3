#pragma once
/// @file
/// Traffic counters per node and per protocol phase, and the report of one run.

#include <cstdint>
#include <string>
#include <vector>

#include "laguerre/sim/Kernel.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::sim {

/// A protocol phase: a small tag the sender attaches to a message (e.g. its codec's message type).
using Phase = std::uint16_t;

/// Message and byte counts. "lost" is the channel's doing (loss probability); "dropped" is a crash's
/// (a send by a crashed node, counted at the sender; a delivery to a crashed node, counted at the
/// receiver).
struct TrafficCounters {
  std::uint64_t messages_sent = 0;        ///< messages handed to the network by the node
  std::uint64_t bytes_sent = 0;           ///< their bytes
  std::uint64_t messages_received = 0;    ///< copies delivered to the node's handler
  std::uint64_t bytes_received = 0;       ///< their bytes
  std::uint64_t messages_lost = 0;        ///< copies sent by the node and lost by the channel
  std::uint64_t bytes_lost = 0;           ///< their bytes
  std::uint64_t messages_dropped = 0;     ///< copies dropped because an endpoint had crashed
  std::uint64_t bytes_dropped = 0;        ///< their bytes
  std::uint64_t messages_duplicated = 0;  ///< extra copies the channel made of the node's messages

  /// Adds `other` field by field.
  TrafficCounters& operator+=(const TrafficCounters& other);
  /// Field-by-field equality.
  friend bool operator==(const TrafficCounters&, const TrafficCounters&) = default;
};

/// Counters indexed by (node, phase); phases appear as they are used. Storage: per phase, one
/// 32-byte record per node for what every message touches (sent and received); the channel's and
/// the crashes' counts (lost, dropped, duplicated) live in a second table per phase, allocated on
/// the first such event, so a run without loss or crashes never pays for it.
class TrafficMetrics {
public:
  /// Counters for `node_count` nodes, no phase yet.
  explicit TrafficMetrics(std::size_t node_count = 0) : node_count_(node_count) {}

  /// Counts one message of `bytes` bytes handed to the network by `node`.
  void add_sent(std::uint32_t node, Phase phase, std::uint64_t bytes) {
    Hot& h = hot(node, phase);
    ++h.messages_sent;
    h.bytes_sent += bytes;
  }
  /// Counts one copy of `bytes` bytes delivered to `node`'s handler.
  void add_received(std::uint32_t node, Phase phase, std::uint64_t bytes) {
    Hot& h = hot(node, phase);
    ++h.messages_received;
    h.bytes_received += bytes;
  }
  /// Counts one copy of `bytes` bytes sent by `node` and lost by the channel.
  void add_lost(std::uint32_t node, Phase phase, std::uint64_t bytes);
  /// Counts `copies` copies of `bytes` bytes each dropped at `node` because an endpoint had crashed.
  void add_dropped(std::uint32_t node, Phase phase, std::uint64_t copies, std::uint64_t bytes);
  /// Counts one extra copy the channel made of a message of `node`.
  void add_duplicated(std::uint32_t node, Phase phase);
  /// Adds `counters` to (`node`, `phase`), creating the phase (e.g. to merge the counts of a
  /// partitioned run); the lost/dropped/duplicated table is created only if one of them is nonzero.
  void add(std::uint32_t node, Phase phase, const TrafficCounters& counters);

  /// Number of phases seen so far (the largest tag + 1).
  std::size_t phase_count() const { return hot_.size(); }
  /// Number of nodes.
  std::size_t node_count() const { return node_count_; }
  /// The counters of (`node`, `phase`), zero if the phase never occurred.
  TrafficCounters get(std::uint32_t node, Phase phase) const;
  /// Sum over phases for one node.
  TrafficCounters node_total(std::uint32_t node) const;
  /// Sum over nodes for one phase.
  TrafficCounters phase_total(Phase phase) const;
  /// Sum over everything.
  TrafficCounters total() const;

private:
  struct Hot {
    std::uint64_t messages_sent = 0, bytes_sent = 0, messages_received = 0, bytes_received = 0;
  };
  struct Cold {
    std::uint64_t messages_lost = 0, bytes_lost = 0, messages_dropped = 0, bytes_dropped = 0, messages_duplicated = 0;
  };
  Hot& hot(std::uint32_t node, Phase phase) {
    if (phase >= hot_.size() || hot_[phase].empty()) grow(phase);
    return hot_[phase][node];
  }
  Cold& cold(std::uint32_t node, Phase phase);
  void grow(Phase phase);
  std::size_t node_count_;
  std::vector<std::vector<Hot>> hot_;   // [phase][node]; empty for a phase never used
  std::vector<std::vector<Cold>> cold_; // [phase][node]; a phase's table is empty until first used
};

/// What one call of Simulator::run did.
struct RunReport {
  StopReason reason = StopReason::queue_empty;  ///< why it returned
  Time simulated_time = 0;                       ///< the clock when it returned
  double wall_seconds = 0;                       ///< wall-clock duration of the call
  std::uint64_t events_processed = 0;            ///< events dispatched during the call
  double events_per_second = 0;                  ///< events_processed / wall_seconds
  std::uint64_t peak_memory_bytes = 0;           ///< the process's peak resident set size so far
};

/// The process's peak resident set size in bytes (getrusage; 0 if unavailable).
std::uint64_t peak_memory_bytes();

}  // namespace laguerre::sim
