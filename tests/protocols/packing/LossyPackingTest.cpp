// The reliability layer (docs/protocol.md, "Loss, duplication and crashes") on the lossy host: the same
// run as core::pack, bit for bit, under loss, duplication and reordering; quiescence; crash detection.

#include <gtest/gtest.h>

#include "laguerre/core/Error.hpp"
#include "../LossyCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

PackingParams lossy_params(int steps = 2) {
  PackingParams p;
  p.steps_per_check = steps;
  enable_lossy_links(p, 5'000'000);  // the lossy host's default latency is 1–5 ms
  return p;
}

}  // namespace

TEST(LossyPacking, EnableLossyLinksFitsThePeriodsToTheLatency) {
  PackingParams p;
  enable_lossy_links(p, 4'000'000);
  EXPECT_EQ(p.ack_delay, 2'000'000);
  EXPECT_EQ(p.retransmit_after, 12'000'000);
  EXPECT_GT(p.retransmit_after, 2 * 4'000'000 + p.ack_delay);  // above the longest round trip
}

TEST(LossyPacking, RejectsBadParameters) {
  const core::PlanarGraph g = delaunay(10, 3);
  PackingParams p = lossy_params();
  p.max_retransmissions = 0;
  EXPECT_THROW(DequeHost(g, p), laguerre::core::InternalError);
  p = lossy_params();
  p.retransmit_after = -1;
  EXPECT_THROW(DequeHost(g, p), laguerre::core::InternalError);
  p = lossy_params();
  p.backoff_cap = 0;
  EXPECT_THROW(DequeHost(g, p), laguerre::core::InternalError);
}

TEST(LossyPacking, LosslessLinksNeedNoRetransmissionAndSeeNoDuplicates) {
  const core::PlanarGraph g = delaunay(40, 11);
  PackingParams p = lossy_params();
  p.adaptive_rto = false;  // the fixed timeout, retransmit_after, is above every round trip
  const LossyTotals t = expect_lossy_equals_core(g, p, LossyConfig{}, "lossless");
  EXPECT_EQ(t.counters.duplicates, 0u);
  EXPECT_EQ(t.counters.retransmissions, 0u);
  EXPECT_EQ(t.host.lost, 0u);
  EXPECT_GT(t.iterations, 2);
  // The adaptive timeout tracks the measured round trips (1–5 ms each way here), so the tail of the
  // latency distribution may outlast it now and then: spurious retransmissions stay rare, and their
  // copies are recognised as duplicates.
  const LossyTotals a = expect_lossy_equals_core(g, lossy_params(), LossyConfig{}, "lossless, adaptive");
  EXPECT_LE(a.counters.retransmissions * 100, a.counters.frames) << "at most 1% of the frames";
  EXPECT_EQ(a.counters.duplicates, a.counters.retransmissions);
}

TEST(LossyPacking, TwentyPercentLossAndDuplicationGiveCoresPackingBitForBit) {
  const core::PlanarGraph g = delaunay(40, 11);
  const LossyConfig c = lossy_config(0.2, 0.1, 5);
  const LossyTotals t = expect_lossy_equals_core(g, lossy_params(), c, "loss 0.2 dup 0.1");
  EXPECT_GT(t.host.lost, 0u);
  EXPECT_GT(t.counters.retransmissions, 0u);
  EXPECT_GT(t.counters.duplicates, 0u);
  EXPECT_EQ(t.counters.out_of_window, 0u);
}

TEST(LossyPacking, ThreeConnectedGraphsWithRelayedFaceTrafficSurviveLoss) {
  const core::PlanarGraph g = three_connected(30, 4);
  ASSERT_TRUE(core::PackingComplex::from_graph(g).has_face_vertices());
  const LossyConfig c = lossy_config(0.2, 0.05, 9);
  const LossyTotals t = expect_lossy_equals_core(g, lossy_params(1), c, "3-connected loss 0.2");
  EXPECT_GT(t.counters.relayed, 0u);
  EXPECT_GT(t.counters.duplicates, 0u);
}

TEST(LossyPacking, HeavyLossStillTerminatesWithTheSameResult) {
  // 40% loss is far beyond the target; the backoff and the bounded retransmissions still suffice.
  const core::PlanarGraph g = delaunay(20, 2);
  const LossyConfig c = lossy_config(0.4, 0.2, 77);
  PackingParams p = lossy_params();
  p.max_retransmissions = 60;  // keep false suspicions out at this loss rate
  expect_lossy_equals_core(g, p, c, "loss 0.4");
}

TEST(LossyPacking, ACrashMidRunEndsEverySurvivorWithTheFailureStatus) {
  const core::PlanarGraph g = delaunay(40, 11);
  const LossyConfig c = lossy_config(0.1, 0.05, 3);
  LossyHost clean(g, lossy_params(), c);
  const Time end = clean.run().end;
  ASSERT_GT(end, 0);
  for (core::Vertex victim : {core::Vertex{0}, core::Vertex{17}, core::Vertex{39}})
    for (Time at : {Time{0}, end / 10, end / 3}) {
      SCOPED_TRACE("victim " + std::to_string(victim) + " at " + std::to_string(at));
      expect_crash_detected(g, lossy_params(), g.id(victim), at, c);
    }
}

TEST(LossyPacking, CrashRunsAreDeterministicPerSeed) {
  const core::PlanarGraph g = three_connected(25, 8);
  const LossyConfig c = lossy_config(0.15, 0, 21);
  const LossyHost::Stats a = expect_crash_detected(g, lossy_params(), g.id(5), 200'000'000, c);
  const LossyHost::Stats b = expect_crash_detected(g, lossy_params(), g.id(5), 200'000'000, c);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.events, b.events);
  EXPECT_EQ(a.sent, b.sent);
}

TEST(LossyPacking, ACrashAfterConvergenceChangesNothing) {
  const core::PlanarGraph g = delaunay(20, 5);
  LossyHost clean(g, lossy_params(), LossyConfig{});
  const Time end = clean.run().end;
  LossyConfig c;
  c.crashes = {{g.id(7), end + 1}};
  LossyHost host(g, lossy_params(), c);
  EXPECT_TRUE(host.run().drained);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) EXPECT_EQ(host.node(v).outcome(), PackingOutcome::converged);
}

TEST(LossyPacking, ForgedFramesAreCountedNotTrusted) {
  // The reliability layer's receive side, message by message, on a node that has not started: a bad
  // payload, a repeat, a frame far beyond the window, an unframed message and a stray ack.
  const core::PlanarGraph g = delaunay(12, 4);
  DequeHost host(g, lossy_params());
  PackingNode& n = host.node(0);
  const NodeId from = local_knowledge(g, 0).neighbours[0];
  const std::vector<std::byte> garbage{std::byte{1}, std::byte{200}};
  n.on_message(from, encode(FrameMsg{0, {}, garbage}));
  EXPECT_EQ(n.counters().bad_payload, 1u);
  n.on_message(from, encode(FrameMsg{0, {}, garbage}));
  EXPECT_EQ(n.counters().duplicates, 1u);
  EXPECT_EQ(n.counters().bad_payload, 1u);  // a duplicate is never decoded, let alone applied
  n.on_message(from, encode(FrameMsg{66, {}, encode(RadiusMsg{0, 0.5})}));
  EXPECT_EQ(n.counters().out_of_window, 1u);
  n.on_message(from, encode(FrameMsg{65, {}, encode(RadiusMsg{0, 0.5})}));
  EXPECT_EQ(n.counters().out_of_window, 1u);  // 64 ahead of the first missing one still fits
  EXPECT_EQ(n.counters().unexpected, 1u);    // …and reaches the (idle) protocol, which rejects it
  n.on_message(from, encode(RadiusMsg{0, 0.5}));
  // On lossy links everything travels in frames: a bare protocol message is not a LinkMessage.
  EXPECT_EQ(n.counters().decode[static_cast<std::size_t>(DecodeStatus::foreign_type)], 1u);
  n.on_message(from, encode(AckMsg{{1000, ~std::uint64_t{0}}}));
  EXPECT_EQ(n.counters().unexpected, 1u);  // acknowledging frames never sent is harmless
  n.on_message(from, encode(FrameMsg{1, {}, encode(FrameMsg{0, {}, {}})}));
  EXPECT_EQ(n.counters().bad_payload, 2u);  // frames never nest: a frame is no FramePayload
  EXPECT_EQ(n.counters().unexpected, 1u);
  EXPECT_EQ(n.counters().received, 7u);
  EXPECT_EQ(n.outcome(), PackingOutcome::running);
}

TEST(LossyPacking, AFailureNoticeEndsTheRunAndIsFloodedOnce) {
  const core::PlanarGraph g = delaunay(12, 4);
  DequeHost host(g, lossy_params());
  PackingNode& n = host.node(0);
  const auto nb = local_knowledge(g, 0).neighbours;
  n.on_message(nb[0], encode(FrameMsg{0, {}, encode(FailureMsg{nb[0] + 1000})}));
  EXPECT_EQ(n.outcome(), PackingOutcome::neighbour_failed);
  EXPECT_EQ(n.suspect(), nb[0] + 1000);
  EXPECT_TRUE(n.is_final());
  const std::uint64_t frames = n.counters().frames;
  EXPECT_EQ(frames, nb.size() - 1);  // to every neighbour but the one it came from
  n.on_message(nb[1], encode(FrameMsg{0, {}, encode(FailureMsg{nb[0] + 1000})}));
  EXPECT_EQ(n.counters().frames, frames);  // the flood passes each node once
}

TEST(LossyPacking, SequenceNumbersWrapSafely) {
  // Links start a few frames before 2^32 (and before 2^31, where a signed comparison would flip):
  // under loss, duplication and reordering, acks, selective bitmaps and duplicate detection must keep
  // working across the wrap (serial-number arithmetic), giving core's packing bit for bit.
  const core::PlanarGraph g = delaunay(30, 5);
  for (std::uint32_t start : {0xffffffffu - 20u, 0x7fffffffu - 20u}) {
    PackingParams p = lossy_params();
    p.initial_seq = start;
    const LossyConfig c = lossy_config(0.2, 0.1, start % 7 + 1);
    const LossyTotals t = expect_lossy_equals_core(g, p, c, "start " + std::to_string(start));
    EXPECT_GT(t.counters.retransmissions, 0u);
    EXPECT_GT(t.counters.duplicates, 0u);
    // More frames than 21 per directed link on average: some link crossed the wrap point.
    EXPECT_GT(t.counters.frames, 21u * 2u * g.num_edges());
  }
}
