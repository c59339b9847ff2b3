#include "laguerre/core/packing/RadiusOnly.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/packing/Placement.hpp"

// The mathematics (why these tests, what they prove) is docs/radius-only.md. In short: for mutually
// tangent v, a, b the radical centre q of their circles is the centre of their orthocircle O (the
// incircle of the triangle of centres, through the three tangency points), pow(q, v) = ρ² > 0, and
// the LPD corner test pow(q, c) − pow(q, v) = 2 r_c ρ · I(c, O) has the sign of the inversive
// distance I, which disc automorphisms preserve. So it can be evaluated in any frame of the two
// triangles; we lay them out from the radii with the layout's own placement functions.

namespace laguerre::core {

namespace {

LayoutVertex vertex(double h) { return {h, std::isfinite(h)}; }

struct Frame {
  Circle v, a, b, c;
  bool ok = false;
};

// The four circles in a frame rooted at an interior one of them (v, else b, else a, else c).
Frame corner_frame(double hv, double ha, double hb, double hc) {
  const LayoutVertex V = vertex(hv), A = vertex(ha), B = vertex(hb), C = vertex(hc);
  const FaceCosines tangent{};
  PlacedCircle pv, pa, pb, pc;
  if (V.interior || B.interior) {
    if (V.interior) {
      pv = place_root(hv);
      pb = place_first_neighbour(hv, B, 1.0);
    } else {
      pb = place_root(hb);
      pv = place_first_neighbour(hb, V, 1.0);
    }
    pa = place_in_face(A, B, pb, V, pv, tangent);  // (a, b, v) counter-clockwise
    pc = place_in_face(C, V, pv, B, pb, tangent);  // (c, v, b)
  } else if (A.interior) {
    pa = place_root(ha);
    pv = place_first_neighbour(ha, V, 1.0);
    pb = place_in_face(B, V, pv, A, pa, tangent);  // (b, v, a)
    pc = place_in_face(C, V, pv, B, pb, tangent);
  } else if (C.interior) {
    pc = place_root(hc);
    pv = place_first_neighbour(hc, V, 1.0);
    pb = place_in_face(B, C, pc, V, pv, tangent);  // (b, c, v)
    pa = place_in_face(A, B, pb, V, pv, tangent);
  } else {
    return {};  // four horocycles: no interior circle to root a frame at
  }
  Frame f{pv.circle, pa.circle, pb.circle, pc.circle, true};
  for (const Circle* c : {&f.v, &f.a, &f.b, &f.c})
    if (!std::isfinite(c->x) || !std::isfinite(c->y) || !std::isfinite(c->r) || !(c->r > 0)) f.ok = false;
  return f;
}

// Inversive distance of c and the orthocircle of (v, a, b), in doubles (NaN if it does not exist).
double inversive(const Frame& f) {
  const double ax = 2 * (f.a.x - f.v.x), ay = 2 * (f.a.y - f.v.y);
  const double bx = 2 * (f.b.x - f.v.x), by = 2 * (f.b.y - f.v.y);
  auto z = [](const Circle& c) { return c.x * c.x + c.y * c.y - c.r * c.r; };
  const double ra = z(f.a) - z(f.v), rb = z(f.b) - z(f.v);
  const double det = ax * by - ay * bx;
  if (det == 0) return std::numeric_limits<double>::quiet_NaN();
  const double qx = (ra * by - ay * rb) / det, qy = (ax * rb - ra * bx) / det;
  const double rho2 = power(qx, qy, f.v);
  if (!(rho2 > 0)) return std::numeric_limits<double>::quiet_NaN();
  return (power(qx, qy, f.c) - rho2) / (2 * f.c.r * std::sqrt(rho2));
}

}  // namespace

double corner_inversive_distance(double h_v, double h_a, double h_b, double h_c) {
  const Frame f = corner_frame(h_v, h_a, h_b, h_c);
  return f.ok ? inversive(f) : std::numeric_limits<double>::quiet_NaN();
}

LocalCondition check_radius_only(double h_v, const StarView& star, bool boundary, const RadiusOnlyTolerance& tol) {
  const std::span<const double> w = star.neighbour_h;
  const std::size_t n = w.size();
  if (!boundary && n > 0) {
    const double theta = star_angle_sum(h_v, star);
    if (!std::isfinite(theta)) return LocalCondition::unrepresentable;
    if (!(std::abs(theta - 2 * std::numbers::pi) <= tol.angle_gap)) return LocalCondition::neighbour_order;
  }
  // Stars touching a face vertex: the closing gap only (a trigger; docs/radius-only.md).
  if (!star.cos_spoke.empty()) return LocalCondition::holds;
  // Interior: every corner, cyclically (n ≥ 3 in a triangulated disc). Boundary: corners 2 … n−1.
  const std::size_t first = boundary ? 1 : 0, last = boundary ? (n >= 2 ? n - 1 : 0) : n;
  for (std::size_t i = first; i < last; ++i) {
    const double ha = w[(i + n - 1) % n], hb = w[i], hc = w[(i + 1) % n];
    const Frame f = corner_frame(h_v, ha, hb, hc);
    if (!f.ok) return LocalCondition::unrepresentable;
    if (radical_centre_power_side(f.v, f.a, f.b, f.c) != Sign::positive) return LocalCondition::missing_edge;
    const double d = inversive(f);
    if (std::isnan(d)) return LocalCondition::unrepresentable;
    if (!(d >= tol.margin)) return LocalCondition::missing_edge;
  }
  return LocalCondition::holds;
}

LocalCondition check_radius_only(const PackingComplex& k, const Radii& h, Vertex v, const RadiusOnlyTolerance& tol) {
  const PlanarGraph& g = k.graph;
  const std::uint32_t deg = g.degree(v);
  const bool boundary = g.is_boundary(v);
  std::vector<double> nh, spoke, rim;
  const Dart start = lpd_first_dart(g, v);
  Dart d = start;
  for (std::uint32_t i = 0; i < deg; ++i, d = g.next_ccw(d)) {
    nh.push_back(h[g.head(d)]);
    if (!k.tangent_only[v]) {
      spoke.push_back(k.cos_angle[d]);
      rim.push_back(k.cos_angle[g.next_in_face(d)]);
    }
  }
  return check_radius_only(boundary ? std::numeric_limits<double>::infinity() : h[v], StarView{nh, spoke, rim},
                           boundary, tol);
}

bool radius_only_everywhere(const PackingComplex& k, const Radii& h, const RadiusOnlyTolerance& tol) {
  for (Vertex v = 0; v < k.graph.num_vertices(); ++v)
    if (check_radius_only(k, h, v, tol) != LocalCondition::holds) return false;
  return true;
}

}  // namespace laguerre::core
