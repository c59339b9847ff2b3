#pragma once
/// @file
/// Riemannian metrics of space: the 3D counterparts of Metric.hpp (thesis §3.2 in dimension 3).
///
/// A metric is a symmetric positive definite 3×3 matrix M; ‖v‖_M = √(vᵀMv), and its symmetric square
/// root F = M^{1/2} stretches space so that d_M(x, y) = ‖F(x − y)‖₂. The relative distortion is, as in
/// the plane, γ(M, N) = √max(λ₊, 1/λ₋) over the roots λ of det(M − λN) = 0 (Metric.hpp explains why).

#include <algorithm>
#include <array>
#include <cmath>

namespace laguerre::core {

/// A symmetric matrix [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]: a metric at one point of space.
struct Metric3 {
  double xx = 1;  ///< M₁₁
  double xy = 0;  ///< M₁₂ = M₂₁
  double xz = 0;  ///< M₁₃ = M₃₁
  double yy = 1;  ///< M₂₂
  double yz = 0;  ///< M₂₃ = M₃₂
  double zz = 1;  ///< M₃₃
};

/// A general 3×3 matrix, row-major (square roots and transfer maps).
using Matrix3 = std::array<double, 9>;

/// True iff `m` is finite and positive definite (its three leading principal minors are positive).
bool is_metric(const Metric3& m);

/// The metric with sizes h1, h2, h3 along the unit orthogonal directions u1, u2, u3 (the columns of
/// the rotation R): M = R diag(1/h1², 1/h2², 1/h3²) Rᵀ. Sizes must be positive and finite.
Metric3 metric3_from_sizes(double h1, double h2, double h3, const Matrix3& rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1});

/// The sizes 1/√λ of `m`, largest first.
std::array<double, 3> sizes_of(const Metric3& m);

/// The symmetric square root F = M^{1/2} (FᵀF = M, det F > 0), by eigen-decomposition.
Matrix3 square_root(const Metric3& m);

/// F·v (inline: the 3D star mesher's inner loops).
inline std::array<double, 3> multiply(const Matrix3& f, const std::array<double, 3>& v) {
  return {f[0] * v[0] + f[1] * v[1] + f[2] * v[2], f[3] * v[0] + f[4] * v[1] + f[5] * v[2],
          f[6] * v[0] + f[7] * v[1] + f[8] * v[2]};
}

/// F⁻¹·v (Cramer's rule; F invertible).
std::array<double, 3> solve(const Matrix3& f, const std::array<double, 3>& v);

/// ‖v‖_M = √(vᵀ M v) (inline: the 3D star mesher's inner loops).
inline double metric_length(const Metric3& m, const std::array<double, 3>& v) {
  const double q = m.xx * v[0] * v[0] + m.yy * v[1] * v[1] + m.zz * v[2] * v[2] +
                   2 * (m.xy * v[0] * v[1] + m.xz * v[0] * v[2] + m.yz * v[1] * v[2]);
  return std::sqrt(std::max(0.0, q));
}

/// The roots λ₋ ≤ λ₊ of det(M − λN) = 0 (the extreme eigenvalues of N⁻¹M; positive).
std::array<double, 2> generalized_eigenvalues(const Metric3& m, const Metric3& n);

/// The relative distortion γ(M, N) ≥ 1.
double distortion(const Metric3& m, const Metric3& n);

/// (1 − t)·M + t·N (SPD for t ∈ [0, 1]).
Metric3 blend(const Metric3& m, const Metric3& n, double t);

}  // namespace laguerre::core
