#pragma once
/// @file
/// Text forms of the simulated network model shared by scenario files and `laguerre simulate`:
/// durations ("250us", "1ms", "2s", "100" = ns), latency laws (constant:D | uniform:LO:HI |
/// distance:BASE:NS_PER_UNIT[:JITTER]) and crashes ("ID@TIME", "ID@T1-T2").
///
/// Every parser throws core::InputError with `source` (an option such as `--latency`, or empty) as
/// its source and a message of the form "found 'TEXT', expected …".

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "laguerre/sim/Link.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::scenarios {

/// One scheduled outage: node `node` (user id) stops at simulated time `at`, for good or until
/// `recover_at` (it then resumes with its state).
struct CrashSpec {
  std::uint64_t node = 0;               ///< user id of the node
  sim::Time at = 0;                     ///< when it crashes (ns from the start)
  std::optional<sim::Time> recover_at;  ///< when it comes back (after `at`), or never
};

/// The accepted latency forms, as messages name them.
inline constexpr std::string_view latency_forms =
    "constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER] (durations like 250us, 1ms, 2s)";
/// The accepted crash forms, as messages name them.
inline constexpr std::string_view crash_forms = "ID@TIME such as 17@40ms or ID@T1-T2 such as 17@40ms-90ms";

/// "250us", "1ms", "2s", "7ns" or "100" (nanoseconds) → nanoseconds. Throws core::InputError
/// ("found '…', expected a non-negative duration such as 250us, 1ms or 2s") otherwise.
sim::Duration parse_duration(std::string_view text, const std::string& source = {});

/// constant:D | uniform:LO:HI (LO ≤ HI) | distance:BASE:NS_PER_UNIT[:JITTER] → a latency law.
/// Throws core::InputError naming the accepted forms (or LO ≤ HI).
sim::LatencyModel parse_latency(std::string_view spec, const std::string& source = {});

/// "ID@TIME" (e.g. "17@40ms", for good) or "ID@T1-T2" (back at T2 > T1) → an outage. Throws
/// core::InputError.
CrashSpec parse_crash(std::string_view spec, const std::string& source = {});

/// "ID@TIME": brings node ID back at TIME, attached to its latest outage before TIME that has no
/// recovery yet. Throws core::InputError if there is none.
void add_recovery(std::vector<CrashSpec>& crashes, std::string_view spec, const std::string& source = {});

/// A duration in the shortest exact unit ("1ms", "250us", "3ns").
std::string format_duration(sim::Duration d);

}  // namespace laguerre::scenarios
