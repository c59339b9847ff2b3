#pragma once
/// @file
/// Interim random graph families, until the uniform samplers (Poulalhon–Schaeffer triangulations,
/// Fusy's 3-connected planar graphs) arrive.
///
/// Both generators are deterministic for a given (n, seed) on every platform: they draw from
/// std::mt19937_64 (whose output the standard fixes) through our own mapping to doubles in [0, 1)
/// (the top 53 bits times 2^-53) and to integers (rejection sampling), never through the standard
/// distributions, whose algorithms differ between standard libraries. Rotations are sorted exactly by
/// angle, so they do not depend on CGAL's internal vertex order either.

#include <cstddef>
#include <cstdint>

#include "laguerre/core/graph/Embedding.hpp"

namespace laguerre::core {

/// Delaunay triangulation of n points drawn uniformly in the unit disc (rejection from the square
/// [-1, 1]², a point redrawn if it repeats an earlier one). A triangulated disc whose outer face is the
/// convex hull (`outer_given` is true), with positions; vertex ids 0..n-1 in drawing order.
/// Requires n ≥ 3 (GraphInputError otherwise). Cost O(n log n) expected.
GraphInput random_delaunay_triangulation(std::size_t n, std::uint64_t seed);

/// A random 3-connected plane graph with n vertices and a straight-line drawing.
///
/// Rule: draw a Delaunay triangulation as above, redrawing the whole point set (from the same random
/// stream) until it is 3-connected, i.e. until no edge joins two non-consecutive hull vertices. Then
/// visit the interior edges in a uniformly random order and delete an edge when
///  - the graph stays 3-connected (decided locally on the two merging faces),
///  - the merged face has at most `max_face_size` vertices (keeps faces from degenerating into a few
///    huge polygons; they may be non-convex),
/// stopping after round(deletions_per_vertex · n) deletions or when the edges run out. Hull edges are
/// never deleted, so the outer face stays the convex hull (`outer_given` is true). The default 0.75
/// deletes roughly a quarter of the edges, bringing the edge count near the ~2.2 n of uniform random
/// planar graphs. Requires n ≥ 4, max_face_size ≥ 4 and a finite deletions_per_vertex ≥ 0 (GraphInputError
/// otherwise, naming the generator).
/// Cost O(n log n) expected.
GraphInput random_three_connected(std::size_t n, std::uint64_t seed, double deletions_per_vertex = 0.75,
                                  std::size_t max_face_size = 8);

}  // namespace laguerre::core
