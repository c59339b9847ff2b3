/// @file
/// Anisotropic diagrams: bisector conics and their intersections (Eigen), vertex filtering with the
/// regular complex, restriction to a domain, the sites reader.

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "AnisotropicDetail.hpp"
#include "ApolloniusDetail.hpp"
#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"
#include "laguerre/core/diagrams/SitesFile.hpp"
#include "detail/Validity.hpp"

namespace laguerre::core {

double anisotropic_distance(Point2 q, const AnisotropicSite& s) {
  const double dx = q.x - s.x, dy = q.y - s.y;
  return s.a * dx * dx + 2 * s.b * dx * dy + s.c * dy * dy;
}

SiteIndex anisotropic_nearest(const std::vector<AnisotropicSite>& sites, Point2 q) {
  return detail::nearest_site(sites.size(), [&](SiteIndex i) { return anisotropic_distance(q, sites[i]); });
}

namespace {

bool is_positive_definite(const AnisotropicSite& s) { return s.a > 0 && s.a * s.c - s.b * s.b > 0; }

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

/// Coefficients {A, B, C, D, E, F} of d(x) = (x − p)ᵀ M (x − p).
Conic distance_quadric(const AnisotropicSite& s) {
  return {s.a, 2 * s.b, s.c, -2 * (s.a * s.x + s.b * s.y), -2 * (s.b * s.x + s.c * s.y),
          s.a * s.x * s.x + 2 * s.b * s.x * s.y + s.c * s.y * s.y};
}

double eval(const Conic& k, double x, double y) {
  return k[0] * x * x + k[1] * x * y + k[2] * y * y + k[3] * x + k[4] * y + k[5];
}

/// The conic in coordinates u with x = centre + scale·R(θ)·u.
Conic transform(const Conic& k, Point2 centre, double scale, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  // x = cx + scale (c u − s v), y = cy + scale (s u + c v).
  const double xu = scale * c, xv = -scale * s, yu = scale * s, yv = scale * c;
  const double A = k[0], B = k[1], C = k[2], D = k[3], E = k[4];
  Conic out{};
  out[0] = A * xu * xu + B * xu * yu + C * yu * yu;
  out[1] = 2 * A * xu * xv + B * (xu * yv + xv * yu) + 2 * C * yu * yv;
  out[2] = A * xv * xv + B * xv * yv + C * yv * yv;
  const double gx = 2 * A * centre.x + B * centre.y + D, gy = B * centre.x + 2 * C * centre.y + E;
  out[3] = gx * xu + gy * yu;
  out[4] = gx * xv + gy * yv;
  out[5] = eval(k, centre.x, centre.y);
  return out;
}

using Poly = std::array<double, 5>;  // coefficients of x⁰ … x⁴

Poly mul(const Poly& p, const Poly& q) {
  Poly r{};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; i + j < 5; ++j) r[static_cast<std::size_t>(i + j)] += p[static_cast<std::size_t>(i)] * q[static_cast<std::size_t>(j)];
  return r;
}
Poly sub(const Poly& p, const Poly& q) {
  Poly r{};
  for (std::size_t i = 0; i < 5; ++i) r[i] = p[i] - q[i];
  return r;
}
double eval_poly(const Poly& p, double x) {
  double v = 0;
  for (int i = 4; i >= 0; --i) v = v * x + p[static_cast<std::size_t>(i)];
  return v;
}

/// Real roots of a polynomial of degree ≤ 4 (companion matrix; leading coefficients below 1e-12 of the
/// largest are treated as zero). Empty for the zero polynomial.
std::vector<double> real_roots(const Poly& p, bool& zero) {
  double big = 0;
  for (double c : p) big = std::max(big, std::abs(c));
  zero = big == 0;
  if (zero) return {};
  int deg = 4;
  while (deg > 0 && std::abs(p[static_cast<std::size_t>(deg)]) <= 1e-12 * big) --deg;
  if (deg == 0) return {};
  std::vector<double> roots;
  const double lead = p[static_cast<std::size_t>(deg)];
  if (deg == 1) {
    roots.push_back(-p[0] / lead);
  } else if (deg == 2) {
    const double b = p[1] / lead, c = p[0] / lead, disc = b * b - 4 * c;
    if (disc >= -1e-12 * b * b) {
      const double sq = std::sqrt(std::max(disc, 0.0)), q = -0.5 * (b + (b >= 0 ? sq : -sq));
      roots.push_back(q);
      if (q != 0) roots.push_back(c / q);
    }
  } else {
    // Companion matrix (fixed size: no allocation on the hot path of the vertex computation).
    auto solve = [&]<int N>() {
      Eigen::Matrix<double, N, N> companion = Eigen::Matrix<double, N, N>::Zero();
      for (int i = 0; i < N; ++i) companion(0, i) = -p[static_cast<std::size_t>(N - 1 - i)] / lead;
      for (int i = 1; i < N; ++i) companion(i, i - 1) = 1;
      Eigen::EigenSolver<Eigen::Matrix<double, N, N>> solver(companion, false);
      for (int i = 0; i < N; ++i) {
        const std::complex<double> z = solver.eigenvalues()[i];
        if (std::abs(z.imag()) <= 1e-5 * (1 + std::abs(z.real()))) roots.push_back(z.real());
      }
    };
    if (deg == 3)
      solve.template operator()<3>();
    else
      solve.template operator()<4>();
  }
  return roots;
}


/// The order of AnisotropicDiagram::vertices: by label, then position.
bool vertex_order(const AnisotropicVertex& a, const AnisotropicVertex& b) {
  if (a.sites != b.sites) return a.sites < b.sites;
  return a.position.x != b.position.x ? a.position.x < b.position.x : a.position.y < b.position.y;
}

/// A point of C_ab ∩ C_bc equidistant from a, b and c (step 2 of the file comment), with the distance
/// and tolerance of the filter.
struct Candidate {
  Point2 position;
  double distance, tolerance;
};

/// Step (2) for the triangle t: its candidate points.
std::vector<Candidate> triangle_candidates(const std::vector<AnisotropicSite>& sites, const std::array<SiteIndex, 3>& t,
                                           const AnisotropicOptions& options) {
  std::vector<Candidate> out;
  const AnisotropicSite &sa = sites[t[0]], &sb = sites[t[1]], &sc = sites[t[2]];
  const Point2 centre{(sa.x + sb.x + sc.x) / 3, (sa.y + sb.y + sc.y) / 3};
  double scale = 0;
  for (const AnisotropicSite* s : {&sa, &sb, &sc}) scale = std::max(scale, std::hypot(s->x - centre.x, s->y - centre.y));
  if (!(scale > 0)) return out;
  for (Point2 x : intersect_conics(bisector_conic(sa, sb), bisector_conic(sb, sc), centre, scale)) {
    const double da = anisotropic_distance(x, sa), db = anisotropic_distance(x, sb), dc = anisotropic_distance(x, sc);
    const double dist = (da + db + dc) / 3, tol = options.tolerance * std::max(dist, 1e-300);
    if (std::abs(da - db) > 1e3 * tol + 1e-9 * dist || std::abs(db - dc) > 1e3 * tol + 1e-9 * dist) continue;
    out.push_back({x, dist, tol});
  }
  return out;
}

/// Step (3): appends to `out` the candidates of t that no regular-complex neighbour of its sites is
/// strictly closer to.
void keep_nearest(const std::vector<AnisotropicSite>& sites, const std::array<SiteIndex, 3>& t,
                  const std::vector<Candidate>& candidates, const std::vector<std::vector<SiteIndex>>& neighbours,
                  std::vector<AnisotropicVertex>& out) {
  for (const Candidate& x : candidates) {
    bool ok = true;
    for (SiteIndex s : t) {
      for (SiteIndex k : neighbours[s]) {
        if (k == t[0] || k == t[1] || k == t[2]) continue;
        if (anisotropic_distance(x.position, sites[k]) < x.distance - x.tolerance) {
          ok = false;
          break;
        }
      }
      if (!ok) break;
    }
    if (ok) out.push_back({t, x.position, x.distance});
  }
}

/// The dual triangles and edges of d.vertices (sorted by vertex_order).
void finish_dual(AnisotropicDiagram& d) {
  d.dual_triangles.clear();
  d.dual_edges.clear();
  for (const AnisotropicVertex& v : d.vertices) {
    if (d.dual_triangles.empty() || d.dual_triangles.back() != v.sites) d.dual_triangles.push_back(v.sites);
    d.dual_edges.emplace_back(v.sites[0], v.sites[1]);
    d.dual_edges.emplace_back(v.sites[0], v.sites[2]);
    d.dual_edges.emplace_back(v.sites[1], v.sites[2]);
  }
  std::sort(d.dual_edges.begin(), d.dual_edges.end());
  d.dual_edges.erase(std::unique(d.dual_edges.begin(), d.dual_edges.end()), d.dual_edges.end());
}

/// Throws InputError unless site i is finite with a positive definite matrix.
void check_site(const AnisotropicSite& s, SiteIndex i) {
  for (double v : {s.x, s.y, s.a, s.b, s.c})
    if (!std::isfinite(v)) throw InputError("anisotropic site " + std::to_string(i) + " is not finite.");
  if (!is_positive_definite(s))
    throw InputError("anisotropic site " + std::to_string(i) +
                                ": the matrix [[a, b], [b, c]] is not positive definite (expected a > 0 and ac − b² > 0).");
}

}  // namespace

Conic bisector_conic(const AnisotropicSite& i, const AnisotropicSite& j) {
  const Conic a = distance_quadric(i), b = distance_quadric(j);
  Conic d{};
  for (std::size_t k = 0; k < 6; ++k) d[k] = a[k] - b[k];
  return d;
}

std::vector<Point2> intersect_conics(const Conic& c1, const Conic& c2, Point2 centre, double scale) {
  // A generic rotation keeps the y² coefficients away from zero and the roots' x distinct.
  for (const double theta : {0.4142135623730951, 1.2360679774997896, 2.718281828459045}) {
    const Conic k1 = transform(c1, centre, scale, theta), k2 = transform(c2, centre, scale, theta);
    double n1 = 0, n2 = 0;
    for (std::size_t i = 0; i < 6; ++i) n1 = std::max(n1, std::abs(k1[i])), n2 = std::max(n2, std::abs(k2[i]));
    if (n1 == 0 || n2 == 0) return {};
    Conic a = k1, b = k2;
    for (double& v : a) v /= n1;
    for (double& v : b) v /= n2;
    // A conic without quadratic part is a line: substitute it into the other conic.
    const bool line_a = std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2])}) <= 1e-13;
    const bool line_b = std::max({std::abs(b[0]), std::abs(b[1]), std::abs(b[2])}) <= 1e-13;
    if (line_a || line_b) {
      const Conic& l = line_a ? a : b;
      const Conic& k = line_a ? b : a;
      const double nn = l[3] * l[3] + l[4] * l[4];
      if (nn == 0) return {};
      const double x0 = -l[5] * l[3] / nn, y0 = -l[5] * l[4] / nn, dx = -l[4], dy = l[3];
      std::vector<double> ts;
      if (line_a && line_b) {
        // Two lines: k is linear too.
        const double den = k[3] * dx + k[4] * dy;
        if (std::abs(den) <= 1e-13 * std::sqrt(nn) * (std::abs(k[3]) + std::abs(k[4]))) return {};
        ts.push_back(-(k[3] * x0 + k[4] * y0 + k[5]) / den);
      } else {
        const double A = k[0] * dx * dx + k[1] * dx * dy + k[2] * dy * dy;
        const double B = 2 * k[0] * x0 * dx + k[1] * (x0 * dy + y0 * dx) + 2 * k[2] * y0 * dy + k[3] * dx + k[4] * dy;
        const double C = eval(k, x0, y0);
        if (std::abs(A) <= 1e-13 * (std::abs(B) + std::abs(C))) {
          if (B != 0) ts.push_back(-C / B);
        } else {
          const double disc = B * B - 4 * A * C;
          if (disc < -1e-12 * B * B) return {};
          // The stable form (no cancellation when A is tiny, the line nearly meeting a nearly-linear
          // conic: one root near, one far away).
          const double sq = std::sqrt(std::max(disc, 0.0)), q = -0.5 * (B + (B >= 0 ? sq : -sq));
          if (q != 0) ts.push_back(C / q);
          if (sq > 0 || q == 0) ts.push_back(q / A);
        }
      }
      const double c = std::cos(theta), sn = std::sin(theta);
      std::vector<Point2> out;
      for (double t : ts) {
        const double u = x0 + t * dx, v = y0 + t * dy;
        out.push_back({centre.x + scale * (c * u - sn * v), centre.y + scale * (sn * u + c * v)});
      }
      return out;
    }
    if (std::abs(a[2]) < 1e-8 && std::abs(b[2]) < 1e-8) continue;
    // As polynomials in y: a2 y² + a1(x) y + a0(x).
    const Poly a2{a[2]}, a1{a[4], a[1]}, a0{a[5], a[3], a[0]};
    const Poly b2{b[2]}, b1{b[4], b[1]}, b0{b[5], b[3], b[0]};
    const Poly p = sub(mul(a2, b0), mul(b2, a0));  // degree 2
    const Poly q = sub(mul(a2, b1), mul(b2, a1));  // degree 1
    const Poly r = sub(mul(a1, b0), mul(b1, a0));  // degree 3
    const Poly res = sub(mul(p, p), mul(q, r));     // Sylvester resultant, degree 4
    bool zero = false;
    const std::vector<double> xs = real_roots(res, zero);
    if (zero) return {};  // a common component: no isolated intersection
    std::vector<std::array<double, 2>> found;
    for (double x : xs) {
      std::vector<double> ys;
      const double qx = eval_poly(q, x);
      if (std::abs(qx) > 1e-7) {
        ys.push_back(-eval_poly(p, x) / qx);
      } else {
        // Both roots of the first conic in y (or the second when the first is linear in y).
        const Conic& k = std::abs(a[2]) >= std::abs(b[2]) ? a : b;
        const double A = k[2], B = k[1] * x + k[4], C = k[0] * x * x + k[3] * x + k[5];
        const double disc = B * B - 4 * A * C;
        if (disc >= -1e-9) {
          const double s = std::sqrt(std::max(disc, 0.0));
          ys.push_back((-B + s) / (2 * A));
          ys.push_back((-B - s) / (2 * A));
        }
      }
      for (double y : ys) {
        double u = x, v = y;
        // Newton on (a, b) = 0.
        for (int it = 0; it < 12; ++it) {
          const double f1 = eval(a, u, v), f2 = eval(b, u, v);
          const double j11 = 2 * a[0] * u + a[1] * v + a[3], j12 = a[1] * u + 2 * a[2] * v + a[4];
          const double j21 = 2 * b[0] * u + b[1] * v + b[3], j22 = b[1] * u + 2 * b[2] * v + b[4];
          const double det = j11 * j22 - j12 * j21;
          if (det == 0 || !std::isfinite(det)) break;
          const double du = (f1 * j22 - f2 * j12) / det, dv = (j11 * f2 - j21 * f1) / det;
          u -= du, v -= dv;
          if (std::abs(du) + std::abs(dv) <= 1e-15 * (1 + std::abs(u) + std::abs(v))) break;
        }
        const double mag = 1 + u * u + v * v;
        if (!std::isfinite(u) || !std::isfinite(v) || std::abs(eval(a, u, v)) > 1e-8 * mag || std::abs(eval(b, u, v)) > 1e-8 * mag)
          continue;
        bool dup = false;
        for (const auto& f : found) dup = dup || (std::abs(f[0] - u) + std::abs(f[1] - v) <= 1e-9 * (1 + std::abs(u) + std::abs(v)));
        if (!dup) found.push_back({u, v});
      }
    }
    const double c = std::cos(theta), s = std::sin(theta);
    std::vector<Point2> out;
    for (const auto& [u, v] : found) out.push_back({centre.x + scale * (c * u - s * v), centre.y + scale * (s * u + c * v)});
    return out;
  }
  // Both conics are nearly lines in every rotation (quadratic parts below 1e-8 of the linear ones: two
  // sites with almost equal metrics each): the bounded intersection is near that of the two lines, the
  // others are beyond ~1e8 length units. Solve the linear parts, then Newton on the full conics.
  const Conic a = transform(c1, centre, scale, 0), b = transform(c2, centre, scale, 0);
  const double det = a[3] * b[4] - a[4] * b[3];
  if (det == 0 || !std::isfinite(det)) return {};
  double u = (-a[5] * b[4] + a[4] * b[5]) / det, v = (-a[3] * b[5] + a[5] * b[3]) / det;
  for (int it = 0; it < 20; ++it) {
    const double f1 = eval(a, u, v), f2 = eval(b, u, v);
    const double j11 = 2 * a[0] * u + a[1] * v + a[3], j12 = a[1] * u + 2 * a[2] * v + a[4];
    const double j21 = 2 * b[0] * u + b[1] * v + b[3], j22 = b[1] * u + 2 * b[2] * v + b[4];
    const double dj = j11 * j22 - j12 * j21;
    if (dj == 0 || !std::isfinite(dj)) return {};
    const double du = (f1 * j22 - f2 * j12) / dj, dv = (j11 * f2 - j21 * f1) / dj;
    u -= du, v -= dv;
    if (std::abs(du) + std::abs(dv) <= 1e-15 * (1 + std::abs(u) + std::abs(v))) break;
  }
  double n1 = 0, n2 = 0;
  for (std::size_t i = 0; i < 6; ++i) n1 = std::max(n1, std::abs(a[i])), n2 = std::max(n2, std::abs(b[i]));
  const double mag = 1 + u * u + v * v;
  if (!std::isfinite(u) || !std::isfinite(v) || std::abs(eval(a, u, v)) > 1e-8 * mag * n1 ||
      std::abs(eval(b, u, v)) > 1e-8 * mag * n2)
    return {};
  return {{centre.x + scale * u, centre.y + scale * v}};
}

AnisotropicDiagram anisotropic_diagram(const std::vector<AnisotropicSite>& sites, const AnisotropicOptions& options) {
  AnisotropicDiagram d;
  d.sites = sites;
  const std::size_t n = sites.size();
  std::vector<char> keep(n, 1);
  std::map<std::array<double, 5>, SiteIndex> seen;
  for (SiteIndex i = 0; i < n; ++i) {
    const AnisotropicSite& s = sites[i];
    check_site(s, i);
    if (!seen.emplace(std::array<double, 5>{s.x, s.y, s.a, s.b, s.c}, i).second) keep[i] = 0, d.hidden.push_back(i);
  }
  std::vector<std::array<SiteIndex, 3>> candidates;
  std::vector<std::vector<SiteIndex>> neighbours(n);
  if (options.all_triples) {
    std::vector<SiteIndex> alive;
    for (SiteIndex i = 0; i < n; ++i)
      if (keep[i]) alive.push_back(i);
    for (std::size_t p = 0; p < alive.size(); ++p) {
      neighbours[alive[p]] = alive;
      for (std::size_t q = p + 1; q < alive.size(); ++q)
        for (std::size_t r = q + 1; r < alive.size(); ++r) candidates.push_back({alive[p], alive[q], alive[r]});
    }
    d.lifted_dimension = -1;
  } else {
    detail::RegularComplex rc = detail::regular_complex(sites, keep);
    candidates = std::move(rc.triangles);
    neighbours = std::move(rc.neighbours);
    d.lifted_dimension = rc.dimension;
  }
  d.candidate_triangles = candidates.size();
  for (const auto& t : candidates) keep_nearest(sites, t, triangle_candidates(sites, t, options), neighbours, d.vertices);
  std::sort(d.vertices.begin(), d.vertices.end(), vertex_order);
  finish_dual(d);
  return d;
}

struct AnisotropicDiagramUpdater::Impl {
  /// A triangle of the regular complex: its candidate points (they depend on its three sites only) and
  /// those kept by the filter (they depend on the sites' neighbours too).
  struct Triangle {
    std::vector<Candidate> candidates;
    std::vector<AnisotropicVertex> vertices;
    std::size_t seen = 0;  ///< the last add() that found it in the regular complex
  };
  AnisotropicOptions options;
  detail::LiftedTriangulation lifted;
  std::map<std::array<double, 5>, SiteIndex> seen;  ///< visible sites by value (equal sites are hidden)
  std::vector<std::vector<SiteIndex>> neighbours;   ///< per site, its regular-complex neighbours
  std::map<std::array<SiteIndex, 3>, Triangle> triangles;
  AnisotropicDiagram diagram;
  std::size_t adds = 0, filtered = 0, intersected = 0;
};

AnisotropicDiagramUpdater::AnisotropicDiagramUpdater(const AnisotropicOptions& options) : impl_(std::make_unique<Impl>()) {
  if (options.all_triples) throw InputError("the anisotropic diagram updater works on the regular complex, not all_triples.");
  impl_->options = options;
}
AnisotropicDiagramUpdater::~AnisotropicDiagramUpdater() = default;

const AnisotropicDiagram& AnisotropicDiagramUpdater::diagram() const { return impl_->diagram; }
std::size_t AnisotropicDiagramUpdater::filtered_triangles() const { return impl_->filtered; }
std::size_t AnisotropicDiagramUpdater::intersected_triangles() const { return impl_->intersected; }

void AnisotropicDiagramUpdater::add(const std::vector<AnisotropicSite>& sites) {
  Impl& m = *impl_;
  AnisotropicDiagram& d = m.diagram;
  const SiteIndex first = d.sites.size();
  for (SiteIndex k = 0; k < sites.size(); ++k) check_site(sites[k], first + k);
  std::vector<SiteIndex> added;
  for (const AnisotropicSite& s : sites) {
    const SiteIndex i = d.sites.size();
    d.sites.push_back(s);
    if (m.seen.emplace(std::array<double, 5>{s.x, s.y, s.a, s.b, s.c}, i).second)
      added.push_back(i);
    else
      d.hidden.push_back(i);
  }
  m.neighbours.resize(d.sites.size());
  bool all = false;
  const std::vector<SiteIndex> changed = m.lifted.insert(d.sites, added, all);
  const std::size_t stamp = ++m.adds;
  std::vector<char> dirty(d.sites.size(), 0);
  for (SiteIndex s : changed) dirty[s] = 1, m.neighbours[s] = m.lifted.neighbours(s);
  if (all)
    for (SiteIndex s = 0; s < d.sites.size(); ++s)
      if (!dirty[s]) m.neighbours[s].clear();  // hidden in the regular triangulation
  // The triangles with a changed site, and only those, are new, gone or have new neighbours to filter
  // with; each is listed once, by its smallest changed site.
  std::vector<std::array<SiteIndex, 3>> around;
  m.filtered = m.intersected = 0;
  for (SiteIndex s : changed) {
    around.clear();
    m.lifted.triangles_of(s, around);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    for (const auto& t : around) {
      if (std::any_of(t.begin(), t.end(), [&](SiteIndex k) { return k < s && dirty[k]; })) continue;
      const auto [it, fresh] = m.triangles.try_emplace(t);
      Impl::Triangle& tri = it->second;
      if (fresh) tri.candidates = triangle_candidates(d.sites, t, m.options), ++m.intersected;
      tri.seen = stamp;
      tri.vertices.clear();
      keep_nearest(d.sites, t, tri.candidates, m.neighbours, tri.vertices);
      std::sort(tri.vertices.begin(), tri.vertices.end(), vertex_order);
      ++m.filtered;
    }
  }
  std::erase_if(m.triangles, [&](const auto& entry) {
    const auto& t = entry.first;
    return entry.second.seen != stamp && (dirty[t[0]] || dirty[t[1]] || dirty[t[2]]);
  });
  d.vertices.clear();
  for (const auto& [t, tri] : m.triangles) d.vertices.insert(d.vertices.end(), tri.vertices.begin(), tri.vertices.end());
  d.candidate_triangles = m.triangles.size();
  d.lifted_dimension = m.lifted.dimension();
  finish_dual(d);
}

bool polygon_contains(const Polygon& polygon, Point2 q) {
  bool inside = false;
  for (std::size_t i = 0, n = polygon.size(), j = n - 1; i < n; j = i++) {
    const Point2 &a = polygon[i], &b = polygon[j];
    // On the boundary: collinear and between.
    const double cr = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    if (cr == 0 && std::min(a.x, b.x) <= q.x && q.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= q.y &&
        q.y <= std::max(a.y, b.y))
      return true;
    if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

RestrictedAnisotropicDiagram restrict_anisotropic(const AnisotropicDiagram& diagram, const Polygon& domain, int resolution) {
  RestrictedAnisotropicDiagram out;
  out.domain = domain;
  for (const AnisotropicVertex& v : diagram.vertices)
    if (polygon_contains(domain, v.position)) out.vertices.push_back(v);
  if (domain.size() < 3 || resolution < 2) return out;
  const auto& sites = diagram.sites;
  Box box{domain[0].x, domain[0].y, domain[0].x, domain[0].y};
  for (Point2 p : domain) box.xmin = std::min(box.xmin, p.x), box.ymin = std::min(box.ymin, p.y), box.xmax = std::max(box.xmax, p.x), box.ymax = std::max(box.ymax, p.y);
  const int N = resolution;
  auto node = [&](int i, int j) {
    return Point2{box.xmin + (box.xmax - box.xmin) * i / N, box.ymin + (box.ymax - box.ymin) * j / N};
  };
  std::vector<SiteIndex> label(static_cast<std::size_t>((N + 1) * (N + 1)));
  std::vector<char> inside(label.size());
  for (int j = 0; j <= N; ++j)
    for (int i = 0; i <= N; ++i) {
      const std::size_t k = static_cast<std::size_t>(j * (N + 1) + i);
      label[k] = anisotropic_nearest(sites, node(i, j));
      inside[k] = polygon_contains(domain, node(i, j));
    }
  auto lab = [&](int i, int j) { return label[static_cast<std::size_t>(j * (N + 1) + i)]; };
  auto in = [&](int i, int j) { return inside[static_cast<std::size_t>(j * (N + 1) + i)] != 0; };
  // Crossing on the grid edge between two nodes with labels a ≠ b: bisection of d_a − d_b.
  struct Crossing {
    long id;
    SiteIndex a, b;
    Point2 x;
  };
  auto crossing = [&](int i0, int j0, int i1, int j1, long id) -> std::optional<Crossing> {
    const SiteIndex a = lab(i0, j0), b = lab(i1, j1);
    if (a == b || !in(i0, j0) || !in(i1, j1)) return std::nullopt;
    Point2 lo = node(i0, j0), hi = node(i1, j1);
    for (int it = 0; it < 40; ++it) {
      const Point2 mid{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2};
      (anisotropic_distance(mid, sites[a]) <= anisotropic_distance(mid, sites[b]) ? lo : hi) = mid;
    }
    return Crossing{id, std::min(a, b), std::max(a, b), {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2}};
  };
  // Segments per label pair, endpoints identified by ids (grid edges ≥ 0, vertices < 0).
  std::map<std::pair<SiteIndex, SiteIndex>, std::vector<std::array<long, 2>>> segments;
  std::map<long, Point2> where;
  const long horizontal = static_cast<long>(N + 1) * (N + 1);
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      std::vector<Crossing> cs;
      const long hid = static_cast<long>(j) * (N + 1) + i;
      for (auto c : {crossing(i, j, i + 1, j, hid), crossing(i + 1, j, i + 1, j + 1, horizontal + hid + 1),
                     crossing(i + 1, j + 1, i, j + 1, hid + N + 1), crossing(i, j + 1, i, j, horizontal + hid)})
        if (c) cs.push_back(*c), where[c->id] = c->x;
      std::vector<char> used(cs.size(), 0);
      for (std::size_t p = 0; p < cs.size(); ++p)
        for (std::size_t q = p + 1; q < cs.size() && !used[p]; ++q)
          if (!used[q] && cs[p].a == cs[q].a && cs[p].b == cs[q].b)
            segments[{cs[p].a, cs[p].b}].push_back({cs[p].id, cs[q].id}), used[p] = used[q] = 1;
      // A dangling crossing ends at a vertex of the diagram inside this square, when there is one.
      const Point2 lo = node(i, j), hi = node(i + 1, j + 1);
      for (std::size_t p = 0; p < cs.size(); ++p) {
        if (used[p]) continue;
        for (std::size_t k = 0; k < out.vertices.size(); ++k) {
          const AnisotropicVertex& v = out.vertices[k];
          const bool has = std::count(v.sites.begin(), v.sites.end(), cs[p].a) && std::count(v.sites.begin(), v.sites.end(), cs[p].b);
          const double sx = hi.x - lo.x, sy = hi.y - lo.y;
          if (has && v.position.x >= lo.x - sx && v.position.x <= hi.x + sx && v.position.y >= lo.y - sy && v.position.y <= hi.y + sy) {
            const long vid = -1 - static_cast<long>(k);
            where[vid] = v.position;
            segments[{cs[p].a, cs[p].b}].push_back({cs[p].id, vid});
            break;
          }
        }
      }
    }
  // Chain the segments of each pair into polylines.
  for (auto& entry : segments) {
    const auto& pair = entry.first;
    auto& segs = entry.second;  // a reference, not a structured binding: the lambda `walk` captures it
    std::map<long, std::vector<std::size_t>> at;
    for (std::size_t s = 0; s < segs.size(); ++s) at[segs[s][0]].push_back(s), at[segs[s][1]].push_back(s);
    std::vector<char> done(segs.size(), 0);
    SampledEdge edge{pair.first, pair.second, {}};
    auto walk = [&](long start) {
      std::vector<Point2> line{where[start]};
      long cur = start;
      for (;;) {
        std::size_t next = segs.size();
        for (std::size_t s : at[cur])
          if (!done[s]) {
            next = s;
            break;
          }
        if (next == segs.size()) break;
        done[next] = 1;
        cur = segs[next][0] == cur ? segs[next][1] : segs[next][0];
        line.push_back(where[cur]);
      }
      if (line.size() >= 2) edge.polylines.push_back(std::move(line));
    };
    for (const auto& [id, list] : at)
      if (list.size() == 1) walk(id);
    for (std::size_t s = 0; s < segs.size(); ++s)
      if (!done[s]) walk(segs[s][0]);
    out.edges.push_back(std::move(edge));
  }
  return out;
}

bool AnisotropicDiagram::is_valid(bool verbose) const {
  const std::string violation = [&]() -> std::string {
    const std::size_t n = sites.size();
    std::vector<char> is_hidden(n, 0);
    auto same = [&](SiteIndex i, SiteIndex j) {
      const AnisotropicSite &a = sites[i], &b = sites[j];
      return a.x == b.x && a.y == b.y && a.a == b.a && a.b == b.b && a.c == b.c;
    };
    for (std::size_t k = 0; k < hidden.size(); ++k) {
      if (hidden[k] >= n || (k > 0 && hidden[k] <= hidden[k - 1]))
        return "the hidden sites are not increasing indices below " + std::to_string(n);
      is_hidden[hidden[k]] = 1;
    }
    for (SiteIndex i = 0; i < n; ++i) {
      bool duplicate = false;
      for (SiteIndex j = 0; j < i && !duplicate; ++j) duplicate = !is_hidden[j] && same(i, j);
      if (duplicate != static_cast<bool>(is_hidden[i]))
        return "site " + std::to_string(i) + (duplicate ? " repeats an earlier site but is not hidden" : " is hidden but repeats no earlier site");
    }
    if (!std::is_sorted(dual_triangles.begin(), dual_triangles.end()) ||
        std::adjacent_find(dual_triangles.begin(), dual_triangles.end()) != dual_triangles.end())
      return "the dual triangles are not sorted and unique";
    std::vector<char> carried(dual_triangles.size(), 0);
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      const AnisotropicVertex& v = vertices[k];
      const std::string name = "vertex " + std::to_string(k);
      if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y)) return name + " is not finite";
      if (!(v.sites[0] < v.sites[1] && v.sites[1] < v.sites[2] && v.sites[2] < n))
        return name + " is not labelled by three increasing site indices";
      const double tol = 1e-8 * (1 + std::abs(v.distance));
      for (SiteIndex s : v.sites) {
        if (is_hidden[s]) return name + " is labelled by hidden site " + std::to_string(s);
        if (std::abs(anisotropic_distance(v.position, sites[s]) - v.distance) > tol)
          return name + " is not at distance " + std::to_string(v.distance) + " from its site " + std::to_string(s);
      }
      for (SiteIndex j = 0; j < n; ++j)
        if (anisotropic_distance(v.position, sites[j]) < v.distance - tol)
          return name + " is strictly closer to site " + std::to_string(j) + " than to its three sites";
      const auto t = std::lower_bound(dual_triangles.begin(), dual_triangles.end(), v.sites);
      if (t == dual_triangles.end() || *t != v.sites) return name + ": its three sites are not a dual triangle";
      carried[static_cast<std::size_t>(t - dual_triangles.begin())] = 1;
    }
    for (std::size_t t = 0; t < dual_triangles.size(); ++t)
      if (!carried[t]) return "dual triangle " + std::to_string(t) + " carries no vertex";
    std::vector<std::pair<SiteIndex, SiteIndex>> sides;
    for (const auto& t : dual_triangles) sides.insert(sides.end(), {{t[0], t[1]}, {t[1], t[2]}, {t[0], t[2]}});
    std::sort(sides.begin(), sides.end());
    sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
    if (sides != dual_edges) return "the dual edges are not the sides of the dual triangles";
    return "";
  }();
  return detail::report_validity(violation, verbose);
}

std::vector<AnisotropicSite> read_anisotropic_sites(const std::string& path) {
  std::vector<AnisotropicSite> sites;
  for (const SiteRow& r : read_site_rows(path, anisotropic_columns, "anisotropic diagram")) {
    const AnisotropicSite s{r.values[0], r.values[1], r.values[2], r.values[3], r.values[4]};
    if (!is_positive_definite(s))
      throw InputError(path, r.line,
                       "found the metric [[" + number_text(s.a) + ", " + number_text(s.b) + "], [" + number_text(s.b) + ", " +
                           number_text(s.c) + "]]; expected a positive definite matrix (a > 0 and ac − b² > 0).");
    sites.push_back(s);
  }
  return sites;
}

}  // namespace laguerre::core
