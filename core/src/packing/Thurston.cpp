#include "laguerre/core/packing/Thurston.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

namespace laguerre::core {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;

// The angle sum at a vertex of degree `deg` and radius lift lv, summed counter-clockwise from
// neighbour 0. `lift_of(i)` is the lift of neighbour i; `spoke(i)` the cosine on edge v–neighbour i
// and `rim(i)` the cosine on edge neighbour i – neighbour i+1 (read only when !tangent_only). The
// centralized and the node-local callers differ only in where they read these values from, so both
// evaluate the very same floating-point operations in the same order.
template <class LiftOf, class Spoke, class Rim>
double star_sum(Lift lv, std::uint32_t deg, bool tangent_only, const LiftOf& lift_of, const Spoke& spoke,
                const Rim& rim) {
  double sum = 0;
  if (tangent_only) {
    for (std::uint32_t i = 0; i < deg; ++i) {
      const std::uint32_t j = i + 1 == deg ? 0 : i + 1;
      sum += tangent_angle(lv, lift_of(i), lift_of(j));
    }
    return sum;
  }
  for (std::uint32_t i = 0; i < deg; ++i) {
    const std::uint32_t j = i + 1 == deg ? 0 : i + 1;  // next counter-clockwise
    sum += overlap_angle(lv, lift_of(i), lift_of(j), spoke(i), spoke(j), rim(i));
  }
  return sum;
}

// Angle sum at v if v had radius hv, neighbours lifted as in `lifts`.
double angle_sum_lifted(const PackingComplex& k, const std::vector<Lift>& lifts, Vertex v, double hv) {
  const PlanarGraph& g = k.graph;
  const Dart first = g.first_dart(v);
  // Dart first+i is v→y; next_in_face(v→y) is y→z, the rim edge closing the triangle left of v→y.
  return star_sum(
      lift(hv), g.degree(v), k.tangent_only[v] != 0, [&](std::uint32_t i) { return lifts[g.head(first + i)]; },
      [&](std::uint32_t i) { return k.cos_angle[first + i]; },
      [&](std::uint32_t i) { return k.cos_angle[g.next_in_face(first + i)]; });
}

double star_angle_sum_lifted(const StarView& s, const std::vector<Lift>& lifts, double hv) {
  return star_sum(
      lift(hv), static_cast<std::uint32_t>(s.neighbour_h.size()), s.cos_spoke.empty(),
      [&](std::uint32_t i) { return lifts[i]; }, [&](std::uint32_t i) { return s.cos_spoke[i]; },
      [&](std::uint32_t i) { return s.cos_rim[i]; });
}

// Solve θ(v; h = e^s) = 2π for s = log h, where `theta(h)` is the angle sum at v with radius h; θ
// decreases with s. Secant iterations started at the current radius `hv` (close to the answer once
// the iteration settles, so 2–4 evaluations suffice), kept inside a bracket [lo, hi] that every
// evaluation tightens, with bisection whenever a secant step would leave it. log h is the natural
// scale for both vanishing circles and near-horocycles. Deterministic: the same inputs give the
// same bits.
template <class Theta>
double solve_exact(double hv, const Theta& theta) {
  double lo = -700, hi = 700;  // h from 10^-304 to 10^304: θ > 2π at lo and θ < 2π at hi
  auto f = [&](double s) { return theta(std::exp(s)) - two_pi; };
  auto tighten = [&](double s, double fs) {
    if (fs > 0) lo = std::max(lo, s);  // circle too small: the answer is larger
    else hi = std::min(hi, s);
  };
  double s0 = hv > 0 && std::isfinite(hv) ? std::log(hv) : 0.0;
  s0 = std::clamp(s0, lo, hi);
  double f0 = f(s0);
  tighten(s0, f0);
  double s1 = s0 + (f0 > 0 ? 0x1p-10 : -0x1p-10);
  double f1 = f(s1);
  tighten(s1, f1);
  for (int it = 0; it < 200; ++it) {
    const double scale = std::max(1.0, std::abs(s1));
    if (f1 == 0 || hi - lo <= 4e-16 * scale) return std::exp(s1);
    double s2 = f1 != f0 ? s1 - f1 * (s1 - s0) / (f1 - f0) : 0.5 * (lo + hi);
    if (!(s2 > lo && s2 < hi)) s2 = 0.5 * (lo + hi);
    if (std::abs(s2 - s1) <= 2e-16 * scale) return std::exp(s2);
    s0 = s1;
    f0 = f1;
    s1 = s2;
    f1 = f(s1);
    tighten(s1, f1);
  }
  return std::exp(s1);
}

std::vector<Lift> lift_all(const Radii& h) {
  std::vector<Lift> out(h.size());
  for (std::size_t v = 0; v < h.size(); ++v) out[v] = lift(h[v]);
  return out;
}

double updated_lifted(const PackingComplex& k, const Radii& h, const std::vector<Lift>& lifts, Vertex v,
                      UpdateRule rule) {
  if (rule == UpdateRule::uniform_neighbour && k.tangent_only[v])
    return uniform_neighbour_update(h[v], angle_sum_lifted(k, lifts, v, h[v]), static_cast<int>(k.graph.degree(v)));
  return solve_exact(h[v], [&](double hv) { return angle_sum_lifted(k, lifts, v, hv); });
}
}  // namespace

Radii initial_radii(const PackingComplex& k) {
  Radii h(k.graph.num_vertices(), 1.0);
  for (Vertex v = 0; v < h.size(); ++v)
    if (k.graph.is_boundary(v)) h[v] = std::numeric_limits<double>::infinity();
  return h;
}

double angle_sum(const PackingComplex& k, const Radii& h, Vertex v) {
  return angle_sum_lifted(k, lift_all(h), v, h[v]);
}

std::vector<double> angle_sums(const PackingComplex& k, const Radii& h) {
  const std::vector<Lift> lifts = lift_all(h);
  std::vector<double> out(h.size(), 0.0);
  for (Vertex v = 0; v < h.size(); ++v)
    if (!k.graph.is_boundary(v)) out[v] = angle_sum_lifted(k, lifts, v, h[v]);
  return out;
}

double angle_error(const PackingComplex& k, const Radii& h) {
  const std::vector<Lift> lifts = lift_all(h);
  double err = 0;
  for (Vertex v = 0; v < h.size(); ++v)
    if (!k.graph.is_boundary(v)) err = std::max(err, std::abs(angle_sum_lifted(k, lifts, v, h[v]) - two_pi));
  return err;
}

double updated_radius(const PackingComplex& k, const Radii& h, Vertex v, UpdateRule rule) {
  return updated_lifted(k, h, lift_all(h), v, rule);
}

namespace {
// The neighbours' lifts of a node-local star, in a per-thread buffer: a node updates once per step,
// and the update should not allocate.
const std::vector<Lift>& star_lifts(const StarView& s) {
  thread_local std::vector<Lift> lifts;
  lifts.resize(s.neighbour_h.size());
  for (std::size_t i = 0; i < lifts.size(); ++i) lifts[i] = lift(s.neighbour_h[i]);
  return lifts;
}
}  // namespace

double star_angle_sum(double hv, const StarView& s) { return star_angle_sum_lifted(s, star_lifts(s), hv); }

double star_updated_radius(double hv, const StarView& s, UpdateRule rule) {
  const std::vector<Lift>& lifts = star_lifts(s);
  if (rule == UpdateRule::uniform_neighbour && s.cos_spoke.empty())
    return uniform_neighbour_update(hv, star_angle_sum_lifted(s, lifts, hv), static_cast<int>(lifts.size()));
  return solve_exact(hv, [&](double x) { return star_angle_sum_lifted(s, lifts, x); });
}

void thurston_sweep(const PackingComplex& k, Radii& h, Sweep sweep, UpdateRule rule, Radii& scratch) {
  const std::size_t n = h.size();
  std::vector<Lift> lifts = lift_all(h);
  if (sweep == Sweep::gauss_seidel) {
    for (Vertex v = 0; v < n; ++v)
      if (!k.graph.is_boundary(v)) {
        h[v] = updated_lifted(k, h, lifts, v, rule);
        lifts[v] = lift(h[v]);
      }
    return;
  }
  scratch = h;
  for (Vertex v = 0; v < n; ++v)
    if (!k.graph.is_boundary(v)) scratch[v] = updated_lifted(k, h, lifts, v, rule);
  h.swap(scratch);
}

}  // namespace laguerre::core
