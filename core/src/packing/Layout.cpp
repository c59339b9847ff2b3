#include "laguerre/core/packing/Layout.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <stdexcept>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"
#include "laguerre/core/packing/Placement.hpp"

namespace laguerre::core {

namespace {
using Complex = std::complex<double>;

// Disc automorphism z ↦ (z − c)/(1 − c̄ z) that sends c to 0, and its inverse.
Complex to_origin(Complex z, Complex c) { return (z - c) / (1.0 - std::conj(c) * z); }
Complex from_origin(Complex z, Complex c) { return (z + c) / (1.0 + std::conj(c) * z); }

// Euclidean radius of a hyperbolic circle of radius h centred at the origin.
double origin_radius(double h) { return std::tanh(h / 2); }

// Euclidean distance from the origin of the centre of w when v sits at the origin: tanh(l/2), where
// cosh l = cosh h_v cosh h_w + c sinh h_v sinh h_w. With a = e^{-h_v}, b = e^{-h_w} and
// L = 4ab cosh l (HyperbolicTriangle.hpp), tanh²(l/2) = (L − 4ab) / (L + 4ab) and
//   L ∓ 4ab = (1+c)(1 ∓ ab)² + (1−c)(a ∓ b)²,
// where 1 − ab = −expm1(−h_v − h_w) and a − b (through expm1 of h_v − h_w) keep small circles exact.
double centre_distance(double hv, double hw, double c) {
  if (c == 1.0) return std::tanh((hv + hw) / 2);
  const double a = std::exp(-hv), b = std::exp(-hw);
  const double p = -std::expm1(-(hv + hw));
  const double m = hv <= hw ? -a * std::expm1(hv - hw) : b * std::expm1(hw - hv);
  const double num = (1 + c) * p * p + (1 - c) * m * m;
  const double sp = 1 + a * b, sm = a + b;
  const double den = (1 + c) * sp * sp + (1 - c) * sm * sm;
  return std::sqrt(num / den);
}

// Euclidean radius of the horocycle meeting the origin-centred circle of Euclidean radius s at an
// angle of cosine c: its centre (1−ρ)ζ satisfies (1−ρ)² = s² + ρ² + 2sρc.
double horocycle_radius(double s, double c) { return (1 - s * s) / (2 * (1 + s * c)); }

// Euclidean circle of the hyperbolic circle with centre z and origin radius s.
Circle euclidean_circle(Complex z, double s) {
  const double z2 = std::norm(z), s2 = s * s;
  const double den = 1 - s2 * z2;
  const Complex c = z * ((1 - s2) / den);
  return {c.real(), c.imag(), s * (1 - z2) / den};
}

// The horocycle through point q with ideal point ζ: centre (1−ρ)ζ, |q − (1−ρ)ζ| = ρ.
Circle horocycle_through(Complex zeta, Complex q) {
  const Complex a = q - zeta;
  const double rho = -std::norm(a) / (2 * (a * std::conj(zeta)).real());
  const Complex c = (1 - rho) * zeta;
  return {c.real(), c.imag(), rho};
}

// Möbius map fixed by three point pairs z_i ↦ w_i (cross-ratio form).
struct Mobius3 {
  Complex z1, z2, z3, w1, w2, w3;
  Complex operator()(Complex z) const {
    const Complex s = ((z - z1) * (z3 - z2)) / ((z - z2) * (z3 - z1));
    return (s * w2 * (w3 - w1) - w1 * (w3 - w2)) / (s * (w3 - w1) - (w3 - w2));
  }
};

Complex tangency_point(const Circle& a, const Circle& b) {
  const Complex ca(a.x, a.y), cb(b.x, b.y);
  return ca + (cb - ca) * (a.r / std::abs(cb - ca));
}

// Angle at x of the triangle (x, y, z) with edge cosines c_xy, c_xz, c_yz.
double triangle_angle(double hx, double hy, double hz, double cxy, double cxz, double cyz, bool overlap) {
  if (!overlap) return tangent_angle(lift(hx), lift(hy), lift(hz));
  return overlap_angle(lift(hx), lift(hy), lift(hz), cxy, cxz, cyz);
}

// Place w in the frame where interior u (value xu, centre zu) is at the origin, at direction `dir`.
PlacedCircle place_in_frame(double hu, LayoutVertex w, double cos_uw, double dir, Complex zu) {
  const Complex e = std::polar(1.0, dir);
  PlacedCircle out;
  if (w.interior) {
    const Complex z = from_origin(e * centre_distance(hu, w.h, cos_uw), zu);
    out.centre = z;
    out.circle = euclidean_circle(z, origin_radius(w.h));
  } else {
    const double rho = horocycle_radius(origin_radius(hu), cos_uw);
    const Complex zeta = from_origin(e, zu);
    out.centre = zeta / std::abs(zeta);
    out.circle = horocycle_through(out.centre, from_origin(e * (1 - 2 * rho), zu));
  }
  return out;
}

// Direction of placed point za seen from interior centre zu moved to the origin.
double direction(Complex zu, Complex za) { return std::arg(to_origin(za, zu)); }

// a, b horocycles (tangent): build (a, b, w) in a canonical frame and move it onto a, b by the
// Möbius map that matches their ideal points and their tangency point.
PlacedCircle place_between_horocycles(LayoutVertex w, LayoutVertex a, const PlacedCircle& pa, LayoutVertex b,
                                      const PlacedCircle& pb, const FaceCosines& c) {
  Complex za, zb;  // local ideal points
  Circle ca, cb;   // local circles
  Complex zw;      // local centre of w (or ideal point)
  double rw = 0;   // local Euclidean radius of w
  if (w.interior) {
    const double s = origin_radius(w.h);
    za = 1.0;
    zb = std::polar(1.0, triangle_angle(w.h, a.h, b.h, c.wa, c.wb, c.ab, c.overlap));
    const double ra = horocycle_radius(s, c.wa), rb = horocycle_radius(s, c.wb);
    ca = {(1 - ra) * za.real(), (1 - ra) * za.imag(), ra};
    cb = {(1 - rb) * zb.real(), (1 - rb) * zb.imag(), rb};
    zw = 0;
    rw = s;
  } else {  // three mutually tangent horocycles, symmetric
    const double rho = std::sqrt(3.0) / (2 + std::sqrt(3.0));
    za = 1.0;
    zb = std::polar(1.0, 2 * std::numbers::pi / 3);
    zw = std::polar(1.0, 4 * std::numbers::pi / 3);
    ca = {1 - rho, 0, rho};
    cb = {(1 - rho) * zb.real(), (1 - rho) * zb.imag(), rho};
    rw = rho;
  }
  const Mobius3 m{za, zb, tangency_point(ca, cb), pa.centre, pb.centre, tangency_point(pa.circle, pb.circle)};
  PlacedCircle out;
  if (w.interior) {
    const Complex z = m(zw);
    out.centre = z;
    out.circle = euclidean_circle(z, rw);
  } else {
    const Complex zeta = m(zw);
    out.centre = zeta / std::abs(zeta);
    out.circle = horocycle_through(out.centre, m(zw * (1 - 2 * rw)));
  }
  return out;
}
}  // namespace

PlacedCircle place_root(double h_root) { return {0.0, Circle{0, 0, origin_radius(h_root)}}; }

PlacedCircle place_first_neighbour(double h_root, LayoutVertex w, double cos_root_w) {
  return place_in_frame(h_root, w, cos_root_w, 0.0, 0.0);
}

PlacedCircle place_in_face(LayoutVertex w, LayoutVertex a, const PlacedCircle& pa, LayoutVertex b,
                           const PlacedCircle& pb, const FaceCosines& c) {
  if (a.interior) {  // around a, (a, b, w) is ccw: w follows b
    const double angle = triangle_angle(a.h, b.h, w.h, c.ab, c.wa, c.wb, c.overlap);
    return place_in_frame(a.h, w, c.wa, direction(pa.centre, pb.centre) + angle, pa.centre);
  }
  if (b.interior) {  // around b, (b, w, a) is ccw: w precedes a
    const double angle = triangle_angle(b.h, w.h, a.h, c.wb, c.ab, c.wa, c.overlap);
    return place_in_frame(b.h, w, c.wb, direction(pb.centre, pa.centre) - angle, pb.centre);
  }
  return place_between_horocycles(w, a, pa, b, pb, c);
}

Vertex choose_root(const PackingComplex& k, RootRule rule) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = k.num_original;
  Vertex best = none;
  if (rule == RootRule::smallest_id) {
    for (Vertex v = 0; v < n; ++v)
      if (!g.is_boundary(v) && (best == none || g.id(v) < g.id(best))) best = v;
    return best;
  }
  // Multi-source BFS from the boundary over the whole complex.
  std::vector<std::uint32_t> depth(g.num_vertices(), none);
  std::deque<Vertex> queue;
  for (Vertex v = 0; v < g.num_vertices(); ++v)
    if (g.is_boundary(v)) {
      depth[v] = 0;
      queue.push_back(v);
    }
  while (!queue.empty()) {
    const Vertex v = queue.front();
    queue.pop_front();
    for (Vertex w : g.neighbours(v))
      if (depth[w] == none) {
        depth[w] = depth[v] + 1;
        queue.push_back(w);
      }
  }
  for (Vertex v = 0; v < n; ++v) {
    if (g.is_boundary(v)) continue;
    if (best == none || depth[v] > depth[best] || (depth[v] == depth[best] && g.id(v) < g.id(best))) best = v;
  }
  return best;
}

Layout lay_out(const PackingComplex& k, const Radii& h, Vertex root) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = g.num_vertices();
  Layout out;
  out.circles.assign(n, Circle{});
  out.centre.assign(n, 0.0);
  out.wave.assign(n, none);
  out.parent.assign(n, none);
  out.root = root;
  const bool overlap = k.has_face_vertices();
  auto interior = [&](Vertex v) { return !g.is_boundary(v); };
  auto cos_of = [&](Vertex u, Vertex v) { return overlap ? k.cos_angle[g.find_dart(u, v)] : 1.0; };
  auto vertex = [&](Vertex v) { return LayoutVertex{h[v], interior(v)}; };
  auto store = [&](Vertex v, const PlacedCircle& p) {
    out.centre[v] = p.centre;
    out.circles[v] = p.circle;
  };

  std::vector<Vertex> placed_now;
  if (root != none) {
    store(root, place_root(h[root]));
    const Vertex first = g.neighbours(root)[0];
    store(first, place_first_neighbour(h[root], vertex(first), cos_of(root, first)));
    out.parent[first] = root;
    placed_now = {root, first};
  } else {  // no interior vertex: three boundary circles of an inner face, symmetric
    const Dart d0 = g.face_darts(g.outer_face()).front();
    const Face f = g.face_of(g.twin(d0));
    const auto darts = g.face_darts(f);
    const double rho = std::sqrt(3.0) / (2 + std::sqrt(3.0));
    for (int i = 0; i < 3; ++i) {
      const Vertex v = g.tail(darts[i]);
      const Complex zeta = std::polar(1.0, 2 * std::numbers::pi * i / 3);
      out.centre[v] = zeta;
      out.circles[v] = {(1 - rho) * zeta.real(), (1 - rho) * zeta.imag(), rho};
      placed_now.push_back(v);
    }
  }
  for (Vertex v : placed_now) out.wave[v] = 0;

  // Synchronous waves: candidates are unplaced neighbours of the vertices placed last round.
  std::vector<Vertex> candidates;
  std::vector<std::uint8_t> listed(n, 0);
  std::uint32_t round = 0;
  std::vector<std::pair<Vertex, std::pair<Vertex, Vertex>>> placements;
  while (!placed_now.empty()) {
    ++round;
    candidates.clear();
    for (Vertex v : placed_now)
      for (Vertex w : g.neighbours(v))
        if (out.wave[w] == none && !listed[w]) {
          listed[w] = 1;
          candidates.push_back(w);
        }
    // No sorting needed: a round's placements read only positions from earlier rounds, so the order
    // in which candidates are visited cannot change any bit of the result.
    placements.clear();
    for (Vertex w : candidates) {
      listed[w] = 0;
      const Dart first = g.first_dart(w);
      const std::uint32_t deg = g.degree(w);
      const auto nb = g.neighbours(w);
      // Wedge i (between neighbours i and i+1) is the face left of dart w→neighbour i.
      const std::uint32_t i = choose_placement_wedge(
          deg, [&](std::uint32_t j) { return g.face_of(first + j) != g.outer_face(); },
          [&](std::uint32_t j) { return out.wave[nb[j]] != none; },
          [&](std::uint32_t j) { return interior(nb[j]); });
      if (i != deg) placements.push_back({w, {nb[i], nb[i + 1 == deg ? 0 : i + 1]}});
    }
    placed_now.clear();
    for (const auto& [w, ab] : placements) {
      const auto [a, b] = ab;
      const FaceCosines c{cos_of(w, a), cos_of(w, b), cos_of(a, b), overlap};
      store(w, place_in_face(vertex(w), vertex(a), {out.centre[a], out.circles[a]}, vertex(b),
                             {out.centre[b], out.circles[b]}, c));
      out.parent[w] = parent_is_first_anchor(interior(a), interior(b)) ? a : b;
    }
    for (const auto& [w, ab] : placements) {
      out.wave[w] = round;
      placed_now.push_back(w);
    }
  }
  for (Vertex v = 0; v < n; ++v)
    if (out.wave[v] == none)
      throw std::logic_error("lay_out: vertex " + std::to_string(g.id(v)) + " was never placed; the complex is not a triangulated disc.");

  out.smallest_radius = std::numeric_limits<double>::infinity();
  for (const Circle& c : out.circles) {
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.r) || !(c.r > 0)) {
      out.precision = Precision::unrepresentable;
    }
    out.smallest_radius = std::min(out.smallest_radius, c.r);
  }
  if (out.precision == Precision::ok && out.smallest_radius < Layout::degraded_radius) out.precision = Precision::degraded;
  return out;
}

double tangency_error(const CircleEmbedding& c, Vertex u, Vertex v) {
  const double d = std::hypot(c[u].x - c[v].x, c[u].y - c[v].y);
  return std::abs(d - (c[u].r + c[v].r)) / std::min(c[u].r, c[v].r);
}

}  // namespace laguerre::core
