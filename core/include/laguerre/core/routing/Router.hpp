#pragma once
/// @file
/// A reusable router: routes many packets over one embedded graph without per-route allocations.

#include <cstdint>
#include <memory>
#include <vector>

#include "laguerre/core/routing/HyperbolicEmbedding.hpp"
#include "laguerre/core/routing/NextHop.hpp"
#include "laguerre/core/routing/Routing.hpp"

namespace laguerre::core {

/// Routes packets over one graph and embedding, keeping scratch state between routes (the visited
/// marks of compass routing, the path buffer). Results are identical to the free function route().
/// The router keeps references: `g` and `phi` must outlive it and stay unchanged. Not thread-safe;
/// use one router per thread.
class Router {
public:
  /// Binds the router to `g` and `phi`. Preconditions (InternalError otherwise): phi.size() ==
  /// g.num_vertices() and every circle finite.
  Router(const PlanarGraph& g, const CircleEmbedding& phi);
  /// Same, and the greedy schemes (greedy_power, greedy_euclid) decide on `phi128`, the binary128
  /// circles of the same embedding (Layout::circles128), exactly on them; the other schemes are then
  /// refused (InternalError), since their rules read doubles. `phi128` must outlive the router;
  /// preconditions as above for `phi128` too.
  Router(const PlanarGraph& g, const CircleEmbedding& phi, const CircleEmbedding128& phi128);

  /// Routes one packet; see route() for the meaning of the arguments and of the result.
  Route route(Scheme s, Vertex source, Vertex target, std::size_t ttl = 0);
  /// Same, writing into `out` and reusing its path's storage.
  void route(Scheme s, Vertex source, Vertex target, std::size_t ttl, Route& out);

  /// One forwarding decision of a memoryless scheme (greedy_power, greedy_euclid, compass): the next
  /// hop from `at` towards `target`, or `none`. Preconditions: `at` and `target` are vertices of
  /// the graph, and `s` is not gfg, whose decisions depend on state carried in the packet. For
  /// hyperbolic, `none` also when the decision is not certified (route() tells the two apart).
  Vertex next_hop(Scheme s, Vertex at, Vertex target) const;

  /// Kleinberg's embedding of a BFS tree of the graph that Scheme::hyperbolic routes on, built on
  /// first use (default HyperbolicOptions) and kept.
  const HyperbolicTreeEmbedding& hyperbolic() const;

  /// The graph routed over.
  const PlanarGraph& graph() const { return *g_; }
  /// The embedding routed on.
  const CircleEmbedding& embedding() const { return *phi_; }

private:
  void route_memoryless(Scheme s, Vertex target, std::size_t ttl, Route& out);
  void route_gfg(Vertex target, std::size_t ttl, Route& out) const;
  void route_hyperbolic(Vertex target, std::size_t ttl, Route& out) const;
  void check_vertex(Vertex v, const char* role) const;
  void check_scheme(Scheme s) const;
  Vertex hop(Scheme s, Vertex at, Vertex target) const;
  GraphView view_of(Vertex v) const { return {*g_, *phi_, v}; }

  const PlanarGraph* g_;
  const CircleEmbedding* phi_;
  const CircleEmbedding128* phi128_ = nullptr;
  std::vector<std::uint32_t> visit_mark_;  // compass loop detection: == epoch_ when visited this route
  std::uint32_t epoch_ = 0;
  mutable std::unique_ptr<HyperbolicTreeEmbedding> hyperbolic_;  // built on first use
};

}  // namespace laguerre::core
