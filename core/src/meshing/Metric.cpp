#include "laguerre/core/meshing/Metric.hpp"
#include "laguerre/core/Error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace laguerre::core {

namespace {

/// Eigenvalues λ₁ ≥ λ₂ of a symmetric 2×2 matrix and the angle of λ₁'s eigenvector, computed without
/// cancellation in the discriminant (hypot of the half-difference and the off-diagonal).
struct SymmetricEigen {
  double l1, l2, theta;
};

SymmetricEigen eigen(const Metric& m) {
  const double mean = 0.5 * (m.a + m.c);
  const double half_diff = 0.5 * (m.a - m.c);
  const double radius = std::hypot(half_diff, m.b);
  const double l1 = mean + radius;
  // λ₂ = det/λ₁ is accurate even when λ₂ ≪ λ₁ (mean − radius would cancel).
  const double l2 = (m.a * m.c - m.b * m.b) / l1;
  const double theta = 0.5 * std::atan2(2 * m.b, m.a - m.c);
  return {l1, l2, theta};
}

}  // namespace

bool is_metric(const Metric& m) {
  return std::isfinite(m.a) && std::isfinite(m.b) && std::isfinite(m.c) && m.a > 0 && m.c > 0 &&
         m.a * m.c - m.b * m.b > 0;
}

Metric metric_from_sizes(double h1, double h2, double theta) {
  if (!(h1 > 0) || !(h2 > 0) || !std::isfinite(h1) || !std::isfinite(h2) || !std::isfinite(theta))
    throw InputError("metric sizes must be positive and finite");
  const double l1 = 1 / (h1 * h1), l2 = 1 / (h2 * h2);
  const double co = std::cos(theta), si = std::sin(theta);
  return {l1 * co * co + l2 * si * si, (l1 - l2) * co * si, l1 * si * si + l2 * co * co};
}

std::array<double, 3> sizes_of(const Metric& m) {
  const SymmetricEigen e = eigen(m);
  // The largest size belongs to the smallest eigenvalue, whose direction is θ + π/2.
  double theta = e.theta + M_PI / 2;
  if (theta > M_PI / 2) theta -= M_PI;
  return {1 / std::sqrt(e.l2), 1 / std::sqrt(e.l1), theta};
}

Matrix2 square_root(const Metric& m) {
  const SymmetricEigen e = eigen(m);
  const double s1 = std::sqrt(e.l1), s2 = std::sqrt(e.l2);
  const double co = std::cos(e.theta), si = std::sin(e.theta);
  const double off = (s1 - s2) * co * si;
  return {s1 * co * co + s2 * si * si, off, off, s1 * si * si + s2 * co * co};
}

double metric_length(const Metric& m, double dx, double dy) {
  return std::sqrt(std::max(0.0, m.a * dx * dx + 2 * m.b * dx * dy + m.c * dy * dy));
}

std::array<double, 2> generalized_eigenvalues(const Metric& m, const Metric& n) {
  // det(M − λN) = det(N)·λ² − (a_M c_N + c_M a_N − 2 b_M b_N)·λ + det(M).
  const double qa = n.a * n.c - n.b * n.b;
  const double qb = m.a * n.c + m.c * n.a - 2 * m.b * n.b;
  const double qc = m.a * m.c - m.b * m.b;
  // Both roots are real and positive for SPD M, N; clamp the discriminant against rounding.
  const double disc = std::sqrt(std::max(0.0, qb * qb - 4 * qa * qc));
  const double big = (qb + disc) / (2 * qa);
  const double small = qc / (qa * big);  // product of the roots is det M / det N
  return {small, big};
}

double distortion(const Metric& m, const Metric& n) {
  const auto [lo, hi] = generalized_eigenvalues(m, n);
  return std::sqrt(std::max({hi, 1 / lo, 1.0}));
}

Metric blend(const Metric& m, const Metric& n, double t) {
  return {(1 - t) * m.a + t * n.a, (1 - t) * m.b + t * n.b, (1 - t) * m.c + t * n.c};
}

}  // namespace laguerre::core
