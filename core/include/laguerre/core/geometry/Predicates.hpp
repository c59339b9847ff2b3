#pragma once
/// @file
/// Filtered exact geometric predicates on double inputs.
///
/// Every predicate treats its double arguments as exact rationals and returns the exact sign of the
/// stated polynomial expression: it is first evaluated in interval arithmetic (CGAL::Interval_nt) and,
/// only when the interval contains 0, again in exact arithmetic: rationals (CGAL::Exact_rational), or
/// for the polynomial radical-centre predicates CGAL::Mpzf (exact + − × on dyadic numbers, no gcd).
/// Most predicates first try plain doubles with a proven error bound (no rounding-mode switch).
/// Circle radii enter squared *exactly*, so a power comparison is exact for the stored (x, y, r).
/// Results are enum results, never errors; degenerate inputs give Sign::zero and each predicate says
/// what that means.
///
/// Binary128 inputs (Circle128, Point128: the coordinates of a LayoutArithmetic::binary128 layout) are
/// decided the same way, on their exact values: the double filters read the differences computed in
/// binary128 and rounded to doubles, with that rounding in their error bounds; the interval stage
/// encloses each number by the sum of its three-double split (x = hi + mid + lo, every part exact);
/// the exact stage sums those parts exactly. Range of the exact stage for binary128: every number 0
/// or of magnitude in [2^-960, 2^1023) (below, the split's last part would be a subnormal double);
/// outside it, or for a NaN or infinity, std::domain_error names the predicate.

#include <concepts>
#include <cstddef>

#include "laguerre/core/geometry/Circle.hpp"

namespace laguerre::core {

/// Sign of an exact expression.
enum class Sign : int { negative = -1, zero = 0, positive = 1 };

/// A point of the plane given by double coordinates.
struct Point2 {
  double x = 0;  ///< abscissa
  double y = 0;  ///< ordinate
};

/// Centre of a circle as a point.
inline Point2 centre(const Circle& c) { return {c.x, c.y}; }

/// A point of the plane given by binary128 coordinates.
struct Point128 {
  Float128 x = 0;  ///< abscissa
  Float128 y = 0;  ///< ordinate
};

/// Centre of a binary128 circle as a point.
inline Point128 centre(const Circle128& c) { return {c.x, c.y}; }

/// Orientation of (a, b, c): positive if counter-clockwise (left turn), negative if clockwise, zero if
/// collinear (including coincident points). Degree 2.
Sign orientation(Point2 a, Point2 b, Point2 c);

/// Sign of pow(q, a) − pow(q, b) = |q − a|² − ra² − |q − b|² + rb²: negative when q is strictly closer
/// to circle a than to circle b in power distance, zero on their radical axis. Degree 2.
Sign compare_power(Point2 q, const Circle& a, const Circle& b);

/// Sign of |q − a|² − |q − b|²: negative when q is strictly closer to a. Degree 2.
Sign compare_distance(Point2 q, Point2 a, Point2 b);

/// Power test of circle t against the radical centre c of (u, a, b), with (u, a, b) non-collinear:
/// sign of pow(c, t) − pow(c, u). Positive means c lies strictly inside the half-plane
/// H_t = {x : pow(x, u) < pow(x, t)}, zero that c is on the radical axis of u and t.
/// Precondition: centres of u, a, b not collinear (otherwise the radical centre does not exist);
/// returns Sign::zero in that case. Degree 4 (the lifted-point determinant times orientation).
/// Cost: doubles on the translated circles (u at the origin) decide all but near-ties, including tiny
/// circles far from the origin (radii 1e-25 at |p| ~ 0.3); near-ties go to intervals, then Mpzf.
Sign radical_centre_power_side(const Circle& u, const Circle& a, const Circle& b, const Circle& t);

/// Whether the radical centre of (u, a, b) lies strictly outside the closed unit disc: positive if
/// |c| > 1, zero if |c| = 1, negative if inside. Precondition: centres not collinear (returns zero).
/// Degree 6.
Sign radical_centre_outside_unit_disc(const Circle& u, const Circle& a, const Circle& b);

/// Binary128 point types (templates constrained to them: a braced list such as {0, 0} deduces no
/// template argument, so calls written with braces keep meaning the double predicates).
template <class P>
concept Binary128Point = std::same_as<P, Point128>;

/// The predicates above on binary128 inputs, with the same meanings and the exact signs (file comment).
template <Binary128Point P>
Sign orientation(P a, P b, P c);
/// See compare_power.
template <Binary128Point P>
Sign compare_power(P q, const Circle128& a, const Circle128& b);
/// See compare_distance.
template <Binary128Point P>
Sign compare_distance(P q, P a, P b);
/// See radical_centre_power_side (Circle): same stages, the double stage on the binary128
/// differences rounded to doubles.
template <Binary128Circle C>
Sign radical_centre_power_side(const C& u, const C& a, const C& b, const C& t);
/// See radical_centre_outside_unit_disc (Circle).
template <Binary128Circle C>
Sign radical_centre_outside_unit_disc(const C& u, const C& a, const C& b);

/// Whether the closed segment [s0, s1] meets the closed power cell of `site` among `others`
/// (the set {x : pow(x, site) ≤ pow(x, o) for all o}). Exact. Cost O(|others|) filtered predicates.
bool segment_meets_power_cell(Point2 s0, Point2 s1, const Circle& site, const Circle* others, std::size_t count);
/// See segment_meets_power_cell (Circle): on binary128 inputs.
template <Binary128Point P>
bool segment_meets_power_cell(P s0, P s1, const Circle128& site, const Circle128* others, std::size_t count);

/// Compass routing comparison at v towards t: sign of angle(a − v, t − v) − angle(b − v, t − v), the
/// unsigned angles in [0, π]. Negative when a deviates strictly less from the direction of t.
/// Zero-length directions compare as angle π/2 (they are never chosen by well-formed callers).
Sign compare_deviation(Point2 v, Point2 t, Point2 a, Point2 b);

/// Whether the closed segments [a, b] and [c, d] intersect. Exact.
bool segments_intersect(Point2 a, Point2 b, Point2 c, Point2 d);

/// For segments [a, b] and [c, d] that intersect in exactly one point x with [a, b] not degenerate,
/// compares the positions of their crossings along the ray from p to q: sign of s1 − s2 where x_i =
/// p + s_i (q − p) is the crossing of [a_i, b_i] with line pq (lines not parallel to pq). Exact.
Sign compare_crossings_along(Point2 p, Point2 q, Point2 a1, Point2 b1, Point2 a2, Point2 b2);

}  // namespace laguerre::core
