// The hyperbolic set-up's messages (Codec.hpp, types 22–25): sizes, round trips, every truncation and
// extension rejected, and the packed address canonical (length, sides in range, unused bits zero).

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "CodecChecks.hpp"
#include "laguerre/protocols/Codec.hpp"

using namespace laguerre::protocols;

namespace {
HyperbolicAddressMsg address(std::uint32_t q, std::vector<std::uint32_t> sides, std::uint8_t whose = 0) {
  return {q, whose, static_cast<std::uint32_t>(sides.size()), pack_hyperbolic_address(sides, q)};
}
}  // namespace

TEST(HyperbolicCodec, SizesAndRoundTrips) {
  EXPECT_EQ(encoded_size(MessageType::hyperbolic_sweep), 15u);
  EXPECT_EQ(encoded_size(MessageType::hyperbolic_echo), 15u);
  EXPECT_EQ(encoded_size(MessageType::hyperbolic_root), 7u);
  EXPECT_EQ(encoded_size(MessageType::hyperbolic_address), 15u);  // the empty address (the root's)
  EXPECT_EQ(to_string(MessageType::hyperbolic_address), "hyperbolic_address");
  // q = 8: 3 bits a side; 11 sides take 33 bits, 5 bytes.
  const HyperbolicAddressMsg a = address(8, {0, 7, 1, 3, 5, 2, 6, 4, 1, 1, 7});
  EXPECT_EQ(a.packed.size(), 5u);
  EXPECT_EQ(unpack_hyperbolic_address(a.packed, a.levels, a.q), (std::vector<std::uint32_t>{0, 7, 1, 3, 5, 2, 6, 4, 1, 1, 7}));
  EXPECT_EQ(encoded_size(Message{a}), 20u);
  const std::vector<Message> samples = {HyperbolicSweepMsg{2, 40, 1u << 31}, HyperbolicEchoMsg{2, 9, 0},
                                        HyperbolicRootMsg{0, 0}, a, address(3, {}, 1), address(1000, {999, 1, 998})};
  for (const Message& m : samples) {
    HyperbolicMessage out;
    ASSERT_EQ(decode(encode(m), out), DecodeStatus::ok);
    EXPECT_EQ(encode(out), encode(m));
  }
  laguerre::protocols::testing::expect_every_truncation_and_extension_rejected(samples);
}

TEST(HyperbolicCodec, OutOfRangeFieldsAreRejected) {
  HyperbolicMessage out;
  EXPECT_EQ(decode(encode(HyperbolicSweepMsg{3, 1, 1}), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(HyperbolicEchoMsg{2, 4, 5}), out), DecodeStatus::out_of_range);  // sweep 2 carries no id
  EXPECT_EQ(decode(encode(HyperbolicRootMsg{0, 2}), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(HyperbolicRootMsg{2, 0}), out), DecodeStatus::out_of_range);
  HyperbolicAddressMsg bad = address(5, {4, 1, 2});
  bad.whose = 2;
  EXPECT_EQ(decode(encode(bad), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(address(2, {1})), out), DecodeStatus::out_of_range);     // q < 3
  EXPECT_EQ(decode(encode(address(5, {4, 0, 2})), out), DecodeStatus::out_of_range);  // side 0 below the root's child
  EXPECT_EQ(decode(encode(address(5, {5, 1})), out), DecodeStatus::out_of_range);  // side ≥ q
  bad = address(5, {4, 1, 2});
  bad.packed[1] |= std::byte{0x80};  // an unused bit (9 bits used of 16)
  EXPECT_EQ(decode(encode(bad), out), DecodeStatus::out_of_range);
  bad = address(5, {4, 1, 2});
  bad.levels = 4;  // 12 bits still fit 2 bytes, but side 4 would be 0
  EXPECT_EQ(decode(encode(bad), out), DecodeStatus::out_of_range);
  bad.levels = 6;  // 18 bits: 3 bytes needed
  EXPECT_EQ(decode(encode(bad), out), DecodeStatus::out_of_range);
  // Another set's type is foreign.
  EXPECT_EQ(decode(encode(RadiusMsg{1, 0.5}), out), DecodeStatus::foreign_type);
}
