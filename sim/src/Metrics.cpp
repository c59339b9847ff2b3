#include "laguerre/sim/Metrics.hpp"

#include <sys/resource.h>

namespace laguerre::sim {

TrafficCounters& TrafficCounters::operator+=(const TrafficCounters& o) {
  messages_sent += o.messages_sent;
  bytes_sent += o.bytes_sent;
  messages_received += o.messages_received;
  bytes_received += o.bytes_received;
  messages_lost += o.messages_lost;
  bytes_lost += o.bytes_lost;
  messages_dropped += o.messages_dropped;
  bytes_dropped += o.bytes_dropped;
  messages_duplicated += o.messages_duplicated;
  return *this;
}

void TrafficMetrics::grow(Phase phase) {
  by_phase_.resize(std::size_t{phase} + 1, std::vector<TrafficCounters>(node_count_));
}

TrafficCounters TrafficMetrics::get(std::uint32_t node, Phase phase) const {
  if (phase >= by_phase_.size()) return {};
  return by_phase_[phase][node];
}

TrafficCounters TrafficMetrics::node_total(std::uint32_t node) const {
  TrafficCounters sum;
  for (const auto& row : by_phase_) sum += row[node];
  return sum;
}

TrafficCounters TrafficMetrics::phase_total(Phase phase) const {
  TrafficCounters sum;
  if (phase >= by_phase_.size()) return sum;
  for (const auto& c : by_phase_[phase]) sum += c;
  return sum;
}

TrafficCounters TrafficMetrics::total() const {
  TrafficCounters sum;
  for (const auto& row : by_phase_) {
    for (const auto& c : row) sum += c;
  }
  return sum;
}

std::uint64_t peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace laguerre::sim
