#pragma once
/// @file
/// Internal to core/src/power: a small inline buffer, the symbolically perturbed power predicates and
/// the lower-hull apex search shared by the φ-triangulation and GLPD.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::core::detail {

/// A push-back-only buffer holding up to N elements inline; beyond N it moves to the heap. Keeps the
/// per-vertex checks allocation-free for typical degrees and face sizes.
template <class T, std::size_t N = 32>
class SmallBuffer {
public:
  /// Appends x.
  void push_back(const T& x) {
    if (size_ < N) {
      local_[size_] = x;
    } else {
      if (size_ == N) heap_.assign(local_.begin(), local_.end());
      heap_.push_back(x);
    }
    ++size_;
  }
  /// Removes every element (keeps heap capacity).
  void clear() {
    size_ = 0;
    heap_.clear();
  }
  /// Number of elements.
  std::size_t size() const { return size_; }
  /// Element i.
  const T& operator[](std::size_t i) const { return size_ <= N ? local_[i] : heap_[i]; }
  /// The elements as a span.
  std::span<const T> span() const {
    return size_ <= N ? std::span<const T>(local_.data(), size_) : std::span<const T>(heap_.data(), size_);
  }

private:
  std::array<T, N> local_{};
  std::vector<T> heap_;
  std::size_t size_ = 0;
};

/// Negation of a Sign.
inline Sign negate(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }
/// Product of two Signs.
inline Sign times(Sign a, Sign b) { return static_cast<Sign>(static_cast<int>(a) * static_cast<int>(b)); }

/// compare_power(p(a), a, b) on the perturbed embedding: sign of pow(p(a), a) − pow(p(a), b).
///
/// Perturbation (see LocalPowerDiagram.hpp): z(u) ← z(u) + ε^(k(u)), k increasing with the id, so
/// the smaller id dominates. With pow(q, u) = |q|² − 2 q·p(u) + z(u) the expression gains
/// ε_a − ε_b, whose sign is that of the dominant term: positive iff id(a) < id(b). `pa`/`pb` are the
/// ids; with `perturbed` false this is the exact predicate. Never zero when perturbed and pa ≠ pb.
/// C is Circle or Circle128 (the same predicates on binary128 coordinates).
template <class C>
Sign compare_power_sos(const C& a, const C& b, bool perturbed, std::uint64_t pa, std::uint64_t pb) {
  const Sign s = compare_power(centre(a), a, b);
  if (s != Sign::zero || !perturbed || pa == pb) return s;
  return pa < pb ? Sign::positive : Sign::negative;
}

/// radical_centre_power_side(u, a, b, t) on the perturbed embedding, ids `pr` = {u, a, b, t}
/// (nullptr: exact predicate).
///
/// Meaning: the sign of the height of the lifted point t̂ = (p(t), z(t)) above the plane through û, â,
/// b̂ (this plane is z = 2 c·x − k with c the radical centre, hence pow(c, t) − pow(c, u) = height);
/// positive iff c lies strictly inside H_t. The height is affine in each z: ∂/∂z(t) = 1 and
/// ∂/∂z(s) = −λ_s(p(t)) for s ∈ {u, a, b}, λ the barycentric coordinates in triangle (u, a, b),
/// λ_u = orient(t, a, b)/orient(u, a, b) and so on. When the exact height is zero the sign is that of
/// the first non-zero coefficient in increasing-id order; t's coefficient is 1, so the result is never
/// zero for distinct ids.
/// Precondition: centres of u, a, b not collinear (returns Sign::zero otherwise, as the exact one).
/// Cost: one degree-4 predicate; in the degenerate case up to four orientations.
template <class C>
Sign power_side_sos(const C& u, const C& a, const C& b, const C& t, const std::uint64_t* pr) {
  const Sign exact = radical_centre_power_side(u, a, b, t);
  if (exact != Sign::zero || pr == nullptr) return exact;
  const Sign o = orientation(centre(u), centre(a), centre(b));
  if (o == Sign::zero) return Sign::zero;
  std::array<int, 4> order{0, 1, 2, 3};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return pr[i] < pr[j]; });
  for (int k : order) {
    Sign bary = Sign::zero;  // sign of orient(…) with t in place of site k
    switch (k) {
      case 0: bary = orientation(centre(t), centre(a), centre(b)); break;
      case 1: bary = orientation(centre(u), centre(t), centre(b)); break;
      case 2: bary = orientation(centre(u), centre(a), centre(t)); break;
      default: return Sign::positive;
    }
    if (bary != Sign::zero) return negate(times(bary, o));
  }
  return Sign::positive;  // unreachable: t is in the order
}

/// Apex of the lower-hull triangle of the perturbed lifted circles on base edge (a, b): among the
/// candidates lo … hi (indices into `poly`, all strictly on one side of line ab), the first point
/// hit by a plane rotating upwards about the lifted line âb̂, i.e. the c such that no candidate lies
/// below the plane through â, b̂, ĉ. "t below plane(a, b, c)" is a strict total order on the
/// candidates (the angle at which the rotating plane meets them), and never a tie after the
/// perturbation, so one linear scan finds it. Cost: hi − lo power tests.
template <class C>
std::uint32_t lower_hull_apex(std::span<const C> poly, std::span<const std::uint64_t> pr, std::uint32_t a,
                              std::uint32_t b, std::uint32_t lo, std::uint32_t hi) {
  std::uint32_t c = lo;
  for (std::uint32_t t = lo + 1; t <= hi; ++t) {
    const std::uint64_t ids[4] = {pr[a], pr[b], pr[c], pr[t]};
    if (power_side_sos(poly[a], poly[b], poly[c], poly[t], ids) == Sign::negative) c = t;
  }
  return c;
}

}  // namespace laguerre::core::detail
