#pragma once
/// @file
/// The slow exact oracle of the radical-centre tests (RadicalCentreTest on doubles, RadicalCentre128Test
/// on binary128): circles as exact rationals (Boost.Multiprecision, independent of CGAL and of the
/// predicates' filters), the radical centre c of u, a, b by Cramer's rule on
/// 2 c·(p_s − p_u) = z_s − z_u (s = a, b; z = |p|² − r²), then the signs of pow(c, t) − pow(c, u) and
/// of |c|² − 1. Each test converts its circles exactly into QCircle.

#include <boost/multiprecision/cpp_int.hpp>

namespace laguerre::testing::oracle {

using Q = boost::multiprecision::cpp_rational;

/// A circle in exact rationals: centre and squared radius.
struct QCircle {
  Q x, y, r2;
};

inline int sign(const Q& q) { return q > 0 ? 1 : q < 0 ? -1 : 0; }

/// The lifted height |p|² − r².
inline Q lifted(const QCircle& c) { return c.x * c.x + c.y * c.y - c.r2; }

/// The radical centre (cx, cy) of u, a, b; false if their centres are collinear.
inline bool radical_centre(const QCircle& u, const QCircle& a, const QCircle& b, Q& cx, Q& cy) {
  const Q a11 = 2 * (a.x - u.x), a12 = 2 * (a.y - u.y), a21 = 2 * (b.x - u.x), a22 = 2 * (b.y - u.y);
  const Q r1 = lifted(a) - lifted(u), r2 = lifted(b) - lifted(u);
  const Q det = a11 * a22 - a12 * a21;
  if (det == 0) return false;
  cx = (r1 * a22 - a12 * r2) / det;
  cy = (a11 * r2 - r1 * a21) / det;
  return true;
}

/// pow((cx, cy), s).
inline Q power(const Q& cx, const Q& cy, const QCircle& s) {
  return (cx - s.x) * (cx - s.x) + (cy - s.y) * (cy - s.y) - s.r2;
}

/// sign(pow(c, t) − pow(c, u)) at the radical centre c of u, a, b; 0 when it does not exist.
inline int power_side(const QCircle& u, const QCircle& a, const QCircle& b, const QCircle& t) {
  Q cx, cy;
  if (!radical_centre(u, a, b, cx, cy)) return 0;
  return sign(power(cx, cy, t) - power(cx, cy, u));
}

/// sign(|c|² − 1) at the radical centre c of u, a, b; 0 when it does not exist.
inline int outside_unit_disc(const QCircle& u, const QCircle& a, const QCircle& b) {
  Q cx, cy;
  if (!radical_centre(u, a, b, cx, cy)) return 0;
  return sign(cx * cx + cy * cy - 1);
}

}  // namespace laguerre::testing::oracle
