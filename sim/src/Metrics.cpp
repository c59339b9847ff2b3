#include "laguerre/sim/Metrics.hpp"

#include <sys/resource.h>

namespace laguerre::sim {

TrafficCounters& TrafficCounters::operator+=(const TrafficCounters& o) {
  for (const auto& [name, count] : traffic_counter_fields) this->*count += o.*count;
  return *this;
}

void TrafficMetrics::grow(Phase phase) {
  if (phase >= hot_.size()) {
    hot_.resize(std::size_t{phase} + 1);
    cold_.resize(std::size_t{phase} + 1);
    wide_.resize(std::size_t{phase} + 1);
  }
  hot_[phase].resize(node_count_);
}

void TrafficMetrics::carry(Hot& h, int k, std::uint64_t sum, std::uint32_t node, Phase phase) {
  std::vector<Wide>& wide = wide_[phase];  // hot() has sized every table for `phase`
  if (wide.empty()) wide.resize(node_count_);
  wide[node].count[k] += sum;
  h.count[k] = 0;
}

TrafficMetrics::Cold& TrafficMetrics::cold(std::uint32_t node, Phase phase) {
  if (phase >= hot_.size()) {
    hot_.resize(std::size_t{phase} + 1);
    cold_.resize(std::size_t{phase} + 1);
    wide_.resize(std::size_t{phase} + 1);
  }
  if (cold_[phase].empty()) cold_[phase].resize(node_count_);
  return cold_[phase][node];
}

void TrafficMetrics::add_lost(std::uint32_t node, Phase phase, std::uint64_t bytes) {
  Cold& c = cold(node, phase);
  ++c.messages_lost;
  c.bytes_lost += bytes;
}

void TrafficMetrics::add_dropped(std::uint32_t node, Phase phase, std::uint64_t copies, std::uint64_t bytes) {
  Cold& c = cold(node, phase);
  c.messages_dropped += copies;
  c.bytes_dropped += copies * bytes;
}

void TrafficMetrics::add_duplicated(std::uint32_t node, Phase phase) { ++cold(node, phase).messages_duplicated; }

void TrafficMetrics::add(std::uint32_t node, Phase phase, const TrafficCounters& c) {
  Hot& h = hot(node, phase);
  bump(h, 0, c.messages_sent, node, phase);
  bump(h, 1, c.bytes_sent, node, phase);
  bump(h, 2, c.messages_received, node, phase);
  bump(h, 3, c.bytes_received, node, phase);
  if (c.messages_lost == 0 && c.bytes_lost == 0 && c.messages_dropped == 0 && c.bytes_dropped == 0 &&
      c.messages_duplicated == 0)
    return;
  Cold& k = cold(node, phase);
  k.messages_lost += c.messages_lost;
  k.bytes_lost += c.bytes_lost;
  k.messages_dropped += c.messages_dropped;
  k.bytes_dropped += c.bytes_dropped;
  k.messages_duplicated += c.messages_duplicated;
}

TrafficCounters TrafficMetrics::get(std::uint32_t node, Phase phase) const {
  TrafficCounters c;
  if (phase >= hot_.size()) return c;
  if (!hot_[phase].empty()) {
    const Hot& h = hot_[phase][node];
    Wide w;
    if (!wide_[phase].empty()) w = wide_[phase][node];
    c.messages_sent = w.count[0] + h.count[0];
    c.bytes_sent = w.count[1] + h.count[1];
    c.messages_received = w.count[2] + h.count[2];
    c.bytes_received = w.count[3] + h.count[3];
  }
  if (!cold_[phase].empty()) {
    const Cold& k = cold_[phase][node];
    c.messages_lost = k.messages_lost;
    c.bytes_lost = k.bytes_lost;
    c.messages_dropped = k.messages_dropped;
    c.bytes_dropped = k.bytes_dropped;
    c.messages_duplicated = k.messages_duplicated;
  }
  return c;
}

TrafficCounters TrafficMetrics::node_total(std::uint32_t node) const {
  TrafficCounters sum;
  for (std::size_t p = 0; p < hot_.size(); ++p) sum += get(node, static_cast<Phase>(p));
  return sum;
}

TrafficCounters TrafficMetrics::phase_total(Phase phase) const {
  TrafficCounters sum;
  if (phase >= hot_.size()) return sum;
  for (std::size_t v = 0; v < node_count_; ++v) sum += get(static_cast<std::uint32_t>(v), phase);
  return sum;
}

TrafficCounters TrafficMetrics::total() const {
  TrafficCounters sum;
  for (std::size_t p = 0; p < hot_.size(); ++p) sum += phase_total(static_cast<Phase>(p));
  return sum;
}

std::uint64_t peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace laguerre::sim
