#include "laguerre/core/packing/Accelerator.hpp"
#include "laguerre/core/packing/PackingNames.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace laguerre::core {

std::string_view to_string(Acceleration a) { return name_of(acceleration_names, a); }

Acceleration parse_acceleration(std::string_view name) { return parse_name(acceleration_names, name); }

bool Accelerator::after_sweep(const PackingComplex& k, const Radii& before, Radii& after) {
  switch (kind_) {
    case Acceleration::plain:
    case Acceleration::chebyshev:
    case Acceleration::local_superstep:  // per vertex: LocalAccelerator
    case Acceleration::newton:
    case Acceleration::newton_krylov: return false;  // pack() takes Newton steps instead of sweeps
    case Acceleration::superstep: return superstep(k, before, after);
    case Acceleration::anderson: return anderson(k, before, after);
  }
  return false;
}

bool Accelerator::superstep(const PackingComplex& k, const Radii& before, Radii& after) {
  const std::size_t n = after.size();
  previous_.resize(n, 0.0);
  double dot = 0, norm_now = 0, norm_prev = 0;
  std::vector<double>& delta = scratch_;
  delta.assign(n, 0.0);
  for (Vertex v = 0; v < n; ++v) {
    if (k.graph.is_boundary(v)) continue;
    const double d = 2 * (before[v] - after[v]);  // Δy in y = log X = −2h
    delta[v] = d;
    norm_now += d * d;
    dot += d * previous_[v];
    norm_prev += previous_[v] * previous_[v];
  }
  const bool had = has_previous_;
  previous_.swap(delta);
  has_previous_ = true;
  if (!had || norm_prev == 0 || norm_now == 0) return false;
  const double lambda = std::sqrt(norm_now / norm_prev);
  const double cosine = dot / std::sqrt(norm_now * norm_prev);
  if (!(lambda < 1) || cosine < 0.95) return false;
  double factor = std::min(50.0, lambda / (1 - lambda));
  // Keep every hyperbolic radius above half its value: y' = y + f Δ ≤ y / 2 where Δ > 0.
  for (Vertex v = 0; v < n; ++v) {
    const double d = previous_[v];
    if (d > 0) factor = std::min(factor, after[v] / d);
  }
  if (!(factor > 0)) return false;
  for (Vertex v = 0; v < n; ++v)
    if (!k.graph.is_boundary(v)) after[v] = -0.5 * (-2 * after[v] + factor * previous_[v]);
  has_previous_ = false;
  ++jumps_;
  return true;
}

bool Accelerator::anderson(const PackingComplex& k, const Radii& before, Radii& after) {
  constexpr std::size_t m = 6;
  if (interior_.empty())
    for (Vertex v = 0; v < after.size(); ++v)
      if (!k.graph.is_boundary(v)) interior_.push_back(v);
  const std::size_t ni = interior_.size();
  if (ni == 0) return false;
  // Residual f = F(y) − y and image g = F(y), in y = log X.
  std::vector<double> f(ni), g(ni);
  double norm = 0;
  for (std::size_t i = 0; i < ni; ++i) {
    const Vertex v = interior_[i];
    g[i] = -2 * after[v];
    f[i] = g[i] + 2 * before[v];
    norm += f[i] * f[i];
  }
  norm = std::sqrt(norm);
  const bool restart = last_f_.empty() || !(norm <= 10 * last_norm_);
  if (restart) {
    dF_.clear();
    dG_.clear();
  } else {
    std::vector<double> df(ni), dg(ni);
    for (std::size_t i = 0; i < ni; ++i) {
      df[i] = f[i] - last_f_[i];
      dg[i] = g[i] - last_g_[i];
    }
    dF_.push_back(std::move(df));
    dG_.push_back(std::move(dg));
    if (dF_.size() > m) {
      dF_.erase(dF_.begin());
      dG_.erase(dG_.begin());
    }
  }
  last_f_ = f;
  last_g_ = g;
  last_norm_ = norm;
  const std::size_t cols = dF_.size();
  if (cols == 0) return false;
  // γ = argmin |f − ΔF γ|: normal equations with a small Tikhonov term for conditioning.
  Eigen::MatrixXd gram(cols, cols);
  Eigen::VectorXd rhs(cols);
  for (std::size_t a = 0; a < cols; ++a) {
    double r = 0;
    for (std::size_t i = 0; i < ni; ++i) r += dF_[a][i] * f[i];
    rhs[static_cast<Eigen::Index>(a)] = r;
    for (std::size_t b = 0; b <= a; ++b) {
      double s = 0;
      for (std::size_t i = 0; i < ni; ++i) s += dF_[a][i] * dF_[b][i];
      gram(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = s;
      gram(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(a)) = s;
    }
  }
  const double trace = gram.trace();
  gram.diagonal().array() += 1e-10 * trace / static_cast<double>(cols) + 1e-300;
  const Eigen::VectorXd gamma = gram.ldlt().solve(rhs);
  if (!gamma.allFinite()) return false;
  // y_{k+1} = g − ΔG γ, with every hyperbolic radius kept above half its current value.
  bool changed = false;
  for (std::size_t i = 0; i < ni; ++i) {
    double y = g[i];
    for (std::size_t a = 0; a < cols; ++a) y -= dG_[a][i] * gamma[static_cast<Eigen::Index>(a)];
    y = std::min(y, 0.5 * g[i]);
    if (!std::isfinite(y)) return false;
    const Vertex v = interior_[i];
    const double h = -0.5 * y;
    changed |= h != after[v];
    after[v] = h;
  }
  if (changed) ++jumps_;
  return changed;
}

namespace {
constexpr double stable_tolerance = 0.04;  // |q − q_prev| ≤ this × (1 − q)
constexpr int stable_needed = 1;           // window ratios agreeing with their predecessor
constexpr double max_rho = 1 - 1e-9;
constexpr int max_restarts = 20;
}  // namespace

bool LocalAccelerator::stable_ratio(double d, double& q) {
  // The ratio over the last `window` steps, (d_k / d_{k−w})^{1/w}, from residuals of one sign: the
  // oscillations that accelerated neighbours feed in average out over the window.
  for (int i = window - 1; i > 0; --i) history_[i] = history_[i - 1];
  history_[0] = d;
  if (seen_ < window) ++seen_;
  bool same_sign = seen_ == window;
  for (int i = 1; i < seen_ && same_sign; ++i) same_sign = (history_[i] > 0) == (d > 0) && history_[i] != 0;
  if (!same_sign || d == 0) {
    has_q_ = false;
    stable_ = 0;
    return false;
  }
  q = std::pow(d / history_[window - 1], 1.0 / (window - 1));
  if (q > 0 && q < 1 && has_q_ && std::abs(q - last_q_) <= stable_tolerance * (1 - q)) ++stable_;
  else stable_ = 0;
  last_q_ = q;
  has_q_ = true;
  return stable_ >= stable_needed;
}

double LocalAccelerator::next(double h, double f) {
  accelerated_ = false;
  if (kind_ != Acceleration::chebyshev && kind_ != Acceleration::local_superstep) return f;
  const double d = f - h;  // the residual of the plain map at this vertex (Δy = −2d in y = log X)
  double q = 0;
  const bool stable = stable_ratio(d, q);
  double out = f;
  if (kind_ == Acceleration::chebyshev) {
    // Only a mode clearly outside the circle |μ| = √(ω − 1) tells something: inside it, any ratio
    // q ≠ μ would give λ > ρ and ratchet ρ towards 1 (and the rate √(ω − 1) towards 1 with it).
    const double mu = std::sqrt(omega_ - 1);
    if (stable && q > mu + 0.25 * (1 - mu)) {
      const double lambda = (q * q + omega_ - 1) / (omega_ * q);
      if (lambda > rho_) {
        rho_ = std::min(lambda, max_rho);
        omega_ = 2 / (1 + std::sqrt(1 - rho_ * rho_));
      }
    }
    if (has_previous_) out = previous_ + omega_ * (f - previous_);
    previous_ = h;
    has_previous_ = true;
  } else if (stable) {
    out = f + std::min(50.0, q / (1 - q)) * d;
    seen_ = 0;  // after a jump the next ratio would mix two regimes
    has_q_ = false;
    stable_ = 0;
  }
  if (out == f) return f;
  if (!(out >= 0.5 * f && out <= 2 * f)) {
    // The safeguard: the plain update, a fresh history, and after max_restarts plain for good.
    has_previous_ = false;
    seen_ = 0;
    has_q_ = false;
    stable_ = 0;
    if (++restarts_ >= max_restarts) kind_ = Acceleration::plain;
    return f;
  }
  accelerated_ = true;
  return out;
}

}  // namespace laguerre::core
