// core/random/Random.hpp: known answers of SplitMix64 and FNV-1a, the bounded draw's rejection rule,
// and golden draws of SeededRandom (the graph generators' and pair samplers' stream).

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string_view>
#include <vector>

#include "laguerre/core/random/Random.hpp"

using namespace laguerre::core;

TEST(SplitMix64, KnownAnswers) {
  // Vigna's splitmix64.c seeded with 0: its first three outputs.
  SplitMix64 g(0);
  EXPECT_EQ(g.next(), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(g.next(), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(g.next(), 0x06c45d188009454fULL);
  EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(splitmix64(golden_gamma), 0x6e789e6aa1b965f4ULL);
  static_assert(splitmix64(0) == mix64(golden_gamma));
  SplitMix64 h(12345);
  for (std::uint64_t n = 0; n < 5; ++n) EXPECT_EQ(h.next(), splitmix64(12345 + n * golden_gamma));
  SplitMix64 u(7);
  EXPECT_EQ(u.uniform01(), to_unit_double(splitmix64(7)));
  EXPECT_EQ(to_unit_double(~std::uint64_t{0}), 1.0 - 0x1.0p-53);
  EXPECT_EQ(to_unit_double(0x7ff), 0.0);
}

TEST(Fnv1a64, KnownAnswers) {
  EXPECT_EQ(fnv1a64(std::string_view{}), fnv1a_basis);
  EXPECT_EQ(fnv1a64(std::string_view{"a"}), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64(std::string_view{"foobar"}), 0x85944171f73967e8ULL);
  const std::array<std::byte, 6> bytes{std::byte{'f'}, std::byte{'o'}, std::byte{'o'},
                                       std::byte{'b'}, std::byte{'a'}, std::byte{'r'}};
  EXPECT_EQ(fnv1a64(std::span<const std::byte>(bytes)), 0x85944171f73967e8ULL);
  // Continuing a hash is hashing the concatenation.
  EXPECT_EQ(fnv1a64(std::string_view{"bar"}, fnv1a64(std::string_view{"foo"})), 0x85944171f73967e8ULL);
  const char high = static_cast<char>(0xff);  // bytes are taken unsigned
  EXPECT_EQ(fnv1a64(std::string_view(&high, 1)), (fnv1a_basis ^ 0xffULL) * 0x100000001b3ULL);
}

TEST(UniformBelow, RejectsTheTopPartialCopyOnly) {
  // 2^64 − 1 is a multiple of 3: only the word 2^64 − 1 is rejected.
  std::vector<std::uint64_t> words{~std::uint64_t{0}, ~std::uint64_t{0}, 7, 5};
  std::size_t used = 0;
  auto next = [&] { return words[used++]; };
  EXPECT_EQ(uniform_below(next, 3), 1u);
  EXPECT_EQ(used, 3u);
  EXPECT_EQ(uniform_below(next, 3), 2u);
  EXPECT_EQ(used, 4u);
  // bound 2^63 + 1: words from 2^63 + 1 on are rejected; 2^63 is accepted and is its own remainder.
  const std::uint64_t half = std::uint64_t{1} << 63;
  words = {half + 1, ~std::uint64_t{0}, half};
  used = 0;
  EXPECT_EQ(uniform_below(next, half + 1), half);
  EXPECT_EQ(used, 3u);
  words = {~std::uint64_t{0}, 41};
  used = 0;
  EXPECT_EQ(uniform_below(next, 1), 0u) << "bound 1: limit 2^64 − 1, the top word is rejected";
  EXPECT_EQ(used, 2u);
}

TEST(SeededRandom, GoldenDraws) {
  // The sequences every generated graph and sampled pair set depends on (std::mt19937_64 is fixed by
  // the standard, the mappings are ours): a change here changes every generated graph.
  SeededRandom r(42);
  const std::array<std::uint64_t, 7> bounds{1, 2, 6, 1000, std::uint64_t{1} << 40, 0x8000000000000001ULL,
                                            0xffffffffffffffffULL};
  const std::array<std::uint64_t, 7> want{0, 0, 4, 662, 611180747093ULL, 1735254072534978428ULL,
                                          10598951352238613536ULL};
  for (std::size_t i = 0; i < bounds.size(); ++i) EXPECT_EQ(r.below(bounds[i]), want[i]) << bounds[i];
  EXPECT_EQ(r.uniform01(), 0x1.7dd645e8fadeep-2);
  EXPECT_EQ(r.uniform01(), 0x1.187273d8bae7ep-2);
  EXPECT_EQ(r.binary_word(12, 5), (std::vector<std::uint8_t>{0, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1}));
  // uniform01 is to_unit_double of one engine draw.
  SeededRandom a(9);
  std::mt19937_64 e(9);
  EXPECT_EQ(a.uniform01(), to_unit_double(e()));
}
