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

// Tiny bucket targets force every path of the two-rung ladder (coarse buckets split into the fine
// rung, small ones taken whole, pushes into the fine rung and the bottom, short years that leave
// events in the overflow) on small inputs.
TEST(EventQueueTest, SmallLadderConfigurationsMatchTheReferenceHeap) {
  for (std::uint64_t seed = 11; seed <= 13; ++seed) {
    cross_check<BasicLadderEventQueue<1, 4, 2>>(seed, 1'000'000, 30'000);
    cross_check<BasicLadderEventQueue<2, 16, 8>>(seed, 1'000, 30'000);
    cross_check<BasicLadderEventQueue<4, 64, 1>>(seed, 3, 30'000);
  }
}

// The PHOLD hold model (one pop, one push at now + d + Exp) at a large population, where years,
// splits and the heap fallback of the bottom tier all occur; peek(k) names the k-th next event.
TEST(EventQueueTest, LadderHoldModelAndPeekMatchTheReferenceHeap) {
  LadderEventQueue ladder;
  DaryEventHeap<2> reference;
  RandomStream rng = RandomStream::of(3, StreamKind::user, 2);
  std::uint64_t seq = 0;
  for (std::uint32_t i = 0; i < 20'000; ++i) {
    const Event e{static_cast<Time>(rng.exponential(1e9)), seq++, i, i, 0, 0};
    ladder.push(e);
    reference.push(e);
  }
  std::size_t peeked = 0;
  for (int step = 0; step < 200'000; ++step) {
    ASSERT_EQ(ladder.top().seq, reference.top().seq) << "step " << step;
    if (step % 499 == 0) {
      for (std::size_t k = 0; k < 6; ++k) {
        const Event* ahead = ladder.peek(k);
        const Event* near = ladder.peek_near(k);  // the kernel's hint: peek(k) when peek knows
        ASSERT_TRUE(ahead == nullptr || near == ahead) << "step " << step << " ahead " << k;
        if (near != nullptr) {
          ASSERT_GE(near->time, reference.top().time) << "step " << step;  // a pending event
        }
        if (ahead == nullptr) continue;
        DaryEventHeap<2> copy = reference;
        for (std::size_t j = 0; j < k; ++j) copy.pop();
        ASSERT_EQ(ahead->seq, copy.top().seq) << "step " << step << " ahead " << k;
        ++peeked;
      }
    }
    const Time now = reference.top().time;
    ladder.pop();
    reference.pop();
    // Bursts of same-time events (heap fallback of the bottom) now and then.
    const int copies = step % 10'000 == 0 ? 200 : 1;
    for (int c = 0; c < copies; ++c) {
      const Time delay = copies == 1 ? static_cast<Time>(rng.exponential(1e9)) : 0;
      const Event e{now + 100'000'000 + delay, seq++, 0, 0, 0, 0};
      ladder.push(e);
      reference.push(e);
    }
  }
  EXPECT_GT(peeked, 1000u);  // the hint is usually available (6 places at each of 401 checks)
}

// A synchronous round: thousands of events at one time, pushed out of seq order (the protocol's
// keys follow the links, not the order of scheduling). The bucket is sorted when taken, so every
// pop is the reference's and peek(k) names the k-th next event exactly (the kernel's prefetch).
TEST(EventQueueTest, LargeSameTimeBucketIsSortedAndPeekable) {
  LadderEventQueue ladder;
  DaryEventHeap<2> reference;
  RandomStream rng = RandomStream::of(5, StreamKind::user, 3);
  std::vector<std::uint64_t> seqs(5000);
  for (std::size_t i = 0; i < seqs.size(); ++i) seqs[i] = i;
  for (std::size_t i = seqs.size() - 1; i > 0; --i) std::swap(seqs[i], seqs[rng.next_u64() % (i + 1)]);
  for (std::uint64_t s : seqs) {
    const Event e{1'000'000, s, s, 0, 0, 0};
    ladder.push(e);
    reference.push(e);
  }
  ladder.push(Event{2'000'000, 9999, 0, 0, 0, 0});  // a later event: the round stays one bucket
  reference.push(Event{2'000'000, 9999, 0, 0, 0, 0});
  for (std::size_t step = 0; step < 5000; ++step) {
    ASSERT_EQ(ladder.top().seq, reference.top().seq) << "step " << step;
    if (step + 4 < 5000) {
      const Event* ahead = ladder.peek(4);
      ASSERT_NE(ahead, nullptr) << "step " << step;
      EXPECT_EQ(ahead->seq, reference.top().seq + 4) << "step " << step;  // seqs 0…4999 in order
    }
    ladder.pop();
    reference.pop();
  }
  EXPECT_EQ(ladder.top().seq, 9999u);
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
