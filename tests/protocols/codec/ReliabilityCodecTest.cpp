// The reliability layer's messages (FrameMsg, AckMsg, FailureMsg): round trips, canonical encoding,
// range checks, truncation.

#include <gtest/gtest.h>

#include "CodecChecks.hpp"
#include "laguerre/protocols/Codec.hpp"

using namespace laguerre::protocols;

namespace {
std::vector<Message> samples() {
  return {FrameMsg{0, {0, 0}, {}},
          FrameMsg{0xffffffff, {7, 0x8000000000000001ull}, encode(RadiusMsg{3, 0.5})},
          FrameMsg{12, {12, 5}, encode(RelayMsg{77, 5, 77, true, encode(ReportMsg{1, true})})},
          AckMsg{{0, 0}},
          AckMsg{{0xfffffffe, 0xffffffffffffffffull}},
          FailureMsg{0},
          FailureMsg{0x8000000100000002ull}};
}
}  // namespace

TEST(ReliabilityCodec, RoundTripsAreExactAndCanonical) {
  for (const Message& m : samples()) {
    const std::vector<std::byte> b = encode(m);
    EXPECT_EQ(b.size(), encoded_size(m));
    Message out;
    ASSERT_EQ(decode(b, out), DecodeStatus::ok) << to_string(type_of(m));
    ASSERT_EQ(out.index(), m.index());
    const bool same = std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, FrameMsg> || std::is_same_v<T, AckMsg> || std::is_same_v<T, FailureMsg>)
            return x == std::get<T>(out);
          else
            return false;
        },
        m);
    EXPECT_TRUE(same) << to_string(type_of(m));
    EXPECT_EQ(encode(out), b);
  }
}

TEST(ReliabilityCodec, TypesHaveNamesAndSizes) {
  EXPECT_EQ(to_string(MessageType::frame), "frame");
  EXPECT_EQ(to_string(MessageType::ack), "ack");
  EXPECT_EQ(to_string(MessageType::failure), "failure");
  EXPECT_EQ(encoded_size(MessageType::frame), 22u);
  EXPECT_EQ(encoded_size(MessageType::ack), 14u);
  EXPECT_EQ(encoded_size(MessageType::failure), 10u);
  EXPECT_EQ(max_message_type, 25);  // route (Forwarding.hpp), the Newton–Krylov, gate-radius, height and hyperbolic set-up messages came after it
}

TEST(ReliabilityCodec, TruncationsExtensionsAndOversizedCountsAreRejected) {
  laguerre::protocols::testing::expect_every_truncation_and_extension_rejected(samples());
  // A frame whose count exceeds max_frame_payload is out of range before anything is sized by it.
  std::vector<std::byte> b = encode(FrameMsg{1, {0, 0}, {}});
  const std::uint32_t big = max_frame_payload + 1;
  for (int i = 0; i < 4; ++i) b[18 + static_cast<std::size_t>(i)] = static_cast<std::byte>((big >> (8 * i)) & 0xffu);
  Message out;
  EXPECT_EQ(decode(b, out), DecodeStatus::out_of_range);
}
