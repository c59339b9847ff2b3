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

Simulator::Simulator(Network network, SimConfig config, NodeHandler& handler)
    : network_(std::move(network)),
      config_(config),
      handler_(&handler),
      traffic_(network_.node_count()),
      trace_(config.trace) {
  network_.validate();
  start_id_ = kernel_.add_handler<&Simulator::on_start_event>("start", *this);
  deliver_id_ = kernel_.add_handler<&Simulator::on_deliver_event>("deliver", *this);
  timer_id_ = kernel_.add_handler<&Simulator::on_timer_event>("timer", *this);
  crash_id_ = kernel_.add_handler<&Simulator::on_crash_event>("crash", *this);
  recover_id_ = kernel_.add_handler<&Simulator::on_recover_event>("recover", *this);
  kernel_.set_prefetch(deliver_id_, &Simulator::prefetch_delivery, this);
  const std::size_t n = network_.node_count();
  node_streams_.reserve(n);
  for (NodeIndex v = 0; v < n; ++v) {
    node_streams_.push_back(RandomStream::of(config_.seed, StreamKind::node, network_.id(v)));
  }
  const std::size_t links = network_.link_count();
  link_sent_.assign(links, 0);
  bool random = false;
  for (LinkIndex l = 0; l < links && !random; ++l) random = !network_.link_model(l).is_deterministic();
  if (random) {
    link_random_.resize(links);
    for (LinkIndex l = 0; l < links; ++l) {
      link_random_[l].key = stream_key(config_.seed, StreamKind::link, network_.id(network_.link_source(l)),
                                       network_.id(network_.link_target(l)));
      link_random_[l].length = network_.link_length(l);
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
  owned_ = std::move(owned);
  outbox_ = &outbox;
  if (trace_.mode() == TraceMode::hash_only) trace_ = Trace(TraceMode::records);  // the merge needs them
}

void Simulator::deliver_remote(Time at, std::uint64_t key, NodeIndex from, NodeIndex to, Phase phase,
                               std::span<const std::byte> bytes) {
  LAGUERRE_PRECONDITION(outbox_ != nullptr && owned_[to] != 0,
                        "Simulator::deliver_remote needs a partitioned simulator that owns the receiver.");
  const std::uint32_t message = store(bytes, phase);
  slot(message).refs = 1;
  kernel_.schedule_keyed_at(at, key, deliver_id_, to, delivery_payload(from, message));
}

RunReport Simulator::run(const RunLimits& limits) {
  if (!launched_) {
    launched_ = true;
    // Failures first, then starts: see the file comment of Simulator.hpp for the resulting order.
    const auto crashes = network_.crashes();
    if (crashes.size() >= (std::uint64_t{1} << (key_counter_bits - 1))) {
      throw std::length_error("Too many scheduled crashes (2^29).");
    }
    const auto mine = [&](NodeIndex v) { return outbox_ == nullptr || owned_[v] != 0; };
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
  traffic_.add_sent(from, phase, size);
  const LinkModel& model = network_.link_model(link);
  const std::uint64_t index = link_sent_[link];
  if (index >= (std::uint64_t{1} << (key_counter_bits - 1))) {
    throw std::length_error("Too many messages on one link (2^29): the event keys would repeat.");
  }
  ++link_sent_[link];
  const auto deliver = [&](bool lost, Duration latency, std::uint64_t copy) {
    if (lost) {
      traffic_.add_lost(from, phase, size);
      return;
    }
    LAGUERRE_PRECONDITION(latency <= time_max - kernel_.now(),
                          "A latency of " + std::to_string(latency) + " ns at time " + std::to_string(kernel_.now()) +
                              " ns would overflow the clock.");
    const std::uint64_t key = event_key(key_message, link, 2 * index + copy);
    if (outbox_ != nullptr && owned_[to] == 0) {
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
  const LinkRandom& state = link_random_[link];  // exists: this link's model is not deterministic
  RandomStream rng(stream_key(config_.seed, StreamKind::message, state.key, index));
  const LinkDecision fate = decide(model, state.length, rng);
  deliver(fate.lost, fate.latency, 0);
  if (fate.duplicated) {
    traffic_.add_duplicated(from, phase);
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
  if (down_[from]) {
    traffic_.add_dropped(from, phase, 1, bytes.size());
    return;
  }
  const std::uint32_t message = store(bytes, phase);
  transmit(link, from, network_.link_target(link), message);
  if (slot(message).refs == 0) free_messages_.push_back(message);  // every copy was lost
}

void Simulator::broadcast(NodeIndex from, std::span<const std::byte> bytes, Phase phase) {
  const auto neighbours = network_.neighbours(from);
  const auto size = static_cast<std::uint32_t>(bytes.size());
  if (down_[from]) {
    traffic_.add_dropped(from, phase, neighbours.size(), size);
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
  const std::uint32_t index = node_timers_[v];
  if (index >= (std::uint32_t{1} << key_counter_bits) - 1) {
    throw std::length_error("Too many timers at one node (2^30): the event keys would repeat.");
  }
  ++node_timers_[v];
  return kernel_.schedule_cancellable_keyed_at(kernel_.now() + after, event_key(key_timer, v, index), timer_id_, v,
                                               timer);
}

void Simulator::on_start_event(Kernel&, const Event& event) {
  const NodeIndex v = event.target;
  if (down_[v]) return;  // started when it first recovers
  started_[v] = 1;
  handler_->on_start(*this, v);
}

void Simulator::prefetch_delivery(const void* self, const Event& event) {
  const auto& sim = *static_cast<const Simulator*>(self);
  const auto message = static_cast<std::uint32_t>(event.payload);  // pending: its slot exists
  __builtin_prefetch(&sim.chunks_[message / chunk_slots][message % chunk_slots]);
  __builtin_prefetch(sim.link_sent_.data() + sim.network_.link_at(event.target, 0));  // for its replies
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
  if (down_[to]) {
    traffic_.add_dropped(to, phase, 1, size);
    release(index);
    return;
  }
  traffic_.add_received(to, phase, size);
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
  if (down_[event.target]) {
    ++timers_dropped_;
    return;
  }
  handler_->on_timer(*this, event.target, event.payload);
}

// Outages may overlap (two crash/recover pairs of one node); the node is up only when every outage
// that began has ended, hence a counter rather than a flag.
void Simulator::on_crash_event(Kernel&, const Event& event) { ++down_[event.target]; }

void Simulator::on_recover_event(Kernel&, const Event& event) {
  const NodeIndex v = event.target;
  if (--down_[v] != 0) return;  // another outage is still in progress
  if (!started_[v]) {
    started_[v] = 1;
    handler_->on_start(*this, v);
  } else {
    handler_->on_recover(*this, v);
  }
}

}  // namespace laguerre::sim
