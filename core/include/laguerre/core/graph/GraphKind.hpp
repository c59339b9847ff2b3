#pragma once
/// @file
/// Classifying a planar graph for circle packing (triangulated disc or 3-connected) and choosing its
/// outer face.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "laguerre/core/EnumNames.hpp"
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

/// How a triangulated sphere (a graph all of whose faces are triangles) becomes a disc for packing.
/// Rationale and measurements of the default (`face`): docs/outer-face.md.
enum class OuterRule {
  face,     ///< keep a face as the outer face: the input's (`# outer:`), else default_outer_dart()'s
  puncture  ///< remove puncture_vertex(); its neighbours, in their cyclic order, become the boundary
};

/// The one spelling of each OuterRule (`--outer`, scenario key `outer` of the file generator).
inline constexpr EnumNames<OuterRule, 2> outer_rule_names{{{OuterRule::face, "face"}, {OuterRule::puncture, "puncture"}}};

/// Whether every face of g is a triangle (g is a triangulated sphere; a disc bounded by a triangle is one).
bool is_triangulated_sphere(const PlanarGraph& g);

/// The vertex OuterRule::puncture removes: the one of largest degree, ties broken by the smallest user
/// id. Precondition: g has a vertex.
Vertex puncture_vertex(const PlanarGraph& g);

/// g without vertex v (and its edges), with v's link as the outer face; the other vertices keep their
/// ids and their relative order. Preconditions: g has at least 4 vertices and every face around v is a
/// triangle (so the link of v is a simple cycle, a face of the result).
PlanarGraph puncture(const PlanarGraph& g, Vertex v);

/// What prepare_input decided.
struct PreparedInput {
  GraphKind kind{};                      ///< triangulated disc or 3-connected
  std::vector<std::uint64_t> removed;    ///< user ids of the vertices removed (OuterRule::puncture), else empty
};

/// Prepares `input` for packing under `rule`, in place (graph and positions replaced):
///  - OuterRule::puncture and is_triangulated_sphere(input.graph) (whether or not the input named an outer
///    face): the vertex puncture_vertex() is removed with its position, its link becomes the outer face, and
///    its id is listed in `removed` (it is not in the embedding: it gets no circle, sends and receives no
///    packet); then as prepare_for_packing with the outer face given;
///  - otherwise exactly prepare_for_packing(input) (OuterRule::puncture only concerns spheres).
/// Throws GraphInputError as prepare_for_packing does, and for a puncture of a sphere of 3 vertices.
PreparedInput prepare_input(GraphInput& input, OuterRule rule);

}  // namespace laguerre::core
