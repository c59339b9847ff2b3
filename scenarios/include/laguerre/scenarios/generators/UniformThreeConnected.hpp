#pragma once
/// @file
/// Uniform random 3-connected planar graphs (rooted 3-connected maps), by the closure of binary trees
/// into irreducible dissections of the hexagon (Fusy–Poulalhon–Schaeffer; Fusy's sampler).

#include <cstddef>
#include <cstdint>

#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::scenarios {

/// Counters of one call of a 3-connected sampler (for benchmarks and tests).
struct ThreeConnectedStats {
  std::size_t attempts = 0;  ///< trees drawn and closed (one more than the number of rejections)
  std::size_t faces = 0;     ///< faces of the returned map (the outer face included)
};

/// A uniformly random rooted 3-connected planar map with n vertices, as a 3-connected planar graph
/// whose outer face is the root face.
///
/// What is uniform. With `faces` = 0: every rooted 3-connected planar map (a 3-connected simple plane
/// graph with a distinguished dart, up to orientation-preserving isomorphism) with n vertices has the
/// same probability, whatever its number of edges. With `faces` = f > 0: every rooted 3-connected map
/// with n vertices and f faces (so n + f − 2 edges) has the same probability; f must satisfy
/// n ≤ 2f − 4 and f ≤ 2n − 4 (Steinitz) (precondition). By Whitney a 3-connected planar
/// graph G with m edges has exactly two embeddings (mirror images), hence 4m/|Aut G| rooted maps, while
/// it has n!/|Aut G| vertex labellings: so with f (hence m) fixed, the graph is exactly uniform among
/// vertex-labelled 3-connected planar graphs with n vertices and m edges once the ids are permuted at
/// random; with f = 0 a labelled graph is weighted by its number of edges m (a relative spread of
/// O(n^-1/2) around the mean). The outer face is the root face (left of the root dart), so it is a face
/// chosen with probability proportional to its degree; the root dart itself is forgotten.
///
/// Method (É. Fusy, D. Poulalhon, G. Schaeffer, *Dissections, orientations, and trees*, ACM TALG 4,
/// 2008; É. Fusy, *Uniform random sampling of planar graphs in linear time*, RSA 34, 2009). Vertices
/// and faces of a map M are the black and white vertices of its quadrangulation Q (one quadrangle per
/// edge of M); M is 3-connected iff Q is irreducible (every 4-cycle bounds a face). Deleting a marked
/// edge of Q leaves an irreducible dissection of the hexagon with no internal path of length 3 between
/// the two ends of the deleted edge ("admissible"), and these are in bijection with binary trees by the
/// closure (each leaf followed by three edge sides closes a quadrangle; the remaining leaves hang on a
/// hexagon). A binary tree with a black inner vertices and b white ones (properly 2-coloured, the
/// colours fixed by the root) gives a map with a + 3 vertices and b + 3 faces. Such trees rooted at a
/// leaf of a black node are drawn exactly uniformly by a two-type cycle lemma (black nodes choose their
/// white children among 2a slots, white nodes their black children among 2b slots, and the unique good
/// rotation of the blocks is taken), and the root of Q among the three black hexagon vertices. A
/// non-admissible result is rejected and everything is redrawn: the accepted map is uniform. With
/// faces = 0 the face count f is first drawn with weight proportional to the number of such trees
/// divided by their number of black leaves, 2a − b + 1 (computed exactly in floating point from the
/// ratio of consecutive weights), which after the admissibility rejection makes the law of f that of
/// a uniform rooted map with n vertices; it concentrates at f ≈ ((3 + √7)/4)·n (the maximum of the
/// exponential growth of the tree counts, binomial(2a, b)·binomial(2b, a)), i.e. about 2.41·n edges.
/// Expected cost: linear time per attempt; `ThreeConnectedStats::attempts` counts the attempts (about
/// 5 on average for n = 10^3 … 10^6 in tools/bench/bench_generators, i.e. an admissibility rate near
/// 1/5). A prescribed f far from 1.41·n is expensive: the admissibility rate falls to order 1/n² as f
/// approaches (n + 4)/2 or 2n − 4 (measured mean attempts at n = 100: 5 for f = 141, 34 for f = 180,
/// 1617 for f = 52, 7528 for f = 196); for f = 2n − 4 use uniform_triangulation. After 10^6 attempts
/// std::runtime_error is thrown.
///
/// Vertex ids 0..n−1. Deterministic for a given (n, seed, faces) on every platform (std::mt19937_64 and
/// IEEE double arithmetic through our own mappings). Precondition: 4 ≤ n < 2^28.
core::PlanarGraph uniform_three_connected(std::size_t n, std::uint64_t seed, std::size_t faces = 0,
                                          ThreeConnectedStats* stats = nullptr);

/// A uniformly random rooted 3-connected planar map with `edges` edges (any number of vertices), its
/// outer face being the root face: every rooted 3-connected map with that many edges has probability
/// 1/C(edges), C = 1, 0, 4, 6, 24, 66, 214, … for 6, 7, 8, … edges (Tutte 1963, OEIS A000287).
///
/// Method: the exact-size sampler of Fusy–Poulalhon–Schaeffer 2008: a uniform binary tree with
/// edges − 4 nodes (Łukasiewicz word and cycle lemma), its closure into a dissection of the hexagon, one
/// of the six hexagon vertices chosen uniformly as the black end of the root edge of Q, and rejection
/// of non-admissible dissections. The numbers of vertices v and faces f vary (v + f = edges + 2, and by
/// duality v and f have the same law, so E[v] = (edges + 2)/2). Precondition:
/// 6 ≤ edges < 2^29 and edges ≠ 7 (no 3-connected planar map has 7 edges).
core::PlanarGraph uniform_three_connected_map_by_edges(std::size_t edges, std::uint64_t seed,
                                                       ThreeConnectedStats* stats = nullptr);

}  // namespace laguerre::scenarios
