#include <gtest/gtest.h>

#include <cstdint>

#include "laguerre/sim/Metrics.hpp"

namespace laguerre::sim {
namespace {

// The 32-bit records carry into 64-bit ones: every count stays exact past 2^32, whichever way it
// grows (many small additions, one large one, a merge).
TEST(TrafficMetricsTest, CountsStayExactPastThirtyTwoBits) {
  TrafficMetrics t(3);
  const std::uint64_t big = (std::uint64_t{1} << 32) - 5;
  t.add_sent(1, 2, big);
  for (int i = 0; i < 10; ++i) t.add_sent(1, 2, 1);  // crosses 2^32 by single bytes
  t.add_received(1, 2, std::uint64_t{3} << 33);        // one addition past 2^32 at once
  t.add_received(1, 2, 7);
  TrafficCounters merged;
  merged.messages_sent = std::uint64_t{1} << 40;
  merged.bytes_received = 1;
  t.add(1, 2, merged);
  const TrafficCounters c = t.get(1, 2);
  EXPECT_EQ(c.messages_sent, 11u + (std::uint64_t{1} << 40));
  EXPECT_EQ(c.bytes_sent, big + 10);
  EXPECT_EQ(c.messages_received, 2u);
  EXPECT_EQ(c.bytes_received, (std::uint64_t{3} << 33) + 8);
  EXPECT_EQ(t.get(0, 2), TrafficCounters{});  // other nodes and phases untouched
  EXPECT_EQ(t.get(1, 0), TrafficCounters{});
  EXPECT_EQ(t.phase_total(2), c);
  EXPECT_EQ(t.node_total(1), c);
  EXPECT_EQ(t.total(), c);
  EXPECT_EQ(t.phase_count(), 3u);
}

TEST(TrafficMetricsTest, LossAndDropsAreCountedApart) {
  TrafficMetrics t(2);
  t.add_sent(0, 1, 10);
  t.add_lost(0, 1, 10);
  t.add_dropped(1, 1, 3, 10);
  t.add_duplicated(0, 1);
  EXPECT_EQ(t.get(0, 1).messages_sent, 1u);
  EXPECT_EQ(t.get(0, 1).bytes_lost, 10u);
  EXPECT_EQ(t.get(0, 1).messages_duplicated, 1u);
  EXPECT_EQ(t.get(1, 1).messages_dropped, 3u);
  EXPECT_EQ(t.get(1, 1).bytes_dropped, 30u);
  EXPECT_EQ(t.total().messages_sent, 1u);
}

}  // namespace
}  // namespace laguerre::sim
