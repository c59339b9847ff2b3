#pragma once
/// @file
/// Layout of a hyperbolic packing in the Poincaré disc: from radii to Euclidean circles φ = (p, σ).

#include <complex>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// Whether a layout's stored doubles carry its circles (docs/precision.md). Measured by the
/// resolution of a circle: its radius in units in the last place of its largest coordinate, r / ulp.
/// Names: `precision_names` (PackingNames.hpp).
enum class Precision {
  ok,              ///< every circle spans at least `Layout::degraded_resolution` ulps
  degraded,        ///< some circle spans fewer, but at least `Layout::collapsed_resolution`: the doubles
                   ///< still separate it from its neighbours, tangencies hold only to ~1/resolution
  collapsed,       ///< some circle spans fewer than `collapsed_resolution` ulps: rounding moves it by a
                   ///< sizeable part of its radius, the doubles no longer carry the packing there
  unrepresentable  ///< a NaN, an infinity or a non-positive radius
};

/// The arithmetic the layout wave computes in. The circles are stored as doubles either way; binary128
/// layouts also keep their binary128 circles (Layout::circles128), on which the checks then decide.
/// Names: `layout_arithmetic_names` (PackingNames.hpp).
enum class LayoutArithmetic {
  binary64,  ///< doubles: what a network node computes (Placement.hpp), bit for bit
  binary128,  ///< IEEE quadruple (113-bit significand, float128 in software, ~10x slower): the wave's
              ///< rounding is 2^60 times smaller; the circles are kept in binary128 (16 bytes per
              ///< coordinate) and also rounded once to doubles
  mixed       ///< LayoutMethod::frames only: the frames, positions and circles in binary128 (kept as
              ///< with binary128), the local quantities computed from the radii alone (triangle angles,
              ///< each step from a parent's frame to a child's) in doubles: binary128's range at a
              ///< fraction of its cost (docs/precision.md)
};

/// How the layout wave computes each placement (docs/precision.md). Both place the same vertices in
/// the same rounds from the same anchors (the same spanning tree).
/// Names: `layout_method_names` (PackingNames.hpp).
enum class LayoutMethod {
  wave,   ///< from the positions of the two placed anchors (Placement.hpp): what a network node
          ///< computes, bit for bit; its rounding grows exponentially with the depth of the tree
          ///< (×10 every ~40 rounds on random Delaunay triangulations)
  frames  ///< from the parent's frame (a disc automorphism carried down the tree) and the triangle
          ///< angles at the parent: rounding grows about linearly with the depth
};

/// How the layout picks its root (the circle placed at the origin, with its first neighbour on the
/// positive real axis).
enum class RootRule {
  deepest,     ///< the interior vertex of G farthest (in hops) from the boundary, ties to the smallest
               ///< id: centres the packing, so the smallest circles are as large as they can be
  smallest_id  ///< the interior vertex of G with the smallest id (a plain leader election)
};

/// Euclidean circles of every vertex of the complex in the unit disc.
struct Layout {
  static constexpr double degraded_resolution = 1 << 20;  ///< below: Precision::degraded (~1e-6 relative rounding)
  static constexpr double collapsed_resolution = 1 << 4;   ///< below: Precision::collapsed

  CircleEmbedding circles;                  ///< Euclidean circle per vertex of the complex (doubles)
  CircleEmbedding128 circles128;            ///< the same circles in binary128 when `arithmetic` is binary128
                                            ///< (empty otherwise): what precision and the checks read then
  std::vector<std::complex<double>> centre; ///< hyperbolic centre (interior) or ideal point (boundary)
  std::vector<std::uint32_t> wave;          ///< round of the layout wave in which each vertex was placed
  std::vector<Vertex> parent;               ///< the anchor each vertex was placed from (spanning tree)
  Vertex root = none;                       ///< root vertex (none if the complex has no interior vertex)
  Precision precision = Precision::ok;      ///< see Precision
  double smallest_radius = 0;               ///< min Euclidean radius
  double resolution = 0;                    ///< min over circles of circle_resolution (0: unrepresentable), of
                                            ///< circles128 when kept (ulps of the binary128 coordinates)
  LayoutMethod method = LayoutMethod::wave;                  ///< how the wave placed the circles
  LayoutArithmetic arithmetic = LayoutArithmetic::binary64;  ///< what the wave computed in
  bool complete = true;  ///< false: stopped after the round that placed the first collapsed circle
                         ///< (`stop_when_collapsed`); unplaced vertices have wave `none` and NaN
                         ///< circles, and smallest_radius/resolution are over the placed circles
};

/// Chooses the layout root by `rule`; `none` if no vertex of G is interior.
Vertex choose_root(const PackingComplex& k, RootRule rule);

/// Lays out the circles with hyperbolic radii h as a synchronous wave from `root` (thesis §5.3.1 step 3).
///
/// Round 0 places `root` at the origin and its first neighbour on the positive real axis. In round
/// r ≥ 1 every unplaced vertex w that has two placed neighbours a, b with (w, a, b) an inner face
/// places itself from the first such pair in its counter-clockwise rotation that contains an interior
/// vertex (else the first pair), using only positions known at the start of the round. This is
/// exactly what the distributed layout wave computes, so the protocol can reproduce it bit for bit:
/// the pair rule is `choose_placement_wedge` and each placement is `place_root`,
/// `place_first_neighbour` or `place_in_face` (Placement.hpp), with the parent chosen by
/// `parent_is_first_anchor`.
/// Before convergence the sweep accumulates inconsistency; that is expected.
/// `method` = frames computes each placement through the parent's frame instead (same rounds, same
/// tree); `arithmetic` = binary128 runs the wave in quadruple precision and rounds only the result to
/// doubles. The defaults are what the network computes.
/// `stop_when_collapsed`: the wave stops after the round in which a circle rounds to a collapsed or
/// unrepresentable one (precision is then Precision::collapsed or unrepresentable, as the whole layout's
/// would be, `complete` false): for callers that only need to know that no claim can be made on it
/// (the packer's mid-run checks). The circles placed up to there are the same bits as without it.
Layout lay_out(const PackingComplex& k, const Radii& h, Vertex root, LayoutMethod method = LayoutMethod::wave,
               LayoutArithmetic arithmetic = LayoutArithmetic::binary64, bool stop_when_collapsed = false);

/// Hyperbolic radii in binary128, per vertex of the complex (∞ on the boundary): Newton's radii refined
/// by NewtonMethod::refine128 when doubles cannot close the flowers finely enough (docs/precision.md).
using Radii128 = std::vector<Float128>;

/// lay_out in LayoutArithmetic::binary128 from binary128 radii: the same rounds, tree and placements,
/// every local quantity computed from the binary128 radii.
Layout lay_out(const PackingComplex& k, const Radii128& h, Vertex root, LayoutMethod method,
               bool stop_when_collapsed = false);

/// θ(v) − 2π for every interior vertex of the complex from binary128 radii, each angle and the sum in
/// binary128 and the difference rounded once to a double (0 on the boundary).
std::vector<double> angle_residuals128(const PackingComplex& k, const Radii128& h);

/// r / ulp(max(|x|, |y|, r)) of a stored circle: how many units in the last place of its coordinates
/// its radius spans (0 if a coordinate is not finite or r ≤ 0).
double circle_resolution(const Circle& c);

/// r / ulp(max(|x|, |y|, r)) in units of the binary128 coordinates (ulp = 2^(e − 113) for a largest
/// coordinate in [2^(e−1), 2^e)); 0 if a coordinate is not finite or r ≤ 0.
template <Binary128Circle C>
double circle_resolution(const C& c);

/// The significand (bits) a node needs for every circle of `layout` to span Layout::degraded_resolution
/// ulps of its coordinates: p − log2(resolution / 2^20), at least p, p = 113 if the layout keeps
/// binary128 circles and 53 otherwise (0 if the layout is unrepresentable).
int significand_bits_needed(const Layout& layout);

/// Bytes per stored coordinate of a layout: 16 when it keeps binary128 circles, 8 otherwise.
int bytes_per_coordinate(const Layout& layout);

/// Tangency error of edge u–v in a layout: | |p(u) − p(v)| − (σ(u) + σ(v)) | / min(σ(u), σ(v)).
double tangency_error(const CircleEmbedding& c, Vertex u, Vertex v);
/// tangency_error on binary128 circles, computed in binary128 (rounded to a double at the end).
double tangency_error(const CircleEmbedding128& c, Vertex u, Vertex v);

}  // namespace laguerre::core
