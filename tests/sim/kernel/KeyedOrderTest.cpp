// Kernel::schedule_keyed_at: among equal times, keyed events fire by key whatever the order in
// which they were scheduled (what lets a partitioned run reproduce a sequential one), cancellation
// works on keyed events, and next_event_time names the first pending time.

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/sim/Kernel.hpp"
#include "laguerre/sim/Random.hpp"

namespace laguerre::sim {
namespace {

struct Log {
  std::vector<std::pair<Time, std::uint64_t>> fired;  // (time, payload)
  void on_event(Kernel& k, const Event& e) { fired.emplace_back(k.now(), e.payload); }
};

TEST(KeyedOrderTest, EqualTimesFireByKeyWhateverTheSchedulingOrder) {
  // The same 300 (time, key) events scheduled in 5 random orders fire in one and the same order:
  // by time, then key.
  std::vector<std::pair<Time, std::uint64_t>> events;
  for (std::uint64_t i = 0; i < 300; ++i) events.emplace_back(static_cast<Time>(i % 7), (i * 2654435761u) % 1000003);
  std::vector<std::pair<Time, std::uint64_t>> expected = events;
  std::sort(expected.begin(), expected.end());
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    RandomStream rng = RandomStream::of(seed, StreamKind::user, 0);
    std::vector<std::size_t> order(events.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    for (std::size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[rng.below(i + 1)]);
    Kernel k;
    Log log;
    const HandlerId h = k.add_handler<&Log::on_event>("log", log);
    for (const std::size_t i : order) k.schedule_keyed_at(events[i].first, events[i].second, h, 0, events[i].second);
    EXPECT_EQ(k.next_event_time(), 0);
    EXPECT_EQ(k.run(), StopReason::queue_empty);
    EXPECT_EQ(log.fired, expected) << "seed " << seed;
    EXPECT_EQ(k.events_scheduled(), events.size());
    EXPECT_EQ(k.next_event_time(), time_max);
  }
}

TEST(KeyedOrderTest, KeyedEventsCanBeCancelled) {
  Kernel k;
  Log log;
  const HandlerId h = k.add_handler<&Log::on_event>("log", log);
  const EventHandle a = k.schedule_cancellable_keyed_at(5, 2, h, 0, 20);
  const EventHandle b = k.schedule_cancellable_keyed_at(5, 1, h, 0, 10);
  k.schedule_keyed_at(5, 3, h, 0, 30);
  EXPECT_TRUE(k.is_pending(a));
  EXPECT_EQ(k.cancel(a), CancelResult::cancelled);
  EXPECT_EQ(k.cancel(a), CancelResult::not_pending);
  k.run();
  EXPECT_EQ(log.fired, (std::vector<std::pair<Time, std::uint64_t>>{{5, 10}, {5, 30}}));
  EXPECT_FALSE(k.is_pending(b));
  EXPECT_EQ(k.events_discarded(), 1u);
}

TEST(KeyedOrderTest, KeyedEventsCannotGoIntoThePast) {
  Kernel k;
  Log log;
  const HandlerId h = k.add_handler<&Log::on_event>("log", log);
  k.schedule_keyed_at(10, 0, h, 0);
  k.run();
  EXPECT_THROW(k.schedule_keyed_at(9, 0, h, 0), core::InternalError);
  EXPECT_THROW(k.schedule_cancellable_keyed_at(9, 0, h, 0), core::InternalError);
}

}  // namespace
}  // namespace laguerre::sim
