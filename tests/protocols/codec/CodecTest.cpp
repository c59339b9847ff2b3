#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include "CodecChecks.hpp"
#include "laguerre/protocols/Codec.hpp"

using namespace laguerre::protocols;

namespace {
std::vector<Message> samples() {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  return {DepthMsg{false, 0, 0},
          DepthMsg{true, DepthMsg::max_depth, 0xffffffffffffffffull},
          ElectionMsg{ElectionStage::settled, 0, 12},
          ElectionMsg{ElectionStage::final, 0, 0xffffffffffffffffull},
          ElectionMsg{ElectionStage::report, 7, 0xfedcba9876543210ull},
          ElectionMsg{ElectionStage::root, 0xffffffff, 0},
          StartMsg{3, 0xffffffffffffffffull},
          WaveMsg{1, 0, 0},
          WaveMsg{0xffffffff, 12, 99},
          RadiusMsg{5, std::numeric_limits<double>::infinity()},
          RadiusMsg{0x01020304, 0.1353352832366127},
          RadiusMsg{1, 5e-324},
          PlacedMsg{2, 0.25, -0.0, 1e-300, nan, -inf, 5e-324},
          PlacedMsg{0, std::numeric_limits<double>::infinity(), 0.5, -0.5, 0.1, 0.2, 0.3},
          ReportMsg{4, true},
          ReportMsg{4, false},
          DecisionMsg{9, Verdict::next},
          DecisionMsg{9, Verdict::converged},
          DecisionMsg{0xffffffff, Verdict::cap},
          DecisionMsg{3, Verdict::layout},
          ShapeMsg{false, true},
          ShapeMsg{true, false},
          HeightMsg{false, 7},
          HeightMsg{true, 0xffffffff},
          GateRadiusMsg{7, std::numeric_limits<double>::infinity(), 0xffffffffffffffffull},
          FaceCirclesMsg{3, {{0.1, 0.2, 0.3}, {nan, -inf, 0.0}, {-0.0, 1e300, 5e-324}}},
          FaceCirclesMsg{0xffffffff, std::vector<FaceCircle>(17, FaceCircle{0.5, -0.5, 0.25})},
          RelayMsg{0x8000000100000002ull, 0x8000000100000002ull, 9, false, encode(RadiusMsg{4, 0.5})},
          RelayMsg{77, 5, 77, true, encode(FaceCirclesMsg{1, {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {1, 1, 1}}})},
          DataMsg{1, 2, 3, 0.5, -0.25, 0.0, 10, 1},
          DataMsg{0xffffffffffffffffull, 0, 9, -0.0, 1e-300, 0.125, 0xffffffff, 0xffffffff},
          RouteMsg{1, 2, 3, RouteScheme::greedy_euclid, 0.5, -0.25, 10, 1},
          RouteMsg{9, 8, 7, RouteScheme::compass, -0.0, 1e300, 0xffffffff, 0xffffffff},
          RouteMsg{4, 5, 6, RouteScheme::gfg, 0.25, 0.75, 100, 3, true, 0.1, -0.2, false, 0, 0, 0, 0, 5, 17},
          RouteMsg{0xffffffffffffffffull, 0, 1, RouteScheme::gfg, 1, 2, 7, 7, true, -0.0, 5e-324, true, 0.1, 0.2,
                   -0.3, 0.4, 0, 0xffffffffffffffffull}};
}

bool same(const Message& a, const Message& b) {
  if (a.index() != b.index()) return false;
  if (const auto* p = std::get_if<PlacedMsg>(&a)) return same_bits(*p, std::get<PlacedMsg>(b));
  if (const auto* f = std::get_if<FaceCirclesMsg>(&a)) return same_bits(*f, std::get<FaceCirclesMsg>(b));
  if (const auto* r = std::get_if<RadiusMsg>(&a))
    return r->step == std::get<RadiusMsg>(b).step &&
           std::bit_cast<std::uint64_t>(r->h) == std::bit_cast<std::uint64_t>(std::get<RadiusMsg>(b).h);
  return std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, PlacedMsg> || std::is_same_v<T, RadiusMsg> || std::is_same_v<T, FaceCirclesMsg>)
          return false;  // handled above
        else return x == std::get<T>(b);
      },
      a);
}

// A decoded message must re-encode to the very bytes it came from (the encoding is canonical).
void expect_canonical(std::span<const std::byte> bytes, const Message& m) {
  const std::vector<std::byte> again = encode(m);
  ASSERT_EQ(again.size(), bytes.size());
  EXPECT_TRUE(std::equal(again.begin(), again.end(), bytes.begin()));
}
}  // namespace

TEST(Codec, RoundTripsEveryMessageBitExactly) {
  for (const Message& m : samples()) {
    const std::vector<std::byte> bytes = encode(m);
    EXPECT_EQ(bytes.size(), encoded_size(m));
    if (!std::holds_alternative<FaceCirclesMsg>(m) && !std::holds_alternative<RelayMsg>(m)) {
      EXPECT_EQ(bytes.size(), encoded_size(type_of(m)));
    }
    EXPECT_EQ(std::to_integer<int>(bytes[0]), wire_version);
    EXPECT_EQ(std::to_integer<int>(bytes[1]), static_cast<int>(type_of(m)));
    Message out;
    ASSERT_EQ(decode(bytes, out), DecodeStatus::ok) << to_string(type_of(m));
    EXPECT_TRUE(same(m, out)) << to_string(type_of(m));
  }
}

TEST(Codec, IsLittleEndian) {
  const std::vector<std::byte> b = encode(RadiusMsg{0x01020304, 1.0});
  ASSERT_EQ(b.size(), 14u);
  EXPECT_EQ(std::to_integer<int>(b[2]), 0x04);
  EXPECT_EQ(std::to_integer<int>(b[5]), 0x01);
  // 1.0 = 0x3ff0000000000000: the top byte comes last.
  EXPECT_EQ(std::to_integer<int>(b[13]), 0x3f);
  EXPECT_EQ(std::to_integer<int>(b[12]), 0xf0);
  EXPECT_EQ(std::to_integer<int>(b[6]), 0x00);
}

TEST(Codec, RejectsHeadersItDoesNotKnow) {
  Message out = DepthMsg{true, 42, 7};
  std::vector<std::byte> b = encode(ReportMsg{1, true});
  EXPECT_EQ(decode(std::span<const std::byte>{}, out), DecodeStatus::truncated);
  EXPECT_EQ(decode(std::span(b).first(1), out), DecodeStatus::truncated);
  for (int v : {0, wire_version - 1, wire_version + 1, 255}) {  // version 1 carried X instead of h
    b[0] = static_cast<std::byte>(v);
    EXPECT_EQ(decode(b, out), DecodeStatus::bad_version) << v;
  }
  b[0] = std::byte{wire_version};
  for (int t : {0, max_message_type + 1, 200, 255}) {
    b[1] = static_cast<std::byte>(t);
    EXPECT_EQ(decode(b, out), DecodeStatus::unknown_type);
  }
  EXPECT_TRUE(same(out, DepthMsg{true, 42, 7})) << "a rejected decode must leave the output alone";
  EXPECT_EQ(encoded_size(static_cast<MessageType>(0)), 0u);
  EXPECT_EQ(to_string(static_cast<MessageType>(77)), "?");
}

TEST(Codec, RejectsOutOfRangeFields) {
  Message out;
  auto with = [](Message m, std::size_t at, std::uint8_t v) {
    std::vector<std::byte> b = encode(m);
    b[at] = std::byte{v};
    return b;
  };
  EXPECT_EQ(decode(with(DepthMsg{true, 1, 3}, 2, 2), out), DecodeStatus::out_of_range);  // ack is a bool
  EXPECT_EQ(decode(encode(DepthMsg{false, DepthMsg::max_depth + 1, 3}), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with(ElectionMsg{ElectionStage::ring, 1, 3}, 2, 5), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(WaveMsg{0, 1, 3}), out), DecodeStatus::out_of_range);  // seq counts from 1
  EXPECT_EQ(decode(with(ReportMsg{1, true}, 6, 0xff), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with(DecisionMsg{1, Verdict::cap}, 6, 4), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(StartMsg{5, 5}), out), DecodeStatus::out_of_range);
  for (double x : {-0.5, 0.0, -0.0, std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(decode(encode(RadiusMsg{1, x}), out), DecodeStatus::out_of_range) << x;
    EXPECT_EQ(decode(encode(GateRadiusMsg{1, x, 0}), out), DecodeStatus::out_of_range) << x;
    EXPECT_EQ(decode(encode(PlacedMsg{1, x, 0, 0, 0, 0, 0}), out), DecodeStatus::out_of_range) << x;
  }
  EXPECT_EQ(decode(with(ShapeMsg{true, true}, 2, 2), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with(ShapeMsg{true, true}, 3, 9), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with(HeightMsg{true, 4}, 2, 2), out), DecodeStatus::out_of_range);
  // Variable sizes: the count is range-checked before it sizes the message.
  const FaceCirclesMsg three{1, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}};
  EXPECT_EQ(decode(encode(FaceCirclesMsg{1, {{0, 0, 1}, {1, 0, 1}}}), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with(three, 9, 0x7f), out), DecodeStatus::out_of_range);  // count ≥ 2^30
  EXPECT_EQ(decode(with(three, 6, 4), out), DecodeStatus::truncated);      // count 4, three circles
  EXPECT_EQ(decode(with(three, 6, 2), out), DecodeStatus::out_of_range);   // count 2 < 3
  const std::vector<std::byte> payload = encode(ReportMsg{1, true});
  EXPECT_EQ(decode(encode(RelayMsg{7, 7, 3, false, payload}), out), DecodeStatus::ok);
  EXPECT_EQ(decode(encode(RelayMsg{7, 3, 3, false, payload}), out), DecodeStatus::out_of_range);  // source = target
  EXPECT_EQ(decode(encode(RelayMsg{7, 3, 4, false, payload}), out), DecodeStatus::out_of_range);  // face not an end
  EXPECT_EQ(decode(with(RelayMsg{7, 7, 3, false, payload}, 26, 2), out), DecodeStatus::out_of_range);  // backward
  EXPECT_EQ(decode(encode(RelayMsg{7, 7, 3, false, {std::byte{1}}}), out), DecodeStatus::out_of_range);  // 1 byte
  EXPECT_EQ(decode(with(RelayMsg{7, 7, 3, false, payload}, 30, 0xff), out), DecodeStatus::out_of_range);  // huge count
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 3, 0, 0, 0, 5, 5}), out), DecodeStatus::ok);
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 3, 0, 0, 0, 5, 6}), out), DecodeStatus::out_of_range);  // hops > ttl
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 3, 0, 0, 0, 5, 0}), out), DecodeStatus::out_of_range);  // no hop yet
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 2, 0, 0, 0, 5, 1}), out), DecodeStatus::out_of_range);  // to itself
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 3, nan, 0, 0, 5, 1}), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 3, 0, inf, 0, 5, 1}), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(encode(DataMsg{1, 2, 3, 0, 0, -1, 5, 1}), out), DecodeStatus::out_of_range);
}

// RelayView (the relays' in-place form) writes the RelayMsg bytes and reads every byte string of
// the relay type as decode(bytes, Message&) does: the same status, and on success the same fields,
// its payload a view into the input; any other known type is foreign_type.
TEST(Codec, RelayViewIsRelayMsgWithoutTheCopy) {
  const std::vector<std::byte> payload = encode(ReportMsg{1, true});
  const RelayMsg relays[] = {{7, 7, 3, false, payload}, {0x8000000100000002ull, 5, 0x8000000100000002ull, true, payload}};
  for (const RelayMsg& r : relays) {
    std::vector<std::byte> bytes;
    encode(RelayView{r.face, r.source, r.target, r.backward, r.payload}, bytes);
    EXPECT_EQ(bytes, encode(r));
  }
  std::vector<std::vector<std::byte>> inputs = {encode(relays[0]), encode(RelayMsg{7, 3, 3, false, payload}),
                                                encode(ReportMsg{2, false}), {}, {std::byte{wire_version}}};
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {  // corruptions and truncations of a valid relay
    std::vector<std::byte> b = encode(relays[trial % 2]);
    b[rng() % b.size()] ^= static_cast<std::byte>(1u << (rng() % 8));
    if (trial % 3 == 0) b.resize(rng() % (b.size() + 1));
    inputs.push_back(b);
  }
  for (const auto& b : inputs) {
    Message m;
    RelayView v{1, 2, 1, false, {}};
    DecodeStatus expected = decode(b, m);
    const auto code = b.size() >= 2 ? std::to_integer<unsigned>(b[1]) : 0u;
    const bool known_header = b.size() >= 2 && b[0] == std::byte{wire_version} && code >= 1 && code <= max_message_type;
    if (known_header && code != static_cast<unsigned>(MessageType::relay)) expected = DecodeStatus::foreign_type;
    ASSERT_EQ(decode(b, v), expected);
    if (expected != DecodeStatus::ok) {
      EXPECT_EQ(v.face, 1u);  // unchanged
      continue;
    }
    const RelayMsg& r = std::get<RelayMsg>(m);
    EXPECT_EQ((RelayMsg{v.face, v.source, v.target, v.backward, std::vector<std::byte>(v.payload.begin(), v.payload.end())}), r);
    EXPECT_TRUE(v.payload.data() >= b.data() && v.payload.data() + v.payload.size() == b.data() + b.size());
  }
}

TEST(Codec, EveryTruncationAndExtensionIsRejected) {
  laguerre::protocols::testing::expect_every_truncation_and_extension_rejected(samples());
}

TEST(Codec, RandomCorruptionIsRejectedOrDecodesToAValidMessage) {
  std::mt19937_64 rng(12345);
  std::size_t accepted = 0, rejected = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const auto all = samples();
    std::vector<std::byte> b = encode(all[rng() % all.size()]);
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) b[rng() % b.size()] ^= static_cast<std::byte>(1u << (rng() % 8));
    if (rng() % 4 == 0) b.resize(rng() % (b.size() + 3), std::byte{0xa5});
    Message out;
    const DecodeStatus s = decode(b, out);
    if (s == DecodeStatus::ok) {
      ++accepted;
      expect_canonical(b, out);
    } else {
      ++rejected;
    }
  }
  EXPECT_GT(accepted, 0u);
  EXPECT_GT(rejected, 0u);
}

TEST(Codec, ArbitraryBytesNeverCrash) {
  std::mt19937_64 rng(777);
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::byte> b(rng() % 64);
    for (auto& x : b) x = static_cast<std::byte>(rng() & 0xff);
    if (!b.empty() && rng() % 2) b[0] = std::byte{wire_version};
    if (b.size() > 1 && rng() % 2) b[1] = static_cast<std::byte>(1 + rng() % max_message_type);
    Message out;
    if (decode(b, out) == DecodeStatus::ok) expect_canonical(b, out);
  }
}
