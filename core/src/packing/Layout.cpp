#include "laguerre/core/packing/Layout.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <stdexcept>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

namespace laguerre::core {

namespace {
using Complex = std::complex<double>;

// Disc automorphism z ↦ (z − c)/(1 − c̄ z) that sends c to 0, and its inverse.
Complex to_origin(Complex z, Complex c) { return (z - c) / (1.0 - std::conj(c) * z); }
Complex from_origin(Complex z, Complex c) { return (z + c) / (1.0 + std::conj(c) * z); }

// Euclidean radius of a hyperbolic circle of value X centred at the origin: tanh(h/2), e^{-h} = √X.
double origin_radius(double X) {
  const double e = std::sqrt(X);
  return (1 - e) / (1 + e);
}

// Euclidean distance from the origin of the centre of w when v sits at the origin: tanh(l/2) with
// cosh l = L / (4√(XvXw)) (see HyperbolicTriangle.hpp).
double centre_distance(double xv, double xw, double c) {
  const double q = std::sqrt(xv * xw);
  if (c == 1.0) return (1 - q) / (1 + q);
  const double l = (1 + xv) * (1 + xw) + c * (1 - xv) * (1 - xw);
  return std::sqrt((l - 4 * q) / (l + 4 * q));
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

struct Placer {
  const PackingComplex& k;
  const Radii& X;
  Layout& out;

  bool interior(Vertex v) const { return !k.graph.is_boundary(v); }
  double cos_of(Vertex u, Vertex v) const {
    return k.has_face_vertices() ? k.cos_angle[k.graph.find_dart(u, v)] : 1.0;
  }

  // Angle at x of the triangle (x, y, z).
  double angle(Vertex x, Vertex y, Vertex z) const {
    if (!k.has_face_vertices()) return tangent_angle(X[x], X[y], X[z]);
    return overlap_angle(X[x], X[y], X[z], cos_of(x, y), cos_of(x, z), cos_of(y, z));
  }

  // Place w in the frame where u (interior) is at the origin, at direction `dir`.
  void place_in_frame(Vertex u, Vertex w, double dir, Complex zu) const {
    const Complex e = std::polar(1.0, dir);
    if (interior(w)) {
      const Complex z = from_origin(e * centre_distance(X[u], X[w], cos_of(u, w)), zu);
      out.centre[w] = z;
      out.circles[w] = euclidean_circle(z, origin_radius(X[w]));
    } else {
      const double rho = horocycle_radius(origin_radius(X[u]), cos_of(u, w));
      const Complex zeta = from_origin(e, zu);
      out.centre[w] = zeta / std::abs(zeta);
      out.circles[w] = horocycle_through(out.centre[w], from_origin(e * (1 - 2 * rho), zu));
    }
  }

  // Direction of placed vertex a seen from interior u moved to the origin.
  double direction(Vertex u, Vertex a) const { return std::arg(to_origin(out.centre[a], out.centre[u])); }

  // Place w in the inner face (w, a, b) (counter-clockwise), a and b placed.
  void place(Vertex w, Vertex a, Vertex b) const {
    if (interior(a)) {  // around a, (a, b, w) is ccw: w follows b
      place_in_frame(a, w, direction(a, b) + angle(a, b, w), out.centre[a]);
    } else if (interior(b)) {  // around b, (b, w, a) is ccw: w precedes a
      place_in_frame(b, w, direction(b, a) - angle(b, w, a), out.centre[b]);
    } else {
      place_between_horocycles(w, a, b);
    }
  }

  // a, b horocycles (tangent): build (a, b, w) in a canonical frame and move it onto a, b by the
  // Möbius map that matches their ideal points and their tangency point.
  void place_between_horocycles(Vertex w, Vertex a, Vertex b) const {
    Complex za, zb;  // local ideal points
    Circle ca, cb;   // local circles
    Complex zw;      // local centre of w (or ideal point)
    double rw = 0;   // local Euclidean radius of w
    if (interior(w)) {
      const double s = origin_radius(X[w]);
      za = 1.0;
      zb = std::polar(1.0, angle(w, a, b));
      const double ra = horocycle_radius(s, cos_of(w, a)), rb = horocycle_radius(s, cos_of(w, b));
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
    const Mobius3 m{za, zb, tangency_point(ca, cb), out.centre[a], out.centre[b],
                    tangency_point(out.circles[a], out.circles[b])};
    if (interior(w)) {
      const Complex z = m(zw);
      out.centre[w] = z;
      out.circles[w] = euclidean_circle(z, rw);
    } else {
      const Complex zeta = m(zw);
      out.centre[w] = zeta / std::abs(zeta);
      out.circles[w] = horocycle_through(out.centre[w], m(zw * (1 - 2 * rw)));
    }
  }
};
}  // namespace

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

Layout lay_out(const PackingComplex& k, const Radii& X, Vertex root) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = g.num_vertices();
  Layout out;
  out.circles.assign(n, Circle{});
  out.centre.assign(n, 0.0);
  out.wave.assign(n, none);
  out.parent.assign(n, none);
  out.root = root;
  Placer placer{k, X, out};

  std::vector<Vertex> placed_now;
  if (root != none) {
    out.centre[root] = 0.0;
    out.circles[root] = {0, 0, origin_radius(X[root])};
    const Vertex first = g.neighbours(root)[0];
    placer.place_in_frame(root, first, 0.0, 0.0);
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
      Vertex pa = none, pb = none;
      for (std::uint32_t i = 0; i < deg; ++i) {
        const Dart d = first + i;
        if (g.face_of(d) == g.outer_face()) continue;  // (w, a, b) must be an inner face
        const Vertex a = g.head(d), b = g.head(g.next_ccw(d));
        if (out.wave[a] == none || out.wave[b] == none) continue;
        if (pa == none) pa = a, pb = b;
        if (placer.interior(a) || placer.interior(b)) {
          pa = a, pb = b;
          break;
        }
      }
      if (pa != none) placements.push_back({w, {pa, pb}});
    }
    placed_now.clear();
    for (const auto& [w, ab] : placements) {
      placer.place(w, ab.first, ab.second);
      out.parent[w] = placer.interior(ab.first) || !placer.interior(ab.second) ? ab.first : ab.second;
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
