// Seeded random properties of the kernel's event loop (label: property): the kernel, with its ladder
// queue, lazy cancellation and prefetch hint, dispatches exactly what a naive reference kernel built
// on the binary heap dispatches, on random interleavings of schedule, cancel and run. The number of
// cases scales with LAGUERRE_PROPERTY_CASES (default 20).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <vector>

#include "laguerre/sim/EventQueue.hpp"
#include "laguerre/sim/Kernel.hpp"
#include "laguerre/sim/Random.hpp"

namespace laguerre::sim {
namespace {

int cases() {
  const char* env = std::getenv("LAGUERRE_PROPERTY_CASES");
  return env != nullptr ? std::max(1, std::atoi(env)) : 20;
}

/// One dispatched event as both kernels report it.
struct Fired {
  Time time;
  std::uint64_t id;  // unique per scheduling, assigned by the workload
  bool operator==(const Fired&) const = default;
};

/// The obviously correct reference: every scheduling pushes (time, seq) into the reference binary
/// heap; cancellation marks the seq; the loop pops in (time, seq) order and skips marked records.
class ReferenceKernel {
public:
  Time now() const { return now_; }
  std::uint64_t schedule(Time at, std::uint64_t id) {
    heap_.push(Event{at, seq_, id, 0, 0, 0});
    return seq_++;
  }
  /// Cancels the scheduling `seq` unless it already fired (or was already cancelled).
  void cancel(std::uint64_t seq) {
    if (fired_.count(seq) == 0) cancelled_.insert(seq);
  }
  template <class OnEvent>
  void run(std::uint64_t max_events, OnEvent&& on_event) {
    while (max_events > 0 && !heap_.empty()) {
      const Event e = heap_.top();
      heap_.pop();
      now_ = e.time;
      if (cancelled_.count(e.seq) != 0) continue;
      fired_.insert(e.seq);
      --max_events;
      on_event(e.payload);
    }
  }

private:
  DaryEventHeap<2> heap_;
  std::set<std::uint64_t> cancelled_, fired_;
  std::uint64_t seq_ = 0;
  Time now_ = 0;
};

/// The workload, identical for both kernels: each event draws from a stream keyed by its id how many
/// events to schedule (0–2, with ties, zero delays, near and far delays) and whether to cancel one
/// of the cancellable events scheduled earlier. Decisions depend only on the event being processed,
/// so the two logs agree if and only if the two kernels dispatch the same events in the same order.
struct Workload {
  std::uint64_t seed = 0;
  Time spread = 1;
  std::uint64_t next_id = 0;
  std::vector<Fired> log;

  struct Plan {
    struct Item {
      Duration delay;
      bool cancellable;
    };
    std::vector<Item> schedule;
    int cancel_pick = -1;  // index into the caller's list of cancellable handles, or -1
  };

  Plan plan(std::uint64_t id, std::size_t handles) const {
    RandomStream rng = RandomStream::of(seed, StreamKind::user, id);
    Plan p;
    const auto count = rng.below(4) == 0 ? 2 : rng.below(2) + (rng.below(8) == 0 ? 0 : 1);
    for (std::uint64_t k = 0; k < count; ++k) {
      Duration d = 0;
      switch (rng.below(5)) {
        case 0: d = 0; break;                                   // same instant (FIFO tie)
        case 1: d = rng.uniform_int(0, 3); break;               // near-ties
        case 2: d = rng.uniform_int(0, spread); break;          // the bulk
        case 3: d = static_cast<Duration>(rng.exponential(static_cast<double>(spread))); break;
        default: d = rng.uniform_int(0, 1000 * spread); break;  // far outliers (ladder overflow)
      }
      p.schedule.push_back({d, rng.bernoulli(0.4)});
    }
    if (handles > 0 && rng.bernoulli(0.3)) p.cancel_pick = static_cast<int>(rng.below(handles));
    return p;
  }
};

/// Runs the workload on the real kernel (optionally with the prefetch hint), in chunks of `chunk`
/// events, and returns the log.
std::vector<Fired> run_kernel(Workload w, std::size_t initial, std::uint64_t total, std::uint64_t chunk, bool hint) {
  struct Model {
    Workload* w;
    HandlerId self = 0;
    std::vector<EventHandle> handles;
    std::vector<std::uint64_t> state;  // touched per target, prefetched by the hint
    void on_event(Kernel& k, const Event& e) {
      w->log.push_back({k.now(), e.payload});
      ++state[e.target % state.size()];
      const Workload::Plan p = w->plan(e.payload, handles.size());
      for (const auto& item : p.schedule) {
        const std::uint64_t id = w->next_id++;
        const auto target = static_cast<std::uint32_t>(id % state.size());
        if (item.cancellable) {
          handles.push_back(k.schedule_cancellable_after(item.delay, self, target, id));
        } else {
          k.schedule_after(item.delay, self, target, id);
        }
      }
      if (p.cancel_pick >= 0) k.cancel(handles[static_cast<std::size_t>(p.cancel_pick)]);
    }
  };
  Kernel k;
  Model m{&w, 0, {}, std::vector<std::uint64_t>(64, 0)};
  m.self = k.add_handler<&Model::on_event>("model", m);
  if (hint) k.set_prefetch(m.self, m.state.data(), sizeof(std::uint64_t));
  for (std::size_t i = 0; i < initial; ++i) {
    const std::uint64_t id = w.next_id++;
    k.schedule_at(static_cast<Time>(RandomStream::of(w.seed, StreamKind::user, ~id).below(static_cast<std::uint64_t>(w.spread) + 1)),
                  m.self, static_cast<std::uint32_t>(id % 64), id);
  }
  while (k.events_processed() < total && k.queue_size() > 0) {
    k.run({.max_events = std::min(chunk, total - k.events_processed())});
  }
  return w.log;
}

/// The same workload on the reference kernel.
std::vector<Fired> run_reference(Workload w, std::size_t initial, std::uint64_t total) {
  ReferenceKernel r;
  std::vector<std::uint64_t> handles;  // seqs of cancellable schedulings
  for (std::size_t i = 0; i < initial; ++i) {
    const std::uint64_t id = w.next_id++;
    r.schedule(static_cast<Time>(RandomStream::of(w.seed, StreamKind::user, ~id).below(static_cast<std::uint64_t>(w.spread) + 1)), id);
  }
  r.run(total, [&](std::uint64_t event_id) {
    w.log.push_back({r.now(), event_id});
    const Workload::Plan p = w.plan(event_id, handles.size());
    for (const auto& item : p.schedule) {
      const std::uint64_t seq = r.schedule(r.now() + item.delay, w.next_id++);
      if (item.cancellable) handles.push_back(seq);
    }
    if (p.cancel_pick >= 0) r.cancel(handles[static_cast<std::size_t>(p.cancel_pick)]);
  });
  return w.log;
}

// Random interleavings of schedule (plain and cancellable), cancel (of pending, fired and already
// cancelled events) and run (in chunks of random length): the kernel's dispatch sequence equals the
// reference's, with and without the prefetch hint.
TEST(KernelProperty, KernelEqualsReferenceOnRandomScheduleCancelRun) {
  for (int c = 0; c < cases(); ++c) {
    RandomStream rng = RandomStream::of(static_cast<std::uint64_t>(c), StreamKind::user, 79);
    Workload w;
    w.seed = static_cast<std::uint64_t>(c);
    w.spread = rng.below(3) == 0 ? 2 : static_cast<Time>(1 + rng.below(1'000'000'000));
    const std::size_t initial = 1 + rng.below(rng.bernoulli(0.5) ? 50 : 5000);
    const std::uint64_t total = 20'000;
    const std::uint64_t chunk = 1 + rng.below(rng.bernoulli(0.5) ? 10 : 100'000);
    const auto reference = run_reference(w, initial, total);
    ASSERT_GT(reference.size(), 100u) << "case " << c;
    EXPECT_EQ(run_kernel(w, initial, total, chunk, false), reference) << "case " << c;
    EXPECT_EQ(run_kernel(w, initial, total, chunk, true), reference) << "case " << c;
  }
}

}  // namespace
}  // namespace laguerre::sim
