#include "laguerre/core/packing/Thurston.hpp"

#include <cmath>
#include <numbers>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

namespace laguerre::core {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;

// Angle sum at v if v had value xv, neighbours as in X.
double angle_sum_at(const PackingComplex& k, const Radii& X, Vertex v, double xv) {
  const PlanarGraph& g = k.graph;
  const Dart first = g.first_dart(v);
  const std::uint32_t deg = g.degree(v);
  double sum = 0;
  if (k.tangent_only[v]) {
    for (std::uint32_t i = 0; i < deg; ++i) {
      const std::uint32_t j = i + 1 == deg ? 0 : i + 1;
      sum += tangent_angle(xv, X[g.head(first + i)], X[g.head(first + j)]);
    }
    return sum;
  }
  for (std::uint32_t i = 0; i < deg; ++i) {
    const Dart a = first + i;                                   // v→y
    const Dart b = first + (i + 1 == deg ? 0 : i + 1);          // v→z, next counter-clockwise
    const Dart yz = g.next_in_face(a);                          // y→z closes the triangle left of v→y
    sum += overlap_angle(xv, X[g.head(a)], X[g.head(b)], k.cos_angle[a], k.cos_angle[b], k.cos_angle[yz]);
  }
  return sum;
}

// Solve θ(v; √X = t) = 2π on t ∈ (0, 1) by the Illinois variant of regula falsi (θ increases with t).
double solve_exact(const PackingComplex& k, const Radii& X, Vertex v) {
  double lo = 0, hi = 1;
  double flo = -two_pi;                                                   // θ(0) = 0 (infinite radius)
  double fhi = angle_sum_at(k, X, v, 1 - 1e-15) - two_pi;                 // vanishing radius: ≥ π·deg − 2π
  double t = std::sqrt(X[v]);
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    t = (lo * fhi - hi * flo) / (fhi - flo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double ft = angle_sum_at(k, X, v, t * t) - two_pi;
    if (ft == 0) break;
    if (ft < 0) {
      lo = t;
      flo = ft;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = t;
      fhi = ft;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
  return t * t;
}
}  // namespace

Radii initial_radii(const PackingComplex& k) {
  Radii X(k.graph.num_vertices(), x_of_radius(1.0));
  for (Vertex v = 0; v < X.size(); ++v)
    if (k.graph.is_boundary(v)) X[v] = 0;
  return X;
}

double angle_sum(const PackingComplex& k, const Radii& X, Vertex v) { return angle_sum_at(k, X, v, X[v]); }

double angle_error(const PackingComplex& k, const Radii& X) {
  double err = 0;
  for (Vertex v = 0; v < X.size(); ++v)
    if (!k.graph.is_boundary(v)) err = std::max(err, std::abs(angle_sum(k, X, v) - two_pi));
  return err;
}

double updated_radius(const PackingComplex& k, const Radii& X, Vertex v, UpdateRule rule) {
  if (rule == UpdateRule::uniform_neighbour && k.tangent_only[v])
    return uniform_neighbour_update(X[v], angle_sum(k, X, v), static_cast<int>(k.graph.degree(v)));
  return solve_exact(k, X, v);
}

void thurston_sweep(const PackingComplex& k, Radii& X, Sweep sweep, UpdateRule rule, Radii& scratch) {
  const std::size_t n = X.size();
  if (sweep == Sweep::gauss_seidel) {
    for (Vertex v = 0; v < n; ++v)
      if (!k.graph.is_boundary(v)) X[v] = updated_radius(k, X, v, rule);
    return;
  }
  scratch = X;
  for (Vertex v = 0; v < n; ++v)
    if (!k.graph.is_boundary(v)) scratch[v] = updated_radius(k, X, v, rule);
  X.swap(scratch);
}

}  // namespace laguerre::core
