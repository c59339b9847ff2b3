// What the GraphML and DOT readers share: user ids from node names, and the checks and embedding of a
// graph given by named nodes.
#include <algorithm>
#include <cctype>
#include <numeric>
#include <set>

#include "../detail/EmbeddingDetail.hpp"
#include "Formats.hpp"

namespace laguerre::core::detail {

namespace {

/// User ids from node names: the names themselves if all are decimal integers; else the numbers after a
/// common non-numeric prefix (n0, n1, … as yEd and networkx write) if those are distinct; else 0, 1, …
/// in file order.
std::vector<std::uint64_t> ids_from_names(const std::vector<std::string>& names) {
  const std::size_t n = names.size();
  std::vector<std::uint64_t> ids(n);
  const auto try_suffix = [&](std::size_t prefix) {
    for (std::size_t i = 0; i < n; ++i) {
      if (names[i].size() <= prefix || (prefix > 0 && names[i].compare(0, prefix, names[0], 0, prefix) != 0)) return false;
      if (!parse_id(std::string_view(names[i]).substr(prefix), ids[i])) return false;
      if (names[i].size() > prefix + 1 && names[i][prefix] == '0') return false;  // "n01" and "n1" must differ
    }
    auto sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
  };
  if (n > 0) {
    if (try_suffix(0)) return ids;
    std::size_t prefix = 0;
    while (prefix < names[0].size() && !std::isdigit(static_cast<unsigned char>(names[0][prefix]))) ++prefix;
    if (prefix > 0 && try_suffix(prefix)) return ids;
  }
  std::iota(ids.begin(), ids.end(), std::uint64_t{0});
  return ids;
}

}  // namespace

std::string node_quoted(const std::string& name) { return "'" + name + "'"; }

/// Checks a named graph (simple, connected, positions all or none) and builds it like the text formats.
GraphInput build_named(const NamedGraph& ng, const std::string& source) {
  const std::size_t n = ng.names.size();
  if (n == 0) throw GraphInputError(source, 0, 0, "the graph has no nodes.");
  std::set<std::pair<std::size_t, std::size_t>> seen;
  for (std::size_t e = 0; e < ng.edges.size(); ++e) {
    const auto [a, b] = ng.edges[e];
    const std::string name = node_quoted(ng.names[a]) + " -- " + node_quoted(ng.names[b]);
    if (a == b)
      throw GraphInputError(source, 0, 0, "edge " + std::to_string(e + 1) + " (" + name + ") is a self-loop; the graph must be simple.");
    if (!seen.emplace(std::min(a, b), std::max(a, b)).second)
      throw GraphInputError(source, 0, 0, "edge " + std::to_string(e + 1) + " (" + name +
                                              ") repeats an earlier edge; the graph must be simple.");
  }
  // connectivity, isolated nodes included
  if (const std::size_t v = first_unreached_by_edges(n, ng.edges); v < n)
    throw GraphInputError(source, 0, 0, "the graph is not connected: node " + node_quoted(ng.names[v]) +
                                            " cannot be reached from node " + node_quoted(ng.names[0]) + ".");
  std::size_t with_position = 0;
  for (std::size_t v = 0; v < n; ++v) with_position += ng.x[v] && ng.y[v];
  if (with_position != 0 && with_position != n)
    for (std::size_t v = 0; v < n; ++v)
      if (!ng.x[v] || !ng.y[v])
        throw GraphInputError(source, 0, 0, "node " + node_quoted(ng.names[v]) +
                                                " has no position, but other nodes have one; give x and y for all nodes or none.");
  const std::vector<std::uint64_t> ids = ids_from_names(ng.names);
  TextGraph text;
  for (auto [a, b] : ng.edges) {
    text.edges.emplace_back(ids[a], ids[b]);
    text.edge_lines.push_back(0);
  }
  for (const std::string& name : ng.outer) {
    const auto it = std::find(ng.names.begin(), ng.names.end(), name);
    if (it == ng.names.end())
      throw GraphInputError(source, 0, 0, "the 'outer' attribute lists node " + node_quoted(name) + ", which is not declared.");
    text.outer.push_back(ids[static_cast<std::size_t>(it - ng.names.begin())]);
  }
  if (!text.outer.empty() && text.outer.size() < 3)
    throw GraphInputError(source, 0, 0, "the 'outer' attribute must list a cycle of at least 3 nodes.");
  if (with_position == 0) {
    if (n == 1) throw GraphInputError(source, 0, 0, "the input contains no edges.");
    return build_from_edges_text(text, source);
  }
  for (std::size_t v = 0; v < n; ++v) {
    text.vertex_ids.push_back(ids[v]);
    text.positions.push_back({*ng.x[v], *ng.y[v]});
  }
  return build_from_coords_text(text, source);
}

std::vector<std::string> split_outer(const std::string& value) {
  std::vector<std::string> out;
  for (std::string_view t : split_blanks(value)) out.emplace_back(t);
  return out;
}

std::optional<double> parse_position_value(const std::string& value, const std::string& what, const std::string& source) {
  double d = 0;
  if (!parse_coordinate(trim(value), d))
    throw GraphInputError(source, 0, 0, what + " is " + quoted(std::string_view(value)) + "; expected a finite number.");
  return d;
}

}  // namespace laguerre::core::detail
