#pragma once
/// @file
/// The triangulated disc on which Thurston's iteration runs, with an intersection angle per edge.

#include <vector>

#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// A triangulated closed disc K with an intersection angle on every edge (thesis §5.1; DESIGN.md,
/// "Packing a 3-connected graph").
///
/// For a triangulated disc G, K = G and every edge is a tangency (angle 0). For a 3-connected graph G,
/// K = G′: G plus one *face vertex* per inner face of G that is not a triangle, joined to the face's
/// vertices at angle π/2, while the edges of G stay tangent. The packing of K then carries, for every
/// inner face f of G, a circle orthogonal to the circles of f's vertices: the G-circle packing of
/// Definition 5.1.4, whose limit satisfies GLPD (Theorem 5.2.6). Vertices 0 .. num_original-1 of K
/// are the vertices of G with the same indices; face vertices follow.
struct PackingComplex {
  PlanarGraph graph;                  ///< K, a triangulated disc whose outer face is G's outer face
  std::vector<double> cos_angle;      ///< per dart of K: cosine of the intersection angle (1 or 0)
  std::size_t num_original = 0;       ///< number of vertices of G
  std::vector<Face> face_of_vertex;   ///< per face vertex (index − num_original): the face of G
  std::vector<std::uint8_t> tangent_only;  ///< per vertex of K: 1 if every triangle around it has only tangencies

  /// Builds K from a triangulated disc or a 3-connected planar graph (outer face already chosen).
  static PackingComplex from_graph(const PlanarGraph& g);
  /// Whether K has face vertices (G was not a triangulation).
  bool has_face_vertices() const { return graph.num_vertices() > num_original; }
};

}  // namespace laguerre::core
