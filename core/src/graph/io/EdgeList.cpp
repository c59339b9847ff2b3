// The edges format: reading (one `u v` per line, an optional `# outer:` directive) and writing.
#include <algorithm>
#include <optional>

#include "../detail/EmbeddingDetail.hpp"
#include "Formats.hpp"
#include "laguerre/core/graph/GraphIO.hpp"

namespace laguerre::core {

namespace detail {

TextGraph parse_edges_text(std::string_view data, const std::string& source) {
  TextGraph out;
  for (const TextLine& line : split_lines(data)) {
    if (parse_outer_directive(line, source, out) || line.content.empty()) continue;
    const auto tokens = split_blanks(line.content);
    add_edge_line(tokens, line, source, out);
  }
  if (out.edges.empty()) throw GraphInputError(source, 0, 0, "the input contains no edges.");
  check_duplicate_edges(out, source);
  return out;
}

GraphInput build_from_edges_text(const TextGraph& text, const std::string& source) {
  std::vector<std::uint64_t> ids;
  ids.reserve(2 * text.edges.size());
  for (auto [a, b] : text.edges) {
    ids.push_back(a);
    ids.push_back(b);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  auto index_of = [&](std::uint64_t id) -> std::optional<Vertex> {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it == ids.end() || *it != id) return std::nullopt;
    return static_cast<Vertex>(it - ids.begin());
  };
  const std::size_t n = ids.size();
  IndexEdges edges;
  edges.reserve(text.edges.size());
  for (auto [a, b] : text.edges) edges.emplace_back(*index_of(a), *index_of(b));
  check_connected(n, edges, ids, source);

  std::vector<Vertex> outer;
  if (!text.outer.empty()) {
    for (std::uint64_t id : text.outer) {
      const auto v = index_of(id);
      if (!v)
        throw GraphInputError(source, text.outer_line, 0,
                              "the '# outer:' directive lists vertex " + std::to_string(id) +
                                  ", which is on no edge.");
      outer.push_back(*v);
    }
    std::vector<std::pair<Vertex, Vertex>> sorted_edges;
    for (auto [a, b] : edges) sorted_edges.emplace_back(std::min(a, b), std::max(a, b));
    std::sort(sorted_edges.begin(), sorted_edges.end());
    for (std::size_t i = 0; i < outer.size(); ++i) {
      const Vertex a = outer[i], b = outer[(i + 1) % outer.size()];
      if (!std::binary_search(sorted_edges.begin(), sorted_edges.end(), std::pair{std::min(a, b), std::max(a, b)}))
        throw GraphInputError(source, text.outer_line, 0,
                              "the '# outer:' cycle uses " + edge_name(ids[a], ids[b]) +
                                  ", which is not an edge of the graph.");
    }
  }

  return embed_combinatorial(edges, ids, outer, source, text.outer_line);
}

}  // namespace detail

std::string write_edge_list(const PlanarGraph& g) {
  std::string out = "# laguerre edge list: " + std::to_string(g.num_vertices()) + " vertices, " +
                    std::to_string(g.num_edges()) + " edges\n";
  if (const std::string outer = detail::outer_ids(g, false); !outer.empty()) out += "# outer: " + outer + "\n";
  for (auto [a, b] : detail::sorted_id_edges(g)) out += std::to_string(a) + " " + std::to_string(b) + "\n";
  return out;
}

}  // namespace laguerre::core
