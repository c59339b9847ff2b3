#pragma once
/// @file
/// The project's random numbers and hashes, each a fixed function of its inputs on every platform
/// (never the standard distributions, whose algorithms differ between standard libraries), so seeds,
/// golden hashes and sampled outputs are the same everywhere:
///  - SplitMix64 (Steele, Lea & Flood, OOPSLA 2014): the `mix64` finalizer, `splitmix64` of one word,
///    and the `SplitMix64` generator;
///  - `fnv1a64`, the 64-bit FNV-1a hash;
///  - `uniform_below`, the unbiased bounded draw from any source of uniform 64-bit words;
///  - `SeededRandom`, std::mt19937_64 (whose output sequence the standard fixes) with those draws,
///    for generators (graphs, deployments, pair samples).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#if __cplusplus >= 202002L  // tools/bench/phold_ns3 includes this header as C++17 (ns-3 3.37 needs it)
#include <span>
#endif
#include <string_view>
#include <vector>

namespace laguerre::core {

/// The SplitMix64 output finalizer (Stafford's "Mix13"): two xor-shift / odd-multiply rounds, a
/// bijection of 64-bit words with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

/// The Weyl increment of SplitMix64 (2^64 divided by the golden ratio, made odd).
inline constexpr std::uint64_t golden_gamma = 0x9e3779b97f4a7c15ULL;

/// mix64(x + golden_gamma): the first output of SplitMix64 seeded with x.
constexpr std::uint64_t splitmix64(std::uint64_t x) { return mix64(x + golden_gamma); }

/// The double k · 2^-53 in [0, 1) made of the top 53 bits of `bits`.
constexpr double to_unit_double(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

/// The SplitMix64 generator: output n is splitmix64(seed + n · golden_gamma).
class SplitMix64 {
public:
  /// The generator seeded with `seed`.
  constexpr explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  /// The next 64 bits.
  constexpr std::uint64_t next() { return mix64(state_ += golden_gamma); }
  /// A uniform double in [0, 1) (to_unit_double of the next output).
  constexpr double uniform01() { return to_unit_double(next()); }

private:
  std::uint64_t state_;
};

/// The FNV-1a 64 offset basis (the hash of nothing).
inline constexpr std::uint64_t fnv1a_basis = 0xcbf29ce484222325ULL;

#if __cplusplus >= 202002L
/// Continues the FNV-1a 64 hash `h` over `bytes`.
constexpr std::uint64_t fnv1a64(std::span<const std::byte> bytes, std::uint64_t h = fnv1a_basis) {
  for (const std::byte b : bytes) {
    h ^= static_cast<std::uint64_t>(b);
    h *= 0x100000001b3ULL;
  }
  return h;
}
#endif

/// Continues the FNV-1a 64 hash `h` over the characters of `text` (as unsigned bytes).
constexpr std::uint64_t fnv1a64(std::string_view text, std::uint64_t h = fnv1a_basis) {
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// A uniform integer in [0, bound), bound ≥ 1, from `next()`, a source of uniform 64-bit words:
/// rejects the words at or above the largest multiple of `bound` that is at most 2^64 − 1, so that the
/// accepted range is a whole number of copies of [0, bound), and returns the accepted word mod bound.
/// Exactly unbiased.
template <class Next>
std::uint64_t uniform_below(Next&& next, std::uint64_t bound) {
  constexpr std::uint64_t max = ~std::uint64_t{0};
  const std::uint64_t limit = max - max % bound;  // a multiple of bound
  std::uint64_t x = next();
  while (x >= limit) x = next();
  return x % bound;
}

/// Draws from std::mt19937_64: the same seed gives the same graphs and points on every platform.
class SeededRandom {
public:
  /// Seeds the engine.
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}
  /// Uniform double in [0, 1): to_unit_double of one draw.
  double uniform01() { return to_unit_double(engine_()); }
  /// Uniform integer in [0, bound), bound > 0 (uniform_below).
  std::uint64_t below(std::uint64_t bound) {
    return uniform_below([this] { return engine_(); }, bound);
  }
  /// A uniformly random 0/1 sequence of length `size` with exactly `ones` ones (Fisher–Yates).
  std::vector<std::uint8_t> binary_word(std::size_t size, std::size_t ones) {
    std::vector<std::uint8_t> word(size, 0);
    std::fill(word.begin(), word.begin() + static_cast<std::ptrdiff_t>(ones), std::uint8_t{1});
    for (std::size_t i = size; i > 1; --i) std::swap(word[i - 1], word[below(i)]);
    return word;
  }

private:
  std::mt19937_64 engine_;
};

}  // namespace laguerre::core
