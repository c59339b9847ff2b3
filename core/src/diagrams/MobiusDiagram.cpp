#include "laguerre/core/diagrams/MobiusDiagram.hpp"

#include "../detail/Filtered.hpp"
#include "detail/Validity.hpp"
#include "laguerre/core/Error.hpp"

// GCC 12 reports a false -Wmaybe-uninitialized inside the copies of CGAL's lazy weighted points (the
// static filter's Epick Weighted_point_3), at instantiations in this file.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <tuple>
#include <type_traits>
#include <stdexcept>
#include <unordered_map>

namespace laguerre::core {

namespace {
// The lifted spheres are built exactly (lazy exact numbers: interval filter, then exact rationals), so
// the triangulation, the hidden sites and point location are those of the true sites, not of their
// double-rounded liftings.
using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using Vb = CGAL::Regular_triangulation_vertex_base_3<K>;
using Vbi = CGAL::Triangulation_vertex_base_with_info_3<SiteIndex, K, Vb>;
using Cb = CGAL::Regular_triangulation_cell_base_3<K, CGAL::Triangulation_cell_base_3<K>, CGAL::Discard_hidden_points>;
using Tds = CGAL::Triangulation_data_structure_3<Vbi, Cb>;
using RT3 = CGAL::Regular_triangulation_3<K, Tds>;
using WP3 = RT3::Weighted_point;

using detail::filtered;
using detail::sign_of;

constexpr double two_pi = 2 * std::numbers::pi;

// ---------------------------------------------------------------------------------------------------
// Exact arithmetic on the vertices. A vertex is a point of L ∩ Q, L the power line of three lifted
// spheres: its coordinates are a + b√D with a, b, D rational in the input doubles. Every predicate
// below is a polynomial sign in such numbers, evaluated by detail::filtered (intervals, then exact
// rationals) on the input doubles, in coordinates centred on one site (a translation: exact).

/// a + b√D, for the D of the computation (D ≥ 0).
template <class NT>
struct Surd {
  NT a, b;
};

template <class NT>
struct SurdPoint {
  Surd<NT> x, y;
};

/// Arithmetic in Q(√D).
template <class NT>
struct Field {
  NT D;
  static Surd<NT> add(const Surd<NT>& u, const Surd<NT>& v) { return {u.a + v.a, u.b + v.b}; }
  static Surd<NT> sub(const Surd<NT>& u, const Surd<NT>& v) { return {u.a - v.a, u.b - v.b}; }
  static Surd<NT> scale(const Surd<NT>& u, const NT& k) { return {u.a * k, u.b * k}; }
  Surd<NT> mul(const Surd<NT>& u, const Surd<NT>& v) const { return {u.a * v.a + u.b * v.b * D, u.a * v.b + u.b * v.a}; }
  /// Exact sign of a + b√D (throws Uncertain_conversion_exception on an uncertain interval).
  Sign sign(const Surd<NT>& u) const {
    if constexpr (std::is_same_v<NT, CGAL::Interval_nt<false>>) {
      // The interval of a + b√D itself first: a may be 0 identically (an interval around 0) while the
      // whole is far from 0; otherwise the algebraic rule below decides (or gives up to exact).
      const NT v = u.a + u.b * CGAL::sqrt(D);
      if (v.inf() > 0) return Sign::positive;
      if (v.sup() < 0) return Sign::negative;
    }
    const Sign sa = sign_of<NT>(u.a);
    const Sign sb = sign_of<NT>(D) == Sign::zero ? Sign::zero : sign_of<NT>(u.b);
    if (sb == Sign::zero) return sa;
    if (sa == Sign::zero || sa == sb) return sb;
    const Sign c = sign_of<NT>(u.a * u.a - u.b * u.b * D);  // |a| against |b|√D
    return c == Sign::positive ? sa : c == Sign::negative ? sb : Sign::zero;
  }
};

/// A site's Möbius distance in coordinates centred on `o`: δ(x) = λ|x − q|² − μ, q = p − o.
template <class NT>
struct LocalSite {
  NT qx, qy, lambda, mu;
  LocalSite(const MobiusSite& s, const MobiusSite& o)
      : qx(NT(s.x) - NT(o.x)), qy(NT(s.y) - NT(o.y)), lambda(NT(s.lambda)), mu(NT(s.mu)) {}
  /// δ at a point of Q(√D).
  Surd<NT> delta(const Field<NT>& f, const SurdPoint<NT>& v) const {
    const Surd<NT> dx{v.x.a - qx, v.x.b}, dy{v.y.a - qy, v.y.b};
    Surd<NT> s = Field<NT>::scale(Field<NT>::add(f.mul(dx, dx), f.mul(dy, dy)), lambda);
    s.a = s.a - mu;
    return s;
  }
  /// ∇δ at v: 2λ(v − q).
  std::array<Surd<NT>, 2> gradient(const SurdPoint<NT>& v) const {
    const NT two_l = NT(2) * lambda;
    return {Surd<NT>{(v.x.a - qx) * two_l, v.x.b * two_l}, Surd<NT>{(v.y.a - qy) * two_l, v.y.b * two_l}};
  }
};

/// The points of L ∩ Q for the sites `tri` (L: the common power line of their lifted spheres), in
/// coordinates centred on sites[tri[0]]: x = x0 + d (t0 + s t1 √D) for the roots s = ±1.
template <class NT>
struct FacetRoots {
  int count = 0;  ///< 0, 1 or 2 distinct points
  Field<NT> field{NT(0)};
  NT x0[2] = {NT(0), NT(0)}, d[2] = {NT(0), NT(0)}, t0 = NT(0), t1 = NT(0);
  SurdPoint<NT> point(int s) const {
    const NT b = s > 0 ? t1 : -t1;
    return {{x0[0] + d[0] * t0, d[0] * b}, {x0[1] + d[1] * t0, d[1] * b}};
  }
};

template <class NT>
FacetRoots<NT> facet_roots(const std::vector<MobiusSite>& sites, const std::array<SiteIndex, 3>& tri) {
  // δ_s(X) = λ_s z − 2 b_s·x + c_s on z = |x|² (b_s = λ_s q_s, c_s = λ_s|q_s|² − μ_s); the bisector
  // planes n·X = h with n = (−2(b_i − b_s), λ_i − λ_s), h = c_s − c_i.
  const MobiusSite& o = sites[tri[0]];
  struct Lin {
    NT b0, b1, c, l;
  };
  auto lin = [&](const MobiusSite& s) {
    const LocalSite<NT> ls(s, o);
    return Lin{ls.lambda * ls.qx, ls.lambda * ls.qy, ls.lambda * (ls.qx * ls.qx + ls.qy * ls.qy) - ls.mu, ls.lambda};
  };
  const Lin ci = lin(o), cj = lin(sites[tri[1]]), ck = lin(sites[tri[2]]);
  const NT n1[3] = {NT(-2) * (ci.b0 - cj.b0), NT(-2) * (ci.b1 - cj.b1), ci.l - cj.l};
  const NT n2[3] = {NT(-2) * (ci.b0 - ck.b0), NT(-2) * (ci.b1 - ck.b1), ci.l - ck.l};
  const NT h1 = cj.c - ci.c, h2 = ck.c - ci.c;
  const NT d[3] = {n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2], n1[0] * n2[1] - n1[1] * n2[0]};
  const NT dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  FacetRoots<NT> r;
  if (sign_of<NT>(dd) == Sign::zero) return r;  // parallel bisector planes (not for a facet)
  // X0 = (h1 (n2 × d) + h2 (d × n1)) / |d|².
  const NT a[3] = {n2[1] * d[2] - n2[2] * d[1], n2[2] * d[0] - n2[0] * d[2], n2[0] * d[1] - n2[1] * d[0]};
  const NT b[3] = {d[1] * n1[2] - d[2] * n1[1], d[2] * n1[0] - d[0] * n1[2], d[0] * n1[1] - d[1] * n1[0]};
  NT x0[3] = {NT(0), NT(0), NT(0)};
  for (int c = 0; c < 3; ++c) x0[c] = (h1 * a[c] + h2 * b[c]) / dd;
  // (x0 + t dx)² + (y0 + t dy)² = z0 + t dz.
  const NT qa = d[0] * d[0] + d[1] * d[1];
  const NT qb = NT(2) * (x0[0] * d[0] + x0[1] * d[1]) - d[2];
  const NT qc = x0[0] * x0[0] + x0[1] * x0[1] - x0[2];
  r.x0[0] = x0[0], r.x0[1] = x0[1], r.d[0] = d[0], r.d[1] = d[1];
  if (sign_of<NT>(qa) == Sign::zero) {  // L vertical: one point (power diagram case)
    if (sign_of<NT>(qb) == Sign::zero) return r;
    r.count = 1, r.t0 = -qc / qb;
    return r;
  }
  const NT disc = qb * qb - NT(4) * qa * qc;
  const Sign sd = sign_of<NT>(disc);
  if (sd == Sign::negative) return r;
  r.t0 = -qb / (NT(2) * qa);
  if (sd == Sign::zero) {  // L tangent to Q: the bisector circles touch, one vertex
    r.count = 1;
    return r;
  }
  r.count = 2, r.t1 = NT(1) / (NT(2) * qa), r.field = Field<NT>{disc};
  return r;
}

/// Double approximation of a + b√D, without cancellation: (a² − b²D)/(a − b√D) when the signs differ.
template <class NT>
double approximate(const Surd<NT>& u, const NT& D) {
  const double a = CGAL::to_double(u.a), b = CGAL::to_double(u.b), r = std::sqrt(std::max(0.0, CGAL::to_double(D)));
  if (b == 0 || r == 0 || (a >= 0) == (b >= 0)) return a + b * r;
  return CGAL::to_double(u.a * u.a - u.b * u.b * D) / (a - b * r);
}

/// What the apex test of a facet decides for one root: whether it is a vertex, and which apexes tie.
struct RootVerdict {
  int s = 1;
  bool kept = false;
  std::array<bool, 3> tie{};
};

/// The vertices of the facet `tri` whose power edge is cut by the apexes (no_site: none): for each
/// point of L ∩ Q, kept when no apex is strictly closer. Exact.
std::vector<RootVerdict> facet_vertices(const std::vector<MobiusSite>& sites, const std::array<SiteIndex, 3>& tri,
                                        const std::array<SiteIndex, 3>& apex) {
  return filtered([&]<class NT>() {
    const FacetRoots<NT> r = facet_roots<NT>(sites, tri);
    std::vector<RootVerdict> out;
    const MobiusSite& o = sites[tri[0]];
    const LocalSite<NT> li(o, o);
    for (int k = 0; k < r.count; ++k) {
      RootVerdict v;
      v.s = k == 0 ? 1 : -1;
      const SurdPoint<NT> x = r.point(v.s);
      const Surd<NT> di = li.delta(r.field, x);
      v.kept = true;
      for (std::size_t a = 0; a < 3 && v.kept; ++a) {
        if (apex[a] == no_site) continue;
        const Sign s = r.field.sign(Field<NT>::sub(LocalSite<NT>(sites[apex[a]], o).delta(r.field, x), di));
        v.kept = s != Sign::negative;
        v.tie[a] = s == Sign::zero;
      }
      out.push_back(v);
    }
    return out;
  });
}

/// Double coordinates of the root s of facet `tri` (intervals when they are tight, else exact inputs).
Point2 vertex_point(const std::vector<MobiusSite>& sites, const std::array<SiteIndex, 3>& tri, int s) {
  const MobiusSite& o = sites[tri[0]];
  // In global coordinates: a vertex near (0, 0) of sites far from it keeps its precision.
  auto global = [&]<class NT>(const FacetRoots<NT>& r) {
    SurdPoint<NT> x = r.point(s);
    x.x.a = x.x.a + NT(o.x), x.y.a = x.y.a + NT(o.y);
    return x;
  };
  auto compute = [&]<class NT>() {
    const FacetRoots<NT> r = facet_roots<NT>(sites, tri);
    const SurdPoint<NT> x = global(r);
    return Point2{approximate(x.x, r.field.D), approximate(x.y, r.field.D)};
  };
  {
    CGAL::Protect_FPU_rounding<true> guard;
    try {
      using I = CGAL::Interval_nt<false>;
      const FacetRoots<I> r = facet_roots<I>(sites, tri);
      const SurdPoint<I> x = global(r);
      auto tight = [](const I& v) { return std::isfinite(v.inf()) && std::isfinite(v.sup()) && v.sup() - v.inf() <= 1e-12 * std::fabs(v.sup() + v.inf()); };
      const I nx = x.x.a * x.x.a - x.x.b * x.x.b * r.field.D, ny = x.y.a * x.y.a - x.y.b * x.y.b * r.field.D;
      if (tight(x.x.a) && tight(x.x.b) && tight(x.y.a) && tight(x.y.b) && tight(r.field.D) && tight(nx) && tight(ny)) {
        const Point2 p = compute.template operator()<I>();
        if (std::isfinite(p.x) && std::isfinite(p.y)) return p;
      }
    } catch (CGAL::Uncertain_conversion_exception&) {
    }
  }
  return compute.template operator()<CGAL::Exact_rational>();
}

/// The bisector of sites i and j in doubles, within 1e-9 relative of the exact values (intervals when
/// they are that tight, else exact rationals rounded once): a circle (centre, radius; λ_i ≠ λ_j; radius 0 when empty) or a line
/// (a point and the unit direction (−g_y, g_x)/|g|, g = λ_i p_i − λ_j p_j).
struct Bisector {
  bool circle = false;
  Point2 c, x0, dir;
  double r = 0;
};

Bisector bisector(const std::vector<MobiusSite>& sites, SiteIndex i, SiteIndex j) {
  auto parts = [&]<class NT>() {
    const NT li(sites[i].lambda), lj(sites[j].lambda), xi(sites[i].x), yi(sites[i].y), xj(sites[j].x), yj(sites[j].y);
    const NT gx = li * xi - lj * xj, gy = li * yi - lj * yj;
    const NT dc = li * (xi * xi + yi * yi) - NT(sites[i].mu) - (lj * (xj * xj + yj * yj) - NT(sites[j].mu));
    const NT dl = li - lj;
    // δ_i − δ_j = dl |x|² − 2 g·x + dc.
    if (sites[i].lambda != sites[j].lambda) {
      const NT cx = gx / dl, cy = gy / dl;
      return std::array<NT, 4>{cx, cy, cx * cx + cy * cy - dc / dl, NT(0)};
    }
    const NT k = dc / (NT(2) * (gx * gx + gy * gy));
    return std::array<NT, 4>{gx * k, gy * k, gx, gy};
  };
  auto finish = [&](const std::array<double, 4>& v) {
    Bisector b;
    b.circle = sites[i].lambda != sites[j].lambda;
    if (b.circle) {
      b.c = {v[0], v[1]}, b.r = std::sqrt(std::max(0.0, v[2]));
    } else {
      const double gn = std::hypot(v[2], v[3]);
      b.x0 = {v[0], v[1]}, b.dir = {-v[3] / gn, v[2] / gn};
    }
    return b;
  };
  if (sites[i].lambda == sites[j].lambda && (sites[i].lambda == 0 || (sites[i].x == sites[j].x && sites[i].y == sites[j].y)))
    return Bisector{};  // g = 0: no line
  {
    CGAL::Protect_FPU_rounding<true> guard;
    using I = CGAL::Interval_nt<false>;
    const std::array<I, 4> v = parts.template operator()<I>();
    bool tight = true;
    for (const I& x : v)
      tight = tight && std::isfinite(x.inf()) && std::isfinite(x.sup()) && x.sup() - x.inf() <= 1e-9 * std::fabs(x.sup() + x.inf());
    if (tight) {
      std::array<double, 4> m{};
      for (int k = 0; k < 4; ++k) m[static_cast<std::size_t>(k)] = CGAL::to_double(v[static_cast<std::size_t>(k)]);
      return finish(m);
    }
  }
  const std::array<CGAL::Exact_rational, 4> v = parts.template operator()<CGAL::Exact_rational>();
  return finish({CGAL::to_double(v[0]), CGAL::to_double(v[1]), CGAL::to_double(v[2]), CGAL::to_double(v[3])});
}

/// Along the bisector of i and j, at the vertex (tri, s) (which is on it): whether the bisector just
/// after (forward) and just before (backward) the vertex is at least as close to i as to every site of
/// `others`. Forward is counter-clockwise around the circle's centre when λ_i ≠ λ_j, the direction
/// (−g_y, g_x) of the line when λ_i = λ_j (g = λ_i p_i − λ_j p_j). Exact, tangencies included (then the
/// sign of δ_k − δ_i is the same on both sides and is read at another point of the bisector).
std::pair<bool, bool> departures(const std::vector<MobiusSite>& sites, const std::array<SiteIndex, 3>& tri, int s,
                                 SiteIndex i, SiteIndex j, const std::vector<SiteIndex>& others) {
  return filtered([&]<class NT>() {
    const FacetRoots<NT> r = facet_roots<NT>(sites, tri);
    const Field<NT>& f = r.field;
    const SurdPoint<NT> v = r.point(s);
    const MobiusSite& o = sites[tri[0]];
    const LocalSite<NT> li(sites[i], o), lj(sites[j], o);
    const auto gi = li.gradient(v), gj = lj.gradient(v);
    const std::array<Surd<NT>, 2> G{Field<NT>::sub(gi[0], gj[0]), Field<NT>::sub(gi[1], gj[1])};
    const NT dl = li.lambda - lj.lambda;
    const bool circle = sign_of<NT>(dl) != Sign::zero;
    const bool flip = circle ? sign_of<NT>(dl) == Sign::negative : true;  // forward = ±rot90(G)
    bool fwd = true, bwd = true;
    for (SiteIndex k : others) {
      const LocalSite<NT> lk(sites[k], o);
      const auto gk = lk.gradient(v);
      const std::array<Surd<NT>, 2> H{Field<NT>::sub(gk[0], gi[0]), Field<NT>::sub(gk[1], gi[1])};
      // H · rot90(G) = H_y G_x − H_x G_y
      Sign d = f.sign(Field<NT>::sub(f.mul(H[1], G[0]), f.mul(H[0], G[1])));
      if (flip) d = d == Sign::positive ? Sign::negative : d == Sign::negative ? Sign::positive : d;
      if (d == Sign::positive) bwd = false;
      else if (d == Sign::negative) fwd = false;
      else {
        // Tangent: δ_k − δ_i has a double zero at v on the bisector; its sign elsewhere is constant.
        SurdPoint<NT> w;
        if (circle) {  // the antipode 2c − v, c = (λ_i q_i − λ_j q_j)/(λ_i − λ_j)
          const NT cx = (li.lambda * li.qx - lj.lambda * lj.qx) / dl, cy = (li.lambda * li.qy - lj.lambda * lj.qy) / dl;
          w = {{NT(2) * cx - v.x.a, -v.x.b}, {NT(2) * cy - v.y.a, -v.y.b}};
        } else {  // v + rot90(G)
          w = {Field<NT>::sub(v.x, G[1]), Field<NT>::add(v.y, G[0])};
        }
        if (f.sign(Field<NT>::sub(lk.delta(f, w), li.delta(f, w))) == Sign::negative) fwd = bwd = false;
      }
    }
    return std::pair{fwd, bwd};
  });
}

/// Whether the bisector circle of i and j (λ_i ≠ λ_j) has a positive radius: a point circle (e.g. two
/// sites at one place, μ equal) or an empty one carries no edge, whatever vertices lie on it. Exact.
bool circle_has_radius(const std::vector<MobiusSite>& sites, SiteIndex i, SiteIndex j) {
  return filtered([&]<class NT>() {
    const MobiusSite& o = sites[i];
    const LocalSite<NT> li(o, o), lj(sites[j], o);
    const NT dl = li.lambda - lj.lambda;
    const NT gx = -lj.lambda * lj.qx, gy = -lj.lambda * lj.qy;
    const NT dc = -li.mu - (lj.lambda * (lj.qx * lj.qx + lj.qy * lj.qy) - lj.mu);
    const NT cx = gx / dl, cy = gy / dl;
    return sign_of<NT>(cx * cx + cy * cy - dc / dl) == Sign::positive;
  });
}

/// For a bisector of i and j with no vertex on it: whether the whole curve (circle or line) is an edge,
/// i.e. one of its points is at least as close to i as to every site of `others`. False when the
/// bisector is empty or a point. Exact.
bool whole_bisector_is_edge(const std::vector<MobiusSite>& sites, SiteIndex i, SiteIndex j, const std::vector<SiteIndex>& others) {
  return filtered([&]<class NT>() {
    const MobiusSite& o = sites[i];
    const LocalSite<NT> li(o, o), lj(sites[j], o);
    const NT dl = li.lambda - lj.lambda;
    const NT gx = -lj.lambda * lj.qx, gy = -lj.lambda * lj.qy;  // b_i − b_j
    const NT dc = -li.mu - (lj.lambda * (lj.qx * lj.qx + lj.qy * lj.qy) - lj.mu);
    Field<NT> f{NT(0)};
    SurdPoint<NT> w;
    if (sign_of<NT>(dl) != Sign::zero) {
      const NT cx = gx / dl, cy = gy / dl, r2 = cx * cx + cy * cy - dc / dl;
      if (sign_of<NT>(r2) != Sign::positive) return false;
      f = Field<NT>{r2};
      w = {{cx, NT(1)}, {cy, NT(0)}};  // (c_x + √r², c_y)
    } else {
      const NT g2 = gx * gx + gy * gy;
      if (sign_of<NT>(g2) == Sign::zero) return false;
      w = {{gx * dc / (NT(2) * g2), NT(0)}, {gy * dc / (NT(2) * g2), NT(0)}};
    }
    const Surd<NT> di = li.delta(f, w);
    for (SiteIndex k : others)
      if (f.sign(Field<NT>::sub(LocalSite<NT>(sites[k], o).delta(f, w), di)) == Sign::negative) return false;
    return true;
  });
}

/// Counter-clockwise order at infinity of two ends of unbounded bisector lines: the ends go in the
/// directions u_a, u_b (u = ±rot90(g), g = λ_i p_i − λ_j p_j) along lines through the points of the
/// sites. Negative when a comes first (for directions less than π apart), zero for the same end.
struct LineEnd {
  SiteIndex i, j;
  bool forward;  ///< the end in direction +rot90(g) (else −rot90(g))
};

Sign compare_ends(const std::vector<MobiusSite>& sites, const LineEnd& a, const LineEnd& b) {
  return filtered([&]<class NT>() {
    const MobiusSite& o = sites[a.i];
    struct Line {
      NT ux, uy, px, py;
    };
    auto line = [&](const LineEnd& e) {
      const LocalSite<NT> li(sites[e.i], o), lj(sites[e.j], o);
      const NT gx = li.lambda * li.qx - lj.lambda * lj.qx, gy = li.lambda * li.qy - lj.lambda * lj.qy;
      // δ_i − δ_j = −2 g·x + (c_i − c_j) (equal λ): the point g (c_i − c_j)/(2|g|²) is on the line.
      const NT ci = li.lambda * (li.qx * li.qx + li.qy * li.qy) - li.mu, cj = lj.lambda * (lj.qx * lj.qx + lj.qy * lj.qy) - lj.mu;
      const NT k = (ci - cj) / (NT(2) * (gx * gx + gy * gy));
      const NT sgn(e.forward ? 1 : -1);
      return Line{-gy * sgn, gx * sgn, gx * k, gy * k};
    };
    const Line la = line(a), lb = line(b);
    const Sign cross = sign_of<NT>(la.ux * lb.uy - la.uy * lb.ux);
    if (cross != Sign::zero) return cross == Sign::positive ? Sign::negative : Sign::positive;
    // Parallel, same direction: the later one counter-clockwise lies further along rot90(u).
    return sign_of<NT>((la.px - lb.px) * -la.uy + (la.py - lb.py) * la.ux);
  });
}

/// Sign of U + V√D2 with U, V in Q(√D1) (two vertices of different facets compared), exactly.
template <class NT>
Sign tower_sign(const Field<NT>& f1, const Surd<NT>& U, const Surd<NT>& V, const NT& D2) {
  if constexpr (std::is_same_v<NT, CGAL::Interval_nt<false>>) {
    const NT r1 = CGAL::sqrt(f1.D), v = U.a + U.b * r1 + (V.a + V.b * r1) * CGAL::sqrt(D2);
    if (v.inf() > 0) return Sign::positive;
    if (v.sup() < 0) return Sign::negative;
  }
  const Sign su = f1.sign(U);
  const Sign sv = sign_of<NT>(D2) == Sign::zero ? Sign::zero : f1.sign(V);
  if (sv == Sign::zero) return su;
  if (su == Sign::zero || su == sv) return sv;
  const Surd<NT> uu = f1.mul(U, U), vv = Field<NT>::scale(f1.mul(V, V), D2);
  const Sign c = f1.sign(Field<NT>::sub(uu, vv));
  return c == Sign::positive ? su : c == Sign::negative ? sv : Sign::zero;
}

/// Whether the roots (tri_a, s_a) and (tri_b, s_b) are the same point. Exact.
bool same_point(const std::vector<MobiusSite>& sites, const std::array<SiteIndex, 3>& tri_a, int s_a,
                const std::array<SiteIndex, 3>& tri_b, int s_b) {
  return filtered([&]<class NT>() {
    const FacetRoots<NT> ra = facet_roots<NT>(sites, tri_a), rb = facet_roots<NT>(sites, tri_b);
    const SurdPoint<NT> va = ra.point(s_a), vb = rb.point(s_b);
    const MobiusSite &oa = sites[tri_a[0]], &ob = sites[tri_b[0]];
    const Surd<NT> ux{va.x.a + NT(oa.x) - vb.x.a - NT(ob.x), va.x.b}, vx{-vb.x.b, NT(0)};
    if (tower_sign(ra.field, ux, vx, rb.field.D) != Sign::zero) return false;
    const Surd<NT> uy{va.y.a + NT(oa.y) - vb.y.a - NT(ob.y), va.y.b}, vy{-vb.y.b, NT(0)};
    return tower_sign(ra.field, uy, vy, rb.field.D) == Sign::zero;
  });
}

/// Order along the bisector of i and j of two distinct vertices on it, given by (tri, s) each: negative
/// when a comes first going forward (the direction of `departures`; around a circle, for two vertices
/// less than π apart). Exact.
Sign compare_along(const std::vector<MobiusSite>& sites, const std::array<SiteIndex, 3>& tri_a, int s_a,
                   const std::array<SiteIndex, 3>& tri_b, int s_b, SiteIndex i, SiteIndex j) {
  return filtered([&]<class NT>() {
    const FacetRoots<NT> ra = facet_roots<NT>(sites, tri_a), rb = facet_roots<NT>(sites, tri_b);
    const SurdPoint<NT> va = ra.point(s_a), vb = rb.point(s_b);
    // Global coordinates: local ones plus the frame's origin (rational).
    const MobiusSite &oa = sites[tri_a[0]], &ob = sites[tri_b[0]];
    const Surd<NT> xa{va.x.a + NT(oa.x), va.x.b}, ya{va.y.a + NT(oa.y), va.y.b};
    const NT xb = vb.x.a + NT(ob.x), yb = vb.y.a + NT(ob.y), xbr = vb.x.b, ybr = vb.y.b;  // b = xb + xbr √D_b
    const NT li(sites[i].lambda), lj(sites[j].lambda);
    const NT gx = li * NT(sites[i].x) - lj * NT(sites[j].x), gy = li * NT(sites[i].y) - lj * NT(sites[j].y);
    const NT dl = li - lj;
    if (sign_of<NT>(dl) == Sign::zero) {
      // (a − b)·u, u = rot90(g) = (−g_y, g_x).
      const NT ux = -gy, uy = gx;
      const Surd<NT> U{(xa.a - xb) * ux + (ya.a - yb) * uy, xa.b * ux + ya.b * uy};
      const Surd<NT> V{-(xbr * ux + ybr * uy), NT(0)};
      return tower_sign(ra.field, U, V, rb.field.D);
    }
    // −cross(a − c, b − c), c = g/(λ_i − λ_j).
    const NT cx = gx / dl, cy = gy / dl;
    const Surd<NT> X{xa.a - cx, xa.b}, Y{ya.a - cy, ya.b};
    const NT p = xb - cx, q = xbr, pp = yb - cy, qq = ybr;
    // cross = X (pp + qq r_b) − Y (p + q r_b)
    const Surd<NT> U = Field<NT>::sub(Field<NT>::scale(X, pp), Field<NT>::scale(Y, p));
    const Surd<NT> V = Field<NT>::sub(Field<NT>::scale(X, qq), Field<NT>::scale(Y, q));
    const Sign c = tower_sign(ra.field, U, V, rb.field.D);
    return c == Sign::positive ? Sign::negative : c == Sign::negative ? Sign::positive : Sign::zero;
  });
}

/// δ_a − δ_b = A|x|² − 2 (B_x x + B_y y) + C as (A, B_x, B_y, C): A = λ_a − λ_b, B = λ_a p_a − λ_b p_b,
/// C = c_a − c_b with c = λ|p|² − μ.
template <class NT>
std::array<NT, 4> difference(const MobiusSite& a, const MobiusSite& b) {
  const NT la(a.lambda), lb(b.lambda), xa(a.x), ya(a.y), xb(b.x), yb(b.y);
  return {la - lb, la * xa - lb * xb, la * ya - lb * yb,
          la * (xa * xa + ya * ya) - NT(a.mu) - (lb * (xb * xb + yb * yb) - NT(b.mu))};
}

/// δ_a − δ_b as from `difference`, in doubles, with a bound m of each component's magnitude: the
/// computed component is within 8ε·m of the exact one (ε = 2^-53; a few roundings of terms
/// bounded by m, about 7ε·m in all), up to underflow.
struct ApproxDifference {
  std::array<double, 4> v, m;
};

ApproxDifference approx_difference(const MobiusSite& a, const MobiusSite& b) {
  const double pa = a.x * a.x + a.y * a.y, pb = b.x * b.x + b.y * b.y;
  ApproxDifference d;
  d.v = {a.lambda - b.lambda, a.lambda * a.x - b.lambda * b.x, a.lambda * a.y - b.lambda * b.y,
         a.lambda * pa - a.mu - (b.lambda * pb - b.mu)};
  d.m = {std::fabs(a.lambda) + std::fabs(b.lambda), std::fabs(a.lambda * a.x) + std::fabs(b.lambda * b.x),
         std::fabs(a.lambda * a.y) + std::fabs(b.lambda * b.y),
         std::fabs(a.lambda * pa) + std::fabs(a.mu) + std::fabs(b.lambda * pb) + std::fabs(b.mu)};
  return d;
}

/// Whether u = δ_k − δ_i and w = δ_k − δ_j may satisfy u = −s w with s > 0 (u · w < 0 and every 2 × 2
/// minor 0): false only when the doubles prove otherwise, a value beyond its error bound. The bound
/// (64ε times the products of the magnitudes: twice the 8ε·m errors of both factors, the roundings of the
/// products and sums, with margin; plus 1e-290 for underflow) keeps every exact candidate, and an
/// overflow gives inf or NaN, which rejects nothing; the candidates are then decided exactly.
bool may_be_between(const ApproxDifference& u, const ApproxDifference& w) {
  constexpr double eps = 0x1p-53, rel = 64 * eps, tiny = 1e-290;
  double dot = 0, dot_err = tiny;
  for (std::size_t a = 0; a < 4; ++a) dot += u.v[a] * w.v[a], dot_err += rel * u.m[a] * w.m[a];
  if (dot > dot_err) return false;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b)
      if (std::fabs(u.v[a] * w.v[b] - u.v[b] * w.v[a]) > rel * (u.m[a] * w.m[b] + u.m[b] * w.m[a]) + tiny) return false;
  return true;
}

/// Whether δ_k = (1 − t) δ_i + t δ_j for some 0 < t < 1, i.e. δ_k − δ_i = −s (δ_k − δ_j) with s > 0:
/// then δ_k ≥ min(δ_i, δ_j) everywhere, with equality only on the bisector of i and j. Exact.
bool strictly_between(const std::vector<MobiusSite>& sites, SiteIndex k, SiteIndex i, SiteIndex j) {
  return filtered([&]<class NT>() {
    const std::array<NT, 4> u = difference<NT>(sites[k], sites[i]), w = difference<NT>(sites[k], sites[j]);
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = a + 1; b < 4; ++b)
        if (sign_of<NT>(u[a] * w[b] - u[b] * w[a]) != Sign::zero) return false;
    return sign_of<NT>(u[0] * w[0] + u[1] * w[1] + u[2] * w[2] + u[3] * w[3]) == Sign::negative;
  });
}

/// Point-in-polygon by crossing number (polygon as a closed polyline, last point may repeat the first).
bool inside_polyline(const std::vector<Point2>& poly, Point2 q) {
  bool in = false;
  for (std::size_t k = 0, n = poly.size(); k < n; ++k) {
    const Point2 a = poly[k], b = poly[(k + 1) % n];
    if ((a.y > q.y) != (b.y > q.y)) {
      const double x = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (q.x < x) in = !in;
    }
  }
  return in;
}

/// Signed area of a loop summed relative to its first point: the rounding is then relative to the
/// loop's size, not to its distance from the origin (a small cell far away).
double own_area(const BoundaryLoop& l) { return l.area(l.pieces.empty() ? Point2{} : l.pieces.front().curve.from); }

double angle_of(Point2 c, Point2 p) { return std::atan2(p.y - c.y, p.x - c.x); }

CurvePiece arc(Point2 c, double r, double start, double sweep) {
  CurvePiece p;
  p.is_arc = true;
  p.centre = c, p.radius = r, p.start = start, p.sweep = sweep;
  p.from = {c.x + r * std::cos(start), c.y + r * std::sin(start)};
  p.to = {c.x + r * std::cos(start + sweep), c.y + r * std::sin(start + sweep)};
  return p;
}

CurvePiece segment(Point2 a, Point2 b) {
  CurvePiece p;
  p.from = a, p.to = b;
  return p;
}
}  // namespace

double lifted_magnitude(const MobiusSite& s) {
  const double l = s.lambda, pp = s.x * s.x + s.y * s.y, h = (1 - l) / 2;
  const double w = l * (l - 1) * pp + h * h + s.mu;
  const double m = std::max({std::fabs(l * s.x), std::fabs(l * s.y), std::fabs(h), std::fabs(w)});
  return std::isnan(m) ? std::numeric_limits<double>::infinity() : m;
}

void require_liftable(const MobiusSite& s, const std::string& source, std::size_t line, const std::string& what) {
  const double m = lifted_magnitude(s);
  if (m <= max_lifted_magnitude) return;
  std::ostringstream msg;
  msg.precision(3);
  msg << what << " (x, y, lambda, mu) = (" << s.x << ", " << s.y << ", " << s.lambda << ", " << s.mu
      << ") lifts to a sphere of magnitude " << m << "; expected at most 1e75 (centre coordinates λx, λy, (1 − λ)/2 and"
      << " weight λ(λ − 1)|p|² + ((1 − λ)/2)² + μ), so that the exact predicates stay within double range.";
  throw InputError(source, line, msg.str());
}

// ---------------------------------------------------------------------------------------------------
// Curve pieces and loops

std::vector<Point2> CurvePiece::sample(double max_step, double max_error) const {
  if (!is_arc) return {from, to};
  // A chord of angle θ deviates r(1 − cos(θ/2)) ≈ rθ²/8 from its arc.
  if (max_error < radius) max_step = std::min(max_step, 2 * std::acos(1 - max_error / radius));
  const auto steps = static_cast<int>(std::min(std::ceil(std::fabs(sweep) / std::max(max_step, 1e-6)), 1e7));
  const int n = std::max(steps, 1);
  std::vector<Point2> out;
  out.reserve(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double t = start + sweep * k / n;
    out.push_back({centre.x + radius * std::cos(t), centre.y + radius * std::sin(t)});
  }
  out.front() = from, out.back() = to;
  return out;
}

CurvePiece CurvePiece::reversed() const {
  CurvePiece r = *this;
  std::swap(r.from, r.to);
  if (is_arc) r.start = start + sweep, r.sweep = -sweep;
  return r;
}

double CurvePiece::area_term(Point2 origin) const {
  if (!is_arc) return 0.5 * ((from.x - origin.x) * (to.y - origin.y) - (from.y - origin.y) * (to.x - origin.x));
  // ∫ (x dy − y dx) over x = c + r(cos t, sin t) = r²Δ + c_x r (sin t1 − sin t0) − c_y r (cos t1 − cos t0).
  const double t0 = start, t1 = start + sweep;
  const double cx = centre.x - origin.x, cy = centre.y - origin.y;
  return 0.5 * (radius * radius * sweep + cx * radius * (std::sin(t1) - std::sin(t0)) - cy * radius * (std::cos(t1) - std::cos(t0)));
}

Point2 CurvePiece::midpoint() const {
  if (!is_arc) return {(from.x + to.x) / 2, (from.y + to.y) / 2};
  const double t = start + sweep / 2;
  return {centre.x + radius * std::cos(t), centre.y + radius * std::sin(t)};
}

double BoundaryLoop::area(Point2 origin) const {
  double a = 0;
  for (const BoundaryPiece& p : pieces) a += p.curve.area_term(origin);
  return a;
}

std::vector<Point2> BoundaryLoop::polyline(double max_step, double max_error) const {
  std::vector<Point2> out;
  for (const BoundaryPiece& p : pieces) {
    auto s = p.curve.sample(max_step, max_error);
    out.insert(out.end(), s.begin(), s.end() - 1);
  }
  return out;
}

double CellComponent::area(Point2 origin) const {
  double a = outer.area(origin);
  for (const BoundaryLoop& h : holes) a += h.area(origin);
  return a;
}

// ---------------------------------------------------------------------------------------------------
// The diagram

struct MobiusDiagram::Impl {
  std::vector<MobiusSite> sites;
  Box box, frame;
  RT3 rt;
  std::vector<bool> hidden, weakly_hidden;
  std::vector<std::vector<SiteIndex>> adjacency;
  std::vector<std::pair<SiteIndex, SiteIndex>> lifted;
  std::vector<MobiusVertex> vertices;
  /// Per vertex: a facet and root that give it exactly, and every site at equal distance there.
  struct Exact {
    std::array<SiteIndex, 3> tri;
    int s;
    std::vector<SiteIndex> sites;
  };
  std::vector<Exact> exact;
  std::vector<MobiusEdge> edges;
  std::vector<std::vector<CellComponent>> cells;
  /// Pieces between two vertices consecutive on a bisector whose two ends disagree on whether the piece
  /// is an edge: the double ordering of two distinct, nearly coincident vertices went wrong.
  std::size_t order_conflicts = 0;
  // Lazily built polylines for locate_in_cells: per (site, component) the outer and hole polylines.
  struct ComponentShape {
    SiteIndex site;
    std::size_t component;
    Box bounds;
    std::vector<Point2> outer;
    std::vector<std::vector<Point2>> holes;
  };
  mutable std::vector<ComponentShape> shapes;
  mutable bool shapes_built = false;

  SiteIndex locate(Point2 q) const {
    if (rt.number_of_vertices() == 0) return no_site;
    const FT x(q.x), y(q.y);
    return rt.nearest_power_vertex(K::Point_3(x, y, x * x + y * y))->info();
  }
  void build();
  /// Removes the weakly hidden sites from rt (adjacency: rt's); whether there were any.
  bool remove_weakly_hidden();
  void build_vertices(std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair);
  void build_edges(const std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair,
                   std::vector<std::pair<std::size_t, std::size_t>>& unbounded);
  void build_cells(const std::vector<std::pair<std::size_t, std::size_t>>& unbounded);
  std::uint64_t key(SiteIndex a, SiteIndex b) const {
    if (a > b) std::swap(a, b);
    return static_cast<std::uint64_t>(a) * sites.size() + b;
  }
  /// The sites of vertex v other than i and j.
  std::vector<SiteIndex> others(std::size_t v, SiteIndex i, SiteIndex j) const {
    std::vector<SiteIndex> out;
    for (SiteIndex k : exact[v].sites)
      if (k != i && k != j) out.push_back(k);
    return out;
  }
};

void MobiusDiagram::Impl::build() {
  const std::size_t n = sites.size();
  // Lifted spheres Σ_i: centre (λp, (1 − λ)/2), weight λ²|p|² + ((1 − λ)/2)² − λ|p|² + μ, exactly.
  std::vector<std::pair<WP3, SiteIndex>> input;
  input.reserve(n);
  for (SiteIndex i = 0; i < n; ++i) {
    const MobiusSite& s = sites[i];
    const FT l(s.lambda), x(s.x), y(s.y), h = (FT(1) - l) / 2;
    input.emplace_back(WP3(K::Point_3(l * x, l * y, h), l * (l - 1) * (x * x + y * y) + h * h + FT(s.mu)), i);
  }
  rt.insert(input.begin(), input.end());
  auto read_edges = [&] {
    adjacency.assign(n, {});
    lifted.clear();
    for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
      const SiteIndex a = e->first->vertex(e->second)->info(), b = e->first->vertex(e->third)->info();
      adjacency[a].push_back(b), adjacency[b].push_back(a);
      lifted.emplace_back(std::min(a, b), std::max(a, b));
    }
  };
  read_edges();
  if (remove_weakly_hidden()) read_edges();  // the triangulation changed
  hidden.assign(n, true);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) hidden[v->info()] = false;
  std::sort(lifted.begin(), lifted.end());

  std::unordered_map<std::uint64_t, std::vector<std::size_t>> on_pair;
  build_vertices(on_pair);
  std::vector<std::pair<std::size_t, std::size_t>> unbounded;
  build_edges(on_pair, unbounded);
  build_cells(unbounded);
}

bool MobiusDiagram::Impl::remove_weakly_hidden() {
  // A weakly hidden site k (see the header): δ_k − δ_i = −s (δ_k − δ_j), s > 0, for two neighbours i, j
  // of k in the triangulation. Its lifted power cell lies in the plane π_i = π_j and has no interior, so
  // removing k changes no other cell (the lower envelope of the power functions is the same without
  // it), but the sites on the two sides of a planar cell, which are such a pair (the lifted centres are
  // collinear, k's between them), become adjacent: their edge is then built like any other.
  // Candidates are the pairs of neighbours that a filter in doubles cannot separate; each is decided
  // exactly.
  weakly_hidden.assign(sites.size(), false);
  if (rt.number_of_vertices() < 3) return false;
  const std::vector<std::vector<SiteIndex>>& around = adjacency;
  std::vector<std::array<SiteIndex, 3>> candidates;
  std::vector<ApproxDifference> d;
  for (SiteIndex k = 0; k < sites.size(); ++k) {
    const std::vector<SiteIndex>& nb = around[k];
    if (nb.size() < 2) continue;
    d.clear();
    for (SiteIndex i : nb) d.push_back(approx_difference(sites[k], sites[i]));
    for (std::size_t a = 0; a < nb.size(); ++a)
      for (std::size_t b = a + 1; b < nb.size(); ++b)
        if (may_be_between(d[a], d[b])) candidates.push_back({k, nb[a], nb[b]});
  }
  bool any = false;
  for (const auto& [k, i, j] : candidates)
    if (!weakly_hidden[k] && strictly_between(sites, k, i, j)) weakly_hidden[k] = any = true;
  if (!any) return false;
  std::vector<RT3::Vertex_handle> weak;
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
    if (weakly_hidden[v->info()]) weak.push_back(v);
  for (const RT3::Vertex_handle& v : weak) rt.remove(v);
  return true;
}

void MobiusDiagram::Impl::build_vertices(std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair) {
  const int dim = rt.dimension();
  if (dim < 2) return;
  // A point X of L_F ∩ Q (F a facet ijk, L_F its power line) is a vertex when it lies on the power edge
  // dual to F, i.e. when neither apex of the two cells on F is strictly closer (dimension 2: the apexes
  // of the three neighbouring faces). Raw vertices at the same point (four or more sites meeting there)
  // are merged (union–find), decided exactly: through the tetrahedron whose apex ties, and by comparing
  // the points exactly where the doubles say they are close.
  struct Raw {
    std::array<SiteIndex, 3> tri;
    int s;
  };
  std::vector<Raw> raw;
  std::vector<std::size_t> parent;
  std::unordered_map<const void*, std::size_t> cell_node;
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto node_of = [&](const void* cell) {
    const auto [it, fresh] = cell_node.emplace(cell, parent.size());
    if (fresh) parent.push_back(parent.size());
    return it->second;
  };
  auto unite = [&](std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  std::vector<std::size_t> raw_node;
  for (auto f = rt.finite_facets_begin(); f != rt.finite_facets_end(); ++f) {
    const auto c = f->first;
    const int idx = f->second;
    std::array<SiteIndex, 3> tri{};
    int m = 0;
    for (int k = 0; k < 4 && m < 3; ++k)
      if (k != idx && (dim == 3 || k < 3)) tri[static_cast<std::size_t>(m++)] = c->vertex(k)->info();
    std::sort(tri.begin(), tri.end());
    std::array<SiteIndex, 3> apex{no_site, no_site, no_site};
    std::array<const void*, 3> apex_cell{};
    if (dim == 3) {
      const auto mirror = c->neighbor(idx);
      if (!rt.is_infinite(c->vertex(idx))) apex[0] = c->vertex(idx)->info(), apex_cell[0] = &*c;
      const auto mv = mirror->vertex(rt.mirror_index(c, idx));
      if (!rt.is_infinite(mv)) apex[1] = mv->info(), apex_cell[1] = &*mirror;
    } else {
      for (int k = 0; k < 3; ++k) {
        const auto nb = c->neighbor(k);
        const auto v = nb->vertex(nb->index(c));
        if (!rt.is_infinite(v)) apex[static_cast<std::size_t>(k)] = v->info(), apex_cell[static_cast<std::size_t>(k)] = &*nb;
      }
    }
    for (const RootVerdict& r : facet_vertices(sites, tri, apex)) {
      if (!r.kept) continue;
      const std::size_t id = parent.size();
      parent.push_back(id);
      raw.push_back({tri, r.s});
      raw_node.push_back(id);
      // A tie with the apex of a tetrahedron: the point is that tetrahedron's orthocentre. (In dimension
      // 2 a face's power line may meet Q twice, and a tie does not say which point of the neighbour's
      // line it is: those are merged below.)
      if (dim == 3)
        for (std::size_t a = 0; a < 3; ++a)
          if (r.tie[a]) unite(id, node_of(apex_cell[a]));
    }
  }
  // Raw vertices at the same point that no tie links (four or more coplanar lifted centres share a
  // power line: co-circular sites of equal λ in a 3-dimensional triangulation) are merged by an exact
  // comparison of the points, among the pairs close in doubles.
  std::vector<Point2> approx(raw.size());
  {
    double scale = 0;
    for (const MobiusSite& st : sites) scale = std::max({scale, std::fabs(st.x), std::fabs(st.y)});
    for (std::size_t k = 0; k < raw.size(); ++k) approx[k] = vertex_point(sites, raw[k].tri, raw[k].s);
    auto eps_at = [&](Point2 p) { return 1e-9 * (std::fabs(p.x) + std::fabs(p.y)) + 1e-12 * scale + 1e-300; };
    std::vector<std::size_t> by_x(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) by_x[k] = k;
    std::sort(by_x.begin(), by_x.end(), [&](std::size_t u, std::size_t v) { return approx[u].x < approx[v].x; });
    for (std::size_t a = 0; a < by_x.size(); ++a) {
      const std::size_t u = by_x[a];
      const double eps = eps_at(approx[u]);
      for (std::size_t b = a + 1; b < by_x.size() && approx[by_x[b]].x - approx[u].x <= 2 * eps; ++b) {
        const std::size_t w = by_x[b];
        if (std::fabs(approx[w].y - approx[u].y) > 2 * eps || find(raw_node[u]) == find(raw_node[w])) continue;
        if (same_point(sites, raw[u].tri, raw[u].s, raw[w].tri, raw[w].s)) unite(raw_node[u], raw_node[w]);
      }
    }
  }
  // One vertex per class, numbered in the order of the smallest raw vertex (sites, root) of the class,
  // which is also its representative: the numbering does not depend on CGAL's storage order (which
  // depends on CGAL's global random state).
  std::vector<std::size_t> order(raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t u, std::size_t v) {
    return std::tie(raw[u].tri, raw[u].s) < std::tie(raw[v].tri, raw[v].s);
  });
  std::unordered_map<std::size_t, std::size_t> vertex_of_root;
  for (const std::size_t k : order) {
    const std::size_t root = find(raw_node[k]);
    auto [it, fresh] = vertex_of_root.emplace(root, vertices.size());
    if (fresh) {
      vertices.push_back({approx[k], raw[k].tri});
      exact.push_back({raw[k].tri, raw[k].s, {}});
    }
    const std::size_t id = it->second;
    auto& vs = exact[id].sites;
    for (SiteIndex s : raw[k].tri)
      if (std::find(vs.begin(), vs.end(), s) == vs.end()) vs.push_back(s);
    const auto& t = raw[k].tri;
    for (auto [u, v] : {std::pair{t[0], t[1]}, std::pair{t[0], t[2]}, std::pair{t[1], t[2]}}) {
      auto& list = on_pair[key(u, v)];
      if (std::find(list.begin(), list.end(), id) == list.end()) list.push_back(id);
    }
  }
}

void MobiusDiagram::Impl::build_edges(const std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair,
                                      std::vector<std::pair<std::size_t, std::size_t>>& unbounded) {
  // Frame: the box, the vertices and the bounded edges (grown below).
  Box fr = box;
  auto include = [&](Point2 p) {
    fr.xmin = std::min(fr.xmin, p.x), fr.xmax = std::max(fr.xmax, p.x);
    fr.ymin = std::min(fr.ymin, p.y), fr.ymax = std::max(fr.ymax, p.y);
  };
  for (const MobiusVertex& v : vertices) include(v.point);
  // Lines are kept as (point, direction, t-range) until the frame is known; `unbounded` records the
  // edge index and which ends are infinite (bit 1: from, bit 2: to).
  struct LineEdge {
    std::size_t edge;
    Point2 x0, dir;
    double t0, t1;
    bool inf0, inf1;
  };
  std::vector<LineEdge> lines;
  const std::vector<std::size_t> none;
  for (const auto& ij : lifted) {
    const SiteIndex i = ij.first, j = ij.second;  // plain variables: the lambdas below capture them
    const MobiusSite &si = sites[i], &sj = sites[j];
    const auto it = on_pair.find(key(i, j));
    const std::vector<std::size_t>& on = it == on_pair.end() ? none : it->second;
    // Which pieces are edges is decided exactly: on both sides of each vertex on the bisector
    // (departures), or at one point of a bisector without vertices; the geometry below is in doubles.
    std::vector<std::pair<bool, bool>> side(on.size());
    for (std::size_t k = 0; k < on.size(); ++k)
      side[k] = departures(sites, exact[on[k]].tri, exact[on[k]].s, i, j, others(on[k], i, j));
    // Vertices sorted by a double position along the bisector: consecutive ones closer than their
    // rounding (`slack`) are put in their exact order (compare_along), keeping the positions sorted.
    auto exact_order = [&](std::vector<std::pair<double, std::size_t>>& list, auto slack) {
      for (std::size_t pass = 0; pass < list.size(); ++pass) {
        bool swapped = false;
        for (std::size_t k = 0; k + 1 < list.size(); ++k) {
          const std::size_t u = list[k].second, w = list[k + 1].second;
          if (list[k + 1].first - list[k].first > slack(u) + slack(w)) continue;
          if (compare_along(sites, exact[on[u]].tri, exact[on[u]].s, exact[on[w]].tri, exact[on[w]].s, i, j) != Sign::positive)
            continue;
          std::swap(list[k].second, list[k + 1].second);
          swapped = true;
        }
        if (!swapped) break;
      }
    };
    auto whole = [&] {
      std::vector<SiteIndex> rest;
      for (SiteIndex l : adjacency[i])
        if (l != j) rest.push_back(l);
      return whole_bisector_is_edge(sites, i, j, rest);
    };
    const Bisector geometry = bisector(sites, i, j);
    if (si.lambda != sj.lambda) {
      if (!circle_has_radius(sites, i, j)) continue;
      const Point2 c = geometry.c;
      const double r = geometry.r;
      const SiteIndex inside = si.lambda > sj.lambda ? i : j;
      std::vector<std::pair<double, std::size_t>> angles;
      for (std::size_t k = 0; k < on.size(); ++k) angles.emplace_back(angle_of(c, vertices[on[k]].point), k);
      std::sort(angles.begin(), angles.end());
      if (angles.size() > 1) {
        // Start after the largest gap, so that no two close vertices straddle the ends of the list.
        std::size_t start = 0;
        double widest = -1;
        for (std::size_t k = 0; k < angles.size(); ++k) {
          const double gap = k + 1 < angles.size() ? angles[k + 1].first - angles[k].first
                                                   : angles[0].first + two_pi - angles[k].first;
          if (gap > widest) widest = gap, start = (k + 1) % angles.size();
        }
        std::rotate(angles.begin(), angles.begin() + static_cast<std::ptrdiff_t>(start), angles.end());
        for (std::size_t k = 1; k < angles.size(); ++k)
          while (angles[k].first < angles[k - 1].first) angles[k].first += two_pi;
        exact_order(angles, [&](std::size_t k) {
          const Point2 p = vertices[on[k]].point;
          return 1e-9 * (1 + (std::fabs(p.x - c.x) + std::fabs(p.y - c.y) + std::fabs(p.x) + std::fabs(p.y)) / std::max(r, 1e-300));
        });
      }
      auto add_arc = [&](double start, double sweep, std::size_t from, std::size_t to) {
        MobiusEdge e{i, j, arc(c, r, start, sweep), from, to, inside};
        if (from != MobiusEdge::npos) e.curve.from = vertices[from].point;
        if (to != MobiusEdge::npos) e.curve.to = vertices[to].point;
        for (const Point2& s : e.curve.sample(0.2)) include(s);
        edges.push_back(e);
      };
      if (angles.empty()) {
        if (whole()) add_arc(0, two_pi, MobiusEdge::npos, MobiusEdge::npos);
        continue;
      }
      for (std::size_t k = 0; k < angles.size(); ++k) {
        const auto [a0, k0] = angles[k];
        const auto [a1raw, k1] = angles[(k + 1) % angles.size()];
        const double a1 = k + 1 < angles.size() ? a1raw : a1raw + two_pi;
        if (side[k0].first != side[k1].second) ++order_conflicts;
        if (side[k0].first) add_arc(a0, a1 - a0, on[k0], on[k1]);
      }
    } else {
      if (si.lambda == 0 || (si.x == sj.x && si.y == sj.y)) continue;  // no line (equal sites: one is hidden)
      const Point2 x0 = geometry.x0, dir = geometry.dir;
      // δ_i − δ_j = −2 g·x + dc decreases along +g: i lies on the +g side; the left of dir is
      // (−dir.y, dir.x) = −g/|g|, the side of j.
      const SiteIndex left = j;
      std::vector<std::pair<double, std::size_t>> ts;
      for (std::size_t k = 0; k < on.size(); ++k)
        ts.emplace_back((vertices[on[k]].point.x - x0.x) * dir.x + (vertices[on[k]].point.y - x0.y) * dir.y, k);
      std::sort(ts.begin(), ts.end());
      exact_order(ts, [&](std::size_t k) {
        const Point2 p = vertices[on[k]].point;
        return 1e-9 * (std::fabs(p.x) + std::fabs(p.y) + std::fabs(x0.x) + std::fabs(x0.y)) + 1e-300;
      });
      auto point_at = [&](double t) { return Point2{x0.x + t * dir.x, x0.y + t * dir.y}; };
      auto add = [&](double t0, double t1, bool inf0, bool inf1, std::size_t from, std::size_t to) {
        if (inf0 && inf1) include(x0);
        MobiusEdge e{i, j, segment(point_at(t0), point_at(t1)), from, to, left};
        if (from != MobiusEdge::npos) e.curve.from = vertices[from].point;
        if (to != MobiusEdge::npos) e.curve.to = vertices[to].point;
        if (inf0 || inf1) lines.push_back({edges.size(), x0, dir, t0, t1, inf0, inf1});
        edges.push_back(e);
      };
      if (ts.empty()) {
        if (whole()) add(0, 0, true, true, MobiusEdge::npos, MobiusEdge::npos);
        continue;
      }
      const auto [tf, kf] = ts.front();
      const auto [tb, kb] = ts.back();
      if (side[kf].second) add(tf, tf, true, false, MobiusEdge::npos, on[kf]);
      for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
        const std::size_t k0 = ts[k].second, k1 = ts[k + 1].second;
        if (side[k0].first != side[k1].second) ++order_conflicts;
        if (side[k0].first) add(ts[k].first, ts[k + 1].first, false, false, on[k0], on[k1]);
      }
      if (side[kb].first) add(tb, tb, false, true, on[kb], MobiusEdge::npos);
    }
  }
  const double grow = 0.05 * std::max(fr.width(), fr.height());
  frame = fr.expanded(grow);
  // Clip the unbounded lines to the frame (slab method).
  for (const LineEdge& l : lines) {
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    const double px[2] = {l.x0.x, l.x0.y}, dv[2] = {l.dir.x, l.dir.y};
    const double mins[2] = {frame.xmin, frame.ymin}, maxs[2] = {frame.xmax, frame.ymax};
    for (int c = 0; c < 2; ++c) {
      if (dv[c] == 0) continue;
      double ta = (mins[c] - px[c]) / dv[c], tb = (maxs[c] - px[c]) / dv[c];
      if (ta > tb) std::swap(ta, tb);
      lo = std::max(lo, ta), hi = std::min(hi, tb);
    }
    MobiusEdge& e = edges[l.edge];
    const double t0 = l.inf0 ? lo : l.t0, t1 = l.inf1 ? hi : l.t1;
    if (l.inf0) e.curve.from = {l.x0.x + t0 * l.dir.x, l.x0.y + t0 * l.dir.y};
    if (l.inf1) e.curve.to = {l.x0.x + t1 * l.dir.x, l.x0.y + t1 * l.dir.y};
    unbounded.emplace_back(l.edge, (l.inf0 ? 1u : 0u) | (l.inf1 ? 2u : 0u));
  }
}

void MobiusDiagram::Impl::build_cells(const std::vector<std::pair<std::size_t, std::size_t>>& unbounded) {
  const std::size_t n = sites.size();
  cells.assign(n, {});
  // Nodes: vertices 0..V−1, then frame nodes (ends of unbounded edges, then the four corners).
  const std::size_t V = vertices.size();
  struct FrameNode {
    double s;
    Point2 p;
    std::size_t node;
    SiteIndex after = no_site;  ///< for the end of an unbounded edge: the site whose cell follows it counter-clockwise
    LineEnd end{no_site, no_site, false};  ///< for the end of an unbounded edge: its line and direction
  };
  const double W = frame.width(), H = frame.height();
  auto perimeter = [&](Point2 p) {
    const double db = std::fabs(p.y - frame.ymin), dr = std::fabs(p.x - frame.xmax), dt = std::fabs(p.y - frame.ymax),
                 dlf = std::fabs(p.x - frame.xmin);
    const double m = std::min({db, dr, dt, dlf});
    if (m == db) return std::clamp(p.x - frame.xmin, 0.0, W);
    if (m == dr) return W + std::clamp(p.y - frame.ymin, 0.0, H);
    if (m == dt) return W + H + std::clamp(frame.xmax - p.x, 0.0, W);
    return 2 * W + H + std::clamp(frame.ymax - p.y, 0.0, H);
  };
  std::vector<FrameNode> fnodes;
  std::vector<std::size_t> edge_from(edges.size()), edge_to(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) edge_from[e] = edges[e].from, edge_to[e] = edges[e].to;
  for (const auto& [e, ends] : unbounded) {
    // Walking the frame counter-clockwise (inside on the left) past an edge end, one enters the cell on
    // the right of the edge as it points inwards: at its `to` end the edge's left site, at its `from`
    // end the other one.
    const MobiusEdge& E = edges[e];
    if (ends & 1u) {
      edge_from[e] = V + fnodes.size();
      fnodes.push_back({perimeter(E.curve.from), E.curve.from, edge_from[e], E.left == E.a ? E.b : E.a, {E.a, E.b, false}});
    }
    if (ends & 2u) {
      edge_to[e] = V + fnodes.size();
      fnodes.push_back({perimeter(E.curve.to), E.curve.to, edge_to[e], E.left, {E.a, E.b, true}});
    }
  }
  {
    const Point2 corners[4] = {{frame.xmin, frame.ymin}, {frame.xmax, frame.ymin}, {frame.xmax, frame.ymax}, {frame.xmin, frame.ymax}};
    const double ss[4] = {0, W, W + H, 2 * W + H};
    for (int c = 0; c < 4; ++c) fnodes.push_back({ss[c], corners[c], V + fnodes.size()});
  }
  std::sort(fnodes.begin(), fnodes.end(), [](const FrameNode& a, const FrameNode& b) { return a.s < b.s; });
  // The order of the edge ends along the frame is their order at infinity (edges do not cross): where
  // two consecutive ends are too close for the doubles, it is decided exactly (compare_ends) and the
  // ends are exchanged if needed (their positions along the frame stay sorted).
  {
    const double tol = 1e-9 * 2 * (W + H);
    std::vector<std::size_t> ends;
    for (std::size_t k = 0; k < fnodes.size(); ++k)
      if (fnodes[k].after != no_site) ends.push_back(k);
    for (std::size_t pass = 0; pass <= ends.size(); ++pass) {
      bool swapped = false;
      for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
        FrameNode &a = fnodes[ends[k]], &b = fnodes[ends[k + 1]];
        if (b.s - a.s > tol || compare_ends(sites, a.end, b.end) != Sign::positive) continue;
        std::swap(a, b);
        std::swap(a.s, b.s);
        swapped = true;
      }
      if (!swapped) break;
    }
  }
  // Frame nodes at the same point are one node (an unbounded edge ending exactly at a corner, two
  // edges crossing the frame at one point: fuzz finding sites-2), else the chain of its cell breaks.
  {
    std::unordered_map<std::size_t, std::size_t> same;
    for (std::size_t k = 1; k <= fnodes.size() && fnodes.size() > 1; ++k) {
      FrameNode &a = fnodes[k - 1], &b = fnodes[k % fnodes.size()];
      if (a.p.x == b.p.x && a.p.y == b.p.y && a.node != b.node) same[b.node] = a.node, b.node = a.node;
    }
    auto one = [&](std::size_t node) {
      for (auto it = same.find(node); it != same.end() && it->second != node; it = same.find(node)) node = it->second;
      return node;
    };
    for (FrameNode& f : fnodes) f.node = one(f.node);
    for (std::size_t e = 0; e < edges.size() && !same.empty(); ++e) edge_from[e] = one(edge_from[e]), edge_to[e] = one(edge_to[e]);
  }

  // Half-edges: (site, from node, to node, piece).
  struct Half {
    SiteIndex site;
    std::size_t from, to;
    BoundaryPiece piece;
  };
  std::vector<Half> halves;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const MobiusEdge& E = edges[e];
    const SiteIndex right = E.left == E.a ? E.b : E.a;
    halves.push_back({E.left, edge_from[e], edge_to[e], {E.curve, right, e}});
    halves.push_back({right, edge_to[e], edge_from[e], {E.curve.reversed(), E.left, e}});
  }
  // The frame's pieces: each belongs to the cell entered at the last edge end before it (by the
  // combinatorics, not by locating the piece's midpoint, which is ambiguous on a piece of length ~ε
  // between an edge end and a corner: fuzz finding sites-2); one site owns the whole frame without
  // unbounded edges.
  SiteIndex owner = no_site;
  for (const FrameNode& f : fnodes)
    if (f.after != no_site) owner = f.after;  // the last end, which precedes the first piece cyclically
  if (owner == no_site) owner = locate({(frame.xmin + frame.xmax) / 2, frame.ymin});
  for (std::size_t k = 0; k < fnodes.size(); ++k) {
    const FrameNode &a = fnodes[k], &b = fnodes[(k + 1) % fnodes.size()];
    if (a.after != no_site) owner = a.after;
    if (a.p.x == b.p.x && a.p.y == b.p.y) continue;
    const CurvePiece piece = segment(a.p, b.p);
    if (owner == no_site) continue;
    halves.push_back({owner, a.node, b.node, {piece, no_site, MobiusEdge::npos}});
  }
  // Chain the half-edges of each site into loops.
  const std::size_t N = V + fnodes.size() + 1;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> starting;
  auto node_key = [&](SiteIndex s, std::size_t node) { return static_cast<std::uint64_t>(s) * N + node; };
  for (std::size_t h = 0; h < halves.size(); ++h)
    if (halves[h].from != MobiusEdge::npos) starting[node_key(halves[h].site, halves[h].from)].push_back(h);
  std::vector<bool> used(halves.size(), false);
  std::vector<std::vector<BoundaryLoop>> loops(n);
  for (std::size_t h0 = 0; h0 < halves.size(); ++h0) {
    if (used[h0]) continue;
    BoundaryLoop loop;
    std::size_t h = h0;
    const SiteIndex s = halves[h0].site;
    while (true) {
      used[h] = true;
      loop.pieces.push_back(halves[h].piece);
      const std::size_t end = halves[h].to;
      if (end == MobiusEdge::npos) break;  // a full circle closes on itself
      if (end == halves[h0].from) break;
      std::size_t next = MobiusEdge::npos;
      if (auto it = starting.find(node_key(s, end)); it != starting.end())
        for (std::size_t c : it->second)
          if (!used[c]) {
            next = c;
            break;
          }
      if (next == MobiusEdge::npos) {
        loop.closed = false;
        break;
      }
      h = next;
    }
    loops[s].push_back(std::move(loop));
  }
  // Outer boundaries (positive area) and holes; a hole goes to the smallest outer loop containing it.
  for (SiteIndex s = 0; s < n; ++s) {
    std::vector<std::size_t> outers;
    std::vector<double> areas(loops[s].size());
    for (std::size_t k = 0; k < loops[s].size(); ++k) {
      areas[k] = own_area(loops[s][k]);
      if (areas[k] > 0) outers.push_back(k);
    }
    // A site with a single loop has it as its outer boundary, whatever the sign of its area in doubles:
    // a lens thinner than an ulp, or a sliver reaching a far vertex, can round to a non-positive area
    // (fuzz finding sites-7), and a hole needs an outer boundary around it.
    if (outers.empty() && loops[s].size() == 1) outers.push_back(0), areas[0] = std::fabs(areas[0]) + 1e-300;
    std::sort(outers.begin(), outers.end(), [&](std::size_t a, std::size_t b) { return areas[a] < areas[b]; });
    std::vector<std::vector<Point2>> outer_poly;
    if (outers.size() > 1)
      for (std::size_t k : outers) outer_poly.push_back(loops[s][k].polyline(0.02, 1e-7 * std::max(frame.width(), frame.height())));
    for (std::size_t k : outers) cells[s].push_back({loops[s][k], {}});
    for (std::size_t k = 0; k < loops[s].size(); ++k) {
      if (areas[k] > 0) continue;
      std::size_t target = 0;
      if (outers.size() > 1) {
        const Point2 q = loops[s][k].pieces.front().curve.midpoint();
        for (std::size_t o = 0; o < outers.size(); ++o)
          if (inside_polyline(outer_poly[o], q)) {
            target = o;
            break;
          }
      }
      if (outers.empty()) cells[s].push_back({BoundaryLoop{{}, false}, {}});
      cells[s][target].holes.push_back(std::move(loops[s][k]));
    }
  }
}

MobiusDiagram::MobiusDiagram(std::vector<MobiusSite> sites, const Box& box) : impl_(std::make_unique<Impl>()) {
  if (!box.valid()) throw InputError("Möbius diagram: the box must satisfy xmin < xmax and ymin < ymax");
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (!std::isfinite(sites[i].x) || !std::isfinite(sites[i].y) || !std::isfinite(sites[i].lambda) ||
        !std::isfinite(sites[i].mu))
      throw InputError("Möbius diagram: site " + std::to_string(i) + " has a non-finite value");
  for (std::size_t i = 0; i < sites.size(); ++i) require_liftable(sites[i], "", 0, "Möbius diagram: site " + std::to_string(i));
  impl_->sites = std::move(sites);
  impl_->box = box;
  impl_->build();
}

MobiusDiagram::~MobiusDiagram() = default;
MobiusDiagram::MobiusDiagram(MobiusDiagram&&) noexcept = default;
MobiusDiagram& MobiusDiagram::operator=(MobiusDiagram&&) noexcept = default;

const std::vector<MobiusSite>& MobiusDiagram::sites() const { return impl_->sites; }
const Box& MobiusDiagram::frame() const { return impl_->frame; }
int MobiusDiagram::dimension() const { return impl_->rt.dimension(); }
std::vector<SiteIndex> MobiusDiagram::hidden_sites() const {
  std::vector<SiteIndex> out;
  for (SiteIndex i = 0; i < impl_->hidden.size(); ++i)
    if (impl_->hidden[i]) out.push_back(i);
  return out;
}
std::vector<SiteIndex> MobiusDiagram::weakly_hidden_sites() const {
  std::vector<SiteIndex> out;
  for (SiteIndex i = 0; i < impl_->weakly_hidden.size(); ++i)
    if (impl_->weakly_hidden[i]) out.push_back(i);
  return out;
}
std::vector<SiteIndex> MobiusDiagram::empty_sites() const {
  std::vector<SiteIndex> out;
  for (SiteIndex i = 0; i < impl_->cells.size(); ++i)
    if (impl_->cells[i].empty()) out.push_back(i);
  return out;
}
const std::vector<std::pair<SiteIndex, SiteIndex>>& MobiusDiagram::lifted_edges() const { return impl_->lifted; }
const std::vector<MobiusVertex>& MobiusDiagram::vertices() const { return impl_->vertices; }
const std::vector<MobiusEdge>& MobiusDiagram::edges() const { return impl_->edges; }
const std::vector<CellComponent>& MobiusDiagram::cell(SiteIndex i) const { return impl_->cells.at(i); }
SiteIndex MobiusDiagram::locate(Point2 q) const { return impl_->locate(q); }

std::pair<SiteIndex, std::size_t> MobiusDiagram::locate_in_cells(Point2 q) const {
  const Impl& m = *impl_;
  if (!m.shapes_built) {
    const double err = 1e-7 * std::max(m.frame.width(), m.frame.height());
    for (SiteIndex s = 0; s < m.cells.size(); ++s)
      for (std::size_t c = 0; c < m.cells[s].size(); ++c) {
        Impl::ComponentShape shape{s, c, {}, m.cells[s][c].outer.polyline(0.02, err), {}};
        if (shape.outer.empty()) continue;
        shape.bounds = Box{shape.outer[0].x, shape.outer[0].y, shape.outer[0].x, shape.outer[0].y};
        for (Point2 p : shape.outer) {
          shape.bounds.xmin = std::min(shape.bounds.xmin, p.x), shape.bounds.xmax = std::max(shape.bounds.xmax, p.x);
          shape.bounds.ymin = std::min(shape.bounds.ymin, p.y), shape.bounds.ymax = std::max(shape.bounds.ymax, p.y);
        }
        for (const BoundaryLoop& h : m.cells[s][c].holes) shape.holes.push_back(h.polyline(0.02, err));
        m.shapes.push_back(std::move(shape));
      }
    m.shapes_built = true;
  }
  for (const Impl::ComponentShape& shape : m.shapes) {
    if (!shape.bounds.contains(q) || !inside_polyline(shape.outer, q)) continue;
    bool in_hole = false;
    for (const auto& h : shape.holes) in_hole = in_hole || inside_polyline(h, q);
    if (!in_hole) return {shape.site, shape.component};
  }
  return {no_site, 0};
}

bool MobiusDiagram::is_valid(bool verbose) const {
  const Impl& m = *impl_;
  auto fail = [](std::string s) { return s; };
  const std::string violation = [&]() -> std::string {
    if (!m.rt.is_valid()) return fail("CGAL's 3D regular triangulation is not valid");
    if (m.order_conflicts > 0)
      return fail(std::to_string(m.order_conflicts) + " piece(s) of bisector between two vertices ordered wrongly in doubles");
    std::vector<int> uses(m.edges.size(), 0);
    double total = 0;

    for (SiteIndex s = 0; s < m.cells.size(); ++s) {
      if (m.hidden[s] && !m.cells[s].empty()) return fail("hidden site " + std::to_string(s) + " has a non-empty cell");
      for (const CellComponent& c : m.cells[s]) {
        if (!c.outer.closed) return fail("an outer boundary of cell " + std::to_string(s) + " is not closed");
        for (const BoundaryLoop& h : c.holes)
          if (!h.closed) return fail("a hole of cell " + std::to_string(s) + " is not closed");
        total += own_area(c.outer);
        for (const BoundaryLoop& h : c.holes) total += own_area(h);
        auto count = [&](const BoundaryLoop& l) {
          for (const BoundaryPiece& p : l.pieces)
            if (p.edge != MobiusEdge::npos) ++uses[p.edge];
        };
        count(c.outer);
        for (const BoundaryLoop& h : c.holes) count(h);
      }
    }
    for (std::size_t e = 0; e < m.edges.size(); ++e)
      if (uses[e] != 2) return fail("edge " + std::to_string(e) + " bounds " + std::to_string(uses[e]) + " cells, not 2");
    for (const MobiusVertex& v : m.vertices) {
      if (!std::isfinite(v.point.x) || !std::isfinite(v.point.y))
        return fail("a vertex is not finite: the sites are beyond what doubles represent");
      // The scale of the three distances' terms, with the effect of the vertex's rounding (relative
      // 1e-16 of its coordinates) on them.
      double scale = 1e-300;
      for (SiteIndex t : v.sites) {
        const MobiusSite& a = m.sites[t];
        const double r2 = squared_distance(v.point, {a.x, a.y});
        scale += std::fabs(a.lambda) * (r2 + 1e-9 * std::sqrt(r2) * (std::fabs(v.point.x) + std::fabs(v.point.y))) + std::fabs(a.mu);
      }
      const double d0 = mobius_distance(v.point, m.sites[v.sites[0]]);
      for (int k = 1; k < 3; ++k) {
        const double dk = mobius_distance(v.point, m.sites[v.sites[static_cast<std::size_t>(k)]]);
        if (std::fabs(d0 - dk) > 1e-6 * scale) return fail("a vertex is not equidistant from its three sites");
      }
    }
    const double area = m.frame.width() * m.frame.height();
    if (!m.sites.empty() && std::fabs(total - area) > 1e-6 * area)
      return fail("cell areas add up to " + std::to_string(total) + ", the frame has area " + std::to_string(area));
    return "";
  }();
  return detail::report_validity(violation, verbose);
}

}  // namespace laguerre::core
