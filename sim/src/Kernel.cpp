#include "laguerre/sim/Kernel.hpp"

#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

namespace {
enum SlotState : std::uint8_t { slot_free = 0, slot_pending = 1, slot_cancelled = 2 };
}  // namespace

std::string_view to_string(StopReason reason) {
  switch (reason) {
    case StopReason::queue_empty: return "queue_empty";
    case StopReason::time_limit: return "time_limit";
    case StopReason::event_limit: return "event_limit";
    case StopReason::stop_requested: return "stop_requested";
  }
  return "unknown";
}

Kernel::Kernel() = default;

HandlerId Kernel::add_handler(std::string name, HandlerFn fn, void* context) {
  LAGUERRE_PRECONDITION(fn != nullptr, "Kernel::add_handler needs a non-null function.");
  if (handlers_.size() > 0xffff) {
    throw std::length_error("The kernel's handler table is full (65536 handlers).");
  }
  handlers_.push_back(Handler{fn, context, std::move(name), nullptr, 0});
  return static_cast<HandlerId>(handlers_.size() - 1);
}

void Kernel::throw_past(Time at) const {
  throw core::InternalError("precondition failed: Cannot schedule an event at time " + std::to_string(at) +
                            " ns, before the current time " + std::to_string(now_) + " ns.");
}

void Kernel::throw_delay(Duration delay) const {
  throw core::InternalError("precondition failed: Cannot schedule an event after a delay of " +
                            std::to_string(delay) + " ns at time " + std::to_string(now_) +
                            " ns: delays must be non-negative and keep the clock representable.");
}

std::uint32_t Kernel::take_slot(std::uint64_t payload) {
  std::uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    if (slots_.size() >= 0xffffffffu) {
      throw std::length_error("Too many pending cancellable events (2^32 - 1).");
    }
    slot = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  }
  Slot& s = slots_[slot];
  s.payload = payload;
  s.state = slot_pending;
  return slot;
}

EventHandle Kernel::schedule_cancellable_at(Time at, HandlerId handler, std::uint32_t target,
                                            std::uint64_t payload) {
  if (at < now_) throw_past(at);
  const std::uint32_t slot = take_slot(payload);
  // The record carries the slot; the caller's payload waits in the slab until dispatch.
  queue_.push(Event{at, next_seq_++, slot, target, handler, flag_cancellable});
  return EventHandle{(std::uint64_t{slots_[slot].generation} << 32) | slot};
}

EventHandle Kernel::schedule_cancellable_keyed_at(Time at, std::uint64_t key, HandlerId handler,
                                                  std::uint32_t target, std::uint64_t payload) {
  if (at < now_) throw_past(at);
  const std::uint32_t slot = take_slot(payload);
  ++next_seq_;
  queue_.push(Event{at, key, slot, target, handler, flag_cancellable});
  return EventHandle{(std::uint64_t{slots_[slot].generation} << 32) | slot};
}

void Kernel::free_slot(std::uint32_t slot) {
  Slot& s = slots_[slot];
  s.state = slot_free;
  // A new generation makes every handle issued for the previous use of this slot stale. Generations
  // start at 1 and skip 0, so no live handle has the value 0.
  if (++s.generation == 0) s.generation = 1;
  free_slots_.push_back(slot);
}

CancelResult Kernel::cancel(EventHandle handle) {
  if (!is_pending(handle)) return CancelResult::not_pending;
  // Lazy: the record stays queued and is discarded when it reaches the front. The slot is freed
  // only then, because the record still refers to it.
  slots_[static_cast<std::uint32_t>(handle.value)].state = slot_cancelled;
  return CancelResult::cancelled;
}

bool Kernel::is_pending(EventHandle handle) const {
  const auto slot = static_cast<std::uint32_t>(handle.value);
  const auto generation = static_cast<std::uint32_t>(handle.value >> 32);
  return slot < slots_.size() && slots_[slot].generation == generation &&
         slots_[slot].state == slot_pending;
}

// The event loop runs each iteration through four named phases:
//
//   1. CHECK    – stop request, event budget, empty queue, time limit: all decided *between* events,
//                 from state that only the previous, completed event could change. No event is ever
//                 half-processed, so a run stopped and resumed equals a run never stopped.
//   2. ADVANCE  – pop the first record in the (time, seq) order and set the clock to its time. The
//                 order is total (seq is unique), so the popped record is determined by the set of
//                 pending records alone, not by the queue's internal layout.
//   3. FILTER   – discard the record if it was cancelled (lazy cancellation), restoring the caller's
//                 payload otherwise and freeing its slot *before* dispatch, so a handler that cancels
//                 its own (firing) handle gets not_pending.
//      PREFETCH – a hint only: if the queue can name the event `prefetch_distance` places ahead
//                 cheaply (or one near it: LadderEventQueue::peek_near) and its handler has a hint
//                 (Kernel::set_prefetch, either form), start loading the state its handler will touch,
//                 so that the cache miss overlaps the work of the events in between. Reads no
//                 state that decides anything, so it cannot change the run.
//   4. DISPATCH – run the handler to completion. Whatever it schedules receives sequence numbers
//                 larger than every pending record, so among equal times it runs after what was
//                 already pending (FIFO).
//
// Reproducibility follows by induction on dispatched events: if the pending set and the sequence
// counter are equal in two runs before an event, phases 1–3 pick the same record, and a handler
// that is a deterministic function of (its state, the event, counter-based random streams) makes
// the same schedule calls in the same order, hence assigns the same sequence numbers.
StopReason Kernel::run(const RunLimits& limits) {
  stop_requested_ = false;
  std::uint64_t budget = limits.max_events;
  for (;;) {
    // 1. CHECK
    if (stop_requested_) return StopReason::stop_requested;
    if (budget == 0) return StopReason::event_limit;
    if (queue_.empty()) return StopReason::queue_empty;
    const Event& first = queue_.top();
    if (first.time > limits.until) {
      if (limits.until > now_) now_ = limits.until;
      return StopReason::time_limit;
    }
    // 2. ADVANCE
    Event event = first;
    queue_.pop();
    now_ = event.time;
    // 3. FILTER
    if (event.flags & flag_cancellable) {
      const auto slot = static_cast<std::uint32_t>(event.payload);
      const bool cancelled = slots_[slot].state == slot_cancelled;
      event.payload = slots_[slot].payload;
      free_slot(slot);
      if (cancelled) {
        ++discarded_;
        continue;
      }
    }
    if (const Event* ahead = queue_.peek_near(prefetch_distance)) {
      const Handler& a = handlers_[ahead->handler];
      if (a.prefetch_base != nullptr) {
        __builtin_prefetch(a.prefetch_base + std::size_t{ahead->target} * a.prefetch_stride);
      } else if (a.prefetch_fn != nullptr) {
        a.prefetch_fn(a.prefetch_context, *ahead);
      }
    }
    // 4. DISPATCH
    const Handler& h = handlers_[event.handler];
    ++processed_;
    --budget;
    h.fn(h.context, *this, event);
  }
}

}  // namespace laguerre::sim
