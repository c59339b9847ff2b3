#pragma once
/// @file
/// Internal: double-precision filters with proven error bounds, the first stage of the exact
/// predicates (Predicates.cpp) and of the routing decisions (Routing.cpp).
///
/// Routing all pairs of a few thousand vertices makes hundreds of millions of comparisons, and the
/// interval filter of Predicates.cpp pays a rounding-mode switch per call. So each decision here first
/// evaluates its expression in plain double arithmetic (round to nearest) together with a proven bound
/// on the absolute error; only when the computed value does not clear the bound do we call the exact
/// predicate. Each approximation states the magnitude range in which its bound is proven (no overflow,
/// no underflow that the bound does not absorb); outside it the error is "unknown" (infinite) and the
/// exact predicate decides. The answers are therefore always the exact ones; a randomized test checks
/// them against the plain exact predicates on near-ties at scales 2^-600 .. 2^600.

#include <cmath>
#include <limits>
#include <optional>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::core::detail {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

inline bool in_range(double d, double lo, double hi) {
  const double a = std::fabs(d);
  return a == 0 || (a >= lo && a <= hi);
}
inline bool in_range(double d) { return in_range(d, 1e-100, 1e100); }

/// A double value approximating an exact real, with a bound on the absolute error (∞: no bound).
struct Approx {
  double value = 0;
  double error = kInfinity;
};

/// Sign of a − b when the error bounds decide it. With both errors generous by a factor ≥ 1.8 over
/// the true worst case (see the constants below), |fl(a − b)| > ea + eb also absorbs the rounding of
/// the subtraction itself.
inline std::optional<Sign> certified_sign(const Approx& a, const Approx& b) {
  const double d = a.value - b.value, e = a.error + b.error;
  if (d > e) return Sign::positive;
  if (d < -e) return Sign::negative;
  return std::nullopt;
}

// Unit roundoff u = 2^-53 ≈ 1.11e-16. Worst-case errors: |p − q|² ≤ 4u·M, power ≤ 5u·M (M the sum of the
// magnitudes of the squared terms); the constant below is about 9u. The bound holds whenever the computed
// M' lies in [1e-200, 1e200]: no term overflowed, and a term that underflowed adds at most ~2^-1074,
// far below 1e-15·M'. Outside that range only the exactly-zero case (coincident centres, zero radius)
// is certified; everything else goes to the exact predicate.
inline constexpr double kSquaresError = 1e-15;

/// pow(q, c) = |q − p(c)|² − r(c)².
inline Approx approx_power(Point2 q, const Circle& c) {
  const double dx = q.x - c.x, dy = q.y - c.y;
  const double sx = dx * dx, sy = dy * dy, sr = c.r * c.r, m = sx + sy + sr;
  if (m >= 1e-200 && m <= 1e200) return {sx + sy - sr, kSquaresError * m};
  if (dx == 0 && dy == 0 && c.r == 0) return {0, 0};
  return {};
}

/// |q − a|².
inline Approx approx_distance(Point2 q, Point2 a) {
  const double dx = q.x - a.x, dy = q.y - a.y;
  const double s = dx * dx + dy * dy;
  if (s >= 1e-200 && s <= 1e200) return {s, kSquaresError * s};
  if (dx == 0 && dy == 0) return {0, 0};
  return {};
}

/// The alignment of a with the direction v → t, the quantity compare_deviation compares:
/// dot·|dot| / |a − v|² with dot = (a − v)·(t − v), a strictly increasing function of the cosine of the
/// angle at v (for a fixed t). Error ≤ 15u·D²/|a − v|² with D = |dx·tx| + |dy·ty|; we use 18u.
inline Approx approx_alignment(Point2 v, Point2 t, Point2 a) {
  const double tx = t.x - v.x, ty = t.y - v.y, dx = a.x - v.x, dy = a.y - v.y;
  constexpr double lo = 1e-60, hi = 1e60;  // keeps the degree-4 terms away from underflow and overflow
  if (!in_range(tx, lo, hi) || !in_range(ty, lo, hi) || !in_range(dx, lo, hi) || !in_range(dy, lo, hi)) return {};
  const double len2 = dx * dx + dy * dy;
  if (len2 == 0) return {};  // the zero-length convention of compare_deviation: let it decide
  const double px = dx * tx, py = dy * ty, dot = px + py, mag = std::fabs(px) + std::fabs(py);
  if (mag == 0) return {0, 0};  // both products exactly zero (no underflow in range): dot is exactly 0
  const double scale = mag * mag / len2;
  if (!(scale >= 1e-280 && scale <= 1e280)) return {};
  return {dot * std::fabs(dot) / len2, 2e-15 * scale};
}

// Shewchuk's orient2d bound is (3 + 16u)u·(|l| + |r|); we use 1e-15 ≈ 9u.
inline constexpr double kOrientError = 1e-15;


/// Sign of l − r (orient2d's two products, or a dot product's with r negated) when the double filter
/// decides it; Shewchuk's bound (3 + 16u)u·(|l| + |r|), taken as 1e-15·(|l| + |r|).
inline std::optional<Sign> certified_difference(double l, double r) {
  const double det = l - r;
  const double err = kOrientError * (std::fabs(l) + std::fabs(r));
  if (det > err) return Sign::positive;
  if (det < -err) return Sign::negative;
  if (err == 0) return Sign::zero;  // both products exactly zero
  return std::nullopt;
}

/// The double stage of radical_centre_power_side (Predicates.cpp): the sign of
///     E = d · (pow(c, t) − pow(c, u)),   d = orient(p(u), p(a), p(b)),  c the radical centre of (u, a, b),
/// and the sign of d, when doubles decide both; the predicate is sign(E)·sign(d).
///
/// E is invariant under translation, so it is evaluated on the differences A = p(a) − p(u),
/// B = p(b) − p(u), T = p(t) − p(u) (u at the origin, lifted height −r(u)²):
///     E = d·β_t − T_x n_x − T_y n_y,  β_s = |S|² − r_s² + r_u²,  n_x = B_y β_a − A_y β_b,  n_y = A_x β_b − B_x β_a.
/// This is what decides the tiny circles of uniform random maps (radii 1e-25 at distance ~0.3 from the
/// origin): in absolute coordinates their lifted heights |p|² − r² lose every bit of r² to |p|², in
/// differences they keep them. E is also homogeneous of degree 4 in (A, B, T, radii), so the leaves are
/// first scaled by a power of two (exact) to a largest magnitude in [1/2, 1): no overflow, and no
/// underflow that the bound does not absorb.
///
/// Bound. Every monomial of E is computed with at most 13 roundings (one per leaf difference, one per
/// operation on its path), so |fl(E) − E| ≤ γ₁₃·M with M the same program on absolute values and sums
/// (γ₁₃ ≈ 13u = 1.44e-15; we use 2e-15, which also covers the rounding of M itself). An underflowed
/// product adds at most 2^-1075 times the largest later factor (≤ 2^9 on the scaled leaves): the
/// 1e-300 term. For d, Shewchuk's orient2d bound (certified_difference), accepted only when the products
/// are far from underflow. Returns nullopt when either sign is not certified (the exact stages decide).
///
/// `certified_power_side_leaves` is the same stage on leaves given directly (A, B, T, radii), each
/// within a relative 2^-53 (1 + 2^-59) of its exact value: what a double difference is, and what a
/// binary128 difference rounded to doubles is (FastFilter128.hpp). The 13-rounding count above already
/// counts one rounding per leaf (radii included), and 2e-15 > 13·2^-53·(1 + 2^-59) + the rounding of M.
inline std::optional<Sign> certified_power_side_leaves(double ax, double ay, double bx, double by, double tx, double ty,
                                                       double ru, double ra, double rb, double rt) {
  double m = 0;
  for (double v : {ax, ay, bx, by, tx, ty, ru, ra, rb, rt}) m = std::fmax(m, std::fabs(v));
  if (!(m > 0) || !std::isfinite(m)) return std::nullopt;  // NaN, infinite or all zero: let the exact stages decide
  int e = 0;
  std::frexp(m, &e);
  for (double* v : {&ax, &ay, &bx, &by, &tx, &ty, &ru, &ra, &rb, &rt}) *v = std::ldexp(*v, -e);
  const double l = ax * by, r = ay * bx, md = std::fabs(l) + std::fabs(r);
  if (md < 1e-280) return std::nullopt;
  const auto sd = certified_difference(l, r);
  if (!sd || *sd == Sign::zero) return std::nullopt;
  const double d = l - r;
  const double ru2 = ru * ru;
  const double ba = (ax * ax + ay * ay - ra * ra) + ru2, mba = ax * ax + ay * ay + ra * ra + ru2;
  const double bb = (bx * bx + by * by - rb * rb) + ru2, mbb = bx * bx + by * by + rb * rb + ru2;
  const double bt = (tx * tx + ty * ty - rt * rt) + ru2, mbt = tx * tx + ty * ty + rt * rt + ru2;
  const double nx = by * ba - ay * bb, mnx = std::fabs(by) * mba + std::fabs(ay) * mbb;
  const double ny = ax * bb - bx * ba, mny = std::fabs(ax) * mbb + std::fabs(bx) * mba;
  const double big_e = d * bt - tx * nx - ty * ny;
  const double bound = 2e-15 * (md * mbt + std::fabs(tx) * mnx + std::fabs(ty) * mny) + 1e-300;
  Sign se;
  if (big_e > bound) se = Sign::positive;
  else if (big_e < -bound) se = Sign::negative;
  else return std::nullopt;
  return static_cast<Sign>(static_cast<int>(se) * static_cast<int>(*sd));
}

/// See certified_power_side_leaves: the leaves are the double differences of the inputs.
inline std::optional<Sign> certified_power_side(const Circle& u, const Circle& a, const Circle& b, const Circle& t) {
  return certified_power_side_leaves(a.x - u.x, a.y - u.y, b.x - u.x, b.y - u.y, t.x - u.x, t.y - u.y, u.r, a.r, b.r,
                                     t.r);
}

}  // namespace laguerre::core::detail
