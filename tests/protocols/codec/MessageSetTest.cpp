// Message sets (Codec.hpp): each receiver decodes only its own types; another set's well-formed type
// is foreign_type, checked after the version and the type byte and before the length; nested sets
// (PackingHop, FramePayload) hold a message in the alternative that contains its type.

#include <gtest/gtest.h>

#include "laguerre/protocols/Codec.hpp"

using namespace laguerre::protocols;

namespace {

// One message of every type, in type-code order.
std::vector<Message> one_of_each() {
  return {DepthMsg{false, 3, 4},
          ElectionMsg{ElectionStage::ring, 2, 9},
          StartMsg{1, 2},
          WaveMsg{4, 2, 7},
          RadiusMsg{5, 0.5},
          PlacedMsg{1, 0.25, 0.1, 0.2, 0.3, 0.4, 0.5},
          ReportMsg{2, true},
          DecisionMsg{2, Verdict::cap},
          ShapeMsg{true, false},
          FaceCirclesMsg{1, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}},
          RelayMsg{7, 7, 3, false, encode(ReportMsg{1, true})},
          DataMsg{1, 2, 3, 0.5, 0.5, 0.1, 9, 1},
          FrameMsg{4, {2, 1}, encode(RadiusMsg{1, 2.0})},
          AckMsg{{5, 3}},
          FailureMsg{11},
          RouteMsg{1, 2, 3, RouteScheme::compass, 0.5, 0.5, 9, 1},
          KrylovValueMsg{3, -0.125},
          KrylovSumMsg{3, 1.5, -2.5, 0.25, 7},
          KrylovDecisionMsg{3, 2, 0.5, 0},
          GateRadiusMsg{4, 1.5, 0x8000000000000001ull},
          HeightMsg{false, 5},

          HyperbolicSweepMsg{1, 4, 9},
          HyperbolicEchoMsg{0, 7, 12},
          HyperbolicRootMsg{1, 3},
          HyperbolicAddressMsg{5, 0, 3, pack_hyperbolic_address(std::vector<std::uint32_t>{4, 1, 2}, 5)}};
}

// The type codes each set accepts.
template <class Set>
std::vector<int> accepted_types() {
  std::vector<int> codes;
  for (const Message& m : one_of_each()) {
    Set out;
    if (decode(encode(m), out) == DecodeStatus::ok) codes.push_back(static_cast<int>(type_of(m)));
  }
  return codes;
}

}  // namespace

TEST(MessageSets, EachSetAcceptsExactlyItsTypes) {
  ASSERT_EQ(one_of_each().size(), std::size_t{max_message_type});
  for (std::size_t k = 0; k < one_of_each().size(); ++k) EXPECT_EQ(one_of_each()[k].index(), k);
  EXPECT_EQ(accepted_types<PackingMessage>(), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 18, 19, 20, 21}));
  EXPECT_EQ(accepted_types<PackingHop>(), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 17, 18, 19, 20, 21}));
  EXPECT_EQ(accepted_types<LinkMessage>(), (std::vector<int>{13, 14}));
  EXPECT_EQ(accepted_types<FramePayload>(), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 15, 17, 18, 19, 20, 21}));
  EXPECT_EQ(accepted_types<ForwardingMessage>(), (std::vector<int>{12, 16}));
  EXPECT_EQ(accepted_types<HyperbolicMessage>(), (std::vector<int>{22, 23, 24, 25}));
  EXPECT_EQ(accepted_types<Message>().size(), std::size_t{max_message_type});
}

TEST(MessageSets, ForeignTypesAreRejectedBeforeTheirLength) {
  LinkMessage out = AckMsg{{42, 1}};
  const std::vector<std::byte> radius = encode(RadiusMsg{1, 0.5});
  EXPECT_EQ(decode(radius, out), DecodeStatus::foreign_type);
  EXPECT_EQ(decode(std::span(radius).first(3), out), DecodeStatus::foreign_type);  // truncated, but foreign first
  std::vector<std::byte> longer = radius;
  longer.push_back(std::byte{0});
  EXPECT_EQ(decode(longer, out), DecodeStatus::foreign_type);
  EXPECT_EQ(std::get<AckMsg>(out), (AckMsg{{42, 1}})) << "a rejected decode must leave the output alone";
  // The header checks still come first.
  std::vector<std::byte> b = radius;
  b[0] = std::byte{wire_version + 1};
  EXPECT_EQ(decode(b, out), DecodeStatus::bad_version);
  b[0] = std::byte{wire_version};
  b[1] = std::byte{max_message_type + 1};
  EXPECT_EQ(decode(b, out), DecodeStatus::unknown_type);
  EXPECT_EQ(decode(std::span(b).first(1), out), DecodeStatus::truncated);
  // A type of the set is checked as always.
  const std::vector<std::byte> ack = encode(AckMsg{{1, 2}});
  EXPECT_EQ(decode(std::span(ack).first(ack.size() - 1), out), DecodeStatus::truncated);
  EXPECT_EQ(to_string(DecodeStatus::foreign_type), "foreign_type");
}

TEST(MessageSets, NestedSetsHoldTheMessageWhereItsTypeBelongs) {
  PackingHop hop;
  ASSERT_EQ(decode(encode(RadiusMsg{3, 0.75}), hop), DecodeStatus::ok);
  ASSERT_TRUE(std::holds_alternative<PackingMessage>(hop));
  EXPECT_EQ(std::get<RadiusMsg>(std::get<PackingMessage>(hop)), (RadiusMsg{3, 0.75}));
  const RelayMsg relay{7, 3, 7, true, encode(ShapeMsg{false, true})};
  ASSERT_EQ(decode(encode(relay), hop), DecodeStatus::ok);
  EXPECT_EQ(std::get<RelayMsg>(hop), relay);

  FramePayload payload;
  ASSERT_EQ(decode(encode(FailureMsg{99}), payload), DecodeStatus::ok);
  EXPECT_EQ(std::get<FailureMsg>(payload), FailureMsg{99});
  ASSERT_EQ(decode(encode(DepthMsg{true, 2, 5}), payload), DecodeStatus::ok);
  EXPECT_EQ(std::get<DepthMsg>(std::get<PackingMessage>(std::get<PackingHop>(payload))), (DepthMsg{true, 2, 5}));
  EXPECT_EQ(decode(encode(FrameMsg{0, {}, {}}), payload), DecodeStatus::foreign_type);  // frames never nest
}

TEST(MessageSets, EncodingASetIsEncodingItsMessage) {
  for (const Message& m : one_of_each()) {
    const std::vector<std::byte> bytes = encode(m);
    FramePayload payload;
    ForwardingMessage forwarding;
    LinkMessage link;
    HyperbolicMessage hyperbolic;
    std::size_t decoded = 0;
    if (decode(bytes, payload) == DecodeStatus::ok) {
      ++decoded;
      EXPECT_EQ(encode(payload), bytes) << to_string(type_of(m));
    }
    if (decode(bytes, forwarding) == DecodeStatus::ok) {
      ++decoded;
      EXPECT_EQ(encode(forwarding), bytes) << to_string(type_of(m));
    }
    if (decode(bytes, link) == DecodeStatus::ok) {
      ++decoded;
      EXPECT_EQ(encode(link), bytes) << to_string(type_of(m));
    }
    if (decode(bytes, hyperbolic) == DecodeStatus::ok) {
      ++decoded;
      EXPECT_EQ(encode(hyperbolic), bytes) << to_string(type_of(m));
    }
    EXPECT_EQ(decoded, 1u) << "the four sets partition the types: " << to_string(type_of(m));
  }
}
