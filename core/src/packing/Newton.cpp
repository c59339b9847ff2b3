#include "laguerre/core/packing/Newton.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#ifdef LAGUERRE_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>
#if defined(__SSE__) || defined(_M_X64)
#include <quadmath.h>
#include <xmmintrin.h>
#define LAGUERRE_HAVE_MXCSR 1
#endif

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

// The symmetric variable (derivation of the closed forms in angle_jacobian).
//
// Write S = sinh, C = cosh, T = tanh, and u = log tanh(h/2), so du = dh / S(h) and ∂/∂u = S(h) ∂/∂h.
//
// Tangency triangle (x, y, z), angle α at x. From sin²(α/2) = S(h_y) S(h_z) / (S(h_x+h_y) S(h_x+h_z))
// and d log sin²(α/2) = cot(α/2) dα, with coth a − coth b = S(b − a) / (S(a) S(b)):
//     ∂α/∂h_y = tan(α/2) S(h_x) / (S(h_y) S(h_x + h_y)).
// The incircle of the triangle of centres (radius ρ) touches the sides at the tangency points, so the
// right triangle (centre x, tangency point, incentre) has legs h_x and ρ: tan(α/2) = T(ρ) / S(h_x).
// Hence, with τ = T(ρ) a symmetric function of the triangle,
//     ∂α/∂u_y = τ / S(h_x + h_y),        ∂α/∂u_x = −τ (coth(h_x + h_y) + coth(h_x + h_z)),
// and ∂α_x/∂u_y = ∂α_y/∂u_x. In the lifts (X = e^{-2h}, X̄ = 1 − X) nothing cancels:
//     τ² = X̄ Ȳ Z̄ / (4 (1 − XYZ)),  1 − XYZ = X̄ + X Ȳ + X Y Z̄,
//     1 / S(h_x + h_y) = 2√(XY) / (1 − XY),  coth(h_x + h_y) = (1 + XY) / (1 − XY),  1 − XY = X̄ + X Ȳ.
// A horocycle y (Y = 0) gives ∂α_x/∂u_y = 0 and α_y ≡ 0: it only drops out.
//
// Triangles of G′ (x, y tangent, face circle f orthogonal to both; HyperbolicTriangle.hpp): the angle
// at x is atan(T(h_f) / S(h_x)), independent of h_y, and the angle at f is the sum of two such parts.
// For one right triangle (x, f):
//     ∂α_x/∂u_f = S_x S_f / (S_x² + S_f² + S_x² S_f²) =: w,   ∂α_x/∂u_x = −C_x C_f w,
// and the part of α_f in it, atan(T_x / S_f), has ∂/∂u_x = w as well (the denominator is symmetric).
// In the lifts, D = 4F X̄² + 4X F̄² + X̄² F̄²:  w = 4√(XF) X̄ F̄ / D,  C_x C_f w = (1+X)(1+F) X̄ F̄ / D.
//
// Definiteness. Per triangle the 3×3 block is symmetric with off-diagonal entries ≥ 0, and its column
// sums are ∂(Σ angles)/∂u_x = −∂(area)/∂u_x < 0 (tangency: −τ (T((h_x+h_y)/2) + T((h_x+h_z)/2)), since
// coth l − 1/S(l) = T(l/2); right triangle: −w (C_x C_f − 1)). Summing the blocks over the triangles
// and keeping the interior rows and columns (boundary entries are ≥ 0 off the diagonal, so dropping
// them only lowers the row sums further), J = ∂θ/∂u is symmetric with negative diagonal, non-negative
// off-diagonal entries and strictly negative row sums: −J is strictly diagonally dominant with a
// positive diagonal, hence symmetric positive definite (Gershgorin). J is the Hessian of the concave
// functional whose critical point is the packing (Colin de Verdière; Chow–Luo); Newton's system is
// −J δu = θ − 2π.

namespace laguerre::core {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;
constexpr double fd_step = 1e-5;  // central-difference step (LU path in s = log h; the general overlap pattern in u)

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Subnormal numbers flushed to zero (x86 MXCSR: FTZ, DAZ) for the lifetime of the guard, on this thread.
// The first Newton steps from the initial radii have circles of huge hyperbolic radius, whose lifts
// e^{-2h} make Jacobian entries and fill of the Cholesky factor subnormal; every operation on them
// takes a microcode assist (~100× slower). Measured on a 10^6-vertex Delaunay triangulation (seed 1,
// CHOLMOD with OpenBLAS): the first two factorizations took 8.1 and 6.5 s against 2.2 s afterwards,
// and 2.2–2.5 s with the guard. Flushing moves an entry of the factor by less than 2.2·10^-308; the
// steps and the statuses of the Newton runs measured (tools/bench/newton.sh) are unchanged by it.
class SubnormalsFlushed {
public:
#ifdef LAGUERRE_HAVE_MXCSR
  SubnormalsFlushed() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ (bit 15) | DAZ (bit 6)
  ~SubnormalsFlushed() { _mm_setcsr(saved_); }
private:
  unsigned saved_;
#endif
public:
  SubnormalsFlushed(const SubnormalsFlushed&) = delete;
  SubnormalsFlushed& operator=(const SubnormalsFlushed&) = delete;
};

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

// Derivatives of the angle at v of triangle (v, a, b) with respect to u_v, u_a, u_b.
struct CornerDerivative {
  double dv = 0, da = 0, db = 0;
};

// The right-triangle part (x, f) (f orthogonal to x): {∂/∂u_x, ∂/∂u_f} of atan(T_f / S_x).
void right_part_derivative(Lift x, Lift f, double& dx, double& df) {
  const double d = 4 * f.x * x.xbar * x.xbar + 4 * x.x * f.xbar * f.xbar + x.xbar * x.xbar * f.xbar * f.xbar;
  const double p = x.xbar * f.xbar / d;
  dx -= (1 + x.x) * (1 + f.x) * p;
  df += 4 * std::sqrt(x.x * f.x) * p;
}

// Central differences in u of overlap_angle, for intersection patterns other than those of G′.
CornerDerivative corner_by_differences(double hv, double ha, double hb, double cva, double cvb, double cab) {
  CornerDerivative out;
  const double h[3] = {hv, ha, hb};
  double* d[3] = {&out.dv, &out.da, &out.db};
  for (int c = 0; c < 3; ++c) {
    if (std::isinf(h[c])) continue;
    const double u = u_of_radius(h[c]), step = fd_step * std::min(1.0, -u);  // u + step < 0
    double angle[2];
    for (int sgn = 0; sgn < 2; ++sgn) {
      Lift l[3] = {lift(hv), lift(ha), lift(hb)};
      l[c] = lift(radius_of_u(u + (sgn == 0 ? step : -step)));
      angle[sgn] = overlap_angle(l[0], l[1], l[2], cva, cvb, cab);
    }
    *d[c] = (angle[0] - angle[1]) / (2 * step);
  }
  return out;
}

CornerDerivative corner_derivative(Lift v, Lift a, Lift b, double hv, double ha, double hb, double cva, double cvb,
                                   double cab) {
  CornerDerivative out;
  if (cva == 1 && cvb == 1 && cab == 1) {
    const double e_va = v.xbar + v.x * a.xbar, e_vb = v.xbar + v.x * b.xbar;
    const double all = v.xbar + v.x * a.xbar + v.x * a.x * b.xbar;  // 1 − VAB
    const double tau = 0.5 * std::sqrt(v.xbar * a.xbar * b.xbar / all);
    const double va = v.x * a.x, vb = v.x * b.x;
    out.da = tau * 2 * std::sqrt(va) / e_va;
    out.db = tau * 2 * std::sqrt(vb) / e_vb;
    out.dv = -tau * ((1 + va) / e_va + (1 + vb) / e_vb);
  } else if (cva == 1 && cvb == 0 && cab == 0) {  // b is the face circle
    right_part_derivative(v, b, out.dv, out.db);
  } else if (cvb == 1 && cva == 0 && cab == 0) {  // a is the face circle
    right_part_derivative(v, a, out.dv, out.da);
  } else if (cab == 1 && cva == 0 && cvb == 0) {  // v is the face circle
    right_part_derivative(v, a, out.dv, out.da);
    right_part_derivative(v, b, out.dv, out.db);
  } else {
    out = corner_by_differences(hv, ha, hb, cva, cvb, cab);
  }
  return out;
}

// The interior numbering of a complex.
struct Interior {
  std::vector<Vertex> vertices;
  std::vector<std::int64_t> row;  // per vertex of K: row, or −1 on the boundary
};

Interior interior_of(const PackingComplex& k) {
  Interior in;
  const PlanarGraph& g = k.graph;
  in.row.assign(g.num_vertices(), -1);
  for (Vertex v = 0; v < g.num_vertices(); ++v)
    if (!g.is_boundary(v)) {
      in.row[v] = static_cast<std::int64_t>(in.vertices.size());
      in.vertices.push_back(v);
    }
  return in;
}

// The sparsity pattern of J = ∂θ/∂u in compressed form (column c = row c by symmetry; the diagonal
// and the interior neighbours of each interior vertex, indices increasing), and where each corner's
// derivatives go: fixed for a complex, so it is built once (JacobianPattern) and every Newton step
// only fills the values.
struct JacobianPattern {
  std::vector<int> outer, inner;
  std::vector<int> diagonal;  // per row: position of its diagonal entry in `inner`
  std::vector<int> slot;      // per dart of an interior vertex (from first_dart): position of the entry
                              // of its head, −1 for a boundary head (unused for boundary tails)
};

JacobianPattern jacobian_pattern(const PackingComplex& k, const Interior& in) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = in.vertices.size();
  JacobianPattern p;
  p.outer.assign(n + 1, 0);
  p.diagonal.resize(n);
  p.slot.assign(g.num_darts(), -1);
  std::vector<std::pair<int, std::uint32_t>> row;  // (column, rotation position + 1; 0 for the diagonal)
  for (std::size_t i = 0; i < n; ++i) {
    const Vertex v = in.vertices[i];
    const Dart first = g.first_dart(v);
    const std::uint32_t deg = g.degree(v);
    row.clear();
    row.emplace_back(static_cast<int>(i), 0);
    for (std::uint32_t e = 0; e < deg; ++e)
      if (in.row[g.head(first + e)] >= 0) row.emplace_back(static_cast<int>(in.row[g.head(first + e)]), e + 1);
    std::sort(row.begin(), row.end());
    for (const auto& [c, e] : row) {
      const int at = static_cast<int>(p.inner.size());
      if (e == 0) p.diagonal[i] = at;
      else p.slot[first + e - 1] = at;
      p.inner.push_back(c);
    }
    p.outer[i + 1] = static_cast<int>(p.inner.size());
  }
  return p;
}

// The values of J on `pattern` (values.size() == pattern.inner.size()). Each entry is the sum of its
// corners' derivatives in the order of the rotation from the first dart (the diagonal: d.dv of every
// corner; a neighbour's entry: da of its own corner, db of the previous one).
void assemble_jacobian(const PackingComplex& k, const Radii& h, const Interior& in, const JacobianPattern& pattern,
                       double* values) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = in.vertices.size();
  std::fill(values, values + pattern.inner.size(), 0.0);
  std::vector<Lift> lifts(h.size());
  for (Vertex v = 0; v < h.size(); ++v) lifts[v] = lift(h[v]);
  for (std::size_t i = 0; i < n; ++i) {
    const Vertex v = in.vertices[i];
    const Dart first = g.first_dart(v);
    const std::uint32_t deg = g.degree(v);
    double& diagonal = values[pattern.diagonal[i]];
    for (std::uint32_t e = 0; e < deg; ++e) {
      const std::uint32_t f = e + 1 == deg ? 0 : e + 1;
      const Vertex a = g.head(first + e), b = g.head(first + f);
      const CornerDerivative d = corner_derivative(lifts[v], lifts[a], lifts[b], h[v], h[a], h[b], k.cos_angle[first + e],
                                                   k.cos_angle[first + f], k.cos_angle[g.next_in_face(first + e)]);
      diagonal += d.dv;
      if (const int s = pattern.slot[first + e]; s >= 0) values[s] += d.da;
      if (const int s = pattern.slot[first + f]; s >= 0) values[s] += d.db;
    }
  }
}

// The original LU path: J = ∂θ/∂s (s = log h) by central differences, corner by corner.
SpMat jacobian_in_log_radius(const PackingComplex& k, const Radii& h, const Interior& in) {
  const PlanarGraph& g = k.graph;
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<Lift> lifts(h.size());
  for (Vertex v = 0; v < h.size(); ++v) lifts[v] = lift(h[v]);
  for (Vertex v : in.vertices) {
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
        entries.emplace_back(in.row[v], in.row[w], (up - down) / (2 * fd_step));
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(in.vertices.size());
  SpMat jac(n, n);
  jac.setFromTriplets(entries.begin(), entries.end());  // sums the corner contributions
  jac.makeCompressed();
  return jac;
}
}  // namespace

std::string_view cholesky_backend() {
#ifdef LAGUERRE_HAVE_CHOLMOD
  return "cholmod";
#else
  return "eigen-ldlt";
#endif
}

double u_of_radius(double h) {
  if (std::isinf(h)) return 0;
  if (h < 1) return std::log(std::tanh(h / 2));
  return std::log1p(-2 / (std::exp(h) + 1));  // tanh(h/2) = 1 − 2/(e^h + 1)
}

double radius_of_u(double u) {
  if (u >= 0) return std::numeric_limits<double>::infinity();
  const double q = std::exp(u);
  return std::log1p(2 * q / -std::expm1(u));  // (1 + q)/(1 − q) = 1 + 2q/(1 − q)
}

AngleJacobian angle_jacobian(const PackingComplex& k, const Radii& h) {
  const Interior in = interior_of(k);
  const JacobianPattern pattern = jacobian_pattern(k, in);
  std::vector<double> values(pattern.inner.size());
  assemble_jacobian(k, h, in, pattern, values.data());
  AngleJacobian out;
  out.interior = in.vertices;
  out.entries.reserve(values.size());
  for (std::size_t r = 0; r + 1 < pattern.outer.size(); ++r)
    for (int p = pattern.outer[r]; p < pattern.outer[r + 1]; ++p)
      out.entries.push_back({static_cast<std::uint32_t>(r),
                             static_cast<std::uint32_t>(pattern.inner[static_cast<std::size_t>(p)]),
                             values[static_cast<std::size_t>(p)]});
  return out;
}

double star_jacobian_row(double hv, const StarView& s, std::vector<double>& off) {
  // The corners of assemble_jacobian, around v from neighbour 0 (the node-local form).
  const std::size_t deg = s.neighbour_h.size();
  const bool tangent = s.cos_spoke.empty();
  off.assign(deg, 0.0);
  const Lift v = lift(hv);
  double diag = 0;
  for (std::size_t e = 0; e < deg; ++e) {
    const std::size_t f = e + 1 == deg ? 0 : e + 1;
    const double ha = s.neighbour_h[e], hb = s.neighbour_h[f];
    const CornerDerivative d = corner_derivative(v, lift(ha), lift(hb), hv, ha, hb, tangent ? 1.0 : s.cos_spoke[e],
                                                 tangent ? 1.0 : s.cos_spoke[f], tangent ? 1.0 : s.cos_rim[e]);
    diag += d.dv;
    off[e] += d.da;
    off[f] += d.db;
  }
  return diag;
}

struct NewtonMethod::State {
  const PackingComplex* complex = nullptr;
  std::size_t num_vertices = 0;
  Interior interior;
#ifdef LAGUERRE_HAVE_CHOLMOD
  using Cholesky = Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower>;
#else
  using Cholesky = Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>>;
#endif
  std::optional<Cholesky> cholesky;  // symbolic analysis kept across steps
  std::optional<JacobianPattern> pattern;
  SpMat a;  // −J on `pattern`, its values refilled every step
  // The residuals of the radii the last step ended with (its accepted trial): the next step starts
  // from them, so θ is not evaluated twice for the same radii.
  Radii residual_radii;
  Eigen::VectorXd residual;
  double residual_norm = 0;

  // A = −J at h (symmetric positive definite) on the pattern, made on first use.
  SpMat& assemble(const PackingComplex& k, const Radii& h) {
    const auto n = static_cast<Eigen::Index>(interior.vertices.size());
    if (!pattern) {
      pattern = jacobian_pattern(k, interior);
      std::vector<double> zeros(pattern->inner.size(), 0.0);
      a = Eigen::Map<const SpMat>(n, n, static_cast<Eigen::Index>(zeros.size()), pattern->outer.data(),
                                  pattern->inner.data(), zeros.data());
    }
    double* values = a.valuePtr();
    assemble_jacobian(k, h, interior, *pattern, values);
    for (Eigen::Index p = 0; p < a.nonZeros(); ++p) values[p] = -values[p];
    return a;
  }
  // The sparse Cholesky factorization of `a` (symbolic analysis once); whether it succeeded. Callers
  // hold a SubnormalsFlushed over it and the solves.
  bool factorize() {
    if (!cholesky) {
      cholesky.emplace();
      cholesky->analyzePattern(a);
    }
    cholesky->factorize(a);
    return cholesky->info() == Eigen::Success;
  }
};

NewtonMethod::NewtonMethod(NewtonSolver solver) : solver_(solver), state_(std::make_unique<State>()) {}
NewtonMethod::~NewtonMethod() = default;

NewtonStep NewtonMethod::step(const PackingComplex& k, Radii& h) {
  NewtonStep out;
  using Clock = std::chrono::steady_clock;
  Clock::time_point mark = Clock::now();
  double* phase = &out.line_search_seconds;  // the phase the clock is running for
  auto switch_to = [&](double* next) {
    const Clock::time_point now = Clock::now();
    *phase += std::chrono::duration<double>(now - mark).count();
    mark = now;
    phase = next;
  };
  step_in(k, h, out, [&](int p) {
    switch_to(p == 0 ? &out.jacobian_seconds : p == 1 ? &out.solve_seconds : &out.line_search_seconds);
  });
  switch_to(phase);
  return out;
}

void NewtonMethod::bind(const PackingComplex& k) {
  State& st = *state_;
  if (st.complex != &k || st.num_vertices != k.graph.num_vertices()) {
    st.complex = &k;
    st.num_vertices = k.graph.num_vertices();
    st.interior = interior_of(k);
    st.cholesky.reset();
    st.pattern.reset();
    st.residual_radii.clear();
  }
}

Radii128 NewtonMethod::refine128(const PackingComplex& k, const Radii& h, double* angle_error, int iterations,
                                 double tolerance) {
  Radii128 q(h.size());
  for (std::size_t v = 0; v < h.size(); ++v) q[v] = h[v];
  if (angle_error) *angle_error = 0;
  bind(k);
  State& st = *state_;
  const std::vector<Vertex>& interior = st.interior.vertices;
  if (interior.empty()) return q;
  const auto n = static_cast<Eigen::Index>(interior.size());
  st.assemble(k, h);
  const SubnormalsFlushed flushed;
  if (!st.factorize()) return q;
  Eigen::VectorXd r(n);
  for (int it = 0;; ++it) {
    const std::vector<double> residual = angle_residuals128(k, q);
    double worst = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      r[i] = residual[interior[static_cast<std::size_t>(i)]];
      worst = std::max(worst, std::abs(r[i]));
    }
    if (angle_error) *angle_error = worst;
    if (!(worst > tolerance) || it == iterations) break;  // converged (or NaN), or out of corrections
    const Eigen::VectorXd du = st.cholesky->solve(r);
    if (st.cholesky->info() != Eigen::Success || !du.allFinite()) break;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vertex v = interior[static_cast<std::size_t>(i)];
      const double ds = du[i] * (h[v] < 1e-8 ? 1.0 : std::sinh(h[v]) / h[v]);  // δs = δu · ds/du, s = log h
      q[v] *= expq(static_cast<Float128>(ds));
    }
  }
  return q;
}

void NewtonMethod::step_in(const PackingComplex& k, Radii& h, NewtonStep& out, const std::function<void(int)>& phase) {
  bind(k);
  State& st = *state_;
  const std::vector<Vertex>& interior = st.interior.vertices;
  if (interior.empty()) return;
  Eigen::VectorXd r;
  double norm0 = 0;
  if (!st.residual_radii.empty() && st.residual_radii == h) {  // h unchanged since the last accepted step
    r.swap(st.residual);
    norm0 = st.residual_norm;
  } else {
    norm0 = residuals(k, h, interior, r);
  }
  st.residual_radii.clear();
  out.error_before = out.error_after = r.cwiseAbs().maxCoeff();
  const auto n = static_cast<Eigen::Index>(interior.size());

  // δs: the Newton direction in s = log h.
  Eigen::VectorXd delta;
  if (solver_ == NewtonSolver::lu) {
    phase(0);
    const SpMat jac = jacobian_in_log_radius(k, h, st.interior);
    phase(1);
    Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(jac);
    if (lu.info() != Eigen::Success) return;
    delta = lu.solve(-r);
    if (lu.info() != Eigen::Success) return;
  } else {
    phase(0);
    const SpMat& a = st.assemble(k, h);  // A = −J, symmetric positive definite
    phase(1);
    Eigen::VectorXd du;
    if (solver_ == NewtonSolver::cholesky) {
      const SubnormalsFlushed flushed;  // the factorization and the triangular solves (see the class)
      if (!st.factorize()) return;
      du = st.cholesky->solve(r);
      if (st.cholesky->info() != Eigen::Success) return;
    } else {
      Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>> cg;
      cg.setTolerance(std::clamp(std::sqrt(norm0), 1e-14, 1e-4));
      cg.setMaxIterations(5000);
      cg.compute(a);
      if (cg.info() != Eigen::Success) return;
      du = cg.solve(r);
      out.linear_iterations = static_cast<int>(cg.iterations());
    }
    delta.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double hv = h[interior[static_cast<std::size_t>(i)]];
      delta[i] = du[i] * (hv < 1e-8 ? 1.0 : std::sinh(hv) / hv);  // δs = δu · ds/du
    }
  }
  if (!delta.allFinite()) return;

  // Damped step: at most a factor e^16 per radius, halved until ‖θ − 2π‖₂ decreases. (The cap was e²
  // until 2026-12-04: on uniform random triangulations, whose radii span many decades, it took 42
  // steps at 10^5 vertices where e^16 takes 17, and 21 against 14 at 10^4; Delaunay and 3-connected
  // graphs take the same steps either way. The halving alone keeps the steps monotone.)
  phase(2);
  double t = std::min(1.0, 16.0 / std::max(1e-300, delta.cwiseAbs().maxCoeff()));
  Radii trial = h;
  for (int halving = 0; halving < 40; ++halving, t *= 0.5) {
    for (std::size_t i = 0; i < interior.size(); ++i)
      trial[interior[i]] = h[interior[i]] * std::exp(t * delta[static_cast<Eigen::Index>(i)]);
    Eigen::VectorXd rt;
    const double norm = residuals(k, trial, interior, rt);
    if (norm < norm0) {
      st.residual_radii = trial;
      st.residual.swap(rt);
      st.residual_norm = norm;
      h.swap(trial);
      out.improved = true;
      out.error_after = st.residual.cwiseAbs().maxCoeff();
      out.halvings = halving;
      return;
    }
  }
}

NewtonStep newton_step(const PackingComplex& k, Radii& h, NewtonSolver solver) {
  NewtonMethod method(solver);
  return method.step(k, h);
}

}  // namespace laguerre::core
