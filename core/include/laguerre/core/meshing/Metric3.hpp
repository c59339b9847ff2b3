#pragma once
/// @file
/// Riemannian metrics of space: the 3D counterparts of Metric.hpp (thesis §3.2 in dimension 3).
///
/// A metric is a symmetric positive definite 3×3 matrix M; ‖v‖_M = √(vᵀMv), and its symmetric square
/// root F = M^{1/2} stretches space so that d_M(x, y) = ‖F(x − y)‖₂. The relative distortion is, as in
/// the plane, γ(M, N) = √max(λ₊, 1/λ₋) over the roots λ of det(M − λN) = 0 (Metric.hpp explains why).

#include <array>

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

/// F·v.
std::array<double, 3> multiply(const Matrix3& f, const std::array<double, 3>& v);

/// F⁻¹·v (Cramer's rule; F invertible).
std::array<double, 3> solve(const Matrix3& f, const std::array<double, 3>& v);

/// ‖v‖_M = √(vᵀ M v).
double metric_length(const Metric3& m, const std::array<double, 3>& v);

/// The roots λ₋ ≤ λ₊ of det(M − λN) = 0 (the extreme eigenvalues of N⁻¹M; positive).
std::array<double, 2> generalized_eigenvalues(const Metric3& m, const Metric3& n);

/// The relative distortion γ(M, N) ≥ 1.
double distortion(const Metric3& m, const Metric3& n);

/// (1 − t)·M + t·N (SPD for t ∈ [0, 1]).
Metric3 blend(const Metric3& m, const Metric3& n, double t);

}  // namespace laguerre::core
