#include "laguerre/core/diagrams/MobiusDiagram.hpp"

#include "detail/Validity.hpp"
#include "laguerre/core/Error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Regular_triangulation_vertex_base_3<K>;
using Vbi = CGAL::Triangulation_vertex_base_with_info_3<SiteIndex, K, Vb>;
using Cb = CGAL::Regular_triangulation_cell_base_3<K, CGAL::Triangulation_cell_base_3<K>, CGAL::Discard_hidden_points>;
using Tds = CGAL::Triangulation_data_structure_3<Vbi, Cb>;
using RT3 = CGAL::Regular_triangulation_3<K, Tds>;
using WP3 = RT3::Weighted_point;

constexpr double two_pi = 2 * std::numbers::pi;
constexpr double relative_tolerance = 1e-10;

/// Whether site l is strictly closer than site i at x beyond the relative tolerance.
bool closer(const MobiusSite& l, const MobiusSite& i, Point2 x) {
  const double di = mobius_distance(x, i), dl = mobius_distance(x, l);
  const double scale = std::fabs(i.lambda) * squared_distance(x, {i.x, i.y}) + std::fabs(i.mu) +
                       std::fabs(l.lambda) * squared_distance(x, {l.x, l.y}) + std::fabs(l.mu);
  return dl < di - relative_tolerance * scale;
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

double CurvePiece::area_term() const {
  if (!is_arc) return 0.5 * (from.x * to.y - from.y * to.x);
  // ∫ (x dy − y dx) over x = c + r(cos t, sin t) = r²Δ + c_x r (sin t1 − sin t0) − c_y r (cos t1 − cos t0).
  const double t0 = start, t1 = start + sweep;
  return 0.5 * (radius * radius * sweep + centre.x * radius * (std::sin(t1) - std::sin(t0)) -
                centre.y * radius * (std::cos(t1) - std::cos(t0)));
}

Point2 CurvePiece::midpoint() const {
  if (!is_arc) return {(from.x + to.x) / 2, (from.y + to.y) / 2};
  const double t = start + sweep / 2;
  return {centre.x + radius * std::cos(t), centre.y + radius * std::sin(t)};
}

double BoundaryLoop::area() const {
  double a = 0;
  for (const BoundaryPiece& p : pieces) a += p.curve.area_term();
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

double CellComponent::area() const {
  double a = outer.area();
  for (const BoundaryLoop& h : holes) a += h.area();
  return a;
}

// ---------------------------------------------------------------------------------------------------
// The diagram

struct MobiusDiagram::Impl {
  std::vector<MobiusSite> sites;
  Box box, frame;
  RT3 rt;
  std::vector<bool> hidden;
  std::vector<std::vector<SiteIndex>> adjacency;
  std::vector<std::pair<SiteIndex, SiteIndex>> lifted;
  std::vector<MobiusVertex> vertices;
  std::vector<MobiusEdge> edges;
  std::vector<std::vector<CellComponent>> cells;
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
    return rt.nearest_power_vertex(K::Point_3(q.x, q.y, q.x * q.x + q.y * q.y))->info();
  }
  /// Whether x (on the bisector of i and another site) has no neighbour of i strictly closer.
  bool minimal(SiteIndex i, Point2 x, SiteIndex skip1, SiteIndex skip2 = no_site) const {
    for (SiteIndex l : adjacency[i])
      if (l != skip1 && l != skip2 && closer(sites[l], sites[i], x)) return false;
    return true;
  }
  void build();
  void build_vertices(std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair);
  void build_edges(const std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair,
                   std::vector<std::pair<std::size_t, std::size_t>>& unbounded);
  void build_cells(const std::vector<std::pair<std::size_t, std::size_t>>& unbounded);
  std::uint64_t key(SiteIndex a, SiteIndex b) const {
    if (a > b) std::swap(a, b);
    return static_cast<std::uint64_t>(a) * sites.size() + b;
  }
};

void MobiusDiagram::Impl::build() {
  const std::size_t n = sites.size();
  // Lifted spheres Σ_i: centre (λp, (1 − λ)/2), weight λ²|p|² + ((1 − λ)/2)² − λ|p|² + μ.
  std::vector<std::pair<WP3, SiteIndex>> input;
  input.reserve(n);
  for (SiteIndex i = 0; i < n; ++i) {
    const MobiusSite& s = sites[i];
    const double l = s.lambda, pp = s.x * s.x + s.y * s.y, h = (1 - l) / 2;
    input.emplace_back(WP3(K::Point_3(l * s.x, l * s.y, h), l * (l - 1) * pp + h * h + s.mu), i);
  }
  rt.insert(input.begin(), input.end());
  hidden.assign(n, true);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) hidden[v->info()] = false;
  adjacency.assign(n, {});
  for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
    const SiteIndex a = e->first->vertex(e->second)->info(), b = e->first->vertex(e->third)->info();
    adjacency[a].push_back(b), adjacency[b].push_back(a);
    lifted.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(lifted.begin(), lifted.end());

  std::unordered_map<std::uint64_t, std::vector<std::size_t>> on_pair;
  build_vertices(on_pair);
  std::vector<std::pair<std::size_t, std::size_t>> unbounded;
  build_edges(on_pair, unbounded);
  build_cells(unbounded);
}

void MobiusDiagram::Impl::build_vertices(std::unordered_map<std::uint64_t, std::vector<std::size_t>>& on_pair) {
  if (rt.dimension() < 2) return;
  std::vector<MobiusVertex> raw;
  for (auto f = rt.finite_facets_begin(); f != rt.finite_facets_end(); ++f) {
    std::array<SiteIndex, 3> tri{};
    int m = 0;
    for (int k = 0; k < 4 && m < 3; ++k)
      if (k != f->second && (rt.dimension() == 3 || k < 3)) tri[static_cast<std::size_t>(m++)] = f->first->vertex(k)->info();
    std::sort(tri.begin(), tri.end());
    const MobiusSite &si = sites[tri[0]], &sj = sites[tri[1]], &sk = sites[tri[2]];
    // Local coordinates centred on site i. δ_s(x) = λ_s z − 2 b_s·x + c_s on z = |x|², with b_s = λ_s p_s,
    // c_s = λ_s|p_s|² − μ_s; the bisector planes n·X = h with n = (−2(b_i − b_s), λ_i − λ_s), h = c_s − c_i.
    const Point2 o{si.x, si.y};
    auto coeffs = [&](const MobiusSite& s) {
      const double px = s.x - o.x, py = s.y - o.y;
      return std::array<double, 4>{s.lambda * px, s.lambda * py, s.lambda * (px * px + py * py) - s.mu, s.lambda};
    };
    const auto ci = coeffs(si), cj = coeffs(sj), ck = coeffs(sk);
    const std::array<double, 3> n1{-2 * (ci[0] - cj[0]), -2 * (ci[1] - cj[1]), ci[3] - cj[3]};
    const std::array<double, 3> n2{-2 * (ci[0] - ck[0]), -2 * (ci[1] - ck[1]), ci[3] - ck[3]};
    const double h1 = cj[2] - ci[2], h2 = ck[2] - ci[2];
    const std::array<double, 3> d{n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2],
                                  n1[0] * n2[1] - n1[1] * n2[0]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(dd > 0)) continue;  // parallel bisector planes: no common point
    // X0 = (h1 (n2 × d) + h2 (d × n1)) / |d|².
    const std::array<double, 3> a{n2[1] * d[2] - n2[2] * d[1], n2[2] * d[0] - n2[0] * d[2], n2[0] * d[1] - n2[1] * d[0]};
    const std::array<double, 3> b{d[1] * n1[2] - d[2] * n1[1], d[2] * n1[0] - d[0] * n1[2], d[0] * n1[1] - d[1] * n1[0]};
    std::array<double, 3> x0{};
    for (int c = 0; c < 3; ++c) x0[c] = (h1 * a[c] + h2 * b[c]) / dd;
    // (x0 + t d)² + (y0 + t d)² = z0 + t dz.
    const double qa = d[0] * d[0] + d[1] * d[1];
    const double qb = 2 * (x0[0] * d[0] + x0[1] * d[1]) - d[2];
    const double qc = x0[0] * x0[0] + x0[1] * x0[1] - x0[2];
    double disc = qb * qb - 4 * qa * qc;
    // Within its rounding error, the discriminant is 0: the bisectors touch (tangent circles), one
    // vertex, not two at ~√ε apart (fuzz finding sites-2).
    if (std::fabs(disc) <= 8 * std::numeric_limits<double>::epsilon() * (qb * qb + 4 * std::fabs(qa * qc))) disc = 0;
    if (disc < 0) continue;
    const double sq = std::sqrt(disc);
    const double q = -0.5 * (qb + (qb >= 0 ? sq : -sq));
    std::vector<double> roots;
    if (qa != 0 && std::isfinite(q / qa)) roots.push_back(q / qa);
    if (q != 0 && disc > 0) roots.push_back(qc / q);
    if (qa == 0 && q == 0) continue;
    for (double t : roots) {
      const Point2 x{o.x + x0[0] + t * d[0], o.y + x0[1] + t * d[1]};
      if (!std::isfinite(x.x) || !std::isfinite(x.y)) continue;
      if (!minimal(tri[0], x, tri[1], tri[2])) continue;
      raw.push_back({x, tri});
    }
  }
  // Merge vertices at the same place (four or more sites meeting at a point): within 1e-10 of the
  // sites' extent plus the vertex's own magnitude (far vertices are less accurate).
  double extent = 0;
  if (!sites.empty()) {
    double x0 = sites[0].x, x1 = x0, y0 = sites[0].y, y1 = y0;
    for (const MobiusSite& s : sites) x0 = std::min(x0, s.x), x1 = std::max(x1, s.x), y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
    extent = std::max({x1 - x0, y1 - y0, std::fabs(x0), std::fabs(x1), std::fabs(y0), std::fabs(y1)});
  }
  auto eps_at = [&](Point2 p) { return 1e-10 * (extent + std::fabs(p.x) + std::fabs(p.y)) + 1e-300; };
  std::vector<std::size_t> order(raw.size()), rep(raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k) order[k] = k, rep[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t u, std::size_t v) { return raw[u].point.x < raw[v].point.x; });
  for (std::size_t a = 0; a < order.size(); ++a) {
    if (rep[order[a]] != order[a]) continue;
    const Point2 pa = raw[order[a]].point;
    const double eps = eps_at(pa);
    for (std::size_t b = a + 1; b < order.size() && raw[order[b]].point.x - pa.x <= eps; ++b)
      if (std::fabs(raw[order[b]].point.y - pa.y) <= eps && rep[order[b]] == order[b]) rep[order[b]] = order[a];
  }
  std::vector<std::size_t> compact(raw.size(), MobiusEdge::npos);
  for (std::size_t k = 0; k < raw.size(); ++k)
    if (rep[k] == k) compact[k] = vertices.size(), vertices.push_back(raw[k]);
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const std::size_t id = compact[rep[k]];
    const auto& t = raw[k].sites;
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
    const Point2 o{si.x, si.y};
    const double pjx = sj.x - o.x, pjy = sj.y - o.y;
    // Local: δ_i − δ_j = (λ_i − λ_j)|x|² − 2(b_i − b_j)·x + (c_i − c_j), b_i = 0, c_i = −μ_i.
    const double dl = si.lambda - sj.lambda;
    const double gx = -sj.lambda * pjx, gy = -sj.lambda * pjy;  // b_i − b_j
    const double dc = -si.mu - (sj.lambda * (pjx * pjx + pjy * pjy) - sj.mu);
    if (dl != 0) {
      const Point2 cl{gx / dl, gy / dl};
      const double r2 = cl.x * cl.x + cl.y * cl.y - dc / dl;
      if (!(r2 > 0)) continue;
      const double r = std::sqrt(r2);
      const Point2 c{cl.x + o.x, cl.y + o.y};
      const SiteIndex inside = dl > 0 ? i : j;
      std::vector<std::pair<double, std::size_t>> angles;
      for (std::size_t v : on) angles.emplace_back(angle_of(c, vertices[v].point), v);
      std::sort(angles.begin(), angles.end());
      auto add_arc = [&](double start, double sweep, std::size_t from, std::size_t to) {
        const CurvePiece p = arc(c, r, start, sweep);
        if (!minimal(i, p.midpoint(), j)) return;
        MobiusEdge e{i, j, p, from, to, inside};
        if (from != MobiusEdge::npos) e.curve.from = vertices[from].point;
        if (to != MobiusEdge::npos) e.curve.to = vertices[to].point;
        edges.push_back(e);
        for (const Point2& s : p.sample(0.2)) include(s);
      };
      if (angles.empty()) {
        add_arc(0, two_pi, MobiusEdge::npos, MobiusEdge::npos);
        continue;
      }
      for (std::size_t k = 0; k < angles.size(); ++k) {
        const auto [a0, v0] = angles[k];
        const auto [a1raw, v1] = angles[(k + 1) % angles.size()];
        const double a1 = k + 1 < angles.size() ? a1raw : a1raw + two_pi;
        if (a1 - a0 <= 1e-12) continue;
        add_arc(a0, a1 - a0, v0, v1);
      }
    } else {
      const double g2 = gx * gx + gy * gy;
      if (!(g2 > 0)) continue;  // equal sites: one is hidden
      // Line 2 g·x = dc (local); direction perpendicular to g.
      const double gn = std::sqrt(g2);
      const Point2 x0{o.x + gx * dc / (2 * g2), o.y + gy * dc / (2 * g2)};
      const Point2 dir{-gy / gn, gx / gn};
      // δ_i − δ_j = −2 g·x + dc decreases along +g: i lies on the +g side; the left of dir is
      // (−dir.y, dir.x) = −g/|g|, the side of j.
      const SiteIndex left = j;
      std::vector<std::pair<double, std::size_t>> ts;
      for (std::size_t v : on)
        ts.emplace_back((vertices[v].point.x - x0.x) * dir.x + (vertices[v].point.y - x0.y) * dir.y, v);
      std::sort(ts.begin(), ts.end());
      auto point_at = [&](double t) { return Point2{x0.x + t * dir.x, x0.y + t * dir.y}; };
      auto add = [&](double t0, double t1, bool inf0, bool inf1, std::size_t from, std::size_t to) {
        double tm = (t0 + t1) / 2;
        if (inf0 && inf1) tm = 0;
        else if (inf0) tm = t1 - 1 - std::fabs(t1);
        else if (inf1) tm = t0 + 1 + std::fabs(t0);
        if (!minimal(i, point_at(tm), j)) return;
        if (inf0 && inf1) include(x0);
        MobiusEdge e{i, j, segment(point_at(t0), point_at(t1)), from, to, left};
        if (from != MobiusEdge::npos) e.curve.from = vertices[from].point;
        if (to != MobiusEdge::npos) e.curve.to = vertices[to].point;
        if (inf0 || inf1) lines.push_back({edges.size(), x0, dir, t0, t1, inf0, inf1});
        edges.push_back(e);
      };
      if (ts.empty()) {
        add(0, 0, true, true, MobiusEdge::npos, MobiusEdge::npos);
        continue;
      }
      add(ts.front().first, ts.front().first, true, false, MobiusEdge::npos, ts.front().second);
      for (std::size_t k = 0; k + 1 < ts.size(); ++k)
        if (ts[k + 1].first - ts[k].first > 1e-12 * (1 + std::fabs(ts[k].first)))
          add(ts[k].first, ts[k + 1].first, false, false, ts[k].second, ts[k + 1].second);
      add(ts.back().first, ts.back().first, false, true, ts.back().second, MobiusEdge::npos);
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
      fnodes.push_back({perimeter(E.curve.from), E.curve.from, edge_from[e], E.left == E.a ? E.b : E.a});
    }
    if (ends & 2u) {
      edge_to[e] = V + fnodes.size();
      fnodes.push_back({perimeter(E.curve.to), E.curve.to, edge_to[e], E.left});
    }
  }
  {
    const Point2 corners[4] = {{frame.xmin, frame.ymin}, {frame.xmax, frame.ymin}, {frame.xmax, frame.ymax}, {frame.xmin, frame.ymax}};
    const double ss[4] = {0, W, W + H, 2 * W + H};
    for (int c = 0; c < 4; ++c) fnodes.push_back({ss[c], corners[c], V + fnodes.size()});
  }
  std::sort(fnodes.begin(), fnodes.end(), [](const FrameNode& a, const FrameNode& b) { return a.s < b.s; });
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
      areas[k] = loops[s][k].area();
      if (areas[k] > 0) outers.push_back(k);
    }
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
    std::vector<int> uses(m.edges.size(), 0);
    double total = 0;
    for (SiteIndex s = 0; s < m.cells.size(); ++s) {
      if (m.hidden[s] && !m.cells[s].empty()) return fail("hidden site " + std::to_string(s) + " has a non-empty cell");
      for (const CellComponent& c : m.cells[s]) {
        if (!c.outer.closed) return fail("an outer boundary of cell " + std::to_string(s) + " is not closed");
        for (const BoundaryLoop& h : c.holes)
          if (!h.closed) return fail("a hole of cell " + std::to_string(s) + " is not closed");
        total += c.area();
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
      const double d0 = mobius_distance(v.point, m.sites[v.sites[0]]);
      for (int k = 1; k < 3; ++k) {
        const double dk = mobius_distance(v.point, m.sites[v.sites[static_cast<std::size_t>(k)]]);
        const MobiusSite& a = m.sites[v.sites[0]];
        const double scale = std::fabs(a.lambda) * squared_distance(v.point, {a.x, a.y}) + std::fabs(a.mu) + std::fabs(dk) + 1e-300;
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
