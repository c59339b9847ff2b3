// GraphML: reading through Boost.PropertyTree's XML parser, and writing.
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <map>
#include <sstream>

#include "Formats.hpp"
#include "laguerre/core/graph/GraphIO.hpp"

namespace laguerre::core {

namespace detail {

namespace {

/// Throws if elements nest deeper than graphml_max_depth. Boost.PropertyTree's XML parser recurses once
/// per level (50,000 levels overflow the stack), so this iterative scan of the tags (skipping comments,
/// CDATA, processing instructions, declarations and quoted attribute values) runs first. Markup it
/// cannot follow is left for the parser to report.
void check_nesting_depth(std::string_view data, const std::string& source) {
  std::size_t depth = 0, line = 1, i = 0;
  const auto advance_to = [&](std::size_t j) {
    line += static_cast<std::size_t>(std::count(data.begin() + static_cast<std::ptrdiff_t>(i),
                                                data.begin() + static_cast<std::ptrdiff_t>(j), '\n'));
    i = j;
  };
  const auto skip_past = [&](std::string_view end) {
    const std::size_t j = data.find(end, i);
    if (j == std::string_view::npos) return false;
    advance_to(j + end.size());
    return true;
  };
  for (;;) {
    const std::size_t open = data.find('<', i);
    if (open == std::string_view::npos) return;
    advance_to(open);
    const std::string_view rest = data.substr(i);
    if (rest.starts_with("<!--")) {
      if (!skip_past("-->")) return;
    } else if (rest.starts_with("<![CDATA[")) {
      if (!skip_past("]]>")) return;
    } else if (rest.starts_with("<?")) {
      if (!skip_past("?>")) return;
    } else if (rest.starts_with("<!")) {
      if (!skip_past(">")) return;
    } else {
      std::size_t j = i + 1;
      char quote = 0;
      for (; j < data.size(); ++j) {
        const char c = data[j];
        if (quote != 0) {
          if (c == quote) quote = 0;
        } else if (c == '"' || c == '\'') {
          quote = c;
        } else if (c == '>') {
          break;
        }
      }
      if (j >= data.size()) return;
      const bool closing = rest.starts_with("</"), self_closing = data[j - 1] == '/';
      const std::size_t tag_line = line;
      std::size_t name_end = i + 1;
      while (name_end < j && !std::isspace(static_cast<unsigned char>(data[name_end])) && data[name_end] != '/') ++name_end;
      const std::string name(data.substr(i + 1, name_end - i - 1));
      advance_to(j + 1);
      if (closing) {
        if (depth > 0) --depth;
      } else if (!self_closing && ++depth > graphml_max_depth) {
        throw GraphInputError(source, tag_line, 0,
                              "the <" + name + "> element here is nested " + std::to_string(depth) +
                                  " deep; laguerre reads GraphML nested at most " + std::to_string(graphml_max_depth) +
                                  " deep.");
      }
    }
  }
}

}  // namespace

GraphInput read_graphml(std::string_view data, const std::string& source) {
  namespace pt = boost::property_tree;
  check_nesting_depth(data, source);
  pt::ptree tree;
  {
    std::istringstream in{std::string(data)};
    try {
      pt::read_xml(in, tree, pt::xml_parser::no_comments);
    } catch (const pt::xml_parser_error& e) {
      throw GraphInputError(source, e.line(), 0, "the GraphML is not well-formed XML: " + e.message() + ".");
    }
  }
  const auto root = tree.get_child_optional("graphml");
  if (!root) throw GraphInputError(source, 0, 0, "the XML document has no <graphml> root element.");
  const auto attribute = [](const pt::ptree& node, const char* name) {
    return node.get_optional<std::string>(pt::ptree::path_type(std::string("<xmlattr>/") + name, '/'));
  };
  // Keys: id -> attr.name, for nodes and for the graph.
  std::map<std::string, std::string> node_keys, graph_keys;
  for (const auto& [tag, child] : *root) {
    if (tag != "key") continue;
    const auto id = attribute(child, "id");
    if (!id) throw GraphInputError(source, 0, 0, "a <key> element has no 'id' attribute.");
    const std::string domain = attribute(child, "for").value_or("all");
    const std::string name = attribute(child, "attr.name").value_or(*id);
    if (domain == "node" || domain == "all") node_keys[*id] = name;
    if (domain == "graph" || domain == "all") graph_keys[*id] = name;
  }
  std::vector<const pt::ptree*> graphs;
  for (const auto& [tag, child] : *root)
    if (tag == "graph") graphs.push_back(&child);
  if (graphs.size() != 1)
    throw GraphInputError(source, 0, 0, "the GraphML file contains " + std::to_string(graphs.size()) +
                                            " <graph> elements; laguerre reads files with exactly one.");
  const pt::ptree& graph = *graphs[0];
  const std::string edgedefault = attribute(graph, "edgedefault").value_or("undirected");
  if (edgedefault != "directed" && edgedefault != "undirected")
    throw GraphInputError(source, 0, 0, "the graph's edgedefault is " + quoted(std::string_view(edgedefault)) +
                                            "; expected 'undirected' (or 'directed', which laguerre rejects).");
  NamedGraph ng;
  std::map<std::string, std::size_t> index;
  for (const auto& [tag, child] : graph) {
    if (tag == "data") {
      const auto key = attribute(child, "key");
      if (key && graph_keys.count(*key) && graph_keys[*key] == "outer") ng.outer = split_outer(child.get_value<std::string>());
    }
    if (tag == "hyperedge") throw GraphInputError(source, 0, 0, "the graph has a <hyperedge>; laguerre reads simple graphs.");
    if (tag != "node") continue;
    const auto id = attribute(child, "id");
    if (!id) throw GraphInputError(source, 0, 0, "node " + std::to_string(ng.names.size() + 1) + " has no 'id' attribute.");
    if (!index.emplace(*id, ng.names.size()).second)
      throw GraphInputError(source, 0, 0, "node " + node_quoted(*id) + " is declared twice.");
    ng.names.push_back(*id);
    ng.x.emplace_back();
    ng.y.emplace_back();
    for (const auto& [inner, item] : child) {
      if (inner == "graph") throw GraphInputError(source, 0, 0, "node " + node_quoted(*id) + " contains a nested graph; laguerre reads flat graphs.");
      if (inner != "data") continue;
      const auto key = attribute(item, "key");
      if (!key || !node_keys.count(*key)) continue;
      const std::string& name = node_keys[*key];
      if (name == "x") ng.x.back() = parse_position_value(item.get_value<std::string>(), "the x of node " + node_quoted(*id), source);
      if (name == "y") ng.y.back() = parse_position_value(item.get_value<std::string>(), "the y of node " + node_quoted(*id), source);
    }
  }
  for (const auto& [tag, child] : graph) {
    if (tag != "edge") continue;
    const std::string number = "edge " + std::to_string(ng.edges.size() + 1);
    const auto s = attribute(child, "source"), t = attribute(child, "target");
    if (!s || !t) throw GraphInputError(source, 0, 0, number + " lacks a 'source' or 'target' attribute.");
    const std::string directed = attribute(child, "directed").value_or(edgedefault == "directed" ? "true" : "false");
    if (directed == "true")
      throw GraphInputError(source, 0, 0, number + " (" + node_quoted(*s) + " -> " + node_quoted(*t) +
                                              ") is directed; laguerre reads undirected graphs (edgedefault=\"undirected\").");
    for (const std::string* end : {&*s, &*t})
      if (!index.count(*end))
        throw GraphInputError(source, 0, 0, number + " (" + node_quoted(*s) + " -- " + node_quoted(*t) + ") refers to node " +
                                                node_quoted(*end) + ", which is not declared.");
    ng.edges.emplace_back(index[*s], index[*t]);
  }
  return build_named(ng, source);
}

/// Whether the text starts (after a byte-order mark and blanks) with an XML or GraphML tag.
bool looks_like_xml(std::string_view data) {
  data = without_bom(data);
  const std::size_t start = data.find_first_not_of(" \t\n\r\v\f");
  if (start == std::string_view::npos) return false;
  const std::string_view rest = data.substr(start);
  return rest.starts_with("<?xml") || rest.starts_with("<graphml") || rest.starts_with("<!--");
}

}  // namespace detail

std::string write_graphml(const PlanarGraph& g, const std::vector<Point2>& positions) {
  detail::check_positions(g, positions, "write_graphml");
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<graphml xmlns=\"http://graphml.graphdrawing.org/xmlns\">\n"
      "  <key id=\"outer\" for=\"graph\" attr.name=\"outer\" attr.type=\"string\"/>\n";
  if (!positions.empty())
    out += "  <key id=\"x\" for=\"node\" attr.name=\"x\" attr.type=\"double\"/>\n"
           "  <key id=\"y\" for=\"node\" attr.name=\"y\" attr.type=\"double\"/>\n";
  out += "  <graph id=\"G\" edgedefault=\"undirected\">\n";
  if (const std::string outer = detail::outer_ids(g, !positions.empty()); !outer.empty())
    out += "    <data key=\"outer\">" + outer + "</data>\n";
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    out += "    <node id=\"" + std::to_string(g.id(v)) + "\"";
    if (positions.empty()) {
      out += "/>\n";
      continue;
    }
    out += "><data key=\"x\">" + detail::exact_number(positions[v].x) + "</data><data key=\"y\">" +
           detail::exact_number(positions[v].y) + "</data></node>\n";
  }
  for (auto [a, b] : detail::sorted_id_edges(g))
    out += "    <edge source=\"" + std::to_string(a) + "\" target=\"" + std::to_string(b) + "\"/>\n";
  return out + "  </graph>\n</graphml>\n";
}

}  // namespace laguerre::core
