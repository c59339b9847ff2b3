#pragma once
// The pieces of Embedding.cpp the readers share: building a PlanarGraph with input errors, the
// connectivity check, face walks, and the Boyer–Myrvold embedding with an optional outer cycle.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "Connectivity.hpp"
#include "laguerre/core/graph/Embedding.hpp"

namespace laguerre::core::detail {

using IndexEdges = std::vector<std::pair<Vertex, Vertex>>;

/// "a-b", how messages name an edge by user ids.
inline std::string edge_name(std::uint64_t a, std::uint64_t b) { return std::to_string(a) + "-" + std::to_string(b); }

/// Throws GraphInputError (naming user ids) unless the graph on n ≥ 1 vertices is connected.
void check_connected(std::size_t n, const IndexEdges& edges, const std::vector<std::uint64_t>& ids,
                     const std::string& source);

/// PlanarGraph::from_rotation, its InputError turned into a GraphInputError.
PlanarGraph build_graph(std::vector<std::vector<Vertex>> rotation, std::vector<std::uint64_t> ids,
                        const std::string& source, std::size_t graph_index, Dart outer = none);

/// The vertex cycle walked by the face to the left of dart d, starting at tail(d).
std::vector<Vertex> face_walk(const PlanarGraph& g, Dart d);

/// Embeds the connected simple graph on ids.size() vertices by Boyer–Myrvold. With a non-empty `outer`
/// (a cycle of the graph, as vertex indices) an apex joined to it forces it to bound a face, which
/// becomes the outer face in the order given (`outer_given`); errors about it name `outer_line`.
/// Throws GraphInputError if the graph is not planar or no embedding has `outer` as a face.
GraphInput embed_combinatorial(const IndexEdges& edges, const std::vector<std::uint64_t>& ids,
                               const std::vector<Vertex>& outer, const std::string& source, std::size_t outer_line);

}  // namespace laguerre::core::detail
