#include "laguerre/core/routing/Routing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/routing/HyperbolicEmbedding.hpp"
#include "laguerre/core/routing/NextHop.hpp"
#include "laguerre/core/routing/Router.hpp"

#include "NextHopRules.hpp"  // the rules themselves, so that the router loops inline them

namespace laguerre::core {

namespace {

bool finite(double x) { return std::isfinite(x); }
bool finite(Float128 x) { return detail::finite128(x); }

// `phi` (doubles, or binary128 with `what` = "binary128 " in messages) has a circle per vertex, every
// one finite.
template <class Embedding>
void check_embedding(const PlanarGraph& g, const Embedding& phi, const std::string& what) {
  LAGUERRE_PRECONDITION(phi.size() == g.num_vertices(),
                        "The " + what + "circle embedding has " + std::to_string(phi.size()) +
                            " circles for a graph of " + std::to_string(g.num_vertices()) + " vertices.");
  // Routing decisions are exact on the stored coordinates: a NaN or infinite circle (an unrepresentable
  // layout) has no answer, so it is refused here with the vertex named rather than deep in a predicate.
  for (Vertex v = 0; v < phi.size(); ++v)
    LAGUERRE_PRECONDITION(finite(phi[v].x) && finite(phi[v].y) && finite(phi[v].r),
                          "The " + what + "circle of vertex " + std::to_string(g.id(v)) +
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
    case Scheme::hyperbolic: return "hyperbolic";
  }
  return "unknown";
}

std::optional<Scheme> parse_scheme(std::string_view name) {
  for (const Scheme s : all_schemes)
    if (to_string(s) == name) return s;
  if (to_string(Scheme::hyperbolic) == name) return Scheme::hyperbolic;
  return std::nullopt;
}

std::string_view to_string(RouteOutcome o) {
  switch (o) {
    case RouteOutcome::delivered: return "delivered";
    case RouteOutcome::dead_end: return "dead_end";
    case RouteOutcome::loop: return "loop";
    case RouteOutcome::ttl_exceeded: return "ttl_exceeded";
    case RouteOutcome::uncertified: return "uncertified";
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

Router::Router(const PlanarGraph& g, const CircleEmbedding& phi) : g_(&g), phi_(&phi) { check_embedding(g, phi, ""); }

Router::Router(const PlanarGraph& g, const CircleEmbedding& phi, const CircleEmbedding128& phi128)
    : g_(&g), phi_(&phi), phi128_(&phi128) {
  check_embedding(g, phi, "");
  check_embedding(g, phi128, "binary128 ");
}

void Router::check_scheme(Scheme s) const {
  LAGUERRE_PRECONDITION(phi128_ == nullptr || s == Scheme::greedy_power || s == Scheme::greedy_euclid,
                        "Only the greedy schemes decide on binary128 circles; " + std::string(to_string(s)) +
                            " reads doubles: route it with a router without binary128 circles.");
}

void Router::check_vertex(Vertex v, const char* role) const {
  LAGUERRE_PRECONDITION(v < g_->num_vertices(), std::string("The ") + role + " vertex index " + std::to_string(v) +
                                                    " is out of range for a graph of " +
                                                    std::to_string(g_->num_vertices()) + " vertices.");
}

Vertex Router::hop(Scheme s, Vertex at, Vertex target) const {
  if (phi128_ != nullptr) {  // check_scheme: a greedy scheme
    const GraphView128 view(*g_, *phi128_, at);
    const Point128 t = centre((*phi128_)[target]);
    const std::size_t i = s == Scheme::greedy_power ? greedy_power_hop(view, t) : greedy_euclid_hop(view, t);
    return i == view.degree() ? none : g_->neighbours(at)[i];
  }
  const GraphView view = view_of(at);
  const Point2 t = centre((*phi_)[target]);
  std::size_t i = view.degree();
  switch (s) {
    case Scheme::greedy_power: i = greedy_power_hop(view, t); break;
    case Scheme::greedy_euclid: i = greedy_euclid_hop(view, t); break;
    case Scheme::compass: i = compass_hop(view, t); break;
    case Scheme::gfg: break;
    case Scheme::hyperbolic: i = hyperbolic_hop(hyperbolic(), g_->neighbours(at), at, target).next; break;
  }
  return i == view.degree() ? none : g_->neighbours(at)[i];
}

Vertex Router::next_hop(Scheme s, Vertex at, Vertex target) const {
  check_vertex(at, "current");
  check_vertex(target, "target");
  LAGUERRE_PRECONDITION(s != Scheme::gfg,
                        "Greedy-face-greedy routing has no memoryless next hop: its decisions depend on the "
                        "perimeter state carried by the packet.");
  check_scheme(s);
  return at == target ? none : hop(s, at, target);
}

Route Router::route(Scheme s, Vertex source, Vertex target, std::size_t ttl) {
  Route r;
  route(s, source, target, ttl, r);
  return r;
}

void Router::route(Scheme s, Vertex source, Vertex target, std::size_t ttl, Route& out) {
  check_vertex(source, "source");
  check_vertex(target, "target");
  check_scheme(s);
  out.path.clear();
  out.path.push_back(source);
  out.stuck = none;
  out.outcome = RouteOutcome::delivered;
  if (source == target) return;
  const std::size_t limit = ttl == 0 ? default_ttl(*g_, s) : ttl;
  if (s == Scheme::gfg) route_gfg(target, limit, out);
  else if (s == Scheme::hyperbolic) route_hyperbolic(target, limit, out);
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
    const Vertex u = hop(s, v, target);
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

const HyperbolicTreeEmbedding& Router::hyperbolic() const {
  if (!hyperbolic_) hyperbolic_ = std::make_unique<HyperbolicTreeEmbedding>(*g_);
  return *hyperbolic_;
}

// Greedy by hyperbolic distance: every hop is certified to decrease it strictly (hyperbolic_hop), so
// the packet cannot revisit a node; a hop the numbers cannot certify ends the route as `uncertified`.
void Router::route_hyperbolic(Vertex target, std::size_t ttl, Route& out) const {
  const HyperbolicTreeEmbedding& e = hyperbolic();
  Vertex v = out.path.back();
  auto stop = [&](RouteOutcome o, Vertex at) {
    out.outcome = o;
    out.stuck = at;
  };
  for (;;) {
    if (v == target) return stop(RouteOutcome::delivered, none);
    const auto nb = g_->neighbours(v);
    const HyperbolicHop h = hyperbolic_hop(e, nb, v, target);
    if (h.next == nb.size()) return stop(h.certified ? RouteOutcome::dead_end : RouteOutcome::uncertified, v);
    if (out.hops() >= ttl) return stop(RouteOutcome::ttl_exceeded, v);
    v = nb[h.next];
    out.path.push_back(v);
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
      const Vertex u = hop(Scheme::greedy_euclid, v, target);
      if (u == none) break;
      if (out.hops() >= ttl) return stop(RouteOutcome::ttl_exceeded, v);
      out.path.push_back(u);
      v = u;
    }

    // Perimeter mode at the local minimum `entry`.
    const Vertex entry = v;
    const Point2 p = pt(entry);
    const std::size_t first = first_face_hop(view_of(entry), t);
    if (first == g.degree(entry)) return stop(RouteOutcome::dead_end, entry);  // no face corner: not a plane drawing
    Dart d = g.first_dart(entry) + static_cast<Dart>(first);

    Dart walk_start = d;  // the walk since the last face change started with this dart
    FaceChange last{};    // the last face change: the entry point, λ = 0
    for (;;) {
      const Vertex a = g.tail(d);
      const FaceHop next = face_hop(view_of(a), p, t, last, d - g.first_dart(a));
      d = g.first_dart(a) + static_cast<Dart>(next.next);
      if (next.changed) walk_start = d;
      if (out.hops() >= ttl) return stop(RouteOutcome::ttl_exceeded, a);
      const Vertex b = g.head(d);
      out.path.push_back(b);
      v = b;
      if (v == target) return stop(RouteOutcome::delivered, none);
      if (leaves_perimeter(pt(v), p, t)) break;  // back to greedy mode
      d = g.next_ccw(g.twin(d));
      if (d == walk_start) return stop(RouteOutcome::loop, v);
    }
  }
}

}  // namespace laguerre::core
