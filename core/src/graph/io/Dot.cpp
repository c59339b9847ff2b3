// Graphviz DOT: reading through Boost.Graph's read_graphviz, and writing.
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/graphviz.hpp>
#include <cctype>
#include <sstream>

#include "Formats.hpp"
#include "laguerre/core/graph/GraphIO.hpp"

namespace laguerre::core {

namespace detail {

namespace {

/// Vertex properties read from DOT.
struct DotNode {
  std::string name, pos, x, y;
};

}  // namespace

GraphInput read_dot(std::string_view data, const std::string& source) {
  using DotGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, DotNode>;
  DotGraph g;
  std::string outer;
  boost::dynamic_properties dp(boost::ignore_other_properties);
  dp.property("node_id", boost::get(&DotNode::name, g));
  dp.property("pos", boost::get(&DotNode::pos, g));
  dp.property("x", boost::get(&DotNode::x, g));
  dp.property("y", boost::get(&DotNode::y, g));
  dp.property("outer", boost::ref_property_map<DotGraph*, std::string>(outer));
  try {
    std::istringstream in{std::string(data)};
    if (!boost::read_graphviz(in, g, dp, "node_id"))
      throw GraphInputError(source, 0, 0, "the DOT input could not be read.");
  } catch (const boost::directed_graph_error&) {
    throw GraphInputError(source, 0, 0, "the DOT input is a digraph; laguerre reads undirected graphs ('graph { a -- b }').");
  } catch (const boost::bad_graphviz_syntax& e) {
    throw GraphInputError(source, 0, 0, "DOT syntax error: " + std::string(e.what()) + ".");
  } catch (const boost::graph_exception& e) {
    throw GraphInputError(source, 0, 0, "the DOT input could not be read: " + std::string(e.what()) + ".");
  }
  NamedGraph ng;
  for (std::size_t v = 0; v < boost::num_vertices(g); ++v) {
    const DotNode& node = g[v];
    ng.names.push_back(node.name);
    ng.x.emplace_back();
    ng.y.emplace_back();
    if (!node.pos.empty()) {
      std::string pos = node.pos;
      if (!pos.empty() && pos.back() == '!') pos.pop_back();  // graphviz's "pinned" mark
      const auto comma = pos.find(',');
      double px = 0, py = 0;
      if (comma == std::string::npos || !parse_coordinate(trim(std::string_view(pos).substr(0, comma)), px) ||
          !parse_coordinate(trim(std::string_view(pos).substr(comma + 1)), py))
        throw GraphInputError(source, 0, 0, "node " + node_quoted(node.name) + " has pos=" + quoted(std::string_view(node.pos)) +
                                                "; expected \"x,y\" with two finite numbers.");
      ng.x.back() = px;
      ng.y.back() = py;
    }
    if (!node.x.empty()) ng.x.back() = parse_position_value(node.x, "the x of node " + node_quoted(node.name), source);
    if (!node.y.empty()) ng.y.back() = parse_position_value(node.y, "the y of node " + node_quoted(node.name), source);
  }
  for (auto [it, end] = boost::edges(g); it != end; ++it) ng.edges.emplace_back(boost::source(*it, g), boost::target(*it, g));
  ng.outer = split_outer(outer);
  return build_named(ng, source);
}

/// Whether the text starts (after a byte-order mark, blanks and comments) with a DOT graph keyword.
bool looks_like_dot(std::string_view data) {
  data = without_bom(data);
  std::size_t i = 0;
  for (;;) {
    while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
    if (data.substr(i, 2) == "//" || (i < data.size() && data[i] == '#')) {
      i = data.find('\n', i);
      if (i == std::string_view::npos) return false;
    } else if (data.substr(i, 2) == "/*") {
      i = data.find("*/", i + 2);
      if (i == std::string_view::npos) return false;
      i += 2;
    } else {
      break;
    }
  }
  std::size_t j = i;
  while (j < data.size() && std::isalpha(static_cast<unsigned char>(data[j]))) ++j;
  std::string word(data.substr(i, j - i));
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word == "graph" || word == "digraph" || word == "strict";
}

}  // namespace detail

std::string write_dot(const PlanarGraph& g, const std::vector<Point2>& positions) {
  detail::check_positions(g, positions, "write_dot");
  std::string out = "graph G {\n";
  if (const std::string outer = detail::outer_ids(g, !positions.empty()); !outer.empty())
    out += "  outer=\"" + outer + "\";\n";
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    out += "  " + std::to_string(g.id(v));
    if (!positions.empty()) out += " [pos=\"" + detail::exact_number(positions[v].x) + "," + detail::exact_number(positions[v].y) + "\"]";
    out += ";\n";
  }
  for (auto [a, b] : detail::sorted_id_edges(g)) out += "  " + std::to_string(a) + " -- " + std::to_string(b) + ";\n";
  return out + "}\n";
}

}  // namespace laguerre::core
