// The PHOLD workload shared by phold_laguerre.cpp and phold_ns3.cpp, so that both sides draw the
// very same numbers and only the event engines differ.
//
// PHOLD (Fujimoto 1990), as issue 3 specifies it: N logical processes (LPs), one initial event per
// LP; each event, when processed, schedules one new event at a uniformly random LP after
// 0.1 + Exp(1) time units. The time unit is one simulated second, so in nanoseconds:
// 100 ms + Exp(mean 1 s), rounded down. Each LP owns a counter-based random stream keyed by
// (seed, LP id), so the workload is a function of the seed alone.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "laguerre/sim/Random.hpp"

namespace phold {

/// 0.1 time unit (100 ms) in nanoseconds.
inline constexpr std::int64_t lookahead_ns = 100'000'000;
/// The mean of the exponential part, 1 time unit (1 s), in nanoseconds.
inline constexpr double mean_ns = 1e9;

/// One LP's stream and the draws an event makes from it.
struct Lp {
  laguerre::sim::RandomStream rng;
  /// The delay of the next event, in nanoseconds.
  std::int64_t delay() { return lookahead_ns + static_cast<std::int64_t>(rng.exponential(mean_ns)); }
  /// The LP the next event goes to.
  std::uint32_t destination(std::uint32_t lps) { return static_cast<std::uint32_t>(rng.below(lps)); }
};

/// The LPs of a run.
inline std::vector<Lp> make_lps(std::uint32_t count, std::uint64_t seed) {
  std::vector<Lp> lps;
  lps.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    lps.push_back(Lp{laguerre::sim::RandomStream::of(seed, laguerre::sim::StreamKind::process, i)});
  }
  return lps;
}

/// Seconds of CPU time used by this process so far (the machine may be shared: wall time would
/// also count the time other processes hold the cores).
inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Command-line options common to both programs.
struct Options {
  std::vector<std::uint32_t> sizes{10'000, 100'000, 1'000'000};
  std::uint64_t events = 10'000'000;
  std::uint64_t seed = 1;
  int repeat = 1;
  std::string scheduler = "ns3::MapScheduler";  // ns-3 only
  std::string rng = "shared";                    // ns-3 only: "shared" (ours) or "ns3" (its own)
  bool prefetch = true;                          // laguerre only: Kernel::set_prefetch hint on the LPs
};

inline Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--events") {
      o.events = std::strtoull(value, nullptr, 10);
    } else if (key == "--seed") {
      o.seed = std::strtoull(value, nullptr, 10);
    } else if (key == "--repeat") {
      o.repeat = std::atoi(value);
    } else if (key == "--rng") {
      o.rng = value;
    } else if (key == "--prefetch") {
      o.prefetch = std::atoi(value) != 0;
    } else if (key == "--scheduler") {
      o.scheduler = value;
    } else if (key == "--lps") {
      o.sizes.clear();
      for (const char* p = value; *p != '\0';) {
        char* end = nullptr;
        o.sizes.push_back(static_cast<std::uint32_t>(std::strtoul(p, &end, 10)));
        p = *end == ',' ? end + 1 : end;
      }
    }
  }
  return o;
}

}  // namespace phold
