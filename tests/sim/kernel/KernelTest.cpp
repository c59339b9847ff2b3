#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/sim/Kernel.hpp"
#include "laguerre/sim/Random.hpp"

namespace laguerre::sim {
namespace {

/// Records (time, target, payload) of every dispatched event.
struct Recorder {
  struct Entry {
    Time time;
    std::uint32_t target;
    std::uint64_t payload;
    bool operator==(const Entry&) const = default;
  };
  std::vector<Entry> log;
  void on_event(Kernel& kernel, const Event& e) { log.push_back({kernel.now(), e.target, e.payload}); }
};

TEST(KernelTest, EventsFireInTimeOrder) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  for (std::uint32_t t : {50u, 10u, 40u, 20u, 30u}) k.schedule_at(t, h, t);
  EXPECT_EQ(k.run(), StopReason::queue_empty);
  ASSERT_EQ(r.log.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(r.log[i].time, static_cast<Time>(10 * (i + 1)));
  EXPECT_EQ(k.now(), 50);
  EXPECT_EQ(k.events_processed(), 5u);
}

TEST(KernelTest, EqualTimesAreFifoByInsertion) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  for (std::uint32_t i = 0; i < 100; ++i) k.schedule_at(7, h, i);
  k.run();
  ASSERT_EQ(r.log.size(), 100u);
  for (std::uint32_t i = 0; i < 100; ++i) EXPECT_EQ(r.log[i].target, i);
}

/// A handler that, at its first firing, schedules a zero-delay event: it must run after the events
/// already pending for the same time (they were inserted earlier).
struct ZeroDelay {
  HandlerId self = 0;
  std::vector<std::uint32_t> order;
  void on_event(Kernel& k, const Event& e) {
    order.push_back(e.target);
    if (e.target == 0) k.schedule_after(0, self, 99);
  }
};

TEST(KernelTest, ZeroDelayEventsRunAfterPendingEventsOfTheSameTime) {
  Kernel k;
  ZeroDelay z;
  z.self = k.add_handler<&ZeroDelay::on_event>("zero", z);
  for (std::uint32_t i = 0; i < 3; ++i) k.schedule_at(5, z.self, i);
  k.run();
  EXPECT_EQ(z.order, (std::vector<std::uint32_t>{0, 1, 2, 99}));
}

TEST(KernelTest, CancelledEventsDoNotFireAndPayloadIsRestored) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  const EventHandle a = k.schedule_cancellable_at(10, h, 1, 111);
  const EventHandle b = k.schedule_cancellable_at(20, h, 2, 222);
  const EventHandle c = k.schedule_cancellable_at(30, h, 3, 333);
  EXPECT_NE(a.value, 0u);
  EXPECT_TRUE(k.is_pending(b));
  EXPECT_EQ(k.cancel(b), CancelResult::cancelled);
  EXPECT_FALSE(k.is_pending(b));
  EXPECT_EQ(k.cancel(b), CancelResult::not_pending);  // twice
  k.run();
  ASSERT_EQ(r.log.size(), 2u);
  EXPECT_EQ(r.log[0], (Recorder::Entry{10, 1, 111}));
  EXPECT_EQ(r.log[1], (Recorder::Entry{30, 3, 333}));
  EXPECT_EQ(k.events_discarded(), 1u);
  EXPECT_EQ(k.cancel(a), CancelResult::not_pending);  // already fired
  EXPECT_EQ(k.cancel(c), CancelResult::not_pending);
  EXPECT_EQ(k.cancel(EventHandle{}), CancelResult::not_pending);              // the null handle
  EXPECT_EQ(k.cancel(EventHandle{0xdeadbeef00001234ULL}), CancelResult::not_pending);  // unknown
}

TEST(KernelTest, StaleHandlesDoNotCancelALaterEventInTheSameSlot) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  const EventHandle first = k.schedule_cancellable_at(1, h, 1);
  k.run();
  const EventHandle second = k.schedule_cancellable_at(2, h, 2);  // reuses the freed slot
  EXPECT_EQ(static_cast<std::uint32_t>(first.value), static_cast<std::uint32_t>(second.value));
  EXPECT_EQ(k.cancel(first), CancelResult::not_pending);
  EXPECT_TRUE(k.is_pending(second));
  k.run();
  EXPECT_EQ(r.log.size(), 2u);
}

/// Cancels its own handle while firing (must be not_pending) and another pending one.
struct SelfCancel {
  EventHandle own, other;
  CancelResult own_result = CancelResult::cancelled, other_result = CancelResult::not_pending;
  int fired = 0;
  void on_event(Kernel& k, const Event&) {
    if (fired++ == 0) {
      own_result = k.cancel(own);
      other_result = k.cancel(other);
    }
  }
};

TEST(KernelTest, CancellingTheFiringEventIsNotPendingAndOthersCanBeCancelledFromHandlers) {
  Kernel k;
  SelfCancel s;
  const HandlerId h = k.add_handler<&SelfCancel::on_event>("self", s);
  s.own = k.schedule_cancellable_at(1, h, 0);
  s.other = k.schedule_cancellable_at(1, h, 0);
  k.run();
  EXPECT_EQ(s.own_result, CancelResult::not_pending);
  EXPECT_EQ(s.other_result, CancelResult::cancelled);
  EXPECT_EQ(s.fired, 1);
}

TEST(KernelTest, TimeLimitIsInclusiveAndAdvancesTheClock) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  for (Time t : {10, 20, 30}) k.schedule_at(t, h, 0);
  EXPECT_EQ(k.run({.until = 20}), StopReason::time_limit);
  EXPECT_EQ(r.log.size(), 2u);
  EXPECT_EQ(k.now(), 20);
  EXPECT_EQ(k.run({.until = 25}), StopReason::time_limit);
  EXPECT_EQ(k.now(), 25);
  EXPECT_EQ(k.run(), StopReason::queue_empty);
  EXPECT_EQ(r.log.size(), 3u);
  EXPECT_EQ(k.now(), 30);
}

TEST(KernelTest, EventLimitCountsDispatchedEventsOnly) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  const EventHandle x = k.schedule_cancellable_at(1, h, 0);
  for (Time t = 2; t <= 10; ++t) k.schedule_at(t, h, 0);
  k.cancel(x);
  EXPECT_EQ(k.run({.max_events = 4}), StopReason::event_limit);
  EXPECT_EQ(r.log.size(), 4u);
  EXPECT_EQ(k.now(), 5);
  EXPECT_EQ(k.run({.max_events = 100}), StopReason::queue_empty);
  EXPECT_EQ(r.log.size(), 9u);
}

struct Stopper {
  int seen = 0;
  void on_event(Kernel& k, const Event&) {
    if (++seen == 3) k.request_stop();
  }
};

TEST(KernelTest, StopRequestReturnsAfterTheCurrentEventAndRunResumes) {
  Kernel k;
  Stopper s;
  const HandlerId h = k.add_handler<&Stopper::on_event>("stop", s);
  for (Time t = 1; t <= 5; ++t) k.schedule_at(t, h, 0);
  EXPECT_EQ(k.run(), StopReason::stop_requested);
  EXPECT_EQ(s.seen, 3);
  EXPECT_EQ(k.run(), StopReason::queue_empty);
  EXPECT_EQ(s.seen, 5);
}

TEST(KernelTest, SchedulingInThePastOrWithABadDelayThrows) {
  Kernel k;
  Recorder r;
  const HandlerId h = k.add_handler<&Recorder::on_event>("rec", r);
  k.schedule_at(100, h, 0);
  k.run();
  EXPECT_THROW(k.schedule_at(99, h, 0), laguerre::core::InternalError);
  EXPECT_THROW(k.schedule_after(-1, h, 0), laguerre::core::InternalError);
  EXPECT_THROW(k.schedule_after(time_max, h, 0), laguerre::core::InternalError);
  EXPECT_THROW(k.schedule_cancellable_at(5, h, 0), laguerre::core::InternalError);
  EXPECT_NO_THROW(k.schedule_after(0, h, 0));
  EXPECT_THROW(k.add_handler("null", nullptr, nullptr), laguerre::core::InternalError);
  EXPECT_EQ(k.handler_name(h), "rec");
}

TEST(KernelTest, StopReasonsHaveNames) {
  EXPECT_EQ(to_string(StopReason::queue_empty), "queue_empty");
  EXPECT_EQ(to_string(StopReason::time_limit), "time_limit");
  EXPECT_EQ(to_string(StopReason::event_limit), "event_limit");
  EXPECT_EQ(to_string(StopReason::stop_requested), "stop_requested");
}

/// A self-sustaining random workload (PHOLD-like) whose log must not depend on how the run is cut.
struct Hold {
  HandlerId self = 0;
  std::vector<RandomStream> streams;
  std::vector<std::pair<Time, std::uint32_t>> log;
  void on_event(Kernel& k, const Event& e) {
    log.emplace_back(k.now(), e.target);
    auto& rng = streams[e.target];
    const auto to = static_cast<std::uint32_t>(rng.below(streams.size()));
    // Coarse delays (multiples of 1000 ns) make equal timestamps frequent: FIFO matters.
    k.schedule_after(1000 * rng.uniform_int(0, 5), self, to);
  }
};

std::vector<std::pair<Time, std::uint32_t>> run_hold(std::uint64_t chunk) {
  Kernel k;
  Hold h;
  h.self = k.add_handler<&Hold::on_event>("hold", h);
  for (std::uint32_t i = 0; i < 50; ++i) {
    h.streams.push_back(RandomStream::of(9, StreamKind::process, i));
    k.schedule_at(0, h.self, i);
  }
  while (k.events_processed() < 5000) k.run({.max_events = std::min<std::uint64_t>(chunk, 5000 - k.events_processed())});
  return h.log;
}

TEST(KernelTest, ARunCutIntoPiecesEqualsAnUninterruptedRun) {
  const auto whole = run_hold(5000);
  EXPECT_EQ(run_hold(1), whole);
  EXPECT_EQ(run_hold(37), whole);
}

}  // namespace
}  // namespace laguerre::sim
