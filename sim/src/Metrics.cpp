#include "laguerre/sim/Metrics.hpp"

#include <sys/resource.h>

#include <algorithm>

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
  const std::size_t phases = std::size_t{phase} + 1;
  std::vector<TrafficCounters> wider(node_count_ * phases);
  for (std::size_t v = 0; v < node_count_; ++v)
    std::copy_n(counters_.begin() + static_cast<std::ptrdiff_t>(v * phases_), phases_,
                wider.begin() + static_cast<std::ptrdiff_t>(v * phases));
  counters_ = std::move(wider);
  phases_ = phases;
}

TrafficCounters TrafficMetrics::get(std::uint32_t node, Phase phase) const {
  if (phase >= phases_) return {};
  return counters_[std::size_t{node} * phases_ + phase];
}

TrafficCounters TrafficMetrics::node_total(std::uint32_t node) const {
  TrafficCounters sum;
  for (std::size_t p = 0; p < phases_; ++p) sum += counters_[std::size_t{node} * phases_ + p];
  return sum;
}

TrafficCounters TrafficMetrics::phase_total(Phase phase) const {
  TrafficCounters sum;
  if (phase >= phases_) return sum;
  for (std::size_t v = 0; v < node_count_; ++v) sum += counters_[v * phases_ + phase];
  return sum;
}

TrafficCounters TrafficMetrics::total() const {
  TrafficCounters sum;
  for (const auto& c : counters_) sum += c;
  return sum;
}

std::uint64_t peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace laguerre::sim
