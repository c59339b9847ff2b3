#pragma once
/// @file
/// Platform-independent random draws for generators (graphs, deployments, samplers).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace laguerre::core {

/// Draws from std::mt19937_64, whose output sequence the standard fixes, never through the standard
/// distributions, whose algorithms differ between standard libraries: the same seed gives the same
/// graphs and points on every platform.
class SeededRandom {
public:
  /// Seeds the engine.
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}
  /// Uniform double in [0, 1): the top 53 bits of one draw, scaled.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform integer in [0, bound), bound > 0, by rejection (no modulo bias).
  std::uint64_t below(std::uint64_t bound) {
    constexpr std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
    const std::uint64_t limit = max - max % bound;  // a multiple of bound
    std::uint64_t x = engine_();
    while (x >= limit) x = engine_();
    return x % bound;
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
