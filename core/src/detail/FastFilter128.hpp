#pragma once
/// @file
/// Internal: the double filters of FastFilter.hpp on binary128 inputs (Circle128, Point128), and the
/// exact conversion of a binary128 number to the number types of the interval and exact stages.
///
/// A filter reads *leaves*: differences of coordinates (and radii), computed in binary128 (relative
/// error ≤ 2^-113) and rounded to doubles (relative error ≤ 2^-53 when the result is a normal double).
/// Each leaf is therefore within a relative 2^-53·(1 + 2^-59) of its exact value, the same as a
/// double difference up to the factor (1 + 2^-59), which the bounds of FastFilter.hpp absorb (each is
/// generous by a factor ≥ 1.8 over its worst case). Underflow is kept out by range checks on the
/// binary128 leaf before it is rounded: a leaf is used only if it is exactly zero or of magnitude in
/// [1e-100, 1e100], else the filter gives up and the exact stages decide.

#include <cmath>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>

#include <quadmath.h>

#include "FastFilter.hpp"
#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::core::detail {

/// |q|.
inline Float128 abs128(Float128 q) { return q < 0 ? -q : q; }

/// Whether q is finite (not NaN, not infinite).
inline bool finite128(Float128 q) { return q - q == 0; }

/// The binary128 leaf q rounded to a double, if it is zero or within [1e-100, 1e100] in magnitude.
inline std::optional<double> leaf(Float128 q) {
  if (q == 0) return 0.0;
  const Float128 a = abs128(q);
  if (a >= Float128(1e-100) && a <= Float128(1e100)) return static_cast<double>(q);
  return std::nullopt;
}

/// pow(q, c) from binary128 inputs, as approx_power.
inline Approx approx_power(Point128 q, const Circle128& c) {
  const auto dx = leaf(q.x - c.x), dy = leaf(q.y - c.y), r = leaf(c.r);
  if (!dx || !dy || !r) return {};
  const double sx = *dx * *dx, sy = *dy * *dy, sr = *r * *r, m = sx + sy + sr;
  if (m >= 1e-200 && m <= 1e200) return {sx + sy - sr, kSquaresError * m};
  if (*dx == 0 && *dy == 0 && *r == 0) return {0, 0};  // leaf() maps only an exact 0 to 0
  return {};
}

/// |q − a|² from binary128 inputs, as approx_distance.
inline Approx approx_distance(Point128 q, Point128 a) {
  const auto dx = leaf(q.x - a.x), dy = leaf(q.y - a.y);
  if (!dx || !dy) return {};
  const double s = *dx * *dx + *dy * *dy;
  if (s >= 1e-200 && s <= 1e200) return {s, kSquaresError * s};
  if (*dx == 0 && *dy == 0) return {0, 0};
  return {};
}

/// orientation(a, b, c) when the double filter decides it: Shewchuk's bound on the rounded leaves.
inline std::optional<Sign> certified_orientation(Point128 a, Point128 b, Point128 c) {
  const auto ux = leaf(b.x - a.x), uy = leaf(b.y - a.y), wx = leaf(c.x - a.x), wy = leaf(c.y - a.y);
  if (!ux || !uy || !wx || !wy) return std::nullopt;
  return certified_difference(*ux * *wy, *uy * *wx);
}

/// certified_power_side on binary128 inputs: the leaves are computed in binary128, scaled there by a
/// power of two (exact) to a largest magnitude in [1/2, 1), then rounded to doubles; what underflows
/// in that rounding is absorbed as in the double version (an absolute 2^-1075 per leaf).
inline std::optional<Sign> certified_power_side(const Circle128& u, const Circle128& a, const Circle128& b,
                                                const Circle128& t) {
  Float128 v[10] = {a.x - u.x, a.y - u.y, b.x - u.x, b.y - u.y, t.x - u.x, t.y - u.y, u.r, a.r, b.r, t.r};
  Float128 m = 0;
  for (const Float128& x : v) {
    if (!finite128(x)) return std::nullopt;
    if (abs128(x) > m) m = abs128(x);
  }
  if (!(m > 0)) return std::nullopt;
  int e = 0;
  frexpq(m, &e);
  double d[10];
  for (int i = 0; i < 10; ++i) d[i] = static_cast<double>(ldexpq(v[i], -e));
  return certified_power_side_leaves(d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8], d[9]);
}

/// Throws std::domain_error naming `predicate` if a binary128 value is NaN or infinite.
inline void require_finite128(const char* predicate, std::initializer_list<Float128> values) {
  for (const Float128& v : values)
    if (!finite128(v))
      throw std::domain_error(std::string("exact predicate ") + predicate +
                              ": an input coordinate or radius is NaN or infinite; the geometry cannot be decided");
}

/// x = hi + mid + lo with three doubles, each part exact: hi = RN(x), mid = RN(x − hi), lo = x − hi −
/// mid. The residuals are exact in binary128 (multiples of x's last unit, below 2^60 and 2^7 of them)
/// and lo is a double when x's last unit 2^(e−113) is at least 2^-1074, i.e. |x| ≥ 2^-960 (or x = 0);
/// hi is finite when |x| < 2^1023 (no overflow in rounding). Throws std::domain_error outside.
struct Split128 {
  double hi = 0, mid = 0, lo = 0;
};
inline Split128 split(Float128 x) {
  Split128 s;
  s.hi = static_cast<double>(x);
  const Float128 r1 = x - s.hi;
  if (r1 == 0 && std::isfinite(s.hi)) return s;
  s.mid = static_cast<double>(r1);
  const Float128 r2 = r1 - s.mid;
  s.lo = static_cast<double>(r2);
  if (!std::isfinite(s.hi) || Float128(s.lo) != r2)
    throw std::domain_error("exact predicate on binary128 inputs: a coordinate or radius outside the exactly converted "
                            "range (0 or magnitude in [2^-960, 2^1023))");
  return s;
}

/// The exact value of x in NT: exact for CGAL::Mpzf and rationals, an enclosure for intervals (the
/// interval sum of the three exact parts, under the rounding mode filtered_with sets).
template <class NT>
NT to_nt(Float128 x) {
  const Split128 s = split(x);
  if (s.mid == 0) return NT(s.hi);
  return NT(s.hi) + NT(s.mid) + NT(s.lo);
}

/// The double's value in NT (exact in every NT the predicates use).
template <class NT>
NT to_nt(double x) {
  return NT(x);
}

}  // namespace laguerre::core::detail
