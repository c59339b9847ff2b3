#pragma once
/// @file
/// The compact event record and the pending-event set of the kernel.
///
/// Total order: events fire by increasing `time`, and among equal times by increasing `seq`, the
/// insertion sequence number the kernel assigns at scheduling (unique, strictly increasing). Equal
/// timestamps are therefore FIFO, and because `seq` is unique the order is total: no two pending
/// events are ever "tied", so any correct priority queue pops the same sequence.
///
/// Queue choice, by measurement (tools/bench/phold_queues.cpp: the PHOLD hold model run directly on
/// each candidate with 32-byte records, 3·10^6 events, best of 3, events per CPU second on the
/// shared, busy 2-core machine; rates include the two random draws per event; "+pf" adds the
/// kernel's prefetch of the process state 4 events ahead, see Kernel::set_prefetch):
///
///     pending events   std::priority_queue  binary heap  4-ary heap  8-ary heap  ladder   ladder+pf
///     10^4                   10.7 M/s         10.7 M/s    11.0 M/s    10.2 M/s   24.1 M/s  24.3 M/s
///     10^5                    7.2 M/s          7.1 M/s     7.7 M/s     6.9 M/s   20.8 M/s  22.1 M/s
///     10^6                    3.0 M/s          2.9 M/s     3.3 M/s     3.2 M/s   10.5 M/s  12.7 M/s
///
/// (A one-rung ladder, ~16 events per bucket over the whole span of the pending times, measured
/// 11.7, 6.7 and 2.6 M/s in a run in which this ladder made about 23, 13 and 9 M/s: its front buckets
/// held over a hundred events at these sizes, and at 10^6 its ~60 000 bucket tails missed the caches
/// on every push.)
///
/// The kernel therefore uses `LadderEventQueue`, a two-rung ladder queue (after Tang, Goh & Thng,
/// ACM TOMACS 2005, simplified): expected O(1) per event on the smooth time distributions of network
/// simulations; when many events share one bucket (e.g. a synchronous round with constant latency)
/// that bucket is sorted (n log n, then O(1) pops and an exact prefetch), and pushes into a large
/// bottom tier turn it into a binary heap, so it degrades to about a binary heap, never to a list.
/// `DaryEventHeap` stays as the reference implementation the tests compare it against.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "laguerre/sim/Time.hpp"

namespace laguerre::sim {

/// Index of a handler in the kernel's table (see Kernel::add_handler).
using HandlerId = std::uint16_t;

/// One scheduled event: 32 bytes, no heap-allocated closure. What `target` and `payload` mean is up
/// to the handler (a node or process id; an index into a message pool, a timer id, a small value).
struct Event {
  Time time = 0;               ///< When the event fires, in simulated nanoseconds.
  std::uint64_t seq = 0;       ///< Insertion sequence number, the FIFO tie-break (assigned by the kernel).
  std::uint64_t payload = 0;   ///< Handler-defined data.
  std::uint32_t target = 0;    ///< Handler-defined target, usually a node or process index.
  HandlerId handler = 0;       ///< Which registered handler runs the event.
  std::uint16_t flags = 0;     ///< Kernel bookkeeping (cancellation); handlers should ignore it.
};
static_assert(sizeof(Event) == 32, "Event records must stay 32 bytes (two per cache line).");

/// Whether `a` fires strictly before `b` in the kernel's total order (time, then seq).
constexpr bool fires_before(const Event& a, const Event& b) {
  return a.time < b.time || (a.time == b.time && a.seq < b.seq);
}

/// An implicit d-ary min-heap of events under `fires_before`. `Arity` 2 is the textbook binary heap;
/// it is the reference the ladder queue is tested against. Not a general container: no iteration, no erase
/// (cancellation is lazy, in the kernel).
template <unsigned Arity>
class DaryEventHeap {
  static_assert(Arity >= 2, "A heap needs at least two children per node.");

public:
  /// Whether no event is pending.
  bool empty() const { return heap_.empty(); }
  /// Number of pending events.
  std::size_t size() const { return heap_.size(); }
  /// Reserves room for `n` events.
  void reserve(std::size_t n) { heap_.reserve(n); }
  /// Removes every event.
  void clear() { heap_.clear(); }
  /// The first event in the total order; requires !empty().
  const Event& top() const { return heap_.front(); }

  /// Inserts `event` (sift-up with a hole: one move per level instead of a swap).
  void push(const Event& event) {
    heap_.push_back(event);
    sift_up(heap_.size() - 1, event);
  }

  /// Removes the first event; requires !empty().
  ///
  /// Bottom-up deletion (Floyd; Wegener): the root hole first walks down to a leaf along the smallest
  /// children without comparing against the displaced last record, which then sifts up from there.
  /// The last record is usually late (it was a leaf), so the upward walk is short, and each level
  /// costs Arity − 1 comparisons instead of Arity.
  void pop() {
    const Event last = heap_.back();
    heap_.pop_back();
    const std::size_t n = heap_.size();
    if (n == 0) return;
    std::size_t hole = 0;
    for (;;) {
      const std::size_t first = hole * Arity + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + Arity < n ? first + Arity : n;
      for (std::size_t c = first + 1; c < end; ++c) {
        if (fires_before(heap_[c], heap_[best])) best = c;
      }
      heap_[hole] = heap_[best];
      hole = best;
    }
    sift_up(hole, last);
  }

private:
  /// Moves the hole at `hole` up past the parents `event` fires before, then stores `event` there.
  void sift_up(std::size_t hole, const Event& event) {
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / Arity;
      if (!fires_before(event, heap_[parent])) break;
      heap_[hole] = heap_[parent];
      hole = parent;
    }
    heap_[hole] = event;
  }

  std::vector<Event> heap_;
};

/// A two-rung ladder queue (after Tang, Goh & Thng, ACM TOMACS 2005, simplified) ordered by
/// `fires_before`, with power-of-two bucket widths sized from a sample of the pending times.
///
/// Four tiers, by the offset of an event's time from `year_start_`:
///  - `bottom_`: every pending event before the first live fine bucket (including any before
///    `year_start_`), sorted latest-first (popped from the back in O(1); every bucket taken
///    from a rung is sorted, whatever its size: usually a few dozen events, but a synchronous round
///    at one time puts all of its messages in one bucket) or, once pushes into a sorted bottom make
///    it grow past `sorted_limit`, a binary heap (so no input makes insertion quadratic);
///  - the fine rung `fine_[f]`, next_fine_ ≤ f < 2^rung_bits_: the sub-buckets of width 2^shift_
///    of the coarse bucket being consumed (number next_coarse_ − 1), unsorted;
///  - the coarse rung `coarse_[c]`, next_coarse_ ≤ c < coarse_count_: unsorted events whose offset
///    lies in [c·2^coarse_shift_, (c+1)·2^coarse_shift_), coarse_shift_ = shift_ + rung_bits_;
///  - `overflow_`: unsorted events past the last coarse bucket (the end of the "year").
/// Invariant: bottom < live fine buckets < live coarse buckets < overflow, each rung in index
/// order, for every pair of events; so the first event overall is the first of `bottom_` whenever
/// `bottom_` is non-empty. When `bottom_` drains, the next non-empty fine bucket is sorted into it;
/// when the fine rung is exhausted, the next non-empty coarse bucket is split into the fine rung (or,
/// if small, sorted straight into the bottom); when the coarse rung is exhausted, a new year is built
/// from the overflow. Why two rungs: a push lands in a random bucket, and with a single rung of
/// small buckets those writes miss the caches once n reaches 10^5–10^6; the coarse rung has at most
/// MaxCoarse buckets, whose tails stay cached, and the split costs one sequential pass per event.
///
/// Routing is by exact integer bucket index (no division: widths are powers of two), so no boundary
/// is rounded or saturated. Ties (equal times) always share a bucket, where the bottom tier orders
/// them by seq: the total order is exactly the one of `DaryEventHeap`, and the widths a year picks
/// never change it (only the speed).
///
/// Width choice (new_year), from an evenly strided sample of at most 256 overflow times:
///  - coarse rung: about n / CoarseEvents buckets (1 … MaxCoarse), the width the smallest power of
///    two with which they reach the sample's median. Each year thus takes at least about half of the
///    overflow, so on a stationary distribution an event is moved O(1) times in expectation; later
///    events wait in the overflow for the next year.
///  - fine rung: the span covered by the earliest eighth of the sample estimates the density ρ at
///    the front of the queue (events per ns), which is what matters: a calendar queue is fast when
///    the buckets about to be consumed hold a few events each, whatever the tail does. The fine
///    width is the largest power of two ≤ EventsPerBucket / ρ (at most the coarse width, at least
///    2^-10 of it).
/// Defaults, by measurement (phold_queues with the prefetch hint): fine buckets of 16 events beat 32
/// by ~10% at 10^4 pending events and lose ~14% at 10^6 (where sorting matters less than bucket
/// count); 8 loses at every size. 1024 events per coarse bucket and at most 4096 of them keep the
/// coarse tails (4096 × 64 bytes) in the L2 cache; 512 or 2048 are within noise.
template <unsigned EventsPerBucket = 16, unsigned CoarseEvents = 1024, unsigned MaxCoarse = 4096>
class BasicLadderEventQueue {
  static_assert(EventsPerBucket >= 1, "Buckets must target at least one event.");
  static_assert(CoarseEvents >= 1 && MaxCoarse >= 1, "The coarse rung needs at least one bucket.");

public:
  /// Whether no event is pending.
  bool empty() const { return size_ == 0; }
  /// Number of pending events.
  std::size_t size() const { return size_; }
  /// Reserves room for `n` events in the overflow tier (where a new run's first events go).
  void reserve(std::size_t n) { overflow_.reserve(n); }
  /// Removes every event.
  void clear() { *this = BasicLadderEventQueue(); }

  /// The first event in the total order; requires !empty(). (Not const: may rebuild tiers.)
  const Event& top() {
    if (bottom_.empty()) settle();
    return heap_mode_ ? bottom_.front() : bottom_.back();
  }

  /// The event `ahead` places after top() if the queue can tell cheaply (it lies in the sorted
  /// bottom tier), else nullptr. Valid until the next push or pop; for prefetching only.
  const Event* peek(std::size_t ahead) const {
    return !heap_mode_ && ahead < bottom_.size() ? &bottom_[bottom_.size() - 1 - ahead] : nullptr;
  }
  /// peek(ahead), or, when the bottom tier is a heap (e.g. a synchronous round: many events at one
  /// time, keyed out of insertion order), entry `ahead` of the heap: near its top, so likely one of
  /// the next few events, not necessarily the `ahead`-th. For prefetching only (what the kernel uses).
  const Event* peek_near(std::size_t ahead) const {
    if (!heap_mode_) return peek(ahead);
    return ahead < bottom_.size() ? &bottom_[ahead] : nullptr;
  }

  /// Inserts `event`.
  void push(const Event& event) {
    ++size_;
    if (event.time >= year_start_) {
      const std::uint64_t off = offset(event.time);
      const std::uint64_t c = off >> coarse_shift_;
      if (c >= next_coarse_) {
        if (c < coarse_count_) {
          coarse_[c].push_back(event);
        } else {
          overflow_.push_back(event);
          overflow_min_ = std::min(overflow_min_, event.time);
          overflow_max_ = std::max(overflow_max_, event.time);
        }
        return;
      }
      if (c + 1 == next_coarse_) {
        const std::uint64_t f = (off >> shift_) & (fine_count_ - 1);
        if (f >= next_fine_) {
          fine_[f].push_back(event);
          return;
        }
      }
    }
    push_bottom(event);
  }

  /// Removes the first event; requires !empty().
  void pop() {
    if (bottom_.empty()) settle();
    if (heap_mode_) std::pop_heap(bottom_.begin(), bottom_.end(), Later{});
    bottom_.pop_back();
    --size_;
  }

private:
  /// Most fine buckets per coarse bucket (log2).
  static constexpr unsigned max_rung_bits = 10;
  /// Most coarse buckets in a year.
  static constexpr std::uint64_t max_coarse = MaxCoarse;
  /// Largest bottom tier kept as a sorted array (insertion costs up to this many moves).
  static constexpr std::size_t sorted_limit = 64;
  /// A coarse bucket this small goes straight to the bottom instead of being split.
  static constexpr std::size_t split_threshold = 2 * EventsPerBucket;
  /// Most overflow times sampled to choose a year's width.
  static constexpr std::size_t sample_limit = 256;

  /// The heap order of `bottom_` (a function object, so that the heap code inlines it).
  struct Later {
    bool operator()(const Event& a, const Event& b) const { return fires_before(b, a); }
  };

  /// time − year_start_ as an unsigned offset (requires time ≥ year_start_; never overflows).
  std::uint64_t offset(Time time) const {
    return static_cast<std::uint64_t>(time) - static_cast<std::uint64_t>(year_start_);
  }

  /// Moves a bucket's events into the (empty) bottom tier and orders them.
  void take(std::vector<Event>& bucket) {
    bottom_.swap(bucket);  // the bucket inherits bottom_'s empty capacity
    // A bucket filled in firing order (e.g. a synchronous round: one time, increasing seq) stays a
    // sorted array whatever its size: reversed in O(n), then popped and peeked from the back.
    if (std::is_sorted(bottom_.begin(), bottom_.end(), fires_before)) {
      std::reverse(bottom_.begin(), bottom_.end());
      heap_mode_ = false;
      return;
    }
    // Any other bucket is sorted too, whatever its size (latest first: back() is next): a sort
    // costs about what the pops of a heap would, but pops are then O(1) and peek(ahead) names the
    // exact event `ahead` places on, so the kernel's prefetch hits (a synchronous round of a 10^4-node
    // protocol run: ~6·10^4 events at one time, keyed out of insertion order). Pushes into a large
    // sorted bottom still turn it into a heap (push_bottom).
    heap_mode_ = false;
    std::sort(bottom_.begin(), bottom_.end(), Later{});
  }

  /// Makes `bottom_` non-empty (requires size_ > 0); the slow path of top() and pop().
  [[gnu::noinline]] void settle() {
    while (bottom_.empty()) {
      while (next_fine_ < fine_count_ && fine_[next_fine_].empty()) ++next_fine_;
      if (next_fine_ < fine_count_) {
        take(fine_[next_fine_++]);
        continue;
      }
      while (next_coarse_ < coarse_count_ && coarse_[next_coarse_].empty()) ++next_coarse_;
      if (next_coarse_ < coarse_count_) {
        std::vector<Event>& bucket = coarse_[next_coarse_++];
        if (bucket.size() <= split_threshold) {
          take(bucket);  // the fine rung stays exhausted: this coarse bucket's range is the bottom's
        } else {
          for (const Event& e : bucket) fine_[(offset(e.time) >> shift_) & (fine_count_ - 1)].push_back(e);
          bucket.clear();
          next_fine_ = 0;
        }
        continue;
      }
      new_year();
    }
  }

  /// Builds a new year from the overflow (requires every other tier to be empty and the overflow
  /// not); see the class comment for the choice of widths and length.
  void new_year() {
    const std::size_t n = overflow_.size();
    const auto span = static_cast<std::uint64_t>(overflow_max_) - static_cast<std::uint64_t>(overflow_min_);
    year_start_ = overflow_min_;
    // Offsets of an evenly strided sample, sorted.
    std::uint64_t sample[sample_limit];
    const std::size_t stride = n > sample_limit ? n / sample_limit : 1;
    std::size_t s = 0;
    for (std::size_t i = 0; i < n && s < sample_limit; i += stride) sample[s++] = offset(overflow_[i].time);
    std::sort(sample, sample + s);
    // Coarse rung: at most `count` buckets reaching past the sample's median.
    const std::uint64_t count_target = std::clamp<std::uint64_t>(n / CoarseEvents, 1, max_coarse);
    const std::uint64_t reach = sample[s / 2];
    unsigned coarse_shift = 0;
    while (coarse_shift < 63 && (reach >> coarse_shift) >= count_target) ++coarse_shift;
    const std::uint64_t count = std::min<std::uint64_t>(count_target, (span >> coarse_shift) + 1);
    // Fine rung: width ≈ EventsPerBucket / ρ, ρ the front density (sample[q] is preceded by about
    // (q + 1) / s of the events), as a power of two at most the coarse width.
    const std::size_t q = s / 8;
    const double width = static_cast<double>(EventsPerBucket) * static_cast<double>(sample[q]) *
                         static_cast<double>(s) / (static_cast<double>(q + 1) * static_cast<double>(n));
    unsigned fine_shift = 0;
    while (fine_shift < coarse_shift && std::ldexp(1.0, static_cast<int>(fine_shift) + 1) <= width) ++fine_shift;
    rung_bits_ = std::min(coarse_shift - fine_shift, max_rung_bits);
    shift_ = coarse_shift - rung_bits_;
    coarse_shift_ = coarse_shift;
    fine_count_ = std::uint64_t{1} << rung_bits_;
    if (fine_.size() < fine_count_) fine_.resize(fine_count_);
    if (coarse_.size() < count) coarse_.resize(count);
    coarse_count_ = count;
    next_coarse_ = 0;
    next_fine_ = fine_count_;
    // Distribute; events past the year stay in the overflow (compacted in place).
    Time kept_min = time_max;
    Time kept_max = std::numeric_limits<Time>::min();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Event& e = overflow_[i];
      const std::uint64_t c = offset(e.time) >> coarse_shift;
      if (c < count) {
        coarse_[c].push_back(e);
      } else {
        kept_min = std::min(kept_min, e.time);
        kept_max = std::max(kept_max, e.time);
        overflow_[kept++] = e;
      }
    }
    overflow_.resize(kept);
    overflow_min_ = kept_min;
    overflow_max_ = kept_max;
  }

  /// Inserts into the bottom tier, keeping its order (sorted or heap; see the class comment).
  void push_bottom(const Event& event) {
    if (heap_mode_) {
      bottom_.push_back(event);
      std::push_heap(bottom_.begin(), bottom_.end(), Later{});
    } else if (bottom_.size() < sorted_limit) {
      // Everything before the insertion point fires after `event` (seq makes the order strict).
      bottom_.insert(std::upper_bound(bottom_.begin(), bottom_.end(), event, Later{}), event);
    } else {
      bottom_.push_back(event);
      std::make_heap(bottom_.begin(), bottom_.end(), Later{});
      heap_mode_ = true;
    }
  }

  std::vector<Event> bottom_;
  std::vector<std::vector<Event>> fine_;
  std::vector<std::vector<Event>> coarse_;
  std::vector<Event> overflow_;
  std::uint64_t fine_count_ = 0;
  std::uint64_t next_fine_ = 0;
  std::uint64_t coarse_count_ = 0;
  std::uint64_t next_coarse_ = 0;
  std::size_t size_ = 0;
  unsigned shift_ = 0;         // fine buckets have width 2^shift_
  unsigned coarse_shift_ = 63; // coarse buckets have width 2^coarse_shift_
  unsigned rung_bits_ = 0;     // coarse_shift_ − shift_
  bool heap_mode_ = false;  // bottom_ is a heap (front first) rather than sorted (back first)
  Time year_start_ = std::numeric_limits<Time>::min();
  Time overflow_min_ = time_max;
  Time overflow_max_ = std::numeric_limits<Time>::min();
};

/// The kernel's ladder queue, with the bucket sizes chosen by measurement (see the file comment).
using LadderEventQueue = BasicLadderEventQueue<>;

/// The kernel's pending-event set (see the file comment for the measurement behind the choice).
using EventQueue = LadderEventQueue;

}  // namespace laguerre::sim
