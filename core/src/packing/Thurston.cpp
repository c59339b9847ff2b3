#include "laguerre/core/packing/Thurston.hpp"

#include <algorithm>
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

// Solve θ(v; √X = t) = 2π for t ∈ (0, 1); θ increases with t. Secant iterations started at the
// current value (which is close to the answer once the iteration settles, so 2–4 evaluations suffice),
// kept inside a bracket [lo, hi] that every evaluation tightens, with bisection whenever a secant step
// would leave it. Deterministic: the same inputs give the same bits.
double solve_exact(const PackingComplex& k, const Radii& X, Vertex v) {
  double lo = 0, hi = 1;
  auto f = [&](double t) { return angle_sum_at(k, X, v, t * t) - two_pi; };
  auto tighten = [&](double t, double ft) {
    if (ft < 0) lo = std::max(lo, t);
    else hi = std::min(hi, t);
  };
  double t0 = std::sqrt(X[v]);
  if (!(t0 > 0 && t0 < 1)) t0 = 0.5;
  double f0 = f(t0);
  tighten(t0, f0);
  double t1 = std::clamp(t0 * (f0 < 0 ? 1.0009765625 : 0.9990234375), 1e-300, 1 - 1e-16);
  double f1 = f(t1);
  tighten(t1, f1);
  for (int it = 0; it < 100; ++it) {
    if (f1 == 0 || hi - lo <= 4e-16 * hi) return t1 * t1;
    double t2 = f1 != f0 ? t1 - f1 * (t1 - t0) / (f1 - f0) : 0.5 * (lo + hi);
    if (!(t2 > lo && t2 < hi)) t2 = 0.5 * (lo + hi);
    if (std::abs(t2 - t1) <= 1e-16 * t1) return t2 * t2;
    t0 = t1;
    f0 = f1;
    t1 = t2;
    f1 = f(t1);
    tighten(t1, f1);
  }
  return t1 * t1;
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
