#pragma once
/// @file
/// Traffic counters per node and per protocol phase, and the report of one run.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
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

/// Every count of TrafficCounters with its name, in declaration order: the one list that sums,
/// flattens (MPI reductions) and reports them.
inline constexpr std::array<std::pair<std::string_view, std::uint64_t TrafficCounters::*>, 9> traffic_counter_fields{{
    {"messages_sent", &TrafficCounters::messages_sent},
    {"bytes_sent", &TrafficCounters::bytes_sent},
    {"messages_received", &TrafficCounters::messages_received},
    {"bytes_received", &TrafficCounters::bytes_received},
    {"messages_lost", &TrafficCounters::messages_lost},
    {"bytes_lost", &TrafficCounters::bytes_lost},
    {"messages_dropped", &TrafficCounters::messages_dropped},
    {"bytes_dropped", &TrafficCounters::bytes_dropped},
    {"messages_duplicated", &TrafficCounters::messages_duplicated},
}};

/// Counters indexed by (node, phase); phases appear as they are used. Storage: per phase, one
/// 16-byte record per node for what every message touches (sent and received, four 32-bit counts);
/// a count that would pass 2^32 − 1 moves, whole, into a 64-bit record of a third table per phase,
/// allocated on the first such carry (so the counts stay exact at any size, and a run whose
/// per-node counts fit in 32 bits never pays for it). The channel's and the crashes' counts (lost,
/// dropped, duplicated) live in a second table per phase, allocated on the first such event, so a
/// run without loss or crashes never pays for it either.
class TrafficMetrics {
public:
  /// Counters for `node_count` nodes, no phase yet.
  explicit TrafficMetrics(std::size_t node_count = 0) : node_count_(node_count) {}

  /// Counts one message of `bytes` bytes handed to the network by `node`.
  void add_sent(std::uint32_t node, Phase phase, std::uint64_t bytes) {
    Hot& h = hot(node, phase);
    bump(h, 0, 1, node, phase);
    bump(h, 1, bytes, node, phase);
  }
  /// Counts one copy of `bytes` bytes delivered to `node`'s handler.
  void add_received(std::uint32_t node, Phase phase, std::uint64_t bytes) {
    Hot& h = hot(node, phase);
    bump(h, 2, 1, node, phase);
    bump(h, 3, bytes, node, phase);
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
  /// messages_sent, bytes_sent, messages_received, bytes_received: the low part of each count.
  struct Hot {
    std::uint32_t count[4] = {0, 0, 0, 0};
  };
  /// The part of each count carried out of Hot (count = wide + low).
  struct Wide {
    std::uint64_t count[4] = {0, 0, 0, 0};
  };
  /// Adds `amount` to count `k` of `h` (the record of (node, phase)), carrying into the wide table
  /// when the 32-bit count would overflow.
  void bump(Hot& h, int k, std::uint64_t amount, std::uint32_t node, Phase phase) {
    const std::uint64_t sum = std::uint64_t{h.count[k]} + amount;
    if (sum <= 0xffffffffu) [[likely]] {
      h.count[k] = static_cast<std::uint32_t>(sum);
      return;
    }
    carry(h, k, sum, node, phase);
  }
  void carry(Hot& h, int k, std::uint64_t sum, std::uint32_t node, Phase phase);
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
  std::vector<std::vector<Wide>> wide_; // [phase][node]; empty until a count of the phase carries
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
