// The coords format: a straight-line drawing in a 'vertices' and an 'edges' section.
#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "../detail/EmbeddingDetail.hpp"
#include "Formats.hpp"

namespace laguerre::core::detail {

TextGraph parse_coords_text(std::string_view data, const std::string& source) {
  TextGraph out;
  enum class Section { none, vertices, edges } section = Section::none;
  std::unordered_map<std::uint64_t, std::size_t> declared;  // id -> line
  std::size_t vertices_line = 0;
  for (const TextLine& line : split_lines(data)) {
    if (parse_outer_directive(line, source, out) || line.content.empty()) continue;
    const auto tokens = split_blanks(line.content);
    if (tokens.size() == 1 && tokens[0] == "vertices") {
      if (section != Section::none)
        throw GraphInputError(source, line.number, 0,
                              "a second 'vertices' section starts here (the first is on line " +
                                  std::to_string(vertices_line) + "); declare all vertices in one section.");
      section = Section::vertices;
      vertices_line = line.number;
      continue;
    }
    if (tokens.size() == 1 && tokens[0] == "edges") {
      if (section != Section::vertices)
        throw GraphInputError(source, line.number, 0,
                              section == Section::none
                                  ? "the 'edges' section must follow a 'vertices' section."
                                  : "a second 'edges' section starts here; list all edges in one section.");
      section = Section::edges;
      continue;
    }
    switch (section) {
      case Section::none:
        throw GraphInputError(source, line.number, 0,
                              "expected the section header 'vertices' before any data, found " +
                                  quoted(line.content) + ".");
      case Section::vertices: {
        std::uint64_t id = 0;
        Point2 p;
        if (tokens.size() != 3 || !parse_id(tokens[0], id) || !parse_coordinate(tokens[1], p.x) ||
            !parse_coordinate(tokens[2], p.y))
          throw GraphInputError(source, line.number, 0,
                                "expected a vertex line 'id x y' (a non-negative integer id and two finite "
                                "numbers), found " + quoted(line.content) + ".");
        const auto [it, inserted] = declared.emplace(id, line.number);
        if (!inserted)
          throw GraphInputError(source, line.number, 0,
                                "vertex " + std::to_string(id) + " is declared twice (first on line " +
                                    std::to_string(it->second) + ").");
        out.vertex_ids.push_back(id);
        out.positions.push_back(p);
        break;
      }
      case Section::edges: {
        add_edge_line(tokens, line, source, out);
        const auto [a, b] = out.edges.back();
        for (std::uint64_t id : {a, b})
          if (!declared.contains(id))
            throw GraphInputError(source, line.number, 0,
                                  "edge " + edge_name(a, b) + " uses vertex " + std::to_string(id) +
                                      ", which the 'vertices' section does not declare.");
        break;
      }
    }
  }
  if (section == Section::none) throw GraphInputError(source, 0, 0, "the input has no 'vertices' section.");
  if (out.vertex_ids.empty()) throw GraphInputError(source, 0, 0, "the 'vertices' section declares no vertex.");
  check_duplicate_edges(out, source);
  return out;
}

GraphInput build_from_coords_text(const TextGraph& text, const std::string& source) {
  // Vertex indices in increasing id order, like the edges format.
  const std::size_t n = text.vertex_ids.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return text.vertex_ids[a] < text.vertex_ids[b]; });
  std::vector<std::uint64_t> ids(n);
  std::vector<Point2> positions(n);
  std::unordered_map<std::uint64_t, Vertex> index;
  for (std::size_t k = 0; k < n; ++k) {
    ids[k] = text.vertex_ids[order[k]];
    positions[k] = text.positions[order[k]];
    index.emplace(ids[k], static_cast<Vertex>(k));
  }
  IndexEdges edges;
  for (auto [a, b] : text.edges) edges.emplace_back(index.at(a), index.at(b));
  GraphInput result = graph_from_drawing(std::move(ids), std::move(positions), edges, source);
  if (text.outer.empty()) return result;
  const PlanarGraph& g = result.graph;
  std::vector<Vertex> outer;
  for (std::uint64_t id : text.outer) {
    const auto it = index.find(id);
    if (it == index.end())
      throw GraphInputError(source, text.outer_line, 0,
                            "the '# outer:' directive lists vertex " + std::to_string(id) + ", which is not declared.");
    outer.push_back(it->second);
  }
  const Dart d = g.find_dart(outer[0], outer[1]);
  if (d != none) {
    if (face_walk(g, d) == outer) {
      result.graph = g.with_outer_dart(d);
      return result;
    }
    std::vector<Vertex> reversed{outer[1], outer[0]};
    for (std::size_t k = outer.size() - 1; k >= 2; --k) reversed.push_back(outer[k]);
    if (face_walk(g, g.twin(d)) == reversed) {
      result.graph = g.with_outer_dart(g.twin(d));
      return result;
    }
  }
  throw GraphInputError(source, text.outer_line, 0, "the '# outer:' cycle is not a face of the drawing.");
}

}  // namespace laguerre::core::detail
