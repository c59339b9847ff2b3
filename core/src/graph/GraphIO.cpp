// Graph formats: detecting and naming them, reading a file or a string through the reader of its format
// (io/*.cpp), and what the writers share.
#include "laguerre/core/graph/GraphIO.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>

#include "io/Formats.hpp"
#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/graph/GraphKind.hpp"

namespace laguerre::core {

namespace {

/// Every format with its name, in the order messages list them.
constexpr std::array<std::pair<GraphFormat, std::string_view>, 6> format_names{{
    {GraphFormat::automatic, "automatic"},
    {GraphFormat::edges, "edges"},
    {GraphFormat::planar_code, "planar_code"},
    {GraphFormat::coords, "coords"},
    {GraphFormat::graphml, "graphml"},
    {GraphFormat::dot, "dot"},
}};

GraphFormat detect_format(std::string_view data) {
  if (data.substr(0, detail::planar_code_magic.size()) == detail::planar_code_magic) return GraphFormat::planar_code;
  if (detail::looks_like_xml(data)) return GraphFormat::graphml;
  if (detail::looks_like_dot(data)) return GraphFormat::dot;
  for (const detail::TextLine& line : detail::split_lines(data))
    if (line.content == "vertices") return GraphFormat::coords;
  return GraphFormat::edges;
}

std::vector<GraphInput> one(GraphInput input) {
  std::vector<GraphInput> out;
  out.push_back(std::move(input));
  return out;
}

}  // namespace

GraphFormat parse_graph_format(std::string_view name) {
  const auto named = [&](const auto& entry) { return entry.second == name; };
  if (const auto it = std::find_if(format_names.begin(), format_names.end(), named); it != format_names.end())
    return it->first;
  std::string expected;
  for (const auto& entry : format_names) expected += (expected.empty() ? "" : ", ") + std::string(entry.second);
  throw GraphInputError("format", 0, 0, "unknown graph format '" + std::string(name) + "'; expected one of " + expected + ".");
}

std::string_view to_string(GraphFormat format) {
  const auto it = std::find_if(format_names.begin(), format_names.end(), [&](const auto& e) { return e.first == format; });
  return it == format_names.end() ? std::string_view("unknown") : it->second;
}

std::vector<GraphInput> read_graphs_from_string(std::string_view data, const std::string& source_name,
                                                GraphFormat format) {
  if (format == GraphFormat::automatic) format = detect_format(data);
  switch (format) {
    case GraphFormat::planar_code: return detail::read_planar_code(data, source_name);
    case GraphFormat::coords:
      return one(detail::build_from_coords_text(detail::parse_coords_text(data, source_name), source_name));
    case GraphFormat::graphml: return one(detail::read_graphml(data, source_name));
    case GraphFormat::dot: return one(detail::read_dot(data, source_name));
    case GraphFormat::edges:
    case GraphFormat::automatic: break;
  }
  return one(detail::build_from_edges_text(detail::parse_edges_text(data, source_name), source_name));
}

std::vector<GraphInput> read_graphs(const std::string& path, GraphFormat format) {
  std::string data;
  try {
    data = read_input_file(path, "graph file");
  } catch (const InputError& e) {  // the same sentence, as the graph error callers catch
    throw GraphInputError(e.source(), e.line(), 0, e.message());
  }
  return read_graphs_from_string(data, path, format);
}

namespace detail {

/// Edges by user ids (smaller first, sorted), as the edge-list writer lists them.
std::vector<std::pair<std::uint64_t, std::uint64_t>> sorted_id_edges(const PlanarGraph& g) {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  for (Dart d = 0; d < g.num_darts(); ++d)
    if (g.id(g.tail(d)) < g.id(g.head(d))) edges.emplace_back(g.id(g.tail(d)), g.id(g.head(d)));
  std::sort(edges.begin(), edges.end());
  return edges;
}

std::string exact_number(double value) {
  std::ostringstream s;
  s.precision(17);  // round-trips every double
  s << value;
  return s.str();
}

void check_positions(const PlanarGraph& g, const std::vector<Point2>& positions, const char* writer) {
  LAGUERRE_PRECONDITION(positions.empty() || positions.size() == g.num_vertices(),
                        std::string(writer) + " needs no positions or one per vertex, got " +
                            std::to_string(positions.size()) + " for " + std::to_string(g.num_vertices()) + " vertices.");
}

// The readers honour an outer face only if it is a simple cycle of at least 3 vertices that is a face of
// the embedding they compute: of the drawing (any face of it), or of Boyer–Myrvold's embedding with an
// apex joined to the cycle, which is forced to have that face when the graph is 3-connected (Whitney) or
// a triangulated disc (graph and apex then form a triangulation of the sphere). A boundary walk that
// repeats a vertex (a path, a pendant vertex on the outer face), a single edge, or a cycle of a graph of
// another kind (whose face Boyer–Myrvold may not keep) is left out, so that what is written reads back.
std::string outer_ids(const PlanarGraph& g, bool drawn) {
  if (g.outer_face() == none) return {};
  const std::vector<Vertex> cycle = g.boundary_cycle();
  std::vector<Vertex> sorted = cycle;
  std::sort(sorted.begin(), sorted.end());
  if (cycle.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};
  if (!drawn && !g.inner_faces_are_triangles() && !is_three_connected(g)) return {};
  std::string out;
  for (Vertex v : cycle) out += (out.empty() ? "" : " ") + std::to_string(g.id(v));
  return out;
}

}  // namespace detail

}  // namespace laguerre::core
