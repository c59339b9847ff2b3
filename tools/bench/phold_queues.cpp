// Chooses the kernel's pending-event structure by measurement: the PHOLD hold model (pop the first
// event, push one at now + 100 ms + Exp(1 s) for a uniform random process) run directly on candidate
// queues of the kernel's 32-byte Event records, without handler dispatch.
//   phold_queues [EVENTS]        (default 5·10^6 events per cell, sizes 10^4, 10^5, 10^6)
#include <algorithm>
#include <chrono>
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

template <class Queue>
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
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t sum = 0;
  for (std::uint64_t k = 0; k < events; ++k) {
    const Event e = q.top();
    q.pop();
    auto& rng = streams[e.target];
    const auto to = static_cast<std::uint32_t>(rng.below(lps));
    const auto delay = 100'000'000 + static_cast<Time>(rng.exponential(1e9));
    q.push(Event{e.time + delay, seq++, 0, to, 0, 0});
    sum += e.target;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  checksum = sum;
  return static_cast<double>(events) / secs;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t events = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 5'000'000;
  std::printf("%-10s %14s %14s %14s %14s %14s\n", "LPs", "std::pq", "binary", "4-ary", "8-ary",
              "ladder");
  for (std::uint32_t lps : {10'000u, 100'000u, 1'000'000u}) {
    std::uint64_t c[5];
    const double a = run_phold<StdQueue>(lps, events, c[0]);
    const double b = run_phold<laguerre::sim::DaryEventHeap<2>>(lps, events, c[1]);
    const double d = run_phold<laguerre::sim::DaryEventHeap<4>>(lps, events, c[2]);
    const double e = run_phold<laguerre::sim::DaryEventHeap<8>>(lps, events, c[3]);
    const double f = run_phold<laguerre::sim::LadderEventQueue>(lps, events, c[4]);
    const bool same = c[0] == c[1] && c[1] == c[2] && c[2] == c[3] && c[3] == c[4];
    std::printf("%-10u %12.2f M %12.2f M %12.2f M %12.2f M %12.2f M %s\n", lps, a / 1e6, b / 1e6,
                d / 1e6, e / 1e6, f / 1e6, same ? "" : "(ORDER MISMATCH)");
  }
  return 0;
}
