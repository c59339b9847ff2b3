#include "laguerre/core/packing/Newton.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

namespace laguerre::core {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;
constexpr double fd_step = 1e-5;  // central-difference step in s = log h

// Residuals r(v) = θ(v) − 2π over the interior vertices (row order), and their squared norm.
double residuals(const PackingComplex& k, const Radii& h, const std::vector<Vertex>& interior, Eigen::VectorXd& r) {
  r.resize(static_cast<Eigen::Index>(interior.size()));
  const std::vector<double> theta = angle_sums(k, h);
  double norm2 = 0;
  for (std::size_t i = 0; i < interior.size(); ++i) {
    const double e = theta[interior[i]] - two_pi;
    r[static_cast<Eigen::Index>(i)] = e;
    norm2 += e * e;
  }
  return norm2;
}
}  // namespace

NewtonStep newton_step(const PackingComplex& k, Radii& h) {
  const PlanarGraph& g = k.graph;
  NewtonStep out;
  std::vector<Vertex> interior;
  std::vector<Eigen::Index> row(g.num_vertices(), -1);
  for (Vertex v = 0; v < g.num_vertices(); ++v)
    if (!g.is_boundary(v)) {
      row[v] = static_cast<Eigen::Index>(interior.size());
      interior.push_back(v);
    }
  if (interior.empty()) return out;
  Eigen::VectorXd r;
  const double norm0 = residuals(k, h, interior, r);
  out.error_before = out.error_after = r.cwiseAbs().maxCoeff();

  // J = ∂θ/∂s by central differences, corner by corner: the angle at v of triangle (v, a, b)
  // depends on h_v, h_a and h_b only; horocycles (boundary) are not unknowns.
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<Lift> lifts(h.size());
  for (Vertex v = 0; v < h.size(); ++v) lifts[v] = lift(h[v]);
  for (Vertex v : interior) {
    const Dart first = g.first_dart(v);
    const std::uint32_t deg = g.degree(v);
    for (std::uint32_t i = 0; i < deg; ++i) {
      const std::uint32_t j = i + 1 == deg ? 0 : i + 1;
      const Vertex a = g.head(first + i), b = g.head(first + j);
      const double cva = k.cos_angle[first + i], cvb = k.cos_angle[first + j];
      const double cab = k.cos_angle[g.next_in_face(first + i)];
      const Vertex corner[3] = {v, a, b};
      for (int c = 0; c < 3; ++c) {
        const Vertex w = corner[c];
        if (g.is_boundary(w)) continue;
        Lift lv[2] = {lifts[v], lifts[v]}, la[2] = {lifts[a], lifts[a]}, lb[2] = {lifts[b], lifts[b]};
        Lift* target = c == 0 ? lv : c == 1 ? la : lb;
        target[0] = lift(h[w] * std::exp(fd_step));
        target[1] = lift(h[w] * std::exp(-fd_step));
        const double up = overlap_angle(lv[0], la[0], lb[0], cva, cvb, cab);
        const double down = overlap_angle(lv[1], la[1], lb[1], cva, cvb, cab);
        entries.emplace_back(row[v], row[w], (up - down) / (2 * fd_step));
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(interior.size());
  Eigen::SparseMatrix<double> jac(n, n);
  jac.setFromTriplets(entries.begin(), entries.end());  // sums the corner contributions
  jac.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(jac);
  if (lu.info() != Eigen::Success) return out;
  const Eigen::VectorXd delta = lu.solve(-r);
  if (lu.info() != Eigen::Success || !delta.allFinite()) return out;

  // Damped step: at most a factor e² per radius, halved until ‖θ − 2π‖₂ decreases.
  double t = std::min(1.0, 2.0 / std::max(1e-300, delta.cwiseAbs().maxCoeff()));
  Radii trial = h;
  for (int halving = 0; halving < 40; ++halving, t *= 0.5) {
    for (std::size_t i = 0; i < interior.size(); ++i)
      trial[interior[i]] = h[interior[i]] * std::exp(t * delta[static_cast<Eigen::Index>(i)]);
    Eigen::VectorXd rt;
    const double norm = residuals(k, trial, interior, rt);
    if (norm < norm0) {
      h.swap(trial);
      out.improved = true;
      out.error_after = rt.cwiseAbs().maxCoeff();
      out.halvings = halving;
      return out;
    }
  }
  return out;
}

}  // namespace laguerre::core
