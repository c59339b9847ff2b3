#pragma once
/// @file
/// Counter-based random streams: the n-th number of a stream is a pure function of
/// (seed, stream kind, id a, id b, n), so it does not depend on how events interleave.
///
/// Construction (all arithmetic mod 2^64):
///  - `mix64` is the SplitMix64 output finalizer of core/random/Random.hpp (Stafford's "Mix13"
///    variant): two xor-shift / odd-multiply rounds. It is a bijection of 64-bit words with full
///    avalanche.
///  - A stream key chains that bijection over the identifying words:
///        k0 = mix64(seed ^ c0),  k1 = mix64(k0 ^ kind),  k2 = mix64(k1 ^ a),  key = mix64(k2 ^ b),
///    with c0 a fixed odd constant (so seed 0 does not give key 0). Each step is injective in its new
///    word for a fixed prefix, so streams that differ in exactly one of (seed, kind, a, b) never share
///    a key; unrelated tuples collide with probability 2^-64.
///  - Value n of the stream with key K is SplitMix64's n-th output started from K:
///        x_n = mix64(K + (n + 1) * gamma),  gamma = 0x9e3779b97f4a7c15 (odd, golden ratio).
///    SplitMix64 passes BigCrush (Steele, Lea & Flood, OOPSLA 2014). Two streams are shifted copies
///    of one Weyl sequence only if their keys differ by j * gamma with a small j, which for keys out
///    of the chained mixer has probability about (draws per stream) / 2^64.
///
/// Whoever owns a stream owns its counter: the simulator keeps one counter per node and derives
/// a fresh stream per message on a link (kind `message`, ids = link, message index), so a message's
/// loss, duplication and latency are fixed by the link and the position of the message on it.
///
/// Derived variates: `uniform01` uses the top 53 bits (all doubles k * 2^-53, k < 2^53, equally
/// likely); `below(n)` is Lemire's multiply-shift with rejection (exactly uniform, no modulo bias;
/// not core::uniform_below, whose other mapping would change every trace hash);
/// `exponential` is inversion, -mean · log(v) with v = 1 − u = (k + 1) · 2^-53 ∈ (0, 1] computed
/// exactly from the bits (so the logarithm is always finite; log is cheaper than log1p).

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/random/Random.hpp"

namespace laguerre::sim {

using core::golden_gamma;
using core::mix64;
using core::to_unit_double;

/// What a stream is attached to; part of its key, so node 3's stream differs from link (3, ·)'s.
enum class StreamKind : std::uint64_t {
  node = 1,     ///< one stream per node (a = node id)
  link = 2,     ///< one stream per directed link (a = sender id, b = receiver id)
  message = 3,  ///< one stream per message on a link (a = link key, b = message index on the link)
  process = 4,  ///< one stream per logical process of a benchmark (a = process id)
  user = 256,   ///< first value free for callers (use user + k)
};

/// The key of the stream identified by (seed, kind, a, b); see the file comment for the construction.
constexpr std::uint64_t stream_key(std::uint64_t seed, StreamKind kind, std::uint64_t a,
                                   std::uint64_t b = 0) {
  std::uint64_t k = mix64(seed ^ 0x6a09e667f3bcc909ULL);
  k = mix64(k ^ static_cast<std::uint64_t>(kind));
  k = mix64(k ^ a);
  return mix64(k ^ b);
}

/// Value number `counter` (0-based) of the stream with key `key`: a pure function.
constexpr std::uint64_t random_at(std::uint64_t key, std::uint64_t counter) {
  return mix64(key + (counter + 1) * golden_gamma);
}

/// A counter-based stream: a key and the index of the next value. Copying a stream copies its
/// position; two copies produce the same numbers.
class RandomStream {
public:
  /// A stream with key 0 at position 0 (valid, but prefer a derived key).
  constexpr RandomStream() = default;
  /// The stream with key `key`, positioned at value number `counter`.
  constexpr explicit RandomStream(std::uint64_t key, std::uint64_t counter = 0)
      : key_(key), counter_(counter) {}
  /// The stream identified by (seed, kind, a, b), at position 0.
  static constexpr RandomStream of(std::uint64_t seed, StreamKind kind, std::uint64_t a,
                                   std::uint64_t b = 0) {
    return RandomStream(stream_key(seed, kind, a, b));
  }

  /// This stream's key.
  constexpr std::uint64_t key() const { return key_; }
  /// How many values have been drawn (the index of the next one).
  constexpr std::uint64_t counter() const { return counter_; }

  /// The next 64 uniformly distributed bits.
  constexpr std::uint64_t next_u64() { return random_at(key_, counter_++); }
  /// A uniform double in [0, 1) with 53 random bits.
  constexpr double uniform01() { return to_unit_double(next_u64()); }
  /// A uniform double in [lo, hi).
  constexpr double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// True with probability `p` (p ≤ 0: never; p ≥ 1: always).
  constexpr bool bernoulli(double p) { return uniform01() < p; }
  /// An exponential variate with the given mean (> 0), by inversion.
  double exponential(double mean) {
    const double v = static_cast<double>((next_u64() >> 11) + 1) * 0x1.0p-53;  // exactly 1 − u
    return -mean * std::log(v);
  }

  /// A uniform integer in [0, n), exactly unbiased (Lemire's method with rejection); n must be > 0.
  std::uint64_t below(std::uint64_t n) {
    LAGUERRE_PRECONDITION(n > 0, "RandomStream::below needs a positive bound, got 0.");
    __extension__ using U128 = unsigned __int128;
    U128 m = static_cast<U128>(next_u64()) * n;
    auto low = static_cast<std::uint64_t>(m);
    if (low < n) {
      // Reject the (2^64 mod n) products whose low word falls below the threshold: what remains
      // is an exact multiple of n outcomes per result.
      const std::uint64_t threshold = (0 - n) % n;
      while (low < threshold) {
        m = static_cast<U128>(next_u64()) * n;
        low = static_cast<std::uint64_t>(m);
      }
    }
    return static_cast<std::uint64_t>(m >> 64);
  }

  /// A uniform integer in [lo, hi] (inclusive, exactly unbiased); requires lo ≤ hi.
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi) {
    LAGUERRE_PRECONDITION(lo <= hi, "RandomStream::uniform_int needs lo <= hi.");
    const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo);
    const std::uint64_t offset = span == ~std::uint64_t{0} ? next_u64() : below(span + 1);
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) + offset);
  }

private:
  std::uint64_t key_ = 0;
  std::uint64_t counter_ = 0;
};

}  // namespace laguerre::sim
