#pragma once
/// @file
/// Internal: the definitions of the next-hop rules of NextHop.hpp. NextHop.cpp instantiates them for
/// both views; Routing.cpp includes them too so that the router's hot loop can inline them.

#include <utility>

#include "../detail/FastFilter.hpp"
#include "../detail/FastFilter128.hpp"
#include "../detail/Filtered.hpp"
#include "laguerre/core/routing/NextHop.hpp"

namespace laguerre::core {

namespace next_hop_detail {

// ---------------------------------------------------------------------------------------------------
// Fast exact decisions: the double filters of detail/FastFilter.hpp, then the exact predicates.
// ---------------------------------------------------------------------------------------------------

using detail::Approx;
using detail::approx_alignment;
using detail::approx_distance;
using detail::approx_power;
using detail::certified_sign;
using detail::in_range;

/// Sign of (a − p)·(b − p). Exact, filtered like orientation().
inline Sign dot_sign(Point2 p, Point2 a, Point2 b) {
  const double ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y;
  if (in_range(ax) && in_range(ay) && in_range(bx) && in_range(by)) {
    if (const auto s = detail::certified_difference(ax * bx, -(ay * by))) return *s;
  }
  detail::require_finite("dot_sign", {p.x, p.y, a.x, a.y, b.x, b.y});
  return detail::filtered([&]<class NT>() {
    const NT ex = (NT(a.x) - NT(p.x)) * (NT(b.x) - NT(p.x)) + (NT(a.y) - NT(p.y)) * (NT(b.y) - NT(p.y));
    return detail::sign_of<NT>(ex);
  });
}

// ---------------------------------------------------------------------------------------------------
// Positions along the perimeter segment.
//
// In perimeter mode the packet remembers the segment [P, T] from the entry node to the target and the
// position λ ∈ [0, 1] (P + λ(T − P)) of the last face change. Crossing positions are kept *symbolically*
// (which edge made them) and compared exactly, never rounded: two crossings a few ulps apart, or a
// crossing exactly at the entry, are ordered correctly.
// ---------------------------------------------------------------------------------------------------

/// A position on the line PT: the entry (λ = 0), the target (λ = 1), or the crossing of the line with
/// the line of the edge [a, b], which must not be parallel to PT.
struct Along {
  enum class Kind { entry, target, edge };
  Kind kind = Kind::entry;
  Point2 a{}, b{};
};

/// λ of a position as an exact fraction num / den (den ≠ 0, any sign). For an edge, orient(a, b, ·) is
/// affine along the line, o(λ) = o_P + λ(o_T − o_P), and vanishes at λ = o_P / (o_P − o_T).
template <class NT>
std::pair<NT, NT> along_fraction(Point2 p, Point2 t, const Along& x) {
  switch (x.kind) {
    case Along::Kind::entry:
      return {NT(0), NT(1)};
    case Along::Kind::target:
      return {NT(1), NT(1)};
    case Along::Kind::edge:
      break;
  }
  auto orient = [](Point2 a, Point2 b, Point2 c) -> NT {
    return (NT(b.x) - NT(a.x)) * (NT(c.y) - NT(a.y)) - (NT(b.y) - NT(a.y)) * (NT(c.x) - NT(a.x));
  };
  const NT op = orient(x.a, x.b, p), ot = orient(x.a, x.b, t);
  return {op, op - ot};
}

/// Sign of λ(x) − λ(y). Exact (interval filter, then rationals).
inline Sign compare_along(Point2 p, Point2 t, const Along& x, const Along& y) {
  return detail::filtered([&]<class NT>() {
    const auto [nx, dx] = along_fraction<NT>(p, t, x);
    const auto [ny, dy] = along_fraction<NT>(p, t, y);
    const int s = static_cast<int>(detail::sign_of<NT>(nx * dy - ny * dx)) *
                  static_cast<int>(detail::sign_of<NT>(dx)) * static_cast<int>(detail::sign_of<NT>(dy));
    return static_cast<Sign>(s);
  });
}

/// Whether the direction T − P lies strictly inside the counter-clockwise angular sector at P from
/// the ray P→A to the ray P→B (A, B the heads of two darts consecutive counter-clockwise around the
/// vertex at P). With `same_ray` (a vertex of degree one: A and B are the same neighbour) the sector is
/// the full turn minus the ray P→A.
inline bool in_open_sector(Point2 p, Point2 a, Point2 b, Point2 t, bool same_ray) {
  const Sign a_t = orientation(p, a, t);  // positive: t strictly left of P→A
  if (same_ray) return a_t != Sign::zero || dot_sign(p, a, t) == Sign::negative;
  const Sign t_b = orientation(p, t, b);
  switch (orientation(p, a, b)) {
    case Sign::positive:  // convex sector (< π): strictly left of P→A and strictly right of P→B
      return a_t == Sign::positive && t_b == Sign::positive;
    case Sign::negative:  // reflex sector (> π): the complement of the closed convex sector B→A
      return a_t == Sign::positive || t_b == Sign::positive;
    case Sign::zero:
      break;
  }
  // P→A and P→B collinear: a straight angle if they point opposite ways (the open half-plane left of
  // P→A); pointing the same way (overlapping edges) or a zero-length edge has no sector in a plane
  // drawing.
  return dot_sign(p, a, b) == Sign::negative && a_t == Sign::positive;
}

// ---------------------------------------------------------------------------------------------------
// Memoryless next-hop rules.
// ---------------------------------------------------------------------------------------------------

enum class Metric { power, euclid };

/// What the greedy rule compares for metric M: the circles (power) or the positions (Euclidean), of
/// either arithmetic (the approx_* filters and the exact predicates have double and binary128 overloads).
template <Metric M>
struct Sites;

template <>
struct Sites<Metric::power> {
  template <class View>
  static const auto& own(const View& v) { return v.circle(); }
  template <class View>
  static const auto& of(const View& v, std::size_t i) { return v.circle_of(i); }
  template <class P, class C>
  static Approx approx(P t, const C& c) { return approx_power(t, c); }
  template <class P, class C>
  static Sign exact(P t, const C& a, const C& b) {
    // Equal radii cancel exactly in pow(t, a) − pow(t, b): the distance comparison is the same exact
    // sign, and its interval filter settles exact ties of well-placed centres (grids, symmetric
    // layouts) without falling back to rational arithmetic, which ties with a radius like 0.3 would
    // otherwise force.
    return a.r == b.r ? compare_distance(t, centre(a), centre(b)) : compare_power(t, a, b);
  }
};

template <>
struct Sites<Metric::euclid> {
  template <class View>
  static auto own(const View& v) { return v.position(); }
  template <class View>
  static auto of(const View& v, std::size_t i) { return v.position_of(i); }
  template <class P>
  static Approx approx(P t, P p) { return approx_distance(t, p); }
  template <class P>
  static Sign exact(P t, P a, P b) { return compare_distance(t, a, b); }
};

/// The greedy rule: argmin over neighbours (smallest key among ties), if strictly better than the
/// holder. (A two-pass variant, approximate argmin then certification, measured slower than this loop.)
template <Metric M, class View>
std::size_t greedy_hop(const View& v, typename View::Point t) {
  using S = Sites<M>;
  const std::size_t deg = v.degree();
  auto compare = [&](const auto& a, const Approx& aa, const auto& b, const Approx& ab) {
    if (const auto s = certified_sign(aa, ab)) return *s;
    return S::exact(t, a, b);
  };
  std::size_t best = deg;
  Approx best_approx;
  for (std::size_t i = 0; i < deg; ++i) {
    const Approx ai = S::approx(t, S::of(v, i));
    if (best != deg) {
      const Sign s = compare(S::of(v, i), ai, S::of(v, best), best_approx);
      if (s == Sign::positive || (s == Sign::zero && v.key(i) > v.key(best))) continue;
    }
    best = i;
    best_approx = ai;
  }
  if (best == deg) return deg;
  const auto own = S::own(v);
  return compare(S::of(v, best), best_approx, own, S::approx(t, own)) == Sign::negative ? best : deg;
}

}  // namespace next_hop_detail

template <class View>
std::size_t greedy_power_hop(const View& view, typename View::Point t) {
  return next_hop_detail::greedy_hop<next_hop_detail::Metric::power>(view, t);
}

template <class View>
std::size_t greedy_euclid_hop(const View& view, typename View::Point t) {
  return next_hop_detail::greedy_hop<next_hop_detail::Metric::euclid>(view, t);
}

template <class View>
std::size_t compass_hop(const View& view, Point2 t) {
  const Point2 v = view.position();
  const std::size_t deg = view.degree();
  std::size_t best = deg;
  next_hop_detail::Approx best_approx;
  for (std::size_t i = 0; i < deg; ++i) {
    const Point2 pu = view.position_of(i);
    const next_hop_detail::Approx au = next_hop_detail::approx_alignment(v, t, pu);
    if (best != deg) {
      // Larger alignment = smaller deviation; compare_deviation is negative when its first point
      // deviates less.
      Sign s;
      if (const auto c = next_hop_detail::certified_sign(best_approx, au)) s = *c;
      else s = compare_deviation(v, t, pu, view.position_of(best));
      if (s == Sign::positive || (s == Sign::zero && view.key(i) > view.key(best))) continue;
    }
    best = i;
    best_approx = au;
  }
  return best;
}

// ---------------------------------------------------------------------------------------------------
// Face routing (the perimeter mode of greedy-face-greedy; the whole walk is described in Routing.cpp).
// ---------------------------------------------------------------------------------------------------

template <class View>
std::size_t first_face_hop(const View& view, Point2 t) {
  const std::size_t deg = view.degree();
  for (std::size_t i = 0; i < deg; ++i) {
    const std::size_t b = i + 1 == deg ? 0 : i + 1;
    if (next_hop_detail::in_open_sector(view.position(), view.position_of(i), view.position_of(b), t, i == b))
      return b;
  }
  return deg;
}

template <class View>
FaceHop face_hop(const View& view, Point2 entry, Point2 t, FaceChange& last, std::size_t d) {
  const std::size_t deg = view.degree();
  const Point2 p = entry, pa = view.position();
  using next_hop_detail::Along;
  const Along at_target{Along::Kind::target, {}, {}};
  FaceHop hop{d, false};
  for (;;) {
    const Point2 pb = view.position_of(hop.next);
    const Sign sa = orientation(p, t, pa), sb = orientation(p, t, pb);
    if (static_cast<int>(sa) * static_cast<int>(sb) >= 0) return hop;
    const Along q{Along::Kind::edge, pa, pb};
    const Along previous = last.crossed ? Along{Along::Kind::edge, last.a, last.b} : Along{};
    using next_hop_detail::compare_along;
    if (compare_along(p, t, q, previous) != Sign::positive || compare_along(p, t, q, at_target) == Sign::positive)
      return hop;
    last = {true, pa, pb};
    hop.changed = true;
    // T right of holder → b: the walked face contains the segment beyond q; the packet goes along the edge.
    if (orientation(pa, pb, t) != Sign::positive) return hop;
    // T left of it: continue in the face on the other side of the edge, from the holder.
    hop.next = hop.next + 1 == deg ? 0 : hop.next + 1;
  }
}

}  // namespace laguerre::core
