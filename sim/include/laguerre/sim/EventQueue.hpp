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
/// each candidate with 32-byte records, 5·10^6 events, best of 3 on the shared, busy 2-core machine;
/// rates include the two random draws per event):
///
///     pending events     std::priority_queue   binary heap   4-ary heap   8-ary heap   ladder (below)
///     10^4                    11.0 M/s           11.0 M/s      11.3 M/s     10.6 M/s      17.4 M/s
///     10^5                     6.2 M/s            5.7 M/s       6.0 M/s      5.5 M/s       7.8 M/s
///     10^6                     2.2 M/s            2.2 M/s       2.6 M/s      2.7 M/s       4.6 M/s
///
/// The kernel therefore uses `LadderEventQueue`, a one-rung ladder queue (after Tang, Goh & Thng,
/// ACM TOMACS 2005, simplified): expected O(1) per event on the smooth time distributions of network
/// simulations; when many events share one bucket (e.g. a synchronous round with constant latency)
/// its bottom tier becomes a binary heap, so it degrades to about a binary heap, never to a list.
/// `DaryEventHeap` stays as the reference implementation the tests compare it against.
///
#include <algorithm>
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
    std::size_t hole = heap_.size();
    heap_.push_back(event);
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / Arity;
      if (!fires_before(event, heap_[parent])) break;
      heap_[hole] = heap_[parent];
      hole = parent;
    }
    heap_[hole] = event;
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
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / Arity;
      if (!fires_before(last, heap_[parent])) break;
      heap_[hole] = heap_[parent];
      hole = parent;
    }
    heap_[hole] = last;
  }

private:
  std::vector<Event> heap_;
};

/// A one-rung ladder queue (lazy calendar queue) ordered by `fires_before`.
///
/// Three tiers, by time:
///  - `bottom_`: every pending event earlier than `bottom_end_`, either sorted latest-first (popped
///    from the back in O(1); the usual case, a bucket holds ~`events_per_bucket` events) or, once it
///    grows past `sorted_limit`, a binary heap (so no input makes insertion quadratic);
///  - `buckets_[i]`, i ≥ `next_bucket_`: unsorted events in [year_start_ + i·width_, … + width_);
///  - `overflow_`: unsorted events at or after `year_end_`.
/// Invariant: times in `bottom_` < bottom_end_ ≤ times in the live buckets < year_end_ ≤ times in
/// `overflow_`, and bucket i < bucket j holds earlier times; so the first event overall is the first
/// of `bottom_` whenever `bottom_` is non-empty. When `bottom_` drains, the next non-empty bucket is
/// heapified into it; when the buckets are exhausted, a new "year" is built from the overflow, with
/// about `events_per_bucket` events per bucket. Each event is moved O(1) times per year, so the
/// amortized cost per event is O(1) plus the bottom tier's cost: O(1) pops from a sorted bucket, or
/// O(log b) in heap mode for a bucket of b events. Ties (equal times) always end up in the same
/// bucket, where the bottom tier orders them by seq: the total order is exactly the one of
/// `DaryEventHeap`.
class LadderEventQueue {
public:
  /// Whether no event is pending.
  bool empty() const { return size_ == 0; }
  /// Number of pending events.
  std::size_t size() const { return size_; }
  /// Reserves room for `n` events in the overflow tier (where a new run's first events go).
  void reserve(std::size_t n) { overflow_.reserve(n); }
  /// Removes every event.
  void clear() { *this = LadderEventQueue(); }

  /// The first event in the total order; requires !empty(). (Not const: may rebuild tiers.)
  const Event& top() {
    if (bottom_.empty()) settle();
    return heap_mode_ ? bottom_.front() : bottom_.back();
  }

  /// Inserts `event`.
  void push(const Event& event) {
    ++size_;
    if (event.time < bottom_end_) {
      push_bottom(event);
    } else if (event.time < year_end_) {
      // year_start_ ≤ bottom_end_ ≤ time < year_end_, so the index lies in [next_bucket_, count).
      buckets_[bucket_of(event.time)].push_back(event);
    } else {
      overflow_.push_back(event);
      overflow_min_ = std::min(overflow_min_, event.time);
      overflow_max_ = std::max(overflow_max_, event.time);
    }
  }

  /// Removes the first event; requires !empty().
  void pop() {
    if (bottom_.empty()) settle();
    if (heap_mode_) std::pop_heap(bottom_.begin(), bottom_.end(), Later{});
    bottom_.pop_back();
    --size_;
  }

private:
  /// Target bucket occupancy when a year is built. Measured (phold_queues, k = 2 … 128): small
  /// buckets favour small queues (the bottom heap stays tiny), large ones favour huge queues (fewer
  /// bucket headers to miss in cache); 16 is within ~10% of the best at 10^4, 10^5 and 10^6 events.
  static constexpr std::size_t events_per_bucket = 16;
  /// Largest bottom tier kept as a sorted array (insertion costs up to this many moves).
  static constexpr std::size_t sorted_limit = 64;

  /// The heap order of `bottom_` (a function object, so that the heap code inlines it).
  struct Later {
    bool operator()(const Event& a, const Event& b) const { return fires_before(b, a); }
  };

  /// Makes `bottom_` non-empty (requires size_ > 0); the slow path of top() and pop().
  [[gnu::noinline]] void settle() {
    while (bottom_.empty()) {
      while (next_bucket_ < bucket_count_ && buckets_[next_bucket_].empty()) ++next_bucket_;
      if (next_bucket_ < bucket_count_) {
        bottom_.swap(buckets_[next_bucket_]);  // the bucket inherits bottom_'s empty capacity
        ++next_bucket_;
        bottom_end_ = boundary(next_bucket_);
        heap_mode_ = bottom_.size() > sorted_limit;
        if (heap_mode_) {
          std::make_heap(bottom_.begin(), bottom_.end(), Later{});
        } else {
          std::sort(bottom_.begin(), bottom_.end(), Later{});  // latest first: back() is next
        }
      } else {
        new_year();
      }
    }
  }

  /// Spreads the overflow over a new year of buckets [overflow_min_, overflow_max_] (requires the
  /// bottom and the buckets to be empty and the overflow not).
  void new_year() {
    std::size_t count = std::max<std::size_t>(1, overflow_.size() / events_per_bucket);
    // The span of the year, max − min, fits in 64 unsigned bits even for negative times.
    const auto span = static_cast<std::uint64_t>(overflow_max_) - static_cast<std::uint64_t>(overflow_min_);
    if (span / count == ~std::uint64_t{0}) count = 2;  // keeps span / count + 1 from wrapping to 0
    // width · count > span, so bucket_of(time) < count for every overflow event.
    width_ = span / count + 1;
    year_start_ = overflow_min_;
    year_end_ = boundary(count);  // saturated at time_max: it only routes later pushes
    if (buckets_.size() < count) buckets_.resize(count);
    bucket_count_ = count;
    for (const Event& e : overflow_) buckets_[bucket_of(e.time)].push_back(e);
    overflow_.clear();
    overflow_min_ = time_max;
    overflow_max_ = std::numeric_limits<Time>::min();
    next_bucket_ = 0;
    bottom_end_ = year_start_;
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

  /// The bucket of a time in [year_start_, year_end_) (unsigned arithmetic: no overflow).
  std::size_t bucket_of(Time t) const {
    return static_cast<std::size_t>(
        (static_cast<std::uint64_t>(t) - static_cast<std::uint64_t>(year_start_)) / width_);
  }

  /// year_start_ + k · width_, saturated at time_max.
  Time boundary(std::size_t k) const {
    __extension__ using I128 = __int128;
    const I128 b = static_cast<I128>(year_start_) + static_cast<I128>(width_) * static_cast<I128>(k);
    return b > static_cast<I128>(time_max) ? time_max : static_cast<Time>(b);
  }

  std::vector<Event> bottom_;
  std::vector<std::vector<Event>> buckets_;
  std::vector<Event> overflow_;
  std::size_t bucket_count_ = 0;
  std::size_t next_bucket_ = 0;
  std::size_t size_ = 0;
  bool heap_mode_ = false;  // bottom_ is a heap (front first) rather than sorted (back first)
  Time bottom_end_ = 0;
  Time year_start_ = 0;
  Time year_end_ = 0;
  std::uint64_t width_ = 1;
  Time overflow_min_ = time_max;
  Time overflow_max_ = std::numeric_limits<Time>::min();
};

/// The kernel's pending-event set (see the file comment for the measurement behind the choice).
using EventQueue = LadderEventQueue;

}  // namespace laguerre::sim
