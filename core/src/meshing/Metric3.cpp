#include "laguerre/core/meshing/Metric3.hpp"

#include "laguerre/core/Error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace laguerre::core {

namespace {

Eigen::Matrix3d matrix(const Metric3& m) {
  Eigen::Matrix3d a;
  a << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
  return a;
}

}  // namespace

bool is_metric(const Metric3& m) {
  for (double v : {m.xx, m.xy, m.xz, m.yy, m.yz, m.zz})
    if (!std::isfinite(v)) return false;
  const double minor2 = m.xx * m.yy - m.xy * m.xy;
  const double det = m.xx * (m.yy * m.zz - m.yz * m.yz) - m.xy * (m.xy * m.zz - m.yz * m.xz) +
                     m.xz * (m.xy * m.yz - m.yy * m.xz);
  if (!(m.xx > 0 && minor2 > 0 && det > 0)) return false;
  // Sylvester's criterion in doubles can accept a matrix whose smallest eigenvalue is rounding noise:
  // require the eigenvalues themselves to be positive.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(matrix(m), Eigen::EigenvaluesOnly);
  return e.eigenvalues()(0) > 0;
}

Metric3 metric3_from_sizes(double h1, double h2, double h3, const Matrix3& r) {
  for (double h : {h1, h2, h3})
    if (!(h > 0) || !std::isfinite(h)) throw InputError("metric sizes must be positive and finite");
  const double l[3] = {1 / (h1 * h1), 1 / (h2 * h2), 1 / (h3 * h3)};
  auto entry = [&](int i, int j) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += r[static_cast<std::size_t>(3 * i + k)] * l[k] * r[static_cast<std::size_t>(3 * j + k)];
    return s;
  };
  return {entry(0, 0), entry(0, 1), entry(0, 2), entry(1, 1), entry(1, 2), entry(2, 2)};
}

std::array<double, 3> sizes_of(const Metric3& m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(matrix(m), Eigen::EigenvaluesOnly);
  const auto& l = e.eigenvalues();  // increasing
  return {1 / std::sqrt(l(0)), 1 / std::sqrt(l(1)), 1 / std::sqrt(l(2))};
}

Matrix3 square_root(const Metric3& m) {
  // Diagonal metrics (every built-in field but the sphere's) get the exact square roots of their
  // entries: stretched coordinates are then exact scalings, which keeps coplanar sites coplanar.
  if (m.xy == 0 && m.xz == 0 && m.yz == 0) return {std::sqrt(m.xx), 0, 0, 0, std::sqrt(m.yy), 0, 0, 0, std::sqrt(m.zz)};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(matrix(m));
  const Eigen::Matrix3d f = e.eigenvectors() * e.eigenvalues().cwiseMax(0).cwiseSqrt().asDiagonal() *
                            e.eigenvectors().transpose();
  Matrix3 out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[static_cast<std::size_t>(3 * i + j)] = f(i, j);
  return out;
}

std::array<double, 3> solve(const Matrix3& f, const std::array<double, 3>& v) {
  const double c00 = f[4] * f[8] - f[5] * f[7], c01 = f[5] * f[6] - f[3] * f[8], c02 = f[3] * f[7] - f[4] * f[6];
  const double det = f[0] * c00 + f[1] * c01 + f[2] * c02;
  const double c10 = f[2] * f[7] - f[1] * f[8], c11 = f[0] * f[8] - f[2] * f[6], c12 = f[1] * f[6] - f[0] * f[7];
  const double c20 = f[1] * f[5] - f[2] * f[4], c21 = f[2] * f[3] - f[0] * f[5], c22 = f[0] * f[4] - f[1] * f[3];
  // inverse = adjugate / det, adjugate = cofactor matrixᵀ
  return {(c00 * v[0] + c10 * v[1] + c20 * v[2]) / det, (c01 * v[0] + c11 * v[1] + c21 * v[2]) / det,
          (c02 * v[0] + c12 * v[1] + c22 * v[2]) / det};
}

std::array<double, 2> generalized_eigenvalues(const Metric3& m, const Metric3& n) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> e(matrix(m), matrix(n), Eigen::EigenvaluesOnly);
  return {e.eigenvalues()(0), e.eigenvalues()(2)};
}

double distortion(const Metric3& m, const Metric3& n) {
  const auto [lo, hi] = generalized_eigenvalues(m, n);
  return std::sqrt(std::max({hi, 1 / lo, 1.0}));
}

Metric3 blend(const Metric3& m, const Metric3& n, double t) {
  const double s = 1 - t;
  return {s * m.xx + t * n.xx, s * m.xy + t * n.xy, s * m.xz + t * n.xz,
          s * m.yy + t * n.yy, s * m.yz + t * n.yz, s * m.zz + t * n.zz};
}

}  // namespace laguerre::core
