/// @file
/// Apollonius diagram by linearization (thesis Algorithm 1): the power diagram of the spheres Σ_i of R³
/// (centre (p_i, w_i), squared radius 2w_i²) intersected with the half-cones C_i : z = |x − p_i| − w_i.
/// See ApolloniusDiagram.hpp for the argument; this file is the only CGAL include of the construction.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hidden_point_memory_policy.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <array>
#include <cmath>
#include <algorithm>
#include <iterator>
#include <map>
#include <set>
#include <tuple>

#include "../detail/Filtered.hpp"
#include "ApolloniusDetail.hpp"

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<SiteIndex, K, CGAL::Regular_triangulation_vertex_base_3<K>>;
// Hidden spheres are not kept: the removals below re-insert them explicitly (with their index).
using Cb = CGAL::Regular_triangulation_cell_base_3<K, CGAL::Triangulation_cell_base_3<K>, CGAL::Discard_hidden_points>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Rt = CGAL::Regular_triangulation_3<K, Tds>;
using Wp = K::Weighted_point_3;

/// F_i(X) = |x − p_i|² − (z + w_i)²: zero on the double cone of i; F_i − F_j is affine in X.
double cone_value(const ApolloniusSite& s, const std::array<double, 3>& X) {
  const double dx = X[0] - s.x, dy = X[1] - s.y, dz = X[2] + s.w;
  return dx * dx + dy * dy - dz * dz;
}

/// Exact sign of |p_k − p_u|² − (w_u − w_k)²: negative when one disc lies strictly inside the other
/// (then the apex of the smaller cone is strictly closer in power to the other sphere).
Sign containment_sign(const ApolloniusSite& k, const ApolloniusSite& u) {
  // Static filter: the double evaluation errs by less than 1e-15 of the sum of the squares (a few
  // roundings of relative size 2⁻⁵³), so a larger value has the exact sign; otherwise filtered exact.
  const double ex = k.x - u.x, ey = k.y - u.y, ew = u.w - k.w;
  const double value = ex * ex + ey * ey - ew * ew, size = ex * ex + ey * ey + ew * ew;
  if (value > 1e-12 * size) return Sign::positive;
  if (value < -1e-12 * size) return Sign::negative;
  return detail::filtered([&]<class NT>() {
    const NT dx = NT(k.x) - NT(u.x), dy = NT(k.y) - NT(u.y), dw = NT(u.w) - NT(k.w);
    return detail::sign_of(dx * dx + dy * dy - dw * dw);
  });
}

/// The points X = (x, δ) of the line ∩ {F_i = F_j = F_k} on the upper half-cones of i, j, k, with
/// the parameter of each point; the line is the intersection of the radical planes ij and ik.
struct LinePoint {
  std::array<double, 3> X;
};

std::vector<LinePoint> tangent_points(const ApolloniusSite& si, const ApolloniusSite& sj, const ApolloniusSite& sk) {
  // Plane F_i − F_j = 0: n·X = h with n = 2(p_j − p_i, w_j − w_i)… written out below.
  auto plane = [&](const ApolloniusSite& a, const ApolloniusSite& b, std::array<double, 3>& n, double& h) {
    n = {2 * (b.x - a.x), 2 * (b.y - a.y), -2 * (a.w - b.w)};
    h = -((a.x * a.x + a.y * a.y - a.w * a.w) - (b.x * b.x + b.y * b.y - b.w * b.w));
  };
  std::array<double, 3> n1, n2;
  double h1, h2;
  plane(si, sj, n1, h1);
  plane(si, sk, n2, h2);
  const std::array<double, 3> dir{n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2],
                                  n1[0] * n2[1] - n1[1] * n2[0]};
  const double dd = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
  if (!(dd > 0)) return {};
  // Point of the line nearest the origin: X0 = (h1 (n2 × dir) + h2 (dir × n1)) / |dir|².
  const std::array<double, 3> a{n2[1] * dir[2] - n2[2] * dir[1], n2[2] * dir[0] - n2[0] * dir[2],
                                n2[0] * dir[1] - n2[1] * dir[0]};
  const std::array<double, 3> b{dir[1] * n1[2] - dir[2] * n1[1], dir[2] * n1[0] - dir[0] * n1[2],
                                dir[0] * n1[1] - dir[1] * n1[0]};
  std::array<double, 3> X0;
  for (int c = 0; c < 3; ++c) X0[static_cast<std::size_t>(c)] = (h1 * a[static_cast<std::size_t>(c)] + h2 * b[static_cast<std::size_t>(c)]) / dd;
  // F_i(X0 + t·dir) = A t² + B t + C.
  const double ex = X0[0] - si.x, ey = X0[1] - si.y, ez = X0[2] + si.w;
  const double A = dir[0] * dir[0] + dir[1] * dir[1] - dir[2] * dir[2];
  const double B = 2 * (ex * dir[0] + ey * dir[1] - ez * dir[2]);
  const double C = ex * ex + ey * ey - ez * ez;
  std::vector<double> roots;
  if (std::abs(A) <= 1e-14 * std::abs(B)) {
    if (B != 0) roots.push_back(-C / B);
  } else {
    const double disc = B * B - 4 * A * C;
    if (disc < -1e-12 * B * B) return {};
    const double sq = std::sqrt(std::max(disc, 0.0));
    const double q = -0.5 * (B + (B >= 0 ? sq : -sq));
    if (q != 0) roots.push_back(C / q);
    roots.push_back(q / A);
    if (q == 0) roots.push_back(0.0);
  }
  std::vector<LinePoint> out;
  for (double t : roots) {
    LinePoint p{{X0[0] + t * dir[0], X0[1] + t * dir[1], X0[2] + t * dir[2]}};
    // Upper half-cones: z + w ≥ 0 for the three sites, relative to the distance from the vertex to
    // the centres (which is |z + w| on the cones): no absolute term, so small diagrams are not blurred.
    const double tol = 1e-9 * std::max({std::hypot(p.X[0] - si.x, p.X[1] - si.y), std::hypot(p.X[0] - sj.x, p.X[1] - sj.y),
                                        std::hypot(p.X[0] - sk.x, p.X[1] - sk.y)});
    if (p.X[2] + si.w < -tol || p.X[2] + sj.w < -tol || p.X[2] + sk.w < -tol) continue;
    bool duplicate = false;
    for (const LinePoint& q : out)
      duplicate = duplicate || (q.X[0] == p.X[0] && q.X[1] == p.X[1] && q.X[2] == p.X[2]);
    if (!duplicate) out.push_back(p);
  }
  return out;
}

}  // namespace

ApolloniusDiagram apollonius_diagram_linearized(const std::vector<ApolloniusSite>& sites) {
  ApolloniusDiagram d = detail::start_apollonius_diagram(sites, "linearized");
  // Drop the sites whose disc lies strictly inside another disc (hidden in the Apollonius diagram,
  // and the only obstruction to "cell = cone ∩ power cell"). A containment k ⊂ u puts the apex of
  // cone k outside L(Σ_k), hence strictly closer to some regular-triangulation neighbour of k; the
  // pair found is a containment one way or the other, and we drop the smaller disc: remove its vertex
  // and insert again the spheres hidden in the power sense (a dropped sphere may have hidden them),
  // until every apex lies in its own power cell.
  std::vector<char> alive(sites.size(), 1);
  {
    // Equal sites: the smallest index stays.
    std::map<std::tuple<double, double, double>, SiteIndex> seen;
    for (SiteIndex i = 0; i < sites.size(); ++i)
      if (!seen.emplace(std::tuple{sites[i].x, sites[i].y, sites[i].w}, i).second) alive[i] = 0;
  }
  Rt rt;
  std::vector<std::vector<SiteIndex>> neighbours(sites.size());
  auto weighted = [&](SiteIndex i) { return Wp(K::Point_3(sites[i].x, sites[i].y, sites[i].w), 2 * sites[i].w * sites[i].w); };
  {
    std::vector<std::pair<Wp, SiteIndex>> points;
    points.reserve(sites.size());
    for (SiteIndex i = 0; i < sites.size(); ++i)
      if (alive[i]) points.emplace_back(weighted(i), i);
    rt.insert(points.begin(), points.end());
  }
  std::vector<Rt::Vertex_handle> handle(sites.size());
  for (;;) {
    // Neighbour lists from one pass over the edges (cheaper than per-vertex adjacency queries).
    for (auto& list : neighbours) list.clear();
    for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
      const SiteIndex i = e->first->vertex(e->second)->info(), j = e->first->vertex(e->third)->info();
      neighbours[i].push_back(j), neighbours[j].push_back(i);
    }
    std::fill(handle.begin(), handle.end(), Rt::Vertex_handle());
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) handle[v->info()] = v;
    std::vector<SiteIndex> doomed;
    for (SiteIndex k = 0; k < sites.size(); ++k) {
      for (SiteIndex u : neighbours[k]) {
        if (containment_sign(sites[k], sites[u]) != Sign::negative) continue;
        const SiteIndex smaller = sites[u].w < sites[k].w ? u : k;
        if (alive[smaller]) alive[smaller] = 0, doomed.push_back(smaller);
        break;
      }
    }
    if (doomed.empty()) break;
    // Remove the dropped spheres; the spheres they hid in the power sense (alive, not vertices) are
    // inserted again, so the triangulation is the regular triangulation of the alive spheres.
    for (SiteIndex k : doomed) rt.remove(handle[k]);
    for (SiteIndex i = 0; i < sites.size(); ++i)
      if (alive[i] && handle[i] == Rt::Vertex_handle()) {
        const Rt::Vertex_handle v = rt.insert(weighted(i));
        if (v != Rt::Vertex_handle()) v->info() = i;
      }
  }

  std::vector<char> visible(sites.size(), 0);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) visible[v->info()] = 1;
  for (SiteIndex i = 0; i < sites.size(); ++i)
    if (!visible[i]) d.hidden.push_back(i);

  std::vector<std::pair<SiteIndex, SiteIndex>> extra;
  if (rt.dimension() >= 2) {
    // Dimension 2 (centres (p_i, w_i) coplanar, e.g. equal weights): each face is dual to a whole line.
    const bool full = rt.dimension() == 3;
    for (auto f = rt.finite_facets_begin(); f != rt.finite_facets_end(); ++f) {
      const Rt::Cell_handle c = f->first;
      const int i = f->second;
      std::vector<Rt::Vertex_handle> opp;
      if (full) {
        const Rt::Cell_handle mirror = c->neighbor(i);
        opp = {c->vertex(i), mirror->vertex(mirror->index(c))};
      }
      std::array<SiteIndex, 3> tri;
      for (int k = 0, m = 0; k < (full ? 4 : 3); ++k)
        if (k != i) tri[static_cast<std::size_t>(m++)] = c->vertex(k)->info();
      const ApolloniusSite &si = sites[tri[0]], &sj = sites[tri[1]], &sk = sites[tri[2]];
      for (const LinePoint& p : tangent_points(si, sj, sk)) {
        // On the power edge dual to the triangle: not closer in power to the two opposite spheres.
        const double fi = cone_value(si, p.X);
        bool inside = true;
        for (const Rt::Vertex_handle& o : opp) {
          if (rt.is_infinite(o)) continue;
          const ApolloniusSite& so = sites[o->info()];
          const double fo = cone_value(so, p.X);
          // F_o − F_i is a difference of squares of lengths ~ r: relative tolerance 1e-10 on r².
          const double r = std::abs(p.X[2] + so.w) + std::hypot(p.X[0] - so.x, p.X[1] - so.y);
          const double tol = 1e-10 * r * r;
          if (fo - fi < -tol) inside = false;
        }
        if (!inside) continue;
        ApolloniusVertex v;
        v.sites = tri;
        v.position = {p.X[0], p.X[1]};
        v.distance = p.X[2];
        d.vertices.push_back(v);
      }
    }
  }
  // Edges without a vertex: a whole hyperbola branch between two cells (e.g. a thin unbounded cell
  // along one neighbour). Such a branch lies entirely in L(Σ_i) ∩ L(Σ_j) or entirely outside, so one
  // point of it (its apex) decides, against the regular-triangulation neighbours of i and j.
  if (rt.dimension() >= 1) {
    std::set<std::pair<SiteIndex, SiteIndex>> with_vertex;
    for (const ApolloniusVertex& v : d.vertices) {
      with_vertex.insert(std::minmax(v.sites[0], v.sites[1]));
      with_vertex.insert(std::minmax(v.sites[1], v.sites[2]));
      with_vertex.insert(std::minmax(v.sites[0], v.sites[2]));
    }
    for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
      const Rt::Vertex_handle vi = e->first->vertex(e->second), vj = e->first->vertex(e->third);
      const auto key = std::minmax(vi->info(), vj->info());
      if (with_vertex.count(key)) continue;
      const ApolloniusSite &si = sites[vi->info()], &sj = sites[vj->info()];
      const double c = std::hypot(sj.x - si.x, sj.y - si.y) / 2, alpha = (si.w - sj.w) / 2;
      if (!(c > std::abs(alpha))) continue;
      const double ux = (sj.x - si.x) / (2 * c), uy = (sj.y - si.y) / (2 * c);
      const std::array<double, 3> X0{(si.x + sj.x) / 2 + alpha * ux, (si.y + sj.y) / 2 + alpha * uy, 0};
      std::array<double, 3> X = X0;
      X[2] = std::hypot(X[0] - si.x, X[1] - si.y) - si.w;
      bool inside = true;
      for (const Rt::Vertex_handle& end : {vi, vj}) {
        for (SiteIndex o : neighbours[end->info()]) {
          const ApolloniusSite& so = sites[o];
          const double r = std::abs(X[2] + so.w) + std::hypot(X[0] - so.x, X[1] - so.y);
          if (cone_value(so, X) < -1e-10 * r * r) inside = false;
        }
      }
      if (inside) extra.emplace_back(key.first, key.second);
    }
  }
  detail::canonicalize(d, std::move(extra), true);
  return d;
}

}  // namespace laguerre::core
