#include "laguerre/core/packing/NewtonKrylov.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "laguerre/core/packing/Newton.hpp"

// Conjugate gradients in the Chronopoulos–Gear form (one global reduction per iteration instead of
// two): with M = diag(A) (Jacobi), x_0 = 0, r_0 = b = θ − 2π, z_0 = M⁻¹ r_0,
//     w_i = A z_i                                  (one neighbour exchange of z)
//     γ_i = (r_i, z_i), δ_i = (z_i, w_i), ρ_i = (r_i, r_i)  (one tree sum)
//     β_i = γ_i / γ_{i−1} (β_0 = 0),  α_i = γ_i / (δ_i − β_i γ_i / α_{i−1})  (α_0 = γ_0 / δ_0)
//     p_i = z_i + β_i p_{i−1},  s_i = w_i + β_i s_{i−1}   (s_i = A p_i)
//     x_{i+1} = x_i + α_i p_i,  r_{i+1} = r_i − α_i s_i,  z_{i+1} = M⁻¹ r_{i+1}
// In exact arithmetic these are PCG's iterates; ρ_i is the stop test ‖r_i‖ ≤ η ‖b‖ with the inexact-
// Newton forcing term η = clamp(‖b‖, 10⁻¹⁴, 0.9) (superlinear convergence as η → 0 with ‖b‖; 0.9 is
// Eisenstat and Walker's safeguard). Each CG iteration costs the network an exchange and a tree sum,
// so early Newton steps solve loosely: on uniform random maps of 500 / 5000 nodes (one seed each,
// triangulation and 3-connected) the cap 0.9 needs 180–262 / 2437–2527 CG iterations to LPD where
// NewtonSolver::pcg's cap 10⁻⁴ needs 963–1077 / 4751–5360, for up to 6 more Newton steps.
// (η = clamp(‖b‖^{1/2}, ·, 0.9) needed 1604–1972 at 5000 nodes, 215–218 at 500: not adopted yet.)
// The first sum also gives ‖θ − 2π‖² for the line search (ρ_0).

namespace laguerre::core {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;
constexpr double infinity = std::numeric_limits<double>::infinity();
}  // namespace

void combine(KrylovSums& into, const KrylovSums& child) {
  for (int i = 0; i < 3; ++i) into.sum[i] += child.sum[i];
  into.max = std::max(into.max, child.max);
}

KrylovDecision KrylovRoot::decide(const KrylovSums& total) {
  switch (stage_) {
    case Stage::cg: {
      const double gamma = total.sum[0], delta = total.sum[1], rr = total.sum[2];
      if (iterations_ == 0) {
        norm0_ = rr;
        if (!(norm0_ > 0) || !std::isfinite(norm0_)) return {KrylovAction::reject};
        const double eta = std::clamp(std::sqrt(norm0_), 1e-14, KrylovLimits::max_forcing);
        tol2_ = eta * eta * norm0_;
      } else if (!(rr > tol2_) || iterations_ >= KrylovLimits::max_cg) {
        stage_ = Stage::direction;
        return {KrylovAction::solved};
      }
      const double beta = iterations_ == 0 ? 0.0 : gamma / gamma_;
      const double alpha = gamma / (iterations_ == 0 ? delta : delta - beta * gamma / alpha_);
      if (!(alpha > 0) || !std::isfinite(alpha) || !std::isfinite(beta)) {  // breakdown
        if (iterations_ == 0) return {KrylovAction::reject};
        stage_ = Stage::direction;
        return {KrylovAction::solved};
      }
      gamma_ = gamma;
      alpha_ = alpha;
      ++iterations_;
      return {KrylovAction::iterate, alpha, beta};
    }
    case Stage::direction:
      if (!(total.max < infinity)) return {KrylovAction::reject};
      t_ = std::min(1.0, 2.0 / std::max(1e-300, total.max));  // at most a factor e² per radius
      stage_ = Stage::trial;
      return {KrylovAction::trial, t_};
    case Stage::trial:
      if (total.sum[0] < norm0_) return {KrylovAction::accept};
      if (++halvings_ >= KrylovLimits::max_halvings) return {KrylovAction::reject};
      t_ *= 0.5;
      return {KrylovAction::trial, t_};
  }
  return {KrylovAction::reject};
}

void KrylovVertex::begin(double h, const StarView& s) {
  h_ = h;
  r_ = star_angle_sum(h, s) - two_pi;
  diag_ = -star_jacobian_row(h, s, off_);
  for (double& a : off_) a = -a;
  x_ = p_ = s_ = w_ = delta_ = 0;
  z_ = r_ / diag_;
  trial_ = h;
  trial_mode_ = false;
}

KrylovSums KrylovVertex::cg_sums(const std::vector<double>& neighbour_z) {
  w_ = diag_ * z_;
  for (std::size_t i = 0; i < off_.size(); ++i) w_ += off_[i] * neighbour_z[i];
  KrylovSums out;
  out.sum[0] = r_ * z_;
  out.sum[1] = z_ * w_;
  out.sum[2] = r_ * r_;
  return out;
}

KrylovSums KrylovVertex::direction_sums() {
  delta_ = x_ * (h_ < 1e-8 ? 1.0 : std::sinh(h_) / h_);  // δs = δu · ds/du
  KrylovSums out;
  out.max = std::isfinite(delta_) ? std::abs(delta_) : infinity;
  return out;
}

KrylovSums KrylovVertex::trial_sums(const StarView& trial_star) const {
  const double e = star_angle_sum(trial_, trial_star) - two_pi;
  KrylovSums out;
  out.sum[0] = e * e;
  out.max = std::abs(e);
  return out;
}

double KrylovVertex::apply(const KrylovDecision& d, double plain) {
  switch (d.action) {
    case KrylovAction::iterate:
      p_ = z_ + d.b * p_;
      s_ = w_ + d.b * s_;
      x_ += d.a * p_;
      r_ -= d.a * s_;
      z_ = r_ / diag_;
      return h_;
    case KrylovAction::solved: return h_;
    case KrylovAction::trial:
      trial_mode_ = true;
      trial_ = h_ * std::exp(d.a * delta_);
      return h_;
    case KrylovAction::accept: return trial_;
    case KrylovAction::reject: return plain;
  }
  return h_;
}

// ---- The centralized reference ---------------------------------------------------------------------

namespace {
// The star of v in node-local form (cosines only where v touches an orthogonal edge), as the
// protocol vertex holds it, with neighbour values `value(w)`.
struct Star {
  std::vector<double> h, spoke, rim;
  template <class Value>
  StarView of(const PackingComplex& k, Vertex v, const Value& value) {
    const PlanarGraph& g = k.graph;
    const Dart first = g.first_dart(v);
    const std::uint32_t deg = g.degree(v);
    h.resize(deg);
    spoke.clear();
    rim.clear();
    for (std::uint32_t e = 0; e < deg; ++e) h[e] = value(g.head(first + e));
    if (!k.tangent_only[v])
      for (std::uint32_t e = 0; e < deg; ++e) {
        spoke.push_back(k.cos_angle[first + e]);
        rim.push_back(k.cos_angle[g.next_in_face(first + e)]);
      }
    return StarView{h, spoke, rim};
  }
};
}  // namespace

KrylovSums NewtonKrylovMethod::reduce(const PackingComplex& k, const Layout& tree) {
  // Children before parents; each vertex adds its children's partials in its neighbour order, as the
  // protocol vertex does once they are all in.
  const PlanarGraph& g = k.graph;
  for (Vertex v : order_) {
    const Dart first = g.first_dart(v);
    for (std::uint32_t e = 0; e < g.degree(v); ++e) {
      const Vertex w = g.head(first + e);
      if (w != tree.root && tree.parent[w] == v) combine(own_[v], own_[w]);
    }
  }
  return own_[tree.root];
}

KrylovStep NewtonKrylovMethod::step(const PackingComplex& k, Radii& h, const Layout& tree, UpdateRule rule) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = g.num_vertices();
  KrylovStep out;
  if (tree.root == none) return out;
  order_.resize(n);
  for (Vertex v = 0; v < n; ++v) order_[v] = v;
  // A child is placed in a later wave than its parent, except the root's first neighbour (wave 0 too):
  // the root goes last.
  std::stable_sort(order_.begin(), order_.end(), [&](Vertex a, Vertex b) {
    return std::make_pair(a != tree.root, tree.wave[a]) > std::make_pair(b != tree.root, tree.wave[b]);
  });
  vertices_.resize(n);
  Radii plain(h.size());
  Star star;
  for (Vertex v = 0; v < n; ++v)
    if (!g.is_boundary(v)) {
      const StarView s = star.of(k, v, [&](Vertex w) { return h[w]; });
      vertices_[v].begin(h[v], s);
      plain[v] = star_updated_radius(h[v], s, rule);
    }
  out.exchanges = 1;  // the radius exchange
  root_.reset();
  std::vector<double> values;
  KrylovAction next = KrylovAction::iterate;  // what the vertices do before the next sum
  for (;;) {
    own_.assign(n, KrylovSums{});
    if (next == KrylovAction::solved) {
      for (Vertex v = 0; v < n; ++v)
        if (!g.is_boundary(v)) own_[v] = vertices_[v].direction_sums();
    } else {
      ++out.exchanges;
      for (Vertex v = 0; v < n; ++v) {
        if (g.is_boundary(v)) continue;
        if (next == KrylovAction::trial) {
          own_[v] = vertices_[v].trial_sums(star.of(k, v, [&](Vertex w) { return g.is_boundary(w) ? infinity : vertices_[w].value(); }));
        } else {
          const Dart first = g.first_dart(v);
          values.resize(g.degree(v));
          for (std::uint32_t e = 0; e < g.degree(v); ++e) {
            const Vertex w = g.head(first + e);
            values[e] = g.is_boundary(w) ? 0.0 : vertices_[w].value();
          }
          own_[v] = vertices_[v].cg_sums(values);
        }
      }
    }
    ++out.sums;
    const KrylovDecision d = root_.decide(reduce(k, tree));
    out.trials += d.action == KrylovAction::trial;
    for (Vertex v = 0; v < n; ++v)
      if (!g.is_boundary(v)) {
        const double x = vertices_[v].apply(d, plain[v]);
        if (d.action == KrylovAction::accept || d.action == KrylovAction::reject) h[v] = x;
      }
    if (d.action == KrylovAction::accept || d.action == KrylovAction::reject) {
      out.improved = d.action == KrylovAction::accept;
      out.cg_iterations = root_.cg_iterations();
      return out;
    }
    next = d.action;
  }
}

}  // namespace laguerre::core
