// Chooses the kernel's pending-event structure by measurement: the PHOLD hold model (pop the first
// event, push one at now + 100 ms + Exp(1 s) for a uniform random process) run directly on candidate
// queues of the kernel's 32-byte Event records, without handler dispatch. The last column adds what
// Kernel::set_prefetch does: prefetch the process state of the event 4 places ahead (Queue::peek).
// Rates are events per second of CPU time (the machine may be shared), best of REPEAT.
//   phold_queues [EVENTS [REPEAT]]   (default 5·10^6 events per cell, best of 3; sizes 10^4–10^6)
#include <algorithm>
#include <ctime>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <queue>
#include <string>
#include <vector>

#include "laguerre/sim/EventQueue.hpp"
#include "laguerre/sim/Random.hpp"

namespace {

using laguerre::sim::Event;
using laguerre::sim::fires_before;
using laguerre::sim::Time;

/// std::priority_queue as the baseline (binary heap through the standard library).
class StdQueue {
public:
  bool empty() const { return q_.empty(); }
  const Event& top() const { return q_.top(); }
  void push(const Event& e) { q_.push(e); }
  void pop() { q_.pop(); }

private:
  struct Later {
    bool operator()(const Event& a, const Event& b) const { return fires_before(b, a); }
  };
  std::priority_queue<Event, std::vector<Event>, Later> q_;
};

/// Seconds of CPU time used by this process.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

template <class Queue, bool Prefetch = false>
double run_phold(std::uint32_t lps, std::uint64_t events, std::uint64_t& checksum) {
  Queue q;
  std::uint64_t seq = 0;
  std::vector<laguerre::sim::RandomStream> streams;
  streams.reserve(lps);
  for (std::uint32_t i = 0; i < lps; ++i) {
    streams.push_back(laguerre::sim::RandomStream::of(1, laguerre::sim::StreamKind::process, i));
  }
  for (std::uint32_t i = 0; i < lps; ++i) {
    const auto delay = static_cast<Time>(streams[i].exponential(1e9));
    q.push(Event{100'000'000 + delay, seq++, 0, i, 0, 0});
  }
  const double start = cpu_seconds();
  std::uint64_t sum = 0;
  for (std::uint64_t k = 0; k < events; ++k) {
    const Event e = q.top();
    q.pop();
    if constexpr (Prefetch) {
      if (const Event* ahead = q.peek(4)) __builtin_prefetch(&streams[ahead->target]);
    }
    auto& rng = streams[e.target];
    const auto to = static_cast<std::uint32_t>(rng.below(lps));
    const auto delay = 100'000'000 + static_cast<Time>(rng.exponential(1e9));
    q.push(Event{e.time + delay, seq++, 0, to, 0, 0});
    sum += e.target;
  }
  const double secs = cpu_seconds() - start;
  checksum = sum;
  return static_cast<double>(events) / secs;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace laguerre::sim;
  const std::uint64_t events = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 5'000'000;
  const int repeat = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  std::printf("%-10s %12s %12s %12s %12s %12s %12s   (M events per CPU second)\n", "LPs", "std::pq",
              "binary", "4-ary", "8-ary", "ladder", "ladder+pf");
  for (std::uint32_t lps : {10'000u, 100'000u, 1'000'000u}) {
    std::uint64_t c[6];
    double r[6] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < repeat; ++k) {
      r[0] = std::max(r[0], run_phold<StdQueue>(lps, events, c[0]));
      r[1] = std::max(r[1], run_phold<DaryEventHeap<2>>(lps, events, c[1]));
      r[2] = std::max(r[2], run_phold<DaryEventHeap<4>>(lps, events, c[2]));
      r[3] = std::max(r[3], run_phold<DaryEventHeap<8>>(lps, events, c[3]));
      r[4] = std::max(r[4], run_phold<LadderEventQueue>(lps, events, c[4]));
      r[5] = std::max(r[5], run_phold<LadderEventQueue, true>(lps, events, c[5]));
    }
    const bool same = c[0] == c[1] && c[1] == c[2] && c[2] == c[3] && c[3] == c[4] && c[4] == c[5];
    std::printf("%-10u", lps);
    for (double x : r) std::printf(" %10.2f M", x / 1e6);
    std::printf("%s\n", same ? "" : "   (ORDER MISMATCH)");
  }
  return 0;
}
