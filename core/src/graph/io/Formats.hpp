#pragma once
// The readers and writers of each graph format (one .cpp each), as GraphIO.cpp dispatches to them,
// and what several of them share.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "Text.hpp"
#include "laguerre/core/graph/Embedding.hpp"

namespace laguerre::core::detail {

// edges (EdgeList.cpp)
TextGraph parse_edges_text(std::string_view data, const std::string& source);
/// Vertex indices in increasing id order; embedded by Boyer–Myrvold (embed_combinatorial).
GraphInput build_from_edges_text(const TextGraph& text, const std::string& source);

// coords (Coords.cpp)
TextGraph parse_coords_text(std::string_view data, const std::string& source);
/// Vertex indices in increasing id order; embedded by graph_from_drawing.
GraphInput build_from_coords_text(const TextGraph& text, const std::string& source);

// planar_code (PlanarCode.cpp)
inline constexpr std::string_view planar_code_magic = ">>planar_code";
std::vector<GraphInput> read_planar_code(std::string_view data, const std::string& source);

// GraphML (GraphML.cpp) and DOT (Dot.cpp)
GraphInput read_graphml(std::string_view data, const std::string& source);
GraphInput read_dot(std::string_view data, const std::string& source);
/// Whether the text starts (after a byte-order mark and blanks) with an XML or GraphML tag.
bool looks_like_xml(std::string_view data);
/// Whether the text starts (after a byte-order mark, blanks and comments) with a DOT graph keyword.
bool looks_like_dot(std::string_view data);

/// A graph read from GraphML or DOT, with the file's node names, before ids are assigned (NamedGraph.cpp).
struct NamedGraph {
  std::vector<std::string> names;                          // node names, in file order
  std::vector<std::optional<double>> x, y;                 // per node, if given
  std::vector<std::pair<std::size_t, std::size_t>> edges;  // node indices, in file order
  std::vector<std::string> outer;                          // the laguerre 'outer' attribute, as node names
};

/// Checks a named graph (simple, connected, positions all or none) and builds it like the text formats.
GraphInput build_named(const NamedGraph& ng, const std::string& source);
/// A node name in messages: 'name'.
std::string node_quoted(const std::string& name);
/// The node names of an `outer` attribute.
std::vector<std::string> split_outer(const std::string& value);
/// A position value, or GraphInputError naming `what`.
std::optional<double> parse_position_value(const std::string& value, const std::string& what, const std::string& source);

// Shared by the writers (GraphIO.cpp).
/// Edges by user ids (smaller first, sorted).
std::vector<std::pair<std::uint64_t, std::uint64_t>> sorted_id_edges(const PlanarGraph& g);
/// 17 significant digits (round-trips every double).
std::string exact_number(double value);
/// Precondition: `positions` is empty or has one entry per vertex.
void check_positions(const PlanarGraph& g, const std::vector<Point2>& positions, const char* writer);
/// The user ids of boundary_cycle(), separated by spaces, if the readers honour it as the outer face
/// (of a drawing when `drawn`, else of the graph alone); else "".
std::string outer_ids(const PlanarGraph& g, bool drawn);

}  // namespace laguerre::core::detail
