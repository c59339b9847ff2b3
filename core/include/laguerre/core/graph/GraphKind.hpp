#pragma once
/// @file
/// Classifying a planar graph for circle packing (triangulated disc or 3-connected) and choosing its
/// outer face.

#include <string>
#include <string_view>
#include <vector>

#include "laguerre/core/graph/Embedding.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// The two kinds of graphs the packing supports.
enum class GraphKind {
  triangulated_disc,  ///< every face but the outer one is a triangle, the outer face a simple cycle
  three_connected     ///< 3-connected (its embedding is unique up to mirror image, by Whitney)
};

/// "triangulated_disc" or "three_connected".
std::string_view to_string(GraphKind kind);

/// Whether g is 3-connected (at least 4 vertices, no separating set of fewer than 3 vertices).
///
/// Method: on the embedding. A connected plane graph with n ≥ 3 is 2-connected iff no face boundary
/// walk repeats a vertex; a 2-connected plane graph with n ≥ 4 is 3-connected iff any two distinct
/// faces meet in nothing, one vertex, or exactly one edge of which they are the two sides (a separating
/// pair {x, y} is crossed by a closed curve through two faces that both contain x and y).
/// Cost O(Σ_v deg(v)²) time and O(n + m) memory.
bool is_three_connected(const PlanarGraph& g);

/// A separating set of 1 or 2 vertices (sorted) if g has one, else empty. Graphs with fewer than 4
/// vertices have no separating set in this sense (use num_vertices()). Same cost as is_three_connected.
std::vector<Vertex> find_small_separator(const PlanarGraph& g);

/// Decides the kind of g and its outer face for packing, and returns g with that outer face.
///
/// Rules, in order:
///  1. fewer than 3 vertices: GraphInputError;
///  2. every face a triangle (a triangulated sphere): triangulated_disc; the outer face is g's if
///     `outer_given`, else the face of `default_outer_dart()`;
///  3. exactly one face not a triangle, and it is g's outer face or `outer_given` is false: that face
///     becomes the outer face, triangulated_disc; its boundary must be a simple cycle, else
///     GraphInputError;
///  4. 3-connected: three_connected; the outer face is g's if `outer_given`, else the largest face, ties
///     broken by the smallest (min id, max id) edge on it, then by the next smallest, and so on (the
///     lexicographic order of the faces' sorted edge lists, which does not depend on the mirror image);
///  5. otherwise GraphInputError (naming a separating set and suggesting a `# outer:` line).
/// `kind_out`, if not null, receives the kind; `source` names the input in errors.
PlanarGraph prepare_for_packing(const PlanarGraph& g, bool outer_given, GraphKind* kind_out = nullptr,
                                const std::string& source = "<input>");

/// prepare_for_packing(input.graph, input.outer_given, kind_out, input.name).
PlanarGraph prepare_for_packing(const GraphInput& input, GraphKind* kind_out = nullptr);

}  // namespace laguerre::core
