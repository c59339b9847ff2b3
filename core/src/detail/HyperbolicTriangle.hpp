#pragma once
/// @file
/// Internal: the angle formulas of HyperbolicTriangle.hpp over any floating-point type T (double, or
/// boost::multiprecision::float128 for the extended layout of Layout.cpp). The public double functions
/// are these templates at T = double, so both compute the same expressions.

#include <algorithm>
#include <cmath>
#include <limits>

namespace laguerre::core::detail {

/// e^x − 1 in T (specialised for float128 in Layout.cpp: Boost's wrapper does not compile in ISO mode).
template <class T>
T expm1_of(const T& x) {
  using std::expm1;
  return expm1(x);
}

/// X = e^{-2h} and X̄ = 1 − X in T (see core::Lift).
template <class T>
struct LiftT {
  T x = 0;
  T xbar = 1;
};

template <class T>
LiftT<T> lift_t(const T& h) {
  using std::exp, std::isinf;
  if (isinf(h)) return {T(0), T(1)};
  return {exp(-2 * h), -expm1_of(T(-2 * h))};
}

template <class T>
T tangent_angle_t(const LiftT<T>& x, const LiftT<T>& y, const LiftT<T>& z) {
  // sin²(α/2) = X Ȳ Z̄ / D and cos²(α/2) = X̄ (X̄ + X (Ȳ + Y Z̄)) / D with D = (X̄ + X Ȳ)(X̄ + X Z̄):
  // the complement expands to X̄² + X̄X(Ȳ + Z̄ − ȲZ̄) and Ȳ + Z̄ − ȲZ̄ = 1 − YZ = Ȳ + Y Z̄, so both
  // are sums of positive terms; atan2 keeps α accurate near 0 (huge x) and near π (vanishing x).
  using std::sqrt, std::atan2;
  const T s = sqrt(x.x * y.xbar * z.xbar);
  const T c = sqrt(x.xbar * (x.xbar + x.x * (y.xbar + y.x * z.xbar)));
  return 2 * atan2(s, c);
}

// Angle at x in the right triangle (x, T, o) of a G′ triangle, where o is the circle that is not
// tangent to x in the pair (x tangent to its other neighbour, o orthogonal to x), or, at a face
// circle x, either of its two tangent neighbours: atan(tanh h_o / sinh h_x) = atan2(2√X Ō, X̄(1+O)).
template <class T>
T right_part_t(const LiftT<T>& x, const LiftT<T>& o) {
  using std::sqrt, std::atan2;
  return atan2(2 * sqrt(x.x) * o.xbar, x.xbar * (1 + o.x));
}

// L_ab = (1+A)(1+B) + c(1−A)(1−B) = 4√(AB) cosh l_ab.
template <class T>
T lifted_cosh_t(const T& A, const T& B, const T& c) {
  return (1 + c) * (1 + A * B) + (1 - c) * (A + B);
}
// L_ab² − 16AB = (L_ab − 4√(AB))(L_ab + 4√(AB)), with the first factor rewritten as
// (1+c)(1−√(AB))² + (1−c)(√A−√B)².
template <class T>
T lifted_sinh2_t(const T& A, const T& B, const T& c, const T& L) {
  using std::sqrt;
  const T a = sqrt(A), b = sqrt(B);
  const T p = 1 - a * b, m = a - b;
  return ((1 + c) * p * p + (1 - c) * m * m) * (L + 4 * a * b);
}

// The general law of cosines in X (any cosines): cos α = N / √P with N = L_xz L_xy − 4X L_yz and
// P = (L_xz² − 16XZ)(L_xy² − 16XY), P − N² = X·Q with
// Q = 8 L_xz L_xy L_yz − 16 (Y L_xz² + Z L_xy² + X L_yz²) + 256 XYZ.
template <class T>
T general_angle_t(const T& X, const T& Y, const T& Z, const T& cxy, const T& cxz, const T& cyz) {
  using std::sqrt, std::atan2, std::max;
  const T lxy = lifted_cosh_t(X, Y, cxy), lxz = lifted_cosh_t(X, Z, cxz), lyz = lifted_cosh_t(Y, Z, cyz);
  const T n = lxz * lxy - 4 * X * lyz;
  const T sp = sqrt(lifted_sinh2_t(X, Z, cxz, lxz) * lifted_sinh2_t(X, Y, cxy, lxy));
  const T q = 8 * lxz * lxy * lyz - 16 * (Y * lxz * lxz + Z * lxy * lxy + X * lyz * lyz) + 256 * X * Y * Z;
  T s2, c2;  // sin²(α/2), cos²(α/2)
  if (n >= 0) {
    s2 = X * q / (2 * sp * (sp + n));
    c2 = (sp + n) / (2 * sp);
  } else {
    s2 = (sp - n) / (2 * sp);
    c2 = X * q / (2 * sp * (sp - n));
  }
  return 2 * atan2(sqrt(T(max(T(0), s2))), sqrt(T(max(T(0), c2))));
}

template <class T>
T overlap_angle_t(const LiftT<T>& x, const LiftT<T>& y, const LiftT<T>& z, double cxy, double cxz, double cyz) {
  if (cxy == 1 && cxz == 1 && cyz == 1) return tangent_angle_t(x, y, z);
  if (cxy == 1 && cxz == 0 && cyz == 0) return right_part_t(x, z);  // z is the face circle
  if (cxz == 1 && cxy == 0 && cyz == 0) return right_part_t(x, y);  // y is the face circle
  if (cyz == 1 && cxy == 0 && cxz == 0) return right_part_t(x, y) + right_part_t(x, z);  // x is the face circle
  return general_angle_t(x.x, y.x, z.x, T(cxy), T(cxz), T(cyz));
}

}  // namespace laguerre::core::detail
