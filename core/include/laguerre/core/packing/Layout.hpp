#pragma once
/// @file
/// Layout of a hyperbolic packing in the Poincaré disc: from radii to Euclidean circles φ = (p, σ).

#include <complex>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// Whether a layout's doubles can carry the packing (DESIGN.md, "Numerical range").
enum class Precision {
  ok,              ///< every radius is finite and at least `Layout::degraded_radius`
  degraded,        ///< finite, but some circle is smaller than `degraded_radius`: decisions stay exact
                   ///< for the stored doubles, tangencies are only meaningful to ~eps/σ_min
  unrepresentable  ///< a NaN, an infinity or a non-positive radius: nothing may be claimed
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
  static constexpr double degraded_radius = 1e-12;  ///< threshold for Precision::degraded

  CircleEmbedding circles;                  ///< Euclidean circle per vertex of the complex
  std::vector<std::complex<double>> centre; ///< hyperbolic centre (interior) or ideal point (boundary)
  std::vector<std::uint32_t> wave;          ///< round of the layout wave in which each vertex was placed
  std::vector<Vertex> parent;               ///< the anchor each vertex was placed from (spanning tree)
  Vertex root = none;                       ///< root vertex (none if the complex has no interior vertex)
  Precision precision = Precision::ok;      ///< see Precision
  double smallest_radius = 0;               ///< min Euclidean radius
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
Layout lay_out(const PackingComplex& k, const Radii& h, Vertex root);

/// Tangency error of edge u–v in a layout: | |p(u) − p(v)| − (σ(u) + σ(v)) | / min(σ(u), σ(v)).
double tangency_error(const CircleEmbedding& c, Vertex u, Vertex v);

}  // namespace laguerre::core
