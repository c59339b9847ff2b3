#pragma once
/// @file
/// Simulated time: a signed 64-bit count of nanoseconds (same representation as protocols::Time).
///
/// Integer time makes event order exact: two events scheduled for the "same" instant compare equal,
/// and the FIFO tie-break of the kernel (see Kernel.hpp) then decides, identically on every run and
/// every machine. 2^63 ns is about 292 years of simulated time.

#include <cstdint>
#include <limits>

namespace laguerre::sim {

/// A point in simulated time, in nanoseconds since the start of the run.
using Time = std::int64_t;
/// A span of simulated time, in nanoseconds.
using Duration = std::int64_t;

/// The largest representable time; "no time limit".
inline constexpr Time time_max = std::numeric_limits<Time>::max();

/// `n` nanoseconds.
constexpr Duration nanoseconds(std::int64_t n) { return n; }
/// `n` microseconds, in nanoseconds.
constexpr Duration microseconds(std::int64_t n) { return n * 1'000; }
/// `n` milliseconds, in nanoseconds.
constexpr Duration milliseconds(std::int64_t n) { return n * 1'000'000; }
/// `n` seconds, in nanoseconds.
constexpr Duration seconds(std::int64_t n) { return n * 1'000'000'000; }
/// A time in nanoseconds expressed in (floating-point) seconds, for reports.
constexpr double to_seconds(Time t) { return static_cast<double>(t) * 1e-9; }

}  // namespace laguerre::sim
