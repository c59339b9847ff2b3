#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "laguerre/sim/EventQueue.hpp"
#include "laguerre/sim/Random.hpp"

namespace laguerre::sim {
namespace {

/// Drives a queue and the reference binary heap with the same random mix of pushes and pops and
/// checks that they pop identical records. `spread` controls how often times tie.
template <class Queue>
void cross_check(std::uint64_t seed, Time spread, std::size_t operations) {
  Queue queue;
  DaryEventHeap<2> reference;
  RandomStream rng = RandomStream::of(seed, StreamKind::user, 1);
  std::uint64_t seq = 0;
  Time now = 0;
  for (std::size_t i = 0; i < operations; ++i) {
    const bool push = reference.empty() || rng.uniform01() < 0.52;
    if (push) {
      // Mostly near-future events, a few far-future outliers to exercise the ladder's overflow.
      const Time delay = rng.bernoulli(0.01) ? rng.uniform_int(0, 1000 * spread) : rng.uniform_int(0, spread);
      const Event e{now + delay, seq++, rng.next_u64(), static_cast<std::uint32_t>(i), 0, 0};
      queue.push(e);
      reference.push(e);
    } else {
      const Event a = queue.top();
      const Event b = reference.top();
      ASSERT_EQ(a.seq, b.seq) << "operation " << i;
      ASSERT_EQ(a.time, b.time);
      ASSERT_EQ(a.payload, b.payload);
      now = a.time;
      queue.pop();
      reference.pop();
    }
    ASSERT_EQ(queue.size(), reference.size());
  }
  while (!reference.empty()) {
    ASSERT_EQ(queue.top().seq, reference.top().seq);
    queue.pop();
    reference.pop();
  }
  EXPECT_TRUE(queue.empty());
}

TEST(EventQueueTest, LadderMatchesTheReferenceHeap) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    cross_check<LadderEventQueue>(seed, 1'000'000, 40'000);  // few ties
    cross_check<LadderEventQueue>(seed, 3, 40'000);          // many ties
    cross_check<LadderEventQueue>(seed, 0, 5'000);           // all ties at each instant
  }
}

TEST(EventQueueTest, DaryHeapsMatchTheReferenceHeap) {
  cross_check<DaryEventHeap<4>>(5, 1000, 40'000);
  cross_check<DaryEventHeap<8>>(6, 2, 40'000);
}

TEST(EventQueueTest, LadderHandlesExtremeTimes) {
  LadderEventQueue q;
  q.push(Event{time_max, 0, 0, 0, 0, 0});
  q.push(Event{0, 1, 0, 0, 0, 0});
  q.push(Event{time_max / 2, 2, 0, 0, 0, 0});
  q.push(Event{time_max, 3, 0, 0, 0, 0});
  std::vector<std::uint64_t> order;
  while (!q.empty()) {
    order.push_back(q.top().seq);
    q.pop();
    if (order.size() == 1) q.push(Event{1, 4, 0, 0, 0, 0});
  }
  EXPECT_EQ(order, (std::vector<std::uint64_t>{1, 4, 2, 0, 3}));

  // The whole signed range at once (the year's span is 2^64 − 1).
  LadderEventQueue wide;
  DaryEventHeap<2> reference;
  const Time times[] = {time_max, std::numeric_limits<Time>::min(), -5, 0, time_max, -5, 7};
  std::uint64_t seq = 0;
  for (Time t : times) {
    wide.push(Event{t, seq, 0, 0, 0, 0});
    reference.push(Event{t, seq++, 0, 0, 0, 0});
  }
  while (!reference.empty()) {
    ASSERT_EQ(wide.top().seq, reference.top().seq);
    wide.pop();
    reference.pop();
  }
  EXPECT_TRUE(wide.empty());
}

}  // namespace
}  // namespace laguerre::sim
