#pragma once
/// @file
/// Riemannian metrics of the plane and the quantities anisotropic meshing measures with them
/// (thesis §2.4 and §3.2): metric lengths, square roots (transfer maps) and relative distortion.
///
/// A metric is a symmetric positive definite 2×2 matrix M; the length of a vector v for M is
/// ‖v‖_M = √(vᵀMv), and d_M(x, y) = ‖x − y‖_M. A square root of M is any F with FᵀF = M and
/// det F > 0; then d_M(x, y) = ‖F(x − y)‖₂, so the M-Delaunay triangulation of a point set is the
/// Euclidean Delaunay triangulation of its image by F.
///
/// The relative distortion of two metrics (Labelle–Shewchuk; thesis §3.2) is
///   γ(M, N) = max(‖F_M F_N⁻¹‖₂, ‖F_N F_M⁻¹‖₂) ≥ 1.
/// It does not depend on the choice of square roots: (F_M F_N⁻¹)ᵀ(F_M F_N⁻¹) = F_N⁻ᵀ M F_N⁻¹ is similar to
/// N⁻¹M, so ‖F_M F_N⁻¹‖₂² is the largest root λ₊ of det(M − λN) = 0 and ‖F_N F_M⁻¹‖₂² = 1/λ₋. Hence
///   γ(M, N) = √max(λ₊, 1/λ₋),
/// which is what `distortion` evaluates. It bounds how much the two metrics disagree on lengths:
/// d_N(x, y)/γ ≤ d_M(x, y) ≤ γ·d_N(x, y).

#include <array>

namespace laguerre::core {

/// A symmetric positive definite matrix [[a, b], [b, c]]: a Riemannian metric at one point.
struct Metric {
  double a = 1;  ///< M₁₁
  double b = 0;  ///< M₁₂ = M₂₁
  double c = 1;  ///< M₂₂
};

/// A general 2×2 matrix [[m00, m01], [m10, m11]] (square roots and transfer maps).
struct Matrix2 {
  double m00 = 1;  ///< row 0, column 0
  double m01 = 0;  ///< row 0, column 1
  double m10 = 0;  ///< row 1, column 0
  double m11 = 1;  ///< row 1, column 1
};

/// True iff `m` is finite, symmetric positive definite (a > 0 and det > 0).
bool is_metric(const Metric& m);

/// The metric whose unit ball is the ellipse with semi-axis h1 along direction θ (radians from the
/// x-axis) and h2 across it: M = R(θ) diag(1/h1², 1/h2²) R(θ)ᵀ. Sizes must be positive and finite.
Metric metric_from_sizes(double h1, double h2, double theta);

/// The eigen-decomposition of `m` as sizes: {h1, h2, θ} with h1 ≥ h2 > 0 (h = 1/√eigenvalue) and θ the
/// direction of h1, in (−π/2, π/2]. Inverse of metric_from_sizes up to the order of the axes.
std::array<double, 3> sizes_of(const Metric& m);

/// The symmetric square root F = M^{1/2} (FᵀF = M, det F > 0), by eigen-decomposition (thesis §3.2).
Matrix2 square_root(const Metric& m);

/// ‖(dx, dy)‖_M = √(vᵀ M v).
double metric_length(const Metric& m, double dx, double dy);

/// The relative distortion γ(M, N) ≥ 1 (see the file comment). Equal metrics give exactly 1 up to
/// rounding.
double distortion(const Metric& m, const Metric& n);

/// The two roots λ₋ ≤ λ₊ of det(M − λN) = 0 (the eigenvalues of N⁻¹M; both positive).
std::array<double, 2> generalized_eigenvalues(const Metric& m, const Metric& n);

/// (1 − t)·M + t·N: a convex combination of SPD matrices is SPD (used to interpolate fields).
Metric blend(const Metric& m, const Metric& n, double t);

}  // namespace laguerre::core
