#include "laguerre/core/packing/Thurston.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

namespace laguerre::core {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;

// The angle sum at a vertex of degree `deg` and value xv, summed counter-clockwise from neighbour 0.
// `x_of(i)` is the X of neighbour i; `spoke(i)` the cosine on edge v–neighbour i and `rim(i)` the
// cosine on edge neighbour i – neighbour i+1 (read only when !tangent_only). The centralized and the
// node-local callers differ only in where they read these values from, so both evaluate the very same
// floating-point operations in the same order.
template <class XOf, class Spoke, class Rim>
double star_sum(double xv, std::uint32_t deg, bool tangent_only, const XOf& x_of, const Spoke& spoke,
                const Rim& rim) {
  double sum = 0;
  if (tangent_only) {
    for (std::uint32_t i = 0; i < deg; ++i) {
      const std::uint32_t j = i + 1 == deg ? 0 : i + 1;
      sum += tangent_angle(xv, x_of(i), x_of(j));
    }
    return sum;
  }
  for (std::uint32_t i = 0; i < deg; ++i) {
    const std::uint32_t j = i + 1 == deg ? 0 : i + 1;  // next counter-clockwise
    sum += overlap_angle(xv, x_of(i), x_of(j), spoke(i), spoke(j), rim(i));
  }
  return sum;
}

// Angle sum at v if v had value xv, neighbours as in X.
double angle_sum_at(const PackingComplex& k, const Radii& X, Vertex v, double xv) {
  const PlanarGraph& g = k.graph;
  const Dart first = g.first_dart(v);
  // Dart first+i is v→y; next_in_face(v→y) is y→z, the rim edge closing the triangle left of v→y.
  return star_sum(
      xv, g.degree(v), k.tangent_only[v] != 0, [&](std::uint32_t i) { return X[g.head(first + i)]; },
      [&](std::uint32_t i) { return k.cos_angle[first + i]; },
      [&](std::uint32_t i) { return k.cos_angle[g.next_in_face(first + i)]; });
}

double star_angle_sum_at(const StarView& s, double xv) {
  return star_sum(
      xv, static_cast<std::uint32_t>(s.neighbour_x.size()), s.cos_spoke.empty(),
      [&](std::uint32_t i) { return s.neighbour_x[i]; }, [&](std::uint32_t i) { return s.cos_spoke[i]; },
      [&](std::uint32_t i) { return s.cos_rim[i]; });
}

// Solve θ(v; √X = t) = 2π for t ∈ (0, 1), where `theta(X)` is the angle sum at v with value X; θ
// increases with t. Secant iterations started at the current value `xv` (which is close to the answer
// once the iteration settles, so 2–4 evaluations suffice), kept inside a bracket [lo, hi] that every
// evaluation tightens, with bisection whenever a secant step would leave it. Deterministic: the same
// inputs give the same bits.
template <class Theta>
double solve_exact(double xv, const Theta& theta) {
  double lo = 0, hi = 1;
  auto f = [&](double t) { return theta(t * t) - two_pi; };
  auto tighten = [&](double t, double ft) {
    if (ft < 0) lo = std::max(lo, t);
    else hi = std::min(hi, t);
  };
  double t0 = std::sqrt(xv);
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
  return solve_exact(X[v], [&](double xv) { return angle_sum_at(k, X, v, xv); });
}

double star_angle_sum(double xv, const StarView& s) { return star_angle_sum_at(s, xv); }

double star_updated_radius(double xv, const StarView& s, UpdateRule rule) {
  if (rule == UpdateRule::uniform_neighbour && s.cos_spoke.empty())
    return uniform_neighbour_update(xv, star_angle_sum_at(s, xv), static_cast<int>(s.neighbour_x.size()));
  return solve_exact(xv, [&](double x) { return star_angle_sum_at(s, x); });
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
