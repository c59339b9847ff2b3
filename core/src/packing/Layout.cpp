#include "laguerre/core/packing/Layout.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <stdexcept>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/packing/HyperbolicTriangle.hpp"
#include "laguerre/core/packing/Placement.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/float128.hpp>

#include <quadmath.h>

#include "../detail/HyperbolicTriangle.hpp"

namespace laguerre::core {

using Quad = boost::multiprecision::float128;

template <>
Quad detail::expm1_of(const Quad& x) {
  return Quad(expm1q(x.backend().value()));
}

namespace {
// The placement formulas over a floating-point type T: double (the network's arithmetic, Placement.hpp)
// or float128 (LayoutArithmetic::binary128). Complex numbers are a plain struct so that the same code
// serves both (std::complex is only specified for the standard floating-point types).
template <class T>
struct Cx {
  T re = 0, im = 0;
  Cx() = default;
  Cx(T r) : re(std::move(r)) {}  // NOLINT(google-explicit-constructor): a real number
  Cx(T r, T i) : re(std::move(r)), im(std::move(i)) {}
  friend Cx operator+(const Cx& a, const Cx& b) { return {a.re + b.re, a.im + b.im}; }
  friend Cx operator-(const Cx& a, const Cx& b) { return {a.re - b.re, a.im - b.im}; }
  friend Cx operator*(const Cx& a, const Cx& b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
  friend Cx operator*(const T& a, const Cx& b) { return {a * b.re, a * b.im}; }
  friend Cx operator*(const Cx& a, const T& b) { return {a.re * b, a.im * b}; }
  friend Cx operator/(const Cx& a, const T& b) { return {a.re / b, a.im / b}; }
  friend Cx operator/(const Cx& a, const Cx& b) {  // |b| ≤ 1 here: no overflow-safe scaling needed
    const T d = b.re * b.re + b.im * b.im;
    return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
  }
};
template <class T> T norm(const Cx<T>& z) { return z.re * z.re + z.im * z.im; }
template <class T> T abs(const Cx<T>& z) { using std::sqrt; return sqrt(norm(z)); }
template <class T> T arg(const Cx<T>& z) { using std::atan2; return atan2(z.im, z.re); }
template <class T> Cx<T> conj(const Cx<T>& z) { return {z.re, -z.im}; }
template <class T> Cx<T> polar(const T& r, const T& t) { using std::cos, std::sin; return {r * cos(t), r * sin(t)}; }

template <class T>
struct CircleT {
  T x = 0, y = 0, r = 0;
};

template <class T>
struct PlacedT {
  Cx<T> centre;
  CircleT<T> circle;
};

template <class T>
struct VertexT {
  T h;
  bool interior;
};

// Disc automorphism z ↦ (z − c)/(1 − c̄ z) that sends c to 0, and its inverse.
template <class T> Cx<T> to_origin(const Cx<T>& z, const Cx<T>& c) { return (z - c) / (Cx<T>(T(1)) - conj(c) * z); }
template <class T> Cx<T> from_origin(const Cx<T>& z, const Cx<T>& c) { return (z + c) / (Cx<T>(T(1)) + conj(c) * z); }

// Euclidean radius of a hyperbolic circle of radius h centred at the origin.
template <class T> T origin_radius(const T& h) { using std::tanh; return tanh(h / 2); }

// Euclidean distance from the origin of the centre of w when v sits at the origin: tanh(l/2), where
// cosh l = cosh h_v cosh h_w + c sinh h_v sinh h_w. With a = e^{-h_v}, b = e^{-h_w} and
// L = 4ab cosh l (HyperbolicTriangle.hpp), tanh²(l/2) = (L − 4ab) / (L + 4ab) and
//   L ∓ 4ab = (1+c)(1 ∓ ab)² + (1−c)(a ∓ b)²,
// where 1 − ab = −expm1(−h_v − h_w) and a − b (through expm1 of h_v − h_w) keep small circles exact.
template <class T>
T centre_distance(const T& hv, const T& hw, double cd) {
  using std::exp, std::sqrt, std::tanh, detail::expm1_of;
  if (cd == 1.0) return tanh((hv + hw) / 2);
  const T c(cd);
  const T a = exp(-hv), b = exp(-hw);
  const T p = -expm1_of(T(-(hv + hw)));
  const T m = hv <= hw ? T(-a * expm1_of(T(hv - hw))) : T(b * expm1_of(T(hw - hv)));
  const T num = (1 + c) * p * p + (1 - c) * m * m;
  const T sp = 1 + a * b, sm = a + b;
  const T den = (1 + c) * sp * sp + (1 - c) * sm * sm;
  return sqrt(num / den);
}

// Euclidean radius of the horocycle meeting the origin-centred circle of Euclidean radius s at an
// angle of cosine c: its centre (1−ρ)ζ satisfies (1−ρ)² = s² + ρ² + 2sρc.
template <class T> T horocycle_radius(const T& s, double c) { return (1 - s * s) / (2 * (1 + s * T(c))); }

// Euclidean circle of the hyperbolic circle with centre z and origin radius s.
template <class T>
CircleT<T> euclidean_circle(const Cx<T>& z, const T& s) {
  const T z2 = norm(z), s2 = s * s;
  const T den = 1 - s2 * z2;
  const Cx<T> c = z * T((1 - s2) / den);
  return {c.re, c.im, s * (1 - z2) / den};
}

// The horocycle through point q with ideal point ζ: centre (1−ρ)ζ, |q − (1−ρ)ζ| = ρ.
template <class T>
CircleT<T> horocycle_through(const Cx<T>& zeta, const Cx<T>& q) {
  const Cx<T> a = q - zeta;
  const T rho = -norm(a) / (2 * (a * conj(zeta)).re);
  const Cx<T> c = T(1 - rho) * zeta;
  return {c.re, c.im, rho};
}

// Möbius map fixed by three point pairs z_i ↦ w_i (cross-ratio form).
template <class T>
struct Mobius3 {
  Cx<T> z1, z2, z3, w1, w2, w3;
  Cx<T> operator()(const Cx<T>& z) const {
    const Cx<T> s = ((z - z1) * (z3 - z2)) / ((z - z2) * (z3 - z1));
    return (s * w2 * (w3 - w1) - w1 * (w3 - w2)) / (s * (w3 - w1) - (w3 - w2));
  }
};

template <class T>
Cx<T> tangency_point(const CircleT<T>& a, const CircleT<T>& b) {
  const Cx<T> ca(a.x, a.y), cb(b.x, b.y);
  return ca + (cb - ca) * T(a.r / abs(cb - ca));
}

// Angle at x of the triangle (x, y, z) with edge cosines c_xy, c_xz, c_yz.
template <class T>
T triangle_angle(const detail::LiftT<T>& x, const detail::LiftT<T>& y, const detail::LiftT<T>& z, double cxy,
                 double cxz, double cyz, bool overlap) {
  if (!overlap) return detail::tangent_angle_t(x, y, z);
  return detail::overlap_angle_t(x, y, z, cxy, cxz, cyz);
}
template <class T>
T triangle_angle(const T& hx, const T& hy, const T& hz, double cxy, double cxz, double cyz, bool overlap) {
  using detail::lift_t;
  return triangle_angle(lift_t(hx), lift_t(hy), lift_t(hz), cxy, cxz, cyz, overlap);
}

// Place w in the frame where interior u (value xu, centre zu) is at the origin, at direction `dir`.
template <class T>
PlacedT<T> place_in_frame(const T& hu, const VertexT<T>& w, double cos_uw, const T& dir, const Cx<T>& zu) {
  const Cx<T> e = polar(T(1), dir);
  PlacedT<T> out;
  if (w.interior) {
    const Cx<T> z = from_origin(e * centre_distance(hu, w.h, cos_uw), zu);
    out.centre = z;
    out.circle = euclidean_circle(z, origin_radius(w.h));
  } else {
    const T rho = horocycle_radius(origin_radius(hu), cos_uw);
    const Cx<T> zeta = from_origin(e, zu);
    out.centre = zeta / abs(zeta);
    out.circle = horocycle_through(out.centre, from_origin(e * T(1 - 2 * rho), zu));
  }
  return out;
}

// Direction of placed point za seen from interior centre zu moved to the origin.
template <class T> T direction(const Cx<T>& zu, const Cx<T>& za) { return arg(to_origin(za, zu)); }

// a, b horocycles (tangent): build (a, b, w) in a canonical frame and move it onto a, b by the
// Möbius map that matches their ideal points and their tangency point.
template <class T>
PlacedT<T> place_between_horocycles(const VertexT<T>& w, const VertexT<T>& a, const PlacedT<T>& pa,
                                    const VertexT<T>& b, const PlacedT<T>& pb, const FaceCosines& c) {
  using std::sqrt;
  const T pi = boost::math::constants::pi<T>();
  Cx<T> za, zb;     // local ideal points
  CircleT<T> ca, cb;  // local circles
  Cx<T> zw;         // local centre of w (or ideal point)
  T rw = 0;         // local Euclidean radius of w
  if (w.interior) {
    const T s = origin_radius(w.h);
    za = Cx<T>(T(1));
    zb = polar(T(1), triangle_angle(w.h, a.h, b.h, c.wa, c.wb, c.ab, c.overlap));
    const T ra = horocycle_radius(s, c.wa), rb = horocycle_radius(s, c.wb);
    ca = {(1 - ra) * za.re, (1 - ra) * za.im, ra};
    cb = {(1 - rb) * zb.re, (1 - rb) * zb.im, rb};
    zw = Cx<T>(T(0));
    rw = s;
  } else {  // three mutually tangent horocycles, symmetric
    const T rho = sqrt(T(3)) / (2 + sqrt(T(3)));
    za = Cx<T>(T(1));
    zb = polar(T(1), T(2 * pi / 3));
    zw = polar(T(1), T(4 * pi / 3));
    ca = {1 - rho, T(0), rho};
    cb = {(1 - rho) * zb.re, (1 - rho) * zb.im, rho};
    rw = rho;
  }
  const Mobius3<T> m{za, zb, tangency_point(ca, cb), pa.centre, pb.centre, tangency_point(pa.circle, pb.circle)};
  PlacedT<T> out;
  if (w.interior) {
    const Cx<T> z = m(zw);
    out.centre = z;
    out.circle = euclidean_circle(z, rw);
  } else {
    const Cx<T> zeta = m(zw);
    out.centre = zeta / abs(zeta);
    out.circle = horocycle_through(out.centre, m(zw * T(1 - 2 * rw)));
  }
  return out;
}

template <class T>
PlacedT<T> place_in_face_t(const VertexT<T>& w, const VertexT<T>& a, const PlacedT<T>& pa, const VertexT<T>& b,
                           const PlacedT<T>& pb, const FaceCosines& c) {
  if (a.interior) {  // around a, (a, b, w) is ccw: w follows b
    const T angle = triangle_angle(a.h, b.h, w.h, c.ab, c.wa, c.wb, c.overlap);
    return place_in_frame(a.h, w, c.wa, T(direction(pa.centre, pb.centre) + angle), pa.centre);
  }
  if (b.interior) {  // around b, (b, w, a) is ccw: w precedes a
    const T angle = triangle_angle(b.h, w.h, a.h, c.wb, c.ab, c.wa, c.overlap);
    return place_in_frame(b.h, w, c.wb, T(direction(pb.centre, pa.centre) - angle), pb.centre);
  }
  return place_between_horocycles(w, a, pa, b, pb, c);
}

template <class T> PlacedT<T> place_root_t(const T& h) { return {Cx<T>(T(0)), CircleT<T>{T(0), T(0), origin_radius(h)}}; }

template <class T>
PlacedT<T> place_first_neighbour_t(const T& h_root, const VertexT<T>& w, double cos_root_w) {
  return place_in_frame(h_root, w, cos_root_w, T(0), Cx<T>(T(0)));
}

// LayoutMethod::frames (docs/precision.md): every placed interior vertex v keeps the disc automorphism
// M_v(z) = (α z + β) / (β̄ z + ᾱ), |α|² − |β|² = 1, that maps its own frame (v at the origin) onto the
// disc. A child is placed through its parent's frame and the triangle angles at the parent (from the
// radii alone), never through a direction measured between two placed positions.
template <class T>
struct Frame {
  Cx<T> alpha{T(1)}, beta{T(0)};
  Cx<T> operator()(const Cx<T>& z) const { return (alpha * z + beta) / (conj(beta) * z + conj(alpha)); }
  Frame then(const Frame& f) const {  // this ∘ f
    return {alpha * f.alpha + beta * conj(f.beta), alpha * f.beta + beta * conj(f.alpha)};
  }
};

// The step from u's frame to w's: move along direction `dir` by the hyperbolic distance l between the
// centres, then turn by `dir`, so that u lies at direction π in w's frame. With c = cos of the edge
// angle, cosh l = cosh h_u cosh h_w + c sinh h_u sinh h_w; the matrix has entries cosh(l/2) e^{i dir/2}
// and sinh(l/2) e^{i dir/2}.
template <class T>
Frame<T> step_frame(const T& hu, const T& hw, double cos_uw, const T& dir) {
  using std::cosh, std::sinh, std::sqrt;
  T ch, sh;
  if (cos_uw == 1.0) {
    ch = cosh((hu + hw) / 2);
    sh = sinh((hu + hw) / 2);
  } else {
    const T d = centre_distance(hu, hw, cos_uw);  // tanh(l/2)
    ch = 1 / sqrt((1 - d) * (1 + d));
    sh = d * ch;
  }
  const Cx<T> e = polar(T(1), T(dir / 2));
  return {e * ch, e * sh};
}

// The frame whose origin is the hyperbolic point c, turned so that direction 0 points at ideal point ζ.
template <class T>
Frame<T> frame_at(const Cx<T>& c, const Cx<T>& zeta) {
  using std::sqrt;
  const T k = 1 / sqrt(1 - norm(c));
  const Cx<T> e = polar(T(1), T(arg(to_origin(zeta, c)) / 2));
  return {e * k, conj(e) * (c * k)};
}

// A local quantity (LayoutArithmetic::mixed: a double) in the arithmetic of the frames (exact).
template <class T, class L> Cx<T> widen(const Cx<L>& z) { return {T(z.re), T(z.im)}; }
template <class T, class L> Frame<T> widen(const Frame<L>& f) { return {widen<T>(f.alpha), widen<T>(f.beta)}; }

// The double interface of Placement.hpp.
PlacedT<double> in(const PlacedCircle& p) { return {{p.centre.real(), p.centre.imag()}, {p.circle.x, p.circle.y, p.circle.r}}; }
PlacedCircle out(const PlacedT<double>& p) { return {{p.centre.re, p.centre.im}, Circle{p.circle.x, p.circle.y, p.circle.r}}; }
VertexT<double> in(LayoutVertex v) { return {v.h, v.interior}; }
}  // namespace

PlacedCircle place_root(double h_root) { return out(place_root_t(h_root)); }

PlacedCircle place_first_neighbour(double h_root, LayoutVertex w, double cos_root_w) {
  return out(place_first_neighbour_t(h_root, in(w), cos_root_w));
}

PlacedCircle place_in_face(LayoutVertex w, LayoutVertex a, const PlacedCircle& pa, LayoutVertex b,
                           const PlacedCircle& pb, const FaceCosines& c) {
  return out(place_in_face_t(in(w), in(a), in(pa), in(b), in(pb), c));
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

namespace {
// T: the arithmetic of the positions, the frames M_v and the coordinates. L: the arithmetic of the
// frames method's local quantities, functions of the radii only (the triangle angles of a flower and
// each step from a parent's frame to its child's): T, or double for LayoutArithmetic::mixed, where
// they are scale-free hyperbolic quantities that doubles carry to 2^-53 whatever the Euclidean size
// of the circles, while the composed frames and the coordinates need binary128 (docs/precision.md).
// H: the radii's container (Radii, or Radii128 for refined radii).
template <class T, class L = T, class H = Radii>
Layout lay_out_t(const PackingComplex& k, const H& h, Vertex root, bool frames, bool stop_when_collapsed) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = g.num_vertices();
  Layout out;
  std::vector<PlacedT<T>> at(n);
  out.wave.assign(n, none);
  out.parent.assign(n, none);
  out.root = root;
  const bool overlap = k.has_face_vertices();
  auto interior = [&](Vertex v) { return !g.is_boundary(v); };
  auto cos_of = [&](Vertex u, Vertex v) { return overlap ? k.cos_angle[g.find_dart(u, v)] : 1.0; };
  auto vertex = [&](Vertex v) { return VertexT<T>{T(h[v]), interior(v)}; };

  // Frames: M_v, and the neighbour (index into v's rotation) whose direction in v's frame is known.
  std::vector<Frame<T>> frame(frames ? n : 0);
  std::vector<std::uint32_t> ref_index(frames ? n : 0, 0);
  std::vector<L> ref_dir(frames ? n : 0, L(0));
  auto index_of = [&](Vertex v, Vertex w) { return g.find_dart(v, w) - g.first_dart(v); };
  // Direction of neighbour i in interior v's frame: the reference direction plus the triangle angles
  // at v counter-clockwise from the reference neighbour; the whole flower once per vertex, per dart.
  std::vector<detail::LiftT<L>> lifts(frames ? n : 0);  // each radius lifted once, not once per angle
  for (Vertex v = 0; v < lifts.size(); ++v) lifts[v] = detail::lift_t(L(h[v]));
  std::vector<L> dart_dir(frames ? g.num_darts() : 0);
  std::vector<std::uint8_t> flower_done(frames ? n : 0, 0);
  auto direction_in_frame = [&](Vertex v, std::uint32_t i) {
    const Dart first = g.first_dart(v);
    if (!flower_done[v]) {
      flower_done[v] = 1;
      const auto nb = g.neighbours(v);
      const std::uint32_t deg = g.degree(v);
      L dir = ref_dir[v];
      for (std::uint32_t j = ref_index[v], count = 0; count < deg; ++count, j = j + 1 == deg ? 0 : j + 1) {
        dart_dir[first + j] = dir;
        if (count + 1 == deg) break;  // the last wedge closes the flower: not needed
        const Vertex x = nb[j], y = nb[j + 1 == deg ? 0 : j + 1];
        dir += triangle_angle(lifts[v], lifts[x], lifts[y], cos_of(v, x), cos_of(v, y), cos_of(x, y), overlap);
      }
    }
    return dart_dir[first + i];
  };
  // Places w from its interior parent p through p's frame (frames only).
  auto place_from_frame = [&](Vertex w, Vertex p) {
    const L dir = direction_in_frame(p, index_of(p, w));
    const Frame<T>& m = frame[p];
    if (interior(w)) {
      frame[w] = m.then(widen<T>(step_frame(L(h[p]), L(h[w]), cos_of(p, w), dir)));
      ref_index[w] = index_of(w, p);
      ref_dir[w] = boost::math::constants::pi<L>();
      const Cx<T> z = frame[w](Cx<T>(T(0)));
      at[w] = {z, euclidean_circle(z, T(origin_radius(L(h[w]))))};
    } else {
      const L rho = horocycle_radius(origin_radius(L(h[p])), cos_of(p, w));
      const Cx<L> e = polar(L(1), dir);
      const Cx<T> zeta = m(widen<T>(e));
      at[w].centre = zeta / abs(zeta);
      at[w].circle = horocycle_through(at[w].centre, m(widen<T>(Cx<L>(e * L(1 - 2 * rho)))));
    }
  };

  bool stopped = false;  // stop_when_collapsed: a collapsed circle was placed
  std::vector<Vertex> placed_now;
  if (root != none) {
    at[root] = place_root_t(T(h[root]));
    const Vertex first = g.neighbours(root)[0];
    if (frames) {
      place_from_frame(first, root);  // the root's frame is the identity, neighbour 0 at direction 0
    } else {
      at[first] = place_first_neighbour_t(T(h[root]), vertex(first), cos_of(root, first));
    }
    out.parent[first] = root;
    placed_now = {root, first};
  } else {  // no interior vertex: three boundary circles of an inner face, symmetric
    using std::sqrt;
    const Dart d0 = g.face_darts(g.outer_face()).front();
    const Face f = g.face_of(g.twin(d0));
    const auto darts = g.face_darts(f);
    const T rho = sqrt(T(3)) / (2 + sqrt(T(3)));
    for (int i = 0; i < 3; ++i) {
      const Vertex v = g.tail(darts[i]);
      const Cx<T> zeta = polar(T(1), T(2 * boost::math::constants::pi<T>() * i / 3));
      at[v] = {zeta, {(1 - rho) * zeta.re, (1 - rho) * zeta.im, rho}};
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
      const Vertex parent = parent_is_first_anchor(interior(a), interior(b)) ? a : b;
      out.parent[w] = parent;
      if (frames && interior(parent)) {
        place_from_frame(w, parent);
        continue;
      }
      const FaceCosines c{cos_of(w, a), cos_of(w, b), cos_of(a, b), overlap};
      at[w] = place_in_face_t(vertex(w), vertex(a), at[a], vertex(b), at[b], c);
      if (frames && interior(w)) {  // from two horocycles: the frame at w's centre, a's ideal point at 0
        frame[w] = frame_at(at[w].centre, at[a].centre);
        ref_index[w] = index_of(w, a);
        ref_dir[w] = L(0);
      }
    }
    for (const auto& [w, ab] : placements) {
      out.wave[w] = round;
      placed_now.push_back(w);
      if (stop_when_collapsed && !stopped) {
        if constexpr (std::is_same_v<T, Quad>) {  // collapsed in the binary128 circles it keeps
          const Circle128 c{at[w].circle.x.backend().value(), at[w].circle.y.backend().value(),
                            at[w].circle.r.backend().value()};
          stopped = circle_resolution(c) < Layout::collapsed_resolution;
        } else {
          const Circle c{static_cast<double>(at[w].circle.x), static_cast<double>(at[w].circle.y),
                         static_cast<double>(at[w].circle.r)};
          stopped = circle_resolution(c) < Layout::collapsed_resolution;
        }
      }
    }
    if (stopped) break;
  }
  out.complete = !stopped;
  for (Vertex v = 0; v < n && !stopped; ++v)
    if (out.wave[v] == none)
      throw std::logic_error("lay_out: vertex " + std::to_string(g.id(v)) + " was never placed; the complex is not a triangulated disc.");

  // Round to the stored doubles (exact when T is double).
  out.circles.resize(n);
  out.centre.resize(n);
  for (Vertex v = 0; v < n; ++v) {
    if (out.wave[v] == none) {  // (stopped) never placed
      constexpr double nan = std::numeric_limits<double>::quiet_NaN();
      out.centre[v] = {nan, nan};
      out.circles[v] = {nan, nan, nan};
      continue;
    }
    out.centre[v] = {static_cast<double>(at[v].centre.re), static_cast<double>(at[v].centre.im)};
    out.circles[v] = {static_cast<double>(at[v].circle.x), static_cast<double>(at[v].circle.y), static_cast<double>(at[v].circle.r)};
  }
  if constexpr (std::is_same_v<T, Quad>) {  // keep the binary128 circles themselves
    out.circles128.resize(n);
    for (Vertex v = 0; v < n; ++v)
      out.circles128[v] = {at[v].circle.x.backend().value(), at[v].circle.y.backend().value(),
                           at[v].circle.r.backend().value()};
  }
  return out;
}
}  // namespace

double circle_resolution(const Circle& c) {
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.r) || !(c.r > 0)) return 0;
  const double m = std::max({std::abs(c.x), std::abs(c.y), c.r});
  const double ulp = std::nextafter(m, std::numeric_limits<double>::infinity()) - m;
  return c.r / ulp;
}

namespace {
// The method, arithmetic, smallest radius, resolution and precision status of a computed layout.
void finish_layout(Layout& out, LayoutMethod method, LayoutArithmetic arithmetic) {
  out.method = method;
  out.arithmetic = arithmetic;
  out.smallest_radius = std::numeric_limits<double>::infinity();
  out.resolution = std::numeric_limits<double>::infinity();
  const bool quad = !out.circles128.empty();  // a binary128 layout: its resolution in binary128 ulps
  for (std::size_t v = 0; v < out.circles.size(); ++v) {
    if (!out.complete && out.wave[v] == none) continue;  // not placed
    const Circle& c = out.circles[v];
    out.smallest_radius = std::min(out.smallest_radius, c.r);
    out.resolution = std::min(out.resolution, quad ? circle_resolution(out.circles128[v]) : circle_resolution(c));
  }
  out.precision = out.resolution == 0                            ? Precision::unrepresentable
                  : out.resolution < Layout::collapsed_resolution ? Precision::collapsed
                  : out.resolution < Layout::degraded_resolution  ? Precision::degraded
                                                                  : Precision::ok;
}
}  // namespace

Layout lay_out(const PackingComplex& k, const Radii& h, Vertex root, LayoutMethod method, LayoutArithmetic arithmetic,
               bool stop_when_collapsed) {
  const bool frames = method == LayoutMethod::frames;
  LAGUERRE_PRECONDITION(arithmetic != LayoutArithmetic::mixed || frames,
                        "The mixed layout arithmetic needs the frames layout (the wave measures directions between "
                        "placed positions, which need the positions' arithmetic).");
  Layout out = arithmetic == LayoutArithmetic::binary128 ? lay_out_t<Quad>(k, h, root, frames, stop_when_collapsed)
               : arithmetic == LayoutArithmetic::mixed   ? lay_out_t<Quad, double>(k, h, root, frames, stop_when_collapsed)
                                                         : lay_out_t<double>(k, h, root, frames, stop_when_collapsed);
  finish_layout(out, method, arithmetic);
  return out;
}

Layout lay_out(const PackingComplex& k, const Radii128& h, Vertex root, LayoutMethod method, bool stop_when_collapsed) {
  Layout out = lay_out_t<Quad, Quad, Radii128>(k, h, root, method == LayoutMethod::frames, stop_when_collapsed);
  finish_layout(out, method, LayoutArithmetic::binary128);
  return out;
}

std::vector<double> angle_residuals128(const PackingComplex& k, const Radii128& h) {
  const PlanarGraph& g = k.graph;
  const std::size_t n = g.num_vertices();
  const bool overlap = k.has_face_vertices();
  auto cos_of = [&](Vertex u, Vertex v) { return overlap ? k.cos_angle[g.find_dart(u, v)] : 1.0; };
  std::vector<detail::LiftT<Quad>> lifts(n);
  for (Vertex v = 0; v < n; ++v) lifts[v] = detail::lift_t(Quad(h[v]));
  const Quad two_pi = 2 * boost::math::constants::pi<Quad>();
  std::vector<double> out(n, 0.0);
  for (Vertex v = 0; v < n; ++v) {
    if (g.is_boundary(v)) continue;
    const auto nb = g.neighbours(v);
    const std::size_t deg = nb.size();
    Quad sum = 0;
    for (std::size_t j = 0; j < deg; ++j) {
      const Vertex x = nb[j], y = nb[j + 1 == deg ? 0 : j + 1];
      sum += triangle_angle(lifts[v], lifts[x], lifts[y], cos_of(v, x), cos_of(v, y), cos_of(x, y), overlap);
    }
    out[v] = static_cast<double>(sum - two_pi);
  }
  return out;
}

template <Binary128Circle C>
double circle_resolution(const C& c) {
  auto finite = [](__float128 q) { return q - q == 0; };
  if (!finite(c.x) || !finite(c.y) || !finite(c.r) || !(c.r > 0)) return 0;
  const __float128 m = std::max({fabsq(c.x), fabsq(c.y), c.r});
  int e = 0;
  frexpq(m, &e);  // m in [2^(e−1), 2^e): its last unit is 2^(e − 113)
  return static_cast<double>(ldexpq(c.r, 113 - e));
}

template double circle_resolution<Circle128>(const Circle128&);

int significand_bits_needed(const Layout& layout) {
  const int p = layout.circles128.empty() ? 53 : 113;
  if (!(layout.resolution > 0)) return 0;
  return std::max(p, static_cast<int>(std::ceil(p + std::log2(Layout::degraded_resolution / layout.resolution))));
}

int bytes_per_coordinate(const Layout& layout) { return layout.circles128.empty() ? 8 : 16; }

double tangency_error(const CircleEmbedding128& c, Vertex u, Vertex v) {
  const __float128 dx = c[u].x - c[v].x, dy = c[u].y - c[v].y;
  const __float128 d = sqrtq(dx * dx + dy * dy);
  const __float128 e = fabsq(d - (c[u].r + c[v].r)) / std::min(c[u].r, c[v].r);
  return static_cast<double>(e);
}

double tangency_error(const CircleEmbedding& c, Vertex u, Vertex v) {
  const double d = std::hypot(c[u].x - c[v].x, c[u].y - c[v].y);
  return std::abs(d - (c[u].r + c[v].r)) / std::min(c[u].r, c[v].r);
}

}  // namespace laguerre::core
