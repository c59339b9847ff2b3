#pragma once
/// @file
/// Uniform random planar triangulations (Poulalhon–Schaeffer bijection).

#include <cstddef>
#include <cstdint>

#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::scenarios {

/// A uniformly random rooted simple triangulation of the sphere with n vertices, as a triangulated
/// disc whose outer face is the root face.
///
/// What is uniform: every rooted triangulation (a simple 3-connected planar map all of whose faces are
/// triangles, with a distinguished dart, up to orientation-preserving isomorphism) with n vertices has
/// probability 1/T(n), T(n) = 2·(4n−11)! / ((n−2)!·(3n−7)!) (Tutte 1962; 1, 1, 3, 13, 68, 399, … for
/// n = 3, 4, …). The returned graph keeps the root face as its outer face (a triangle); the root dart
/// inside it is forgotten. So an unrooted triangulation with a marked face (Δ, f) comes out with
/// probability 3 / (|Aut(Δ, f)|·T(n)), and the isomorphism type Δ with probability 6(n−2)/(|Aut Δ|·T(n)).
///
/// Method (Poulalhon & Schaeffer, *Optimal coding and sampling of triangulations*, Algorithmica 46,
/// 2006): plane trees with n−2 inner nodes each carrying two leaves ("stems"), rooted at a stem, are
/// counted by 2(4m−3)!/((m−1)!(3m−1)!) (m = n−2 nodes) and correspond to pairs of quaternary trees
/// (through Seq(T) = 1 + z·Seq(T)⁴ with T = z·Seq(T)³). Such a pair is drawn uniformly by the cycle
/// lemma from a uniform word with m−1 letters of weight +3 and 3m−1 of weight −1 (of its 2 good
/// rotations one is chosen at random). The tree's closure (each stem followed by two edge sides
/// becomes an edge closing a triangle) leaves stems that are hung on two new vertices; exactly two
/// faces then contain both new vertices, and one of them, chosen by a fair coin, is the root face.
/// The map from (tree up to rotation, one of its two root faces) to rooted triangulations is the
/// Poulalhon–Schaeffer bijection, so the result is uniform. Linear time and memory.
///
/// Vertex ids are 0..n−1: the tree's nodes in decoding order, then the two new vertices (n−2 and n−1,
/// both on the outer face). Deterministic for a given (n, seed) on every platform (std::mt19937_64
/// through our own integer mapping). Precondition: 3 ≤ n < 2^30.
core::PlanarGraph uniform_triangulation(std::size_t n, std::uint64_t seed);

}  // namespace laguerre::scenarios

namespace laguerre::scenarios {

/// `g` minus its vertex of largest degree (smallest id on ties: core::puncture_vertex), with that vertex's
/// link as the outer face (core::puncture) — a sensor field's boundary rather than three far-away corners. A
/// punctured triangulation of n + 1 vertices is a triangulated disc of n vertices. Ids are kept.
/// Precondition: g has at least 4 vertices (the result at least 3).
core::PlanarGraph puncture_at_max_degree(const core::PlanarGraph& g);

/// `g` with its largest face (smallest canonical dart on ties) as the outer face.
core::PlanarGraph with_largest_outer_face(const core::PlanarGraph& g);

}  // namespace laguerre::scenarios
