#pragma once
/// @file
/// Text forms of the simulated network model shared by scenario files and `laguerre simulate`:
/// durations ("250us", "1ms", "2s", "100" = ns), latency laws (constant:D | uniform:LO:HI |
/// distance:BASE:NS_PER_UNIT[:JITTER]) and crashes ("ID@TIME").

#include <cstdint>
#include <string>
#include <string_view>

#include "laguerre/sim/Link.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::scenarios {

/// One scheduled crash: node `node` (user id) stops for good at simulated time `at`.
struct CrashSpec {
  std::uint64_t node = 0;  ///< user id of the node
  sim::Time at = 0;        ///< when it crashes (ns from the start)
};

/// "250us", "1ms", "2s", "7ns" or "100" (nanoseconds) → nanoseconds. Throws std::invalid_argument
/// ("expected a non-negative duration such as 250us, 1ms or 2s, found '…'") otherwise.
sim::Duration parse_duration(std::string_view text);

/// constant:D | uniform:LO:HI | distance:BASE:NS_PER_UNIT[:JITTER] → a latency law. Throws
/// std::invalid_argument naming the accepted forms.
sim::LatencyModel parse_latency(std::string_view spec);

/// "ID@TIME" (e.g. "17@40ms") → a crash. Throws std::invalid_argument.
CrashSpec parse_crash(std::string_view spec);

/// A duration in the shortest exact unit ("1ms", "250us", "3ns").
std::string format_duration(sim::Duration d);

}  // namespace laguerre::scenarios
