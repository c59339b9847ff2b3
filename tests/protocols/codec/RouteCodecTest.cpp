// RouteMsg (type 16, the baseline forwarding schemes with GFG's perimeter state): size, layout,
// round trips, and rejection of every field outside its documented range, including non-canonical
// encodings of the fields a mode does not use.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "laguerre/protocols/Codec.hpp"

using namespace laguerre::protocols;

namespace {

RouteMsg perimeter_msg() {
  RouteMsg m{4, 5, 6, RouteScheme::gfg, 0.25, 0.75, 100, 3};
  m.perimeter = true;
  m.px = 0.1;
  m.py = -0.2;
  m.crossed = true;
  m.ax = 1;
  m.ay = 2;
  m.bx = 3;
  m.by = 4;
  m.walk_tail = 5;
  m.walk_head = 17;
  return m;
}

// Byte offsets of the fields (after the 2-byte header), in declaration order.
constexpr std::size_t at_scheme = 2 + 24, at_tx = at_scheme + 1, at_ttl = at_tx + 16, at_perimeter = at_ttl + 8,
                      at_px = at_perimeter + 1, at_crossed = at_px + 16, at_ax = at_crossed + 1, at_tail = at_ax + 32;

std::vector<std::byte> with_f64(const RouteMsg& m, std::size_t at, double v) {
  std::vector<std::byte> b = encode(m);
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(v);
  for (int i = 0; i < 8; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::byte>((bits >> (8 * i)) & 0xffu);
  return b;
}

std::vector<std::byte> with_u8(const RouteMsg& m, std::size_t at, std::uint8_t v) {
  std::vector<std::byte> b = encode(m);
  b[at] = std::byte{v};
  return b;
}

}  // namespace

TEST(RouteCodec, LayoutAndRoundTrip) {
  EXPECT_EQ(to_string(MessageType::route), "route");
  EXPECT_EQ(encoded_size(MessageType::route), 2u + 24 + 1 + 16 + 8 + 1 + 16 + 1 + 32 + 16);
  const RouteMsg m = perimeter_msg();
  const std::vector<std::byte> b = encode(m);
  ASSERT_EQ(b.size(), encoded_size(MessageType::route));
  EXPECT_EQ(std::to_integer<int>(b[1]), 16);
  EXPECT_EQ(std::to_integer<int>(b[at_scheme]), 3);
  EXPECT_EQ(std::to_integer<int>(b[at_perimeter]), 1);
  EXPECT_EQ(std::to_integer<int>(b[at_crossed]), 1);
  EXPECT_EQ(std::to_integer<int>(b[at_tail]), 5);
  EXPECT_EQ(std::to_integer<int>(b[at_tail + 8]), 17);
  Message out;
  ASSERT_EQ(decode(b, out), DecodeStatus::ok);
  EXPECT_EQ(std::get<RouteMsg>(out), m);
}

TEST(RouteCodec, RejectsOutOfRangeFields) {
  Message out;
  const RouteMsg greedy{1, 2, 3, RouteScheme::gfg, 0.5, 0.5, 10, 2};
  const RouteMsg p = perimeter_msg();
  ASSERT_EQ(decode(encode(greedy), out), DecodeStatus::ok);
  for (int s : {0, 4, 255}) EXPECT_EQ(decode(with_u8(greedy, at_scheme, static_cast<std::uint8_t>(s)), out), DecodeStatus::out_of_range) << s;
  EXPECT_EQ(decode(encode(RouteMsg{1, 2, 3, RouteScheme::compass, 0, 0, 5, 0}), out), DecodeStatus::out_of_range);  // no hop
  EXPECT_EQ(decode(encode(RouteMsg{1, 2, 3, RouteScheme::compass, 0, 0, 5, 6}), out), DecodeStatus::out_of_range);  // hops > ttl
  EXPECT_EQ(decode(encode(RouteMsg{1, 3, 3, RouteScheme::compass, 0, 0, 5, 1}), out), DecodeStatus::out_of_range);  // to itself
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(decode(with_f64(greedy, at_tx, nan), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with_f64(greedy, at_tx + 8, -inf), out), DecodeStatus::out_of_range);
  // Booleans are 0 or 1.
  EXPECT_EQ(decode(with_u8(p, at_perimeter, 2), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with_u8(p, at_crossed, 7), out), DecodeStatus::out_of_range);
  // Perimeter mode only for gfg.
  RouteMsg q = p;
  q.scheme = RouteScheme::compass;
  EXPECT_EQ(decode(encode(q), out), DecodeStatus::out_of_range);
  // Perimeter state must be finite and name a real edge.
  EXPECT_EQ(decode(with_f64(p, at_px, inf), out), DecodeStatus::out_of_range);
  EXPECT_EQ(decode(with_f64(p, at_ax + 24, nan), out), DecodeStatus::out_of_range);
  q = p;
  q.walk_head = q.walk_tail;
  EXPECT_EQ(decode(encode(q), out), DecodeStatus::out_of_range);
  // Canonical: unused fields are +0 bits.
  for (std::size_t at : {at_px, at_px + 8, at_ax, at_ax + 24}) {
    EXPECT_EQ(decode(with_f64(greedy, at, -0.0), out), DecodeStatus::out_of_range) << at;
    EXPECT_EQ(decode(with_f64(greedy, at, 1.0), out), DecodeStatus::out_of_range) << at;
  }
  EXPECT_EQ(decode(with_u8(greedy, at_crossed, 1), out), DecodeStatus::out_of_range);  // crossed without perimeter
  EXPECT_EQ(decode(with_u8(greedy, at_tail, 1), out), DecodeStatus::out_of_range);     // a walk without perimeter
  q = p;
  q.crossed = false;  // no crossing yet, but an edge given
  EXPECT_EQ(decode(encode(q), out), DecodeStatus::out_of_range);
  q.ax = q.ay = q.bx = q.by = 0;
  EXPECT_EQ(decode(encode(q), out), DecodeStatus::ok);
  EXPECT_TRUE(std::holds_alternative<RouteMsg>(out));
}
