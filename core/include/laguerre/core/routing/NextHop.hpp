#pragma once
/// @file
/// The forwarding decisions of the routing schemes (Routing.hpp) over what one node knows: its own
/// circle and position, its neighbours' in counter-clockwise rotation order, the target's position,
/// and for face routing the perimeter state the packet carries. The centralized Router and the
/// per-node protocols::ForwardingNode both decide with these functions, so a packet routed hop by hop
/// takes core::route's path bit for bit: never re-implement a rule inline.
///
/// Every decision is exact on the stored coordinates, doubles or binary128 (Routing.hpp). A decision
/// returns the index of the next hop in the view's neighbour order (counter-clockwise), or
/// `view.degree()` when there is none; among equally good neighbours the smallest key wins. The
/// callers check "the holder is the target" before asking.

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// Vertex `at` of an embedded graph as it knows itself: what core::Router decides on. `C` is the
/// circle type of the embedding: Circle (doubles) or Circle128 (the binary128 circles of a
/// LayoutArithmetic::binary128 layout, on which the greedy rules decide with the binary128 predicates).
/// Keeps references: `g` and `phi` must outlive it.
template <class C>
class BasicGraphView {
public:
  /// The circle type, and the point type of its centres (Point2 or Point128).
  using Circle = C;
  using Point = decltype(centre(std::declval<const C&>()));
  /// The view of vertex `at` (an index of `g`; `phi` has one circle per vertex).
  BasicGraphView(const PlanarGraph& g, const std::vector<C>& phi, Vertex at)
      : phi_(&phi), at_(at), neighbours_(g.neighbours(at)) {}
  /// Number of neighbours.
  std::size_t degree() const { return neighbours_.size(); }
  /// Own circle.
  const C& circle() const { return (*phi_)[at_]; }
  /// Own position: the circle's centre.
  Point position() const { return centre(circle()); }
  /// Circle of neighbour i (counter-clockwise order of g's rotation).
  const C& circle_of(std::size_t i) const { return (*phi_)[neighbours_[i]]; }
  /// Position of neighbour i: its circle's centre.
  Point position_of(std::size_t i) const { return centre(circle_of(i)); }
  /// Tie-break key of neighbour i: its vertex index.
  std::uint64_t key(std::size_t i) const { return neighbours_[i]; }

private:
  const std::vector<C>* phi_;
  Vertex at_;
  std::span<const Vertex> neighbours_;
};

/// The view of a double embedding (every scheme decides on it).
using GraphView = BasicGraphView<Circle>;
/// The view of a binary128 embedding (the greedy schemes decide on it).
using GraphView128 = BasicGraphView<Circle128>;

/// What a node of the forwarding protocol knows (protocols::ForwardingNode). Keeps spans: the data
/// must outlive it.
class NeighbourView {
public:
  /// The circle and point types (doubles).
  using Circle = core::Circle;
  using Point = Point2;
  /// Own circle and position; neighbours' circles, positions and tie-break keys (node ids), all in
  /// counter-clockwise order and of equal sizes.
  NeighbourView(const Circle& circle, Point2 position, std::span<const Circle> circles,
                std::span<const Point2> positions, std::span<const std::uint64_t> keys)
      : circle_(circle), position_(position), circles_(circles), positions_(positions), keys_(keys) {}
  /// Number of neighbours.
  std::size_t degree() const { return circles_.size(); }
  /// Own circle.
  const Circle& circle() const { return circle_; }
  /// Own position.
  Point2 position() const { return position_; }
  /// Circle of neighbour i.
  const Circle& circle_of(std::size_t i) const { return circles_[i]; }
  /// Position of neighbour i.
  Point2 position_of(std::size_t i) const { return positions_[i]; }
  /// Tie-break key of neighbour i.
  std::uint64_t key(std::size_t i) const { return keys_[i]; }

private:
  Circle circle_;
  Point2 position_;
  std::span<const Circle> circles_;
  std::span<const Point2> positions_;
  std::span<const std::uint64_t> keys_;
};

// The rules below take a View: GraphView, NeighbourView or (the greedy rules) GraphView128, each
// instantiated (and compiled once) in NextHop.cpp. The target t is a View::Point.

/// Greedy power: the neighbour u minimising pow(t, u) (smallest key among ties) if that is strictly
/// less than pow(t, own circle); otherwise a dead end.
template <class View>
std::size_t greedy_power_hop(const View& view, typename View::Point t);

/// Greedy Euclidean: like greedy_power_hop with |t − position|².
template <class View>
std::size_t greedy_euclid_hop(const View& view, typename View::Point t);

/// Compass: the neighbour whose direction from the own position makes the smallest angle with the
/// direction of t (smallest key among ties); none only without neighbours.
template <class View>
std::size_t compass_hop(const View& view, Point2 t);

/// Face routing (greedy-face-greedy's perimeter mode) entered at the holder, a greedy local minimum:
/// the first face is the one whose corner at the holder, between neighbours i and i+1 (cyclically,
/// searched from i = 0), contains the open ray towards t; returns i+1 (the first dart of its
/// right-hand walk), or none when no corner does (not a plane drawing).
template <class View>
std::size_t first_face_hop(const View& view, Point2 t);

/// Whether a packet in perimeter mode at `holder` returns to greedy mode: holder strictly closer to
/// t than the phase's entry point.
bool leaves_perimeter(Point2 holder, Point2 entry, Point2 t);

/// The last face change of a perimeter phase on the segment [entry, t]: the entry point itself, or
/// the proper crossing of the line (entry, t) with the edge [a, b], kept symbolically.
struct FaceChange {
  bool crossed = false;  ///< false: the entry point (λ = 0)
  Point2 a{};            ///< the crossing edge's end points (when crossed)
  Point2 b{};
};

/// The edge a perimeter packet leaves along, after the face change rule.
struct FaceHop {
  std::size_t next = 0;  ///< index of the neighbour it is sent to
  bool changed = false;  ///< a face change happened: the walk restarts with this edge
};

/// The face change rule at the holder before it sends along the edge to neighbour `d`: while that
/// edge properly crosses the line (entry, t) strictly beyond `last` and not beyond t, the crossing
/// becomes `last`; if t lies left of the edge the packet turns to neighbour d+1 (the other face of
/// the edge) and the rule is applied again, else it is sent along the edge.
template <class View>
FaceHop face_hop(const View& view, Point2 entry, Point2 t, FaceChange& last, std::size_t d);

}  // namespace laguerre::core
