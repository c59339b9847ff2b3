#pragma once
/// @file
/// The discrete-event kernel: a clock, the pending-event queue, a handler table registered up front,
/// lazy O(1) cancellation, and the event loop with its stopping rules.
///
/// Models never own the loop: they register handlers, schedule events and react. The kernel knows
/// nothing of nodes, links or messages (Simulator.hpp builds those on top).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "laguerre/sim/EventQueue.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::sim {

class Kernel;

/// A handler: a plain function and a context pointer (no closure per event).
using HandlerFn = void (*)(void* context, Kernel& kernel, const Event& event);

/// Identifies one cancellable event; the value 0 never names a live event.
struct EventHandle {
  std::uint64_t value = 0;  ///< generation (high 32 bits) and slot (low 32 bits) in the kernel's table
  /// Whether two handles name the same scheduling.
  friend bool operator==(EventHandle, EventHandle) = default;
};

/// Outcome of Kernel::cancel.
enum class CancelResult {
  cancelled,    ///< the event was pending and will not fire
  not_pending,  ///< already fired, already cancelled, or never scheduled by this kernel (not an error)
};

/// Why Kernel::run returned.
enum class StopReason {
  queue_empty,     ///< no pending event is left
  time_limit,      ///< the next event lies after RunLimits::until
  event_limit,     ///< RunLimits::max_events events were processed
  stop_requested,  ///< a handler called Kernel::request_stop
};

/// Human-readable name of a StopReason ("queue_empty", …).
std::string_view to_string(StopReason reason);

/// When Kernel::run must return (whichever comes first; the queue running dry always stops it).
struct RunLimits {
  Time until = time_max;                   ///< process only events with time ≤ until
  std::uint64_t max_events = UINT64_MAX;   ///< process at most this many events in this call
};

/// The event kernel. Single-threaded; handlers run to completion one at a time.
class Kernel {
public:
  /// An empty kernel at time 0 with no handlers.
  Kernel();

  /// Registers a handler and returns its id (ids are dense, in registration order).
  /// Throws std::length_error past 65535 handlers.
  HandlerId add_handler(std::string name, HandlerFn fn, void* context);

  /// Registers `object.*Method(kernel, event)` as a handler, without any allocation per event.
  template <auto Method, class T>
  HandlerId add_handler(std::string name, T& object) {
    return add_handler(
        std::move(name),
        [](void* context, Kernel& kernel, const Event& event) {
          (static_cast<T*>(context)->*Method)(kernel, event);
        },
        &object);
  }

  /// Declares that handler `id` touches the record at `base + target · stride` bytes of each of its
  /// events, so that the loop can prefetch it a few events ahead (see Kernel.cpp, "PREFETCH"). A
  /// pure performance hint: it never changes which events run or in what order. `base` must stay
  /// valid (e.g. a vector that is not resized) until the hint is replaced or cleared with nullptr.
  void set_prefetch(HandlerId id, const void* base, std::size_t stride) {
    Handler& h = handlers_.at(id);
    h.prefetch_base = static_cast<const char*>(base);
    h.prefetch_stride = stride;
  }

  /// A prefetch hook: starts loading (with __builtin_prefetch) the state the handler of `event`
  /// will touch; it must only read state that stays valid while `event` is pending.
  using PrefetchFn = void (*)(const void* context, const Event& event);
  /// Like set_prefetch(id, base, stride), for state that is not one record per target (e.g. found
  /// through the payload): the loop calls `fn(context, event)` a few events ahead. A pure
  /// performance hint, like the other form; `fn` nullptr clears it.
  void set_prefetch(HandlerId id, PrefetchFn fn, const void* context) {
    Handler& h = handlers_.at(id);
    h.prefetch_fn = fn;
    h.prefetch_context = context;
  }

  /// The name a handler was registered with.
  const std::string& handler_name(HandlerId id) const { return handlers_.at(id).name; }

  /// Current simulated time: the time of the event being processed (or of the last one).
  Time now() const { return now_; }

  /// Schedules `handler(target, payload)` at absolute time `at` ≥ now().
  /// Throws core::InternalError (a broken precondition) if `at` lies in the past.
  void schedule_at(Time at, HandlerId handler, std::uint32_t target, std::uint64_t payload = 0) {
    if (at < now_) throw_past(at);
    queue_.push(Event{at, next_seq_++, payload, target, handler, 0});
  }

  /// Schedules `handler(target, payload)` after `delay` ≥ 0 nanoseconds.
  /// Throws core::InternalError (a broken precondition) for a negative delay or one that overflows the clock.
  void schedule_after(Duration delay, HandlerId handler, std::uint32_t target,
                      std::uint64_t payload = 0) {
    if (delay < 0 || delay > time_max - now_) throw_delay(delay);
    queue_.push(Event{now_ + delay, next_seq_++, payload, target, handler, 0});
  }

  /// Schedules `handler(target, payload)` at `at` ≥ now() with tie-break `key` in place of the
  /// insertion number: among equal times, events fire by increasing key (see EventQueue.hpp). The
  /// caller keeps keys unique among pending events of equal time (the order is then total and does
  /// not depend on the order of scheduling, which is what makes a partitioned run reproduce a
  /// sequential one); keyed and numbered events of equal time compare by the raw values.
  /// Throws core::InternalError (a broken precondition) if `at` lies in the past.
  void schedule_keyed_at(Time at, std::uint64_t key, HandlerId handler, std::uint32_t target,
                         std::uint64_t payload = 0) {
    if (at < now_) throw_past(at);
    ++next_seq_;
    queue_.push(Event{at, key, payload, target, handler, 0});
  }
  /// Like schedule_keyed_at, and returns a handle for `cancel`.
  EventHandle schedule_cancellable_keyed_at(Time at, std::uint64_t key, HandlerId handler,
                                            std::uint32_t target, std::uint64_t payload = 0);

  /// Like schedule_at, and returns a handle for `cancel`.
  EventHandle schedule_cancellable_at(Time at, HandlerId handler, std::uint32_t target,
                                      std::uint64_t payload = 0);
  /// Like schedule_after, and returns a handle for `cancel`.
  EventHandle schedule_cancellable_after(Duration delay, HandlerId handler, std::uint32_t target,
                                         std::uint64_t payload = 0) {
    if (delay < 0 || delay > time_max - now_) throw_delay(delay);
    return schedule_cancellable_at(now_ + delay, handler, target, payload);
  }

  /// Cancels a pending cancellable event in O(1) (it stays in the queue and is skipped when it
  /// reaches the front). Cancelling a handle that already fired, was already cancelled, or is
  /// unknown returns not_pending.
  CancelResult cancel(EventHandle handle);
  /// Whether `handle` names an event that is still pending (scheduled, not fired, not cancelled).
  bool is_pending(EventHandle handle) const;

  /// Runs the event loop until a limit, a stop request or an empty queue (see Kernel.cpp for the
  /// phases). May be called again to continue. When it stops on the time limit the clock is
  /// advanced to `limits.until`.
  StopReason run(const RunLimits& limits = {});
  /// The time of the first pending record (cancelled ones included), or time_max if none is.
  Time next_event_time() { return queue_.empty() ? time_max : queue_.top().time; }
  /// Asks run() to return after the current event (callable from a handler).
  void request_stop() { stop_requested_ = true; }

  /// Events dispatched to handlers so far (cancelled events are not counted).
  std::uint64_t events_processed() const { return processed_; }
  /// Cancelled events discarded when they reached the front of the queue.
  std::uint64_t events_discarded() const { return discarded_; }
  /// Events scheduled so far (the next sequence number).
  std::uint64_t events_scheduled() const { return next_seq_; }
  /// Records in the queue, including cancelled ones not yet discarded.
  std::size_t queue_size() const { return queue_.size(); }
  /// Reserves queue room for `n` pending events.
  void reserve(std::size_t n) { queue_.reserve(n); }

private:
  struct Handler {
    HandlerFn fn;
    void* context;
    std::string name;
    const char* prefetch_base = nullptr;  // see set_prefetch
    std::size_t prefetch_stride = 0;
    PrefetchFn prefetch_fn = nullptr;     // see set_prefetch(id, fn, context)
    const void* prefetch_context = nullptr;
  };
  /// How many events ahead of the one dispatched the loop prefetches (measured with
  /// tools/bench/phold_queues: 2–8 are within noise of each other at 10^5 and 10^6 processes).
  static constexpr std::size_t prefetch_distance = 4;
  /// The state of a cancellable event, in a slab indexed by the low half of its handle.
  struct Slot {
    std::uint64_t payload = 0;      // the caller's payload, restored before dispatch
    std::uint32_t generation = 1;   // high half of the handle; bumped each time the slot is freed
    std::uint8_t state = 0;         // free, pending or cancelled
  };
  static constexpr std::uint16_t flag_cancellable = 1;

  [[noreturn]] void throw_past(Time at) const;
  std::uint32_t take_slot(std::uint64_t payload);
  [[noreturn]] void throw_delay(Duration delay) const;
  void free_slot(std::uint32_t slot);

  EventQueue queue_;
  std::vector<Handler> handlers_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_slots_;
  Time now_ = 0;
  std::uint64_t next_seq_ = 0;
  std::uint64_t processed_ = 0;
  std::uint64_t discarded_ = 0;
  bool stop_requested_ = false;
};

}  // namespace laguerre::sim
