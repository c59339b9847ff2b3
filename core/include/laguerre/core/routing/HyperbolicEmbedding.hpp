#pragma once
/// @file
/// Kleinberg's greedy embedding of a spanning tree in the hyperbolic plane (INFOCOM 2007, "Geographic
/// routing using hyperbolic space"), the literature baseline of Scheme::hyperbolic.
///
/// A breadth-first spanning tree T is laid on the tiling of the hyperbolic plane by regular ideal
/// q-gons, q = max(3, max degree of T): every node sits at the centre of one tile, children in tiles
/// adjacent to their parent's. Adjacent centres are mirror images across their shared side, so the
/// side is their perpendicular bisector and it separates a child's subtree from the rest of the tree:
/// every node other than t has a tree neighbour strictly closer to t, and greedy routing by hyperbolic
/// distance over all graph edges always delivers (docs/hyperbolic-baseline.md has the construction,
/// its proof and the precision analysis).
///
/// Representation. A node's point is kept exactly, as its tree address (the word of child indices
/// from the root, each a fixed isometry of the tiling), never as rounded coordinates: Poincaré-disc
/// coordinates need about depth·D/ln 2 bits (D the parent–child distance) and doubles fail from
/// depth ~10 on our fields. Distances are evaluated on demand along the reduced tree path between the
/// two nodes (the common prefix cancels symbolically), with double interval arithmetic and a
/// power-of-two scale: each comparison is certified or reported undecided, never guessed.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// What a node holds as its coordinate, and so what the distance comparisons are evaluated from.
enum class HyperbolicCoordinates {
  address,      ///< its tree address: exact; distances along the reduced tree path (the default)
  disc_double,  ///< its Poincaré-disc point rounded to two doubles (the classical representation):
                ///< comparisons from the rounding boxes, undecided once the boxes reach the boundary
};

/// Options of the embedding.
struct HyperbolicOptions {
  Vertex root = none;              ///< the tree's root; none: the middle of a double BFS sweep's path
  std::uint32_t tiling_degree = 0; ///< q; 0: max(3, max tree degree); else at least that (InputError)
  HyperbolicCoordinates coordinates = HyperbolicCoordinates::address;  ///< what nodes hold
};

/// The embedding of one connected graph. Deterministic: a function of the adjacency order and options.
class HyperbolicTreeEmbedding {
public:
  /// Embeds a BFS tree of `g`: each vertex's parent is its smallest-index neighbour one level up (the
  /// local rule of the distributed set-up, protocols/HyperbolicSetup.hpp); children take their sides
  /// in g's rotation order.
  explicit HyperbolicTreeEmbedding(const PlanarGraph& g, const HyperbolicOptions& options = {});
  /// Same from adjacency lists (any connected simple graph; InputError if disconnected or empty).
  explicit HyperbolicTreeEmbedding(const std::vector<std::vector<Vertex>>& adjacency,
                                   const HyperbolicOptions& options = {});

  std::size_t size() const { return parent_.size(); }  ///< number of nodes
  Vertex root() const { return root_; }                ///< the tree's root
  std::uint32_t tiling_degree() const { return q_; }   ///< q
  Vertex parent(Vertex v) const { return parent_[v]; } ///< tree parent (none at the root)
  std::uint32_t depth(Vertex v) const { return depth_[v]; }  ///< hops from the root in the tree
  std::uint32_t max_depth() const { return max_depth_; }     ///< the tree's height
  /// Length of the double sweep's second BFS path (0 when the root was given).
  std::uint32_t sweep_length() const { return sweep_length_; }
  /// Hops from vertex 0 to the far end of the double sweep's first BFS (0 when the root was given).
  std::uint32_t sweep_start_depth() const { return sweep_start_depth_; }
  /// Whether the root was chosen by the double sweep (HyperbolicOptions::root was none).
  bool swept() const { return swept_; }
  /// v's tree address: the child index of each vertex on the tree path from the root (excluded) to v.
  std::vector<std::uint32_t> address(Vertex v) const;
  /// The side of the parent's tile v's tile is glued to: in [0, q) at depth 1, [1, q) deeper.
  std::uint32_t child_index(Vertex v) const { return index_[v]; }
  /// D = 2 artanh cos(π/q), the hyperbolic distance between a parent and a child.
  double edge_length() const;

  /// Sign of d(a, t) − d(b, t) in the exact embedding, or nothing when the interval evaluation cannot
  /// decide it (an exact tie, or the numbers' limit).
  std::optional<Sign> compare_distance(Vertex t, Vertex a, Vertex b) const;
  /// d(a, b), approximately (double, from the address evaluation whatever the coordinates): for tests
  /// and statistics only.
  double distance(Vertex a, Vertex b) const;

  /// Bits of v's address: ⌈log2 q⌉ per tree level (what a node stores and a coordinate message
  /// carries, besides q).
  std::size_t address_bits(Vertex v) const;
  /// Bits a Poincaré-disc coordinate pair of v would need for the same resolution: 2·(⌈d(root, v)/ln 2⌉
  /// + 53), the estimate of docs/hyperbolic-baseline.md (reported, not used).
  std::size_t disc_coordinate_bits(Vertex v) const;

  /// A scaled interval evaluation of 2·cosh d(a, b) (opaque; see the .cpp).
  struct Norm {
    double lo = 0, hi = 0;  ///< enclosure of the mantissa
    int exp = 0;            ///< value = mantissa · 4^exp
  };
  /// 2·cosh d(a, b), enclosed, from the nodes' coordinates (HyperbolicOptions::coordinates).
  Norm norm(Vertex a, Vertex b) const;
  /// The same from the addresses, whatever the coordinates.
  Norm address_norm(Vertex a, Vertex b) const;
  /// The disc_double coordinates of v as enclosing boxes (x_lo, x_hi, y_lo, y_hi); empty otherwise.
  std::span<const double> disc_box(Vertex v) const;

private:
  void build(const std::vector<std::uint32_t>& offsets, const std::vector<Vertex>& targets, const HyperbolicOptions& o);

  std::vector<Vertex> parent_;
  std::vector<std::uint32_t> depth_, index_;
  Vertex root_ = none;
  std::uint32_t q_ = 3, max_depth_ = 0, sweep_length_ = 0, sweep_start_depth_ = 0;
  bool swept_ = false;
  std::vector<double> gen_;   // evaluation matrices (see the .cpp), 8 doubles each
  std::vector<double> disc_;  // disc_double: 4 doubles per node
};

/// The side of its parent's tile that child number `rank` (1-based, in the parent's adjacency order)
/// of `children` takes: spread evenly over the root's sides 0..q−1, or over a non-root parent's
/// 1..q−1 (mirrored j ↦ q − j below parents at odd `depth`). One rule for the central embedding and
/// the distributed set-up.
std::uint32_t hyperbolic_child_side(std::uint32_t q, bool root, std::uint32_t depth, std::uint32_t rank,
                                    std::uint32_t children);
/// ⌈log2 q⌉: the bits of one level of an address.
std::size_t hyperbolic_side_bits(std::uint32_t q);

/// What the distributed set-up of the embedding costs (protocols/HyperbolicSetup.hpp, whose simulated
/// counts equal these), and what a node holds.
struct HyperbolicSetupCost {
  /// Per BFS (the double sweep's two, when the root is not given, and the tree's): a flood of 2|E|
  /// (every node tells each neighbour its depth and parent once) and an echo of |V| − 1; the steering
  /// messages of the sweep (sweep_start_depth to its far end, ⌈sweep length / 2⌉ to the middle);
  /// |V| − 1 addresses down the tree; 2(|E| − |V| + 1) over the non-tree edges (neighbour table).
  std::uint64_t messages = 0;
  double address_bits_mean = 0;  ///< a node's own coordinate (its address), mean over nodes
  std::size_t address_bits_max = 0;  ///< and largest
  std::size_t disc_bits_max = 0;     ///< largest disc_coordinate_bits, for comparison
};

/// The setup cost of `e` on a graph with `edges` edges.
HyperbolicSetupCost hyperbolic_setup_cost(const HyperbolicTreeEmbedding& e, std::size_t edges);

/// One greedy forwarding decision by hyperbolic distance.
struct HyperbolicHop {
  std::size_t next = 0;    ///< index into the neighbour list, or its size when there is no next hop
  bool certified = true;   ///< false: the numbers could not prove any neighbour strictly closer
};

/// The greedy decision at `at` for `target` among `neighbours` (at ≠ target): the target itself if it
/// is a neighbour; otherwise, among the neighbours whose enclosure may be the least, the smallest
/// index that is certified strictly closer to the target than `at`. So the packet only moves when its
/// distance provably decreases, and it is the exact greedy choice whenever the enclosures isolate
/// the minimum (ties from the tiling's symmetries go to the smallest index). No next hop and
/// certified: every neighbour is provably no closer (impossible for a connected graph); not
/// certified: the numbers could not decide.
HyperbolicHop hyperbolic_hop(const HyperbolicTreeEmbedding& e, std::span<const Vertex> neighbours, Vertex at,
                             Vertex target);

}  // namespace laguerre::core
