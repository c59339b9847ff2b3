#pragma once
/// @file
/// Geographic routing schemes on a circle embedding φ = (p, σ): greedy power, greedy Euclidean,
/// compass and greedy-face-greedy, and the result of routing one packet.
///
/// Every forwarding decision is an exact predicate on the stored doubles (a double-precision filter
/// with a proven error bound first, the filtered exact predicates of Predicates.hpp when it cannot
/// decide), so a route is an exact statement about the embedding the nodes hold.
///
/// Shared conventions:
///  - ties between equally good neighbours go to the smallest vertex index;
///  - a route never "jumps" to the target: adjacency to t gives no special treatment, t is reached
///    only when the scheme's own rule selects it;
///  - `Route::path` lists every vertex that held the packet, source first, repeats included.

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// A routing scheme.
enum class Scheme {
  greedy_power,   ///< forward to the neighbour of least power pow(p(t), u); stop at a local minimum
  greedy_euclid,  ///< forward to the neighbour whose centre is nearest to p(t); stop at a local minimum
  compass,        ///< forward to the neighbour whose direction deviates least from that of p(t)
  gfg,            ///< greedy-face-greedy (greedy Euclidean + face routing on the straight-line drawing)
  /// literature baseline: greedy by hyperbolic distance in Kleinberg's embedding of a BFS tree of the
  /// graph (HyperbolicEmbedding.hpp); ignores φ. Centralized router only (no per-node protocol).
  hyperbolic,
};

/// The schemes on the circle embedding, in declaration order: what `all` selects and what the
/// per-node forwarding protocol implements (Scheme::hyperbolic is asked for by name).
inline constexpr std::array<Scheme, 4> all_schemes{Scheme::greedy_power, Scheme::greedy_euclid, Scheme::compass,
                                                   Scheme::gfg};

/// The scheme's name: "greedy_power", "greedy_euclid", "compass", "gfg" or "hyperbolic".
std::string_view to_string(Scheme s);
/// Inverse of to_string(Scheme); `std::nullopt` for any other string.
std::optional<Scheme> parse_scheme(std::string_view name);

/// How routing one packet ended.
enum class RouteOutcome {
  delivered,     ///< the packet reached the target
  dead_end,      ///< a node had no admissible next hop (greedy local minimum; GFG found no face to enter)
  loop,          ///< the packet would cycle forever (compass revisited a node; GFG walked a whole face
                 ///< without progress, which only a non-plane drawing can cause)
  ttl_exceeded,  ///< the hop limit was reached first
  uncertified,   ///< the numbers could not prove the next hop closer (Scheme::hyperbolic): not delivered
};

/// The outcome's name: "delivered", "dead_end", "loop", "ttl_exceeded" or "uncertified".
std::string_view to_string(RouteOutcome o);

/// The journey of one packet.
struct Route {
  RouteOutcome outcome = RouteOutcome::dead_end;  ///< how it ended
  std::vector<Vertex> path;                       ///< every vertex that held the packet, source..last
  Vertex stuck = none;  ///< where it failed: the local minimum, the revisited node, the node that
                        ///< closed the fruitless face walk, or the holder at the hop limit; none if delivered
  /// Number of hops taken (path length minus one).
  std::size_t hops() const { return path.empty() ? 0 : path.size() - 1; }
};

/// The hop limit used when route() is given ttl = 0: 4·|V| + 16 for greedy (also hyperbolic) and compass routing (which
/// stop on their own within |V| hops) and, for gfg, |V|·(2|E|·(|E|+1) + |V|) + 16, a bound its
/// progress argument guarantees is never reached (saturated at SIZE_MAX).
std::size_t default_ttl(const PlanarGraph& g, Scheme s);

/// Routes one packet from `source` to `target` with scheme `s` on the embedding `phi` of `g`.
/// `ttl` is the maximal number of hops (0 = default_ttl(g, s)). A packet with source == target is
/// delivered with zero hops. For gfg the rotation of `g` must be the counter-clockwise order of the
/// centres (a plane straight-line drawing); otherwise the result says `loop` or `dead_end` rather than
/// misbehaving. Preconditions (InternalError otherwise): `phi` has one finite circle per vertex, and
/// `source` and `target` are vertices of `g`.
Route route(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s, Vertex source, Vertex target,
            std::size_t ttl = 0);

/// One forwarding decision of greedy power routing (what a node does with a packet for `target`): the
/// neighbour u of `at` minimising pow(p(target), u) (smallest index among ties) if that is strictly
/// less than pow(p(target), at), otherwise `none` (a dead end). `none` as well when at == target.
Vertex greedy_power_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target);

/// One forwarding decision of greedy Euclidean routing: like greedy_power_next_hop with |p(t) − p(u)|².
Vertex greedy_euclid_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target);

/// One forwarding decision of compass routing: the neighbour of `at` whose direction from p(at) makes
/// the smallest angle with p(target) − p(at) (smallest index among ties); `none` when at == target or
/// `at` has no neighbour.
Vertex compass_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Vertex at, Vertex target);

}  // namespace laguerre::core
