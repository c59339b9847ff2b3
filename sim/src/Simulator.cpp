#include "laguerre/sim/Simulator.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

namespace {
// Event keys (see the file comment of Simulator.hpp).
enum KeyKind : std::uint64_t { key_failure = 0, key_start = 1, key_message = 2, key_timer = 3 };
constexpr unsigned key_counter_bits = 30;
constexpr std::uint64_t event_key(KeyKind kind, std::uint32_t field, std::uint64_t counter) {
  return (std::uint64_t{kind} << 62) | (std::uint64_t{field} << key_counter_bits) | counter;
}
}  // namespace

Simulator::Simulator(Network network, SimConfig config, NodeHandler& handler, std::vector<std::uint8_t> held)
    : network_(std::move(network)), config_(config), handler_(&handler), trace_(config.trace) {
  network_.validate();
  LAGUERRE_PRECONDITION(held.empty() || held.size() == network_.node_count(),
                        "A simulator of a part needs one flag per node.");
  // Holding every node is the whole simulator (no position tables; partition() takes any flags).
  if (std::find(held.begin(), held.end(), std::uint8_t{0}) != held.end()) {
    local_.assign(held.size(), not_held);
    std::size_t links = 0;
    for (NodeIndex v = 0; v < held.size(); ++v) {
      if (held[v] == 0) continue;
      local_[v] = static_cast<NodeIndex>(held_.size());
      held_.push_back(v);
      link_shift_.push_back(static_cast<LinkIndex>(network_.link_at(v, 0) - links));
      links += network_.neighbours(v).size();
    }
  }
  traffic_ = TrafficMetrics(local_count());
  if (local_count() > 0) prefetched_[0] = prefetched_[1] = local_node(0);  // the hint's ring names held nodes
  start_id_ = kernel_.add_handler<&Simulator::on_start_event>("start", *this);
  deliver_id_ = kernel_.add_handler<&Simulator::on_deliver_event>("deliver", *this);
  timer_id_ = kernel_.add_handler<&Simulator::on_timer_event>("timer", *this);
  crash_id_ = kernel_.add_handler<&Simulator::on_crash_event>("crash", *this);
  recover_id_ = kernel_.add_handler<&Simulator::on_recover_event>("recover", *this);
  kernel_.set_prefetch(deliver_id_, &Simulator::prefetch_delivery, this);
  // The held nodes' state, and their links', each keyed by the node or link alone (never by its
  // position here), so that every part draws what the whole simulator draws.
  const std::size_t n = local_count();
  node_streams_.reserve(n);
  std::size_t links = 0;
  bool random = false;
  for (std::size_t i = 0; i < n; ++i) {
    const NodeIndex v = local_node(i);
    node_streams_.push_back(RandomStream::of(config_.seed, StreamKind::node, network_.id(v)));
    const std::size_t degree = network_.neighbours(v).size();
    links += degree;
    for (std::size_t j = 0; j < degree && !random; ++j) random = !network_.link_model(network_.link_at(v, j)).is_deterministic();
  }
  link_sent_.assign(links, 0);
  if (random) {
    link_random_.resize(links);
    for (std::size_t i = 0; i < n; ++i) {
      const NodeIndex v = local_node(i);
      for (std::size_t j = 0; j < network_.neighbours(v).size(); ++j) {
        const LinkIndex l = network_.link_at(v, j);
        LinkRandom& r = link_random_[local_link(l, static_cast<NodeIndex>(i))];
        r.key = stream_key(config_.seed, StreamKind::link, network_.id(v), network_.id(network_.link_target(l)));
        r.length = network_.link_length(l);
      }
    }
  }
  down_.assign(n, 0);
  started_.assign(n, 0);
  node_timers_.assign(n, 0);
}

void Simulator::partition(std::vector<std::uint8_t> owned, RemoteOutbox& outbox) {
  LAGUERRE_PRECONDITION(!launched_, "Simulator::partition must be called before the first run.");
  LAGUERRE_PRECONDITION(owned.size() == network_.node_count(),
                        "Simulator::partition needs one ownership flag per node.");
  if (local_.empty()) {
    owned_ = std::move(owned);
  } else {  // built for a part: that part
    for (NodeIndex v = 0; v < owned.size(); ++v) {
      LAGUERRE_PRECONDITION((owned[v] != 0) == (local_[v] != not_held),
                            "Simulator::partition: node " + std::to_string(v) +
                                (owned[v] != 0 ? " is owned but the simulator was built without it."
                                               : " is not owned but the simulator was built with it."));
    }
  }
  outbox_ = &outbox;
  if (trace_.mode() == TraceMode::hash_only) trace_ = Trace(TraceMode::records);  // the merge needs them
}

void Simulator::deliver_remote(Time at, std::uint64_t key, NodeIndex from, NodeIndex to, Phase phase,
                               std::span<const std::byte> bytes) {
  LAGUERRE_PRECONDITION(outbox_ != nullptr && !foreign(to),
                        "Simulator::deliver_remote needs a partitioned simulator that owns the receiver.");
  const std::uint32_t message = store(bytes, phase);
  slot(message).refs = 1;
  kernel_.schedule_keyed_at(at, key, deliver_id_, to, delivery_payload(from, message));
}

RunReport Simulator::run(const RunLimits& limits) {
  if (!launched_) {
    LAGUERRE_PRECONDITION(local_.empty() || outbox_ != nullptr,
                          "A simulator built for a part runs only as a part of a partitioned run (partition).");
    launched_ = true;
    // Failures first, then starts: see the file comment of Simulator.hpp for the resulting order.
    const auto crashes = network_.crashes();
    if (crashes.size() >= (std::uint64_t{1} << (key_counter_bits - 1))) {
      throw std::length_error("Too many scheduled crashes (2^29).");
    }
    const auto mine = [&](NodeIndex v) { return !foreign(v); };
    for (std::size_t i = 0; i < crashes.size(); ++i) {
      const Crash& c = crashes[i];
      if (!mine(c.node)) continue;
      kernel_.schedule_keyed_at(c.at, event_key(key_failure, c.node, 2 * i), crash_id_, c.node);
      if (c.recover_at) {
        kernel_.schedule_keyed_at(*c.recover_at, event_key(key_failure, c.node, 2 * i + 1), recover_id_, c.node);
      }
    }
    for (NodeIndex v = 0; v < network_.node_count(); ++v) {
      if (mine(v)) kernel_.schedule_keyed_at(0, event_key(key_start, v, 0), start_id_, v);
    }
  }
  const std::uint64_t before = kernel_.events_processed();
  const auto start = std::chrono::steady_clock::now();
  RunReport report;
  if (!observer_) {
    report.reason = kernel_.run(limits);
  } else {
    // The same run in slices of observe_every_ events, the observer called between them.
    for (std::uint64_t left = limits.max_events;;) {
      const std::uint64_t at = kernel_.events_processed();
      report.reason = kernel_.run({limits.until, std::min(left, observe_every_)});
      left -= kernel_.events_processed() - at;
      if (report.reason != StopReason::event_limit || left == 0) break;
      observer_();
    }
  }
  report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.simulated_time = kernel_.now();
  report.events_processed = kernel_.events_processed() - before;
  report.events_per_second = report.wall_seconds > 0
                                 ? static_cast<double>(report.events_processed) / report.wall_seconds
                                 : 0;
  report.peak_memory_bytes = peak_memory_bytes();
  return report;
}

void Simulator::set_observer(std::uint64_t every, std::function<void()> observer) {
  LAGUERRE_PRECONDITION(every >= 1 || !observer, "Simulator::set_observer needs a period of at least one event.");
  observe_every_ = every;
  observer_ = std::move(observer);
}

std::span<const std::byte> Simulator::bytes_of(std::uint32_t message) {
  const Message& m = slot(message);
  if (m.size <= inline_bytes) return {m.bytes, m.size};
  return spill_[message];
}

std::uint32_t Simulator::store(std::span<const std::byte> bytes, Phase phase) {
  std::uint32_t index;
  if (!free_messages_.empty()) {
    index = free_messages_.back();  // the most recently freed slot: likely still cached
    free_messages_.pop_back();
  } else {
    if (slots_used_ % chunk_slots == 0) chunks_.push_back(std::make_unique<Message[]>(chunk_slots));
    index = slots_used_++;
  }
  Message& m = slot(index);
  m.size = static_cast<std::uint32_t>(bytes.size());
  m.refs = 0;
  m.phase = phase;
  if (bytes.size() <= inline_bytes) {
    std::copy(bytes.begin(), bytes.end(), m.bytes);
  } else {
    if (spill_.size() <= index) spill_.resize(std::size_t{index} + 1);
    spill_[index].assign(bytes.begin(), bytes.end());  // reuses the slot's capacity
  }
  return index;
}

void Simulator::release(std::uint32_t message) {
  if (--slot(message).refs == 0) free_messages_.push_back(message);
}

void Simulator::transmit(LinkIndex link, NodeIndex from, NodeIndex to, std::uint32_t message) {
  Message& m = slot(message);
  const std::uint32_t size = m.size;
  const Phase phase = m.phase;
  const NodeIndex sender = local_index(from);
  const std::size_t here = local_link(link, sender);
  traffic_.add_sent(sender, phase, size);
  const LinkModel& model = network_.link_model(link);
  const std::uint64_t index = link_sent_[here];
  if (index >= (std::uint64_t{1} << (key_counter_bits - 1))) {
    throw std::length_error("Too many messages on one link (2^29): the event keys would repeat.");
  }
  ++link_sent_[here];
  const auto deliver = [&](bool lost, Duration latency, std::uint64_t copy) {
    if (lost) {
      traffic_.add_lost(sender, phase, size);
      return;
    }
    LAGUERRE_PRECONDITION(latency <= time_max - kernel_.now(),
                          "A latency of " + std::to_string(latency) + " ns at time " + std::to_string(kernel_.now()) +
                              " ns would overflow the clock.");
    const std::uint64_t key = event_key(key_message, link, 2 * index + copy);
    if (foreign(to)) {
      outbox_->post(kernel_.now() + latency, key, from, to, phase, bytes_of(message));
      return;
    }
    ++m.refs;
    kernel_.schedule_keyed_at(kernel_.now() + latency, key, deliver_id_, to, delivery_payload(from, message));
  };
  if (model.is_deterministic()) {  // decide() would draw, but nothing it draws matters
    deliver(false, model.latency.base, 0);
    return;
  }
  // The message's own stream: a pure function of (seed, link, position of the message on the link).
  const LinkRandom& state = link_random_[here];  // exists: this link's model is not deterministic
  RandomStream rng(stream_key(config_.seed, StreamKind::message, state.key, index));
  const LinkDecision fate = decide(model, state.length, rng);
  deliver(fate.lost, fate.latency, 0);
  if (fate.duplicated) {
    traffic_.add_duplicated(sender, phase);
    deliver(fate.duplicate_lost, fate.duplicate_latency, 1);
  }
}

void Simulator::send(NodeIndex from, NodeIndex to, std::span<const std::byte> bytes, Phase phase) {
  const auto link = network_.find_link(from, to);
  LAGUERRE_PRECONDITION(link.has_value(), "Node " + std::to_string(network_.id(from)) + " cannot send to node " +
                                              std::to_string(network_.id(to)) + ": they are not neighbours.");
  send_on_link(*link, bytes, phase);
}

void Simulator::send_on_link(LinkIndex link, std::span<const std::byte> bytes, Phase phase) {
  const NodeIndex from = network_.link_source(link);
  if (down_[local_index(from)]) {
    traffic_.add_dropped(local_index(from), phase, 1, bytes.size());
    return;
  }
  const std::uint32_t message = store(bytes, phase);
  transmit(link, from, network_.link_target(link), message);
  if (slot(message).refs == 0) free_messages_.push_back(message);  // every copy was lost
}

void Simulator::broadcast(NodeIndex from, std::span<const std::byte> bytes, Phase phase) {
  const auto neighbours = network_.neighbours(from);
  const auto size = static_cast<std::uint32_t>(bytes.size());
  if (down_[local_index(from)]) {
    traffic_.add_dropped(local_index(from), phase, neighbours.size(), size);
    return;
  }
  if (neighbours.empty()) return;
  const std::uint32_t message = store(bytes, phase);
  for (std::size_t i = 0; i < neighbours.size(); ++i)
    transmit(network_.link_at(from, i), from, neighbours[i], message);
  if (slot(message).refs == 0) free_messages_.push_back(message);
}

TimerHandle Simulator::schedule_timer(NodeIndex v, Duration after, std::uint64_t timer) {
  LAGUERRE_PRECONDITION(after >= 0 && after <= time_max - kernel_.now(),
                        "Cannot set a timer after " + std::to_string(after) + " ns at time " +
                            std::to_string(kernel_.now()) + " ns: delays must be non-negative and keep the clock representable.");
  const std::uint32_t index = node_timers_[local_index(v)];
  if (index >= (std::uint32_t{1} << key_counter_bits) - 1) {
    throw std::length_error("Too many timers at one node (2^30): the event keys would repeat.");
  }
  ++node_timers_[local_index(v)];
  return kernel_.schedule_cancellable_keyed_at(kernel_.now() + after, event_key(key_timer, v, index), timer_id_, v,
                                               timer);
}

void Simulator::on_start_event(Kernel&, const Event& event) {
  const NodeIndex v = event.target;
  if (down_[local_index(v)]) return;  // started when it first recovers
  started_[local_index(v)] = 1;
  handler_->on_start(*this, v);
}

void Simulator::prefetch_delivery(const void* self, const Event& event) {
  const auto& sim = *static_cast<const Simulator*>(self);
  const auto message = static_cast<std::uint32_t>(event.payload);  // pending: its slot exists
  __builtin_prefetch(&sim.chunks_[message / chunk_slots][message % chunk_slots]);
  __builtin_prefetch(sim.link_sent_.data() + sim.local_link_start(event.target));  // for its replies
  sim.handler_->prefetch(event.target);
  NodeIndex& earlier = sim.prefetched_[sim.prefetch_turn_++ & 1];
  sim.handler_->prefetch_state(earlier);  // two calls ago: its node record has likely arrived
  earlier = event.target;
}

void Simulator::on_deliver_event(Kernel& kernel, const Event& event) {
  const NodeIndex to = event.target;
  const auto index = static_cast<std::uint32_t>(event.payload);
  const Message& m = slot(index);
  const std::uint32_t size = m.size;
  const auto from = static_cast<NodeIndex>(event.payload >> 32);
  const Phase phase = m.phase;
  const NodeIndex here = local_index(to);
  if (down_[here]) {
    traffic_.add_dropped(here, phase, 1, size);
    release(index);
    return;
  }
  traffic_.add_received(here, phase, size);
  // The span stays valid during the callback even if the handler sends: slots live in chunks that
  // never move, spilled bytes in buffers that never move, and the slot cannot be recycled before
  // release() below because this copy still holds a reference.
  const std::span<const std::byte> bytes = bytes_of(index);
  if (trace_.mode() != TraceMode::off) {
    trace_.add(TraceRecord{kernel.now(), network_.id(from), network_.id(to), fnv1a(bytes), size, phase});
    if (outbox_ != nullptr) trace_keys_.push_back(event.seq);
  }
  handler_->on_message(*this, to, from, phase, bytes);
  release(index);
}

void Simulator::on_timer_event(Kernel&, const Event& event) {
  if (down_[local_index(event.target)]) {
    ++timers_dropped_;
    return;
  }
  handler_->on_timer(*this, event.target, event.payload);
}

// Outages may overlap (two crash/recover pairs of one node); the node is up only when every outage
// that began has ended, hence a counter rather than a flag.
void Simulator::on_crash_event(Kernel&, const Event& event) { ++down_[local_index(event.target)]; }

void Simulator::on_recover_event(Kernel&, const Event& event) {
  const NodeIndex v = event.target;
  if (--down_[local_index(v)] != 0) return;  // another outage is still in progress
  if (!started_[local_index(v)]) {
    started_[local_index(v)] = 1;
    handler_->on_start(*this, v);
  } else {
    handler_->on_recover(*this, v);
  }
}

}  // namespace laguerre::sim
