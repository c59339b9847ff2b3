#include "laguerre/core/routing/Routing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "../detail/FastFilter.hpp"
#include "../detail/Filtered.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/routing/Router.hpp"

namespace laguerre::core {

namespace {


// ---------------------------------------------------------------------------------------------------
// Fast exact decisions: the double filters of detail/FastFilter.hpp, then the exact predicates.
// ---------------------------------------------------------------------------------------------------

using detail::Approx;
using detail::approx_alignment;
using detail::approx_distance;
using detail::approx_power;
using detail::certified_sign;
using detail::in_range;

/// Sign of (a − p)·(b − p). Exact, filtered like orientation().
Sign dot_sign(Point2 p, Point2 a, Point2 b) {
  const double ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y;
  if (in_range(ax) && in_range(ay) && in_range(bx) && in_range(by)) {
    if (const auto s = detail::certified_difference(ax * bx, -(ay * by))) return *s;
  }
  detail::require_finite("dot_sign", {p.x, p.y, a.x, a.y, b.x, b.y});
  return detail::filtered([&]<class NT>() {
    const NT ex = (NT(a.x) - NT(p.x)) * (NT(b.x) - NT(p.x)) + (NT(a.y) - NT(p.y)) * (NT(b.y) - NT(p.y));
    return detail::sign_of<NT>(ex);
  });
}

// ---------------------------------------------------------------------------------------------------
// Positions along the perimeter segment.
//
// In perimeter mode the packet remembers the segment [P, T] from the entry node to the target and the
// position λ ∈ [0, 1] (P + λ(T − P)) of the last face change. Crossing positions are kept *symbolically*
// (which edge made them) and compared exactly, never rounded: two crossings a few ulps apart, or a
// crossing exactly at the entry, are ordered correctly.
// ---------------------------------------------------------------------------------------------------

/// A position on the line PT: the entry (λ = 0), the target (λ = 1), or the crossing of the line with
/// the line of the edge [a, b], which must not be parallel to PT.
struct Along {
  enum class Kind { entry, target, edge };
  Kind kind = Kind::entry;
  Point2 a{}, b{};
};

/// λ of a position as an exact fraction num / den (den ≠ 0, any sign). For an edge, orient(a, b, ·) is
/// affine along the line, o(λ) = o_P + λ(o_T − o_P), and vanishes at λ = o_P / (o_P − o_T).
template <class NT>
std::pair<NT, NT> along_fraction(Point2 p, Point2 t, const Along& x) {
  switch (x.kind) {
    case Along::Kind::entry:
      return {NT(0), NT(1)};
    case Along::Kind::target:
      return {NT(1), NT(1)};
    case Along::Kind::edge:
      break;
  }
  auto orient = [](Point2 a, Point2 b, Point2 c) -> NT {
    return (NT(b.x) - NT(a.x)) * (NT(c.y) - NT(a.y)) - (NT(b.y) - NT(a.y)) * (NT(c.x) - NT(a.x));
  };
  const NT op = orient(x.a, x.b, p), ot = orient(x.a, x.b, t);
  return {op, op - ot};
}

/// Sign of λ(x) − λ(y). Exact (interval filter, then rationals).
Sign compare_along(Point2 p, Point2 t, const Along& x, const Along& y) {
  return detail::filtered([&]<class NT>() {
    const auto [nx, dx] = along_fraction<NT>(p, t, x);
    const auto [ny, dy] = along_fraction<NT>(p, t, y);
    const int s = static_cast<int>(detail::sign_of<NT>(nx * dy - ny * dx)) *
                  static_cast<int>(detail::sign_of<NT>(dx)) * static_cast<int>(detail::sign_of<NT>(dy));
    return static_cast<Sign>(s);
  });
}

/// Whether the direction T − P lies strictly inside the counter-clockwise angular sector at P from
/// the ray P→A to the ray P→B (A, B the heads of two darts consecutive counter-clockwise around the
/// vertex at P). With `same_ray` (a vertex of degree one: A and B are the same neighbour) the sector is
/// the full turn minus the ray P→A.
bool in_open_sector(Point2 p, Point2 a, Point2 b, Point2 t, bool same_ray) {
  const Sign a_t = orientation(p, a, t);  // positive: t strictly left of P→A
  if (same_ray) return a_t != Sign::zero || dot_sign(p, a, t) == Sign::negative;
  const Sign t_b = orientation(p, t, b);
  switch (orientation(p, a, b)) {
    case Sign::positive:  // convex sector (< π): strictly left of P→A and strictly right of P→B
      return a_t == Sign::positive && t_b == Sign::positive;
    case Sign::negative:  // reflex sector (> π): the complement of the closed convex sector B→A
      return a_t == Sign::positive || t_b == Sign::positive;
    case Sign::zero:
      break;
  }
  // P→A and P→B collinear: a straight angle if they point opposite ways (the open half-plane left of
  // P→A); pointing the same way (overlapping edges) or a zero-length edge has no sector in a plane
  // drawing.
  return dot_sign(p, a, b) == Sign::negative && a_t == Sign::positive;
}

// ---------------------------------------------------------------------------------------------------
// Memoryless next-hop rules.
// ---------------------------------------------------------------------------------------------------

enum class Metric { power, euclid };

template <Metric M>
Approx approx_metric(Point2 t, const Circle& c) {
  if constexpr (M == Metric::power) return approx_power(t, c);
  else return approx_distance(t, centre(c));
}

template <Metric M>
Sign exact_metric(Point2 t, const Circle& a, const Circle& b) {
  // Equal radii cancel exactly in pow(t, a) − pow(t, b): the distance comparison is the same exact sign,
  // and its interval filter settles exact ties of well-placed centres (grids, symmetric layouts) without
  // falling back to rational arithmetic, which ties with a radius like 0.3 would otherwise force.
  if constexpr (M == Metric::power) return a.r == b.r ? compare_distance(t, centre(a), centre(b)) : compare_power(t, a, b);
  else return compare_distance(t, centre(a), centre(b));
}

/// The greedy rule: argmin over neighbours (smallest index among ties), if strictly better than `at`.
/// (A two-pass variant, approximate argmin then certification, measured slower than this loop.)
template <Metric M>
Vertex greedy_next(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target) {
  if (at == target) return none;
  const Point2 t = centre(phi[target]);
  auto compare = [&](Vertex u, const Approx& au, Vertex w, const Approx& aw) {
    if (const auto s = certified_sign(au, aw)) return *s;
    return exact_metric<M>(t, phi[u], phi[w]);
  };
  Vertex best = none;
  Approx best_approx;
  for (const Vertex u : g.neighbours(at)) {
    const Approx au = approx_metric<M>(t, phi[u]);
    if (best != none) {
      const Sign s = compare(u, au, best, best_approx);
      if (s == Sign::positive || (s == Sign::zero && u > best)) continue;
    }
    best = u;
    best_approx = au;
  }
  if (best == none) return none;
  return compare(best, best_approx, at, approx_metric<M>(t, phi[at])) == Sign::negative ? best : none;
}

Vertex compass_next(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target) {
  if (at == target) return none;
  const Point2 v = centre(phi[at]), t = centre(phi[target]);
  Vertex best = none;
  Approx best_approx;
  for (const Vertex u : g.neighbours(at)) {
    const Point2 pu = centre(phi[u]);
    const Approx au = approx_alignment(v, t, pu);
    if (best != none) {
      // Larger alignment = smaller deviation; compare_deviation is negative when its first point
      // deviates less.
      Sign s;
      if (const auto c = certified_sign(best_approx, au)) s = *c;
      else s = compare_deviation(v, t, pu, centre(phi[best]));
      if (s == Sign::positive || (s == Sign::zero && u > best)) continue;
    }
    best = u;
    best_approx = au;
  }
  return best;
}

void check_embedding(const PlanarGraph& g, const CircleEmbedding& phi) {
  if (phi.size() != g.num_vertices())
    throw std::invalid_argument("The circle embedding has " + std::to_string(phi.size()) + " circles for a graph of " +
                                std::to_string(g.num_vertices()) + " vertices.");
  // Routing decisions are exact on the stored doubles: a NaN or infinite circle (an unrepresentable
  // layout) has no answer, so it is refused here with the vertex named rather than deep in a predicate.
  for (Vertex v = 0; v < phi.size(); ++v)
    if (!std::isfinite(phi[v].x) || !std::isfinite(phi[v].y) || !std::isfinite(phi[v].r))
      throw std::invalid_argument("The circle of vertex " + std::to_string(g.id(v)) +
                                  " is not finite (NaN or infinite): the embedding cannot be routed on.");
}

std::size_t saturating_mul(std::size_t a, std::size_t b) {
  if (a != 0 && b > std::numeric_limits<std::size_t>::max() / a) return std::numeric_limits<std::size_t>::max();
  return a * b;
}
std::size_t saturating_add(std::size_t a, std::size_t b) {
  return b > std::numeric_limits<std::size_t>::max() - a ? std::numeric_limits<std::size_t>::max() : a + b;
}

}  // namespace

// -----------------------------------------------------------------------------------------------------
// Names.
// -----------------------------------------------------------------------------------------------------

std::string_view to_string(Scheme s) {
  switch (s) {
    case Scheme::greedy_power: return "greedy_power";
    case Scheme::greedy_euclid: return "greedy_euclid";
    case Scheme::compass: return "compass";
    case Scheme::gfg: return "gfg";
  }
  return "unknown";
}

std::optional<Scheme> parse_scheme(std::string_view name) {
  for (const Scheme s : all_schemes)
    if (to_string(s) == name) return s;
  return std::nullopt;
}

std::string_view to_string(RouteOutcome o) {
  switch (o) {
    case RouteOutcome::delivered: return "delivered";
    case RouteOutcome::dead_end: return "dead_end";
    case RouteOutcome::loop: return "loop";
    case RouteOutcome::ttl_exceeded: return "ttl_exceeded";
  }
  return "unknown";
}

std::size_t default_ttl(const PlanarGraph& g, Scheme s) {
  const std::size_t n = g.num_vertices(), m = g.num_edges();
  if (s != Scheme::gfg) return saturating_add(saturating_mul(4, n), 16);
  // GFG: at most n perimeter phases (their entry nodes get strictly closer to t), each preceded by at
  // most n greedy hops; in a phase at most m face changes (λ strictly grows and each edge has one
  // crossing), and between two of them at most one walk around a face (≤ 2m darts).
  const std::size_t per_phase = saturating_add(saturating_mul(saturating_mul(2, m), m + 1), n);
  return saturating_add(saturating_mul(n, per_phase), 16);
}

Vertex greedy_power_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target) {
  return Router(g, phi).next_hop(Scheme::greedy_power, at, target);
}

Vertex greedy_euclid_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target) {
  return Router(g, phi).next_hop(Scheme::greedy_euclid, at, target);
}

Vertex compass_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target) {
  return Router(g, phi).next_hop(Scheme::compass, at, target);
}

Route route(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s, Vertex source, Vertex target,
            std::size_t ttl) {
  return Router(g, phi).route(s, source, target, ttl);
}

// -----------------------------------------------------------------------------------------------------
// Router.
// -----------------------------------------------------------------------------------------------------

Router::Router(const PlanarGraph& g, const CircleEmbedding& phi) : g_(&g), phi_(&phi) { check_embedding(g, phi); }

void Router::check_vertex(Vertex v, const char* role) const {
  if (v >= g_->num_vertices())
    throw std::invalid_argument(std::string("The ") + role + " vertex index " + std::to_string(v) +
                                " is out of range for a graph of " + std::to_string(g_->num_vertices()) +
                                " vertices.");
}

Vertex Router::next_hop(Scheme s, Vertex at, Vertex target) const {
  check_vertex(at, "current");
  check_vertex(target, "target");
  switch (s) {
    case Scheme::greedy_power: return greedy_next<Metric::power>(*g_, *phi_, at, target);
    case Scheme::greedy_euclid: return greedy_next<Metric::euclid>(*g_, *phi_, at, target);
    case Scheme::compass: return compass_next(*g_, *phi_, at, target);
    case Scheme::gfg: break;
  }
  throw std::invalid_argument("Greedy-face-greedy routing has no memoryless next hop: its decisions depend on the "
                              "perimeter state carried by the packet.");
}

Route Router::route(Scheme s, Vertex source, Vertex target, std::size_t ttl) {
  Route r;
  route(s, source, target, ttl, r);
  return r;
}

void Router::route(Scheme s, Vertex source, Vertex target, std::size_t ttl, Route& out) {
  check_vertex(source, "source");
  check_vertex(target, "target");
  out.path.clear();
  out.path.push_back(source);
  out.stuck = none;
  out.outcome = RouteOutcome::delivered;
  if (source == target) return;
  const std::size_t limit = ttl == 0 ? default_ttl(*g_, s) : ttl;
  if (s == Scheme::gfg) route_gfg(target, limit, out);
  else route_memoryless(s, target, limit, out);
}

void Router::route_memoryless(Scheme s, Vertex target, std::size_t ttl, Route& out) {
  // Greedy routing strictly decreases its metric, so it cannot revisit a node. Compass routing is
  // memoryless and deterministic: its state is the node holding the packet, so the first revisit
  // proves an infinite loop.
  const bool detect_loops = s == Scheme::compass;
  Vertex v = out.path.back();
  if (detect_loops) {
    if (visit_mark_.size() != g_->num_vertices()) visit_mark_.assign(g_->num_vertices(), 0);
    if (++epoch_ == 0) {  // wrapped: forget all marks
      std::fill(visit_mark_.begin(), visit_mark_.end(), 0);
      epoch_ = 1;
    }
    visit_mark_[v] = epoch_;
  }
  auto stop = [&](RouteOutcome o, Vertex at) {
    out.outcome = o;
    out.stuck = at;
  };
  for (;;) {
    if (v == target) return stop(RouteOutcome::delivered, none);
    Vertex u = none;
    switch (s) {
      case Scheme::greedy_power: u = greedy_next<Metric::power>(*g_, *phi_, v, target); break;
      case Scheme::greedy_euclid: u = greedy_next<Metric::euclid>(*g_, *phi_, v, target); break;
      case Scheme::compass: u = compass_next(*g_, *phi_, v, target); break;
      case Scheme::gfg: break;
    }
    if (u == none) return stop(RouteOutcome::dead_end, v);
    if (out.hops() >= ttl) return stop(RouteOutcome::ttl_exceeded, v);
    out.path.push_back(u);
    v = u;
    if (detect_loops) {
      if (visit_mark_[v] == epoch_) return stop(RouteOutcome::loop, v);
      visit_mark_[v] = epoch_;
    }
  }
}

// Greedy-face-greedy (Bose, Morin, Stojmenović, Urrutia; the greedy + perimeter modes of GPSR) on the
// straight-line drawing given by the centres and the rotation system of g.
//
// Greedy mode: greedy Euclidean routing until a local minimum e (no neighbour strictly closer to t).
//
// Perimeter mode, entered at e with P = p(e), T = p(t), the segment [P, T] fixed for the whole phase:
//  1. First face: the face whose corner at e contains the direction T − P, i.e. the sector between
//     two counter-clockwise-consecutive darts e→v, e→w that contains the open ray from P towards T.
//     The ray cannot run along an edge e→y: y would be strictly closer to t than the local minimum e.
//  2. The packet walks that face by the right-hand rule (arriving at x from y it leaves along the
//     next dart counter-clockwise after x→y: next_ccw(twin(d))), so the face lies to the right of
//     every traversed dart.
//  3. Face change: before traversing a dart u→w it tests whether the edge properly crosses the line
//     PT (u and w strictly on opposite sides) at a point q of the segment strictly beyond the last
//     face change (λ_last < λ_q ≤ 1, compared exactly, λ_last = 0 at the entry). If so λ_last := λ_q
//     and the packet continues in the face that contains the segment just beyond q: the face on the
//     side of the edge where T lies. If T is left of u→w that is the other face of the edge, whose
//     right-hand walk from u leaves along next_ccw(u→w) (the packet stays at u); if T is right of
//     u→w it is the face being walked, and the packet simply traverses u→w.
//  4. Back to greedy mode at the first node strictly closer to t than e; delivered at t.
//
// Degenerate crossings need no special rule. A vertex x lying on the segment beyond P has
// |x − T| = (1 − λ)|P − T| < |P − T|, so reaching it ends the phase by rule 4; an edge through a vertex
// of the segment, or collinear with it, therefore never needs a face change and is not a proper
// crossing. Invariant: the walked face contains the points of the segment just beyond λ_last. While
// it does, the segment leaves that face (or reaches T, a vertex of it) at a boundary point with
// λ > λ_last; that point is either a vertex (rule 4 fires when the walk reaches it) or interior to an
// edge that is not collinear with the segment, hence a proper crossing (rule 3 fires at the latest
// there). So a complete walk around a face without a face change, delivery or return to greedy is
// impossible in a plane drawing that matches the rotation system; we report it as `loop` at the node
// that closed the walk. Termination: λ_last strictly increases within a phase over finitely many
// edge crossings, and successive entry nodes are strictly closer to t.
void Router::route_gfg(Vertex target, std::size_t ttl, Route& out) const {
  const PlanarGraph& g = *g_;
  auto pt = [&](Vertex x) { return centre((*phi_)[x]); };
  const Point2 t = pt(target);
  Vertex v = out.path.back();
  auto stop = [&](RouteOutcome o, Vertex at) {
    out.outcome = o;
    out.stuck = at;
  };
  for (;;) {
    // Greedy mode.
    for (;;) {
      if (v == target) return stop(RouteOutcome::delivered, none);
      const Vertex u = greedy_next<Metric::euclid>(g, *phi_, v, target);
      if (u == none) break;
      if (out.hops() >= ttl) return stop(RouteOutcome::ttl_exceeded, v);
      out.path.push_back(u);
      v = u;
    }

    // Perimeter mode at the local minimum `entry`.
    const Vertex entry = v;
    const Point2 p = pt(entry);
    Dart d = none;
    const std::uint32_t deg = g.degree(entry);
    for (std::uint32_t i = 0; i < deg && d == none; ++i) {
      const Dart a = g.first_dart(entry) + i, b = g.next_ccw(a);
      if (in_open_sector(p, pt(g.head(a)), pt(g.head(b)), t, a == b)) d = b;
    }
    if (d == none) return stop(RouteOutcome::dead_end, entry);  // no face corner: not a plane drawing

    Dart walk_start = d;  // the walk since the last face change started with this dart
    Along last{};         // position of the last face change: the entry point, λ = 0
    const Along at_target{Along::Kind::target, {}, {}};
    for (;;) {
      const Vertex a = g.tail(d), b = g.head(d);
      const Point2 pa = pt(a), pb = pt(b);
      const Sign sa = orientation(p, t, pa), sb = orientation(p, t, pb);
      if (static_cast<int>(sa) * static_cast<int>(sb) < 0) {
        const Along q{Along::Kind::edge, pa, pb};
        if (compare_along(p, t, q, last) == Sign::positive && compare_along(p, t, q, at_target) != Sign::positive) {
          last = q;
          if (orientation(pa, pb, t) == Sign::positive) {
            // T is left of a→b: continue in the face on the other side of the edge, from a.
            d = g.next_ccw(d);
            walk_start = d;
            continue;
          }
          walk_start = d;  // T is right of a→b: the walked face contains the segment beyond q
        }
      }
      if (out.hops() >= ttl) return stop(RouteOutcome::ttl_exceeded, a);
      out.path.push_back(b);
      v = b;
      if (v == target) return stop(RouteOutcome::delivered, none);
      if (compare_distance(t, pt(v), p) == Sign::negative) break;  // back to greedy mode
      d = g.next_ccw(g.twin(d));
      if (d == walk_start) return stop(RouteOutcome::loop, v);
    }
  }
}

}  // namespace laguerre::core
