#include "laguerre/sim/Simulator.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

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
  links_.resize(links);
  for (LinkIndex l = 0; l < links; ++l) {
    LinkState& s = links_[l];
    s.key = stream_key(config_.seed, StreamKind::link, network_.id(network_.link_source(l)),
                       network_.id(network_.link_target(l)));
    s.length = network_.link_length(l);
    s.model = &network_.link_model(l);
  }
  down_.assign(n, 0);
  started_.assign(n, 0);
}

RunReport Simulator::run(const RunLimits& limits) {
  if (!launched_) {
    launched_ = true;
    // Failures first, then starts: see the file comment of Simulator.hpp for the resulting order.
    for (const Crash& c : network_.crashes()) {
      kernel_.schedule_at(c.at, crash_id_, c.node);
      if (c.recover_at) kernel_.schedule_at(*c.recover_at, recover_id_, c.node);
    }
    for (NodeIndex v = 0; v < network_.node_count(); ++v) kernel_.schedule_at(0, start_id_, v);
  }
  const std::uint64_t before = kernel_.events_processed();
  const auto start = std::chrono::steady_clock::now();
  RunReport report;
  report.reason = kernel_.run(limits);
  report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.simulated_time = kernel_.now();
  report.events_processed = kernel_.events_processed() - before;
  report.events_per_second = report.wall_seconds > 0
                                 ? static_cast<double>(report.events_processed) / report.wall_seconds
                                 : 0;
  report.peak_memory_bytes = peak_memory_bytes();
  return report;
}

std::span<const std::byte> Simulator::bytes_of(std::uint32_t message) {
  const Message& m = slot(message);
  if (m.size <= inline_bytes) return {m.bytes, m.size};
  return spill_[message];
}

std::uint32_t Simulator::store(NodeIndex from, std::span<const std::byte> bytes, Phase phase) {
  std::uint32_t index;
  if (!free_messages_.empty()) {
    index = free_messages_.back();  // the most recently freed slot: likely still cached
    free_messages_.pop_back();
  } else {
    if (slots_used_ % chunk_slots == 0) chunks_.push_back(std::make_unique<Message[]>(chunk_slots));
    index = slots_used_++;
  }
  Message& m = slot(index);
  m.from = from;
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
  LinkState& state = links_[link];
  const LinkModel& model = *state.model;
  const std::uint64_t position = state.sent++;
  if (model.is_deterministic()) {  // decide() would draw, but nothing it draws matters
    ++m.refs;
    kernel_.schedule_after(model.latency.base, deliver_id_, to, message);
    return;
  }
  // The message's own stream: a pure function of (seed, link, position of the message on the link).
  RandomStream rng(stream_key(config_.seed, StreamKind::message, state.key, position));
  const LinkDecision fate = decide(model, state.length, rng);
  const auto deliver = [&](bool lost, Duration latency) {
    if (lost) {
      traffic_.add_lost(from, phase, size);
      return;
    }
    ++m.refs;
    kernel_.schedule_after(latency, deliver_id_, to, message);
  };
  deliver(fate.lost, fate.latency);
  if (fate.duplicated) {
    traffic_.add_duplicated(from, phase);
    deliver(fate.duplicate_lost, fate.duplicate_latency);
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
  const std::uint32_t message = store(from, bytes, phase);
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
  const std::uint32_t message = store(from, bytes, phase);
  for (std::size_t i = 0; i < neighbours.size(); ++i)
    transmit(network_.link_at(from, i), from, neighbours[i], message);
  if (slot(message).refs == 0) free_messages_.push_back(message);
}

TimerHandle Simulator::schedule_timer(NodeIndex v, Duration after, std::uint64_t timer) {
  return kernel_.schedule_cancellable_after(after, timer_id_, v, timer);
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
  __builtin_prefetch(sim.links_.data() + sim.network_.link_at(event.target, 0));  // for its replies
  sim.handler_->prefetch(event.target);
}

void Simulator::on_deliver_event(Kernel& kernel, const Event& event) {
  const NodeIndex to = event.target;
  const auto index = static_cast<std::uint32_t>(event.payload);
  const Message& m = slot(index);
  const std::uint32_t size = m.size;
  const NodeIndex from = m.from;
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
  if (trace_.mode() != TraceMode::off)
    trace_.add(TraceRecord{kernel.now(), network_.id(from), network_.id(to), fnv1a(bytes), size, phase});
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
