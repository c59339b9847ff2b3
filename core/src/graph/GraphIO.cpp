#include "laguerre/core/graph/GraphIO.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boyer_myrvold_planar_test.hpp>
#include <boost/graph/graphviz.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace laguerre::core {

namespace {

constexpr std::string_view planar_code_magic = ">>planar_code";

// ---------------------------------------------------------------------------------------------------
// Text scanning.

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_blanks(std::string_view s) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != '\r') ++i;
    if (i > start) tokens.push_back(s.substr(start, i - start));
  }
  return tokens;
}

bool parse_id(std::string_view token, std::uint64_t& out) {
  if (token.empty() || token.front() < '0' || token.front() > '9') return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size();
}

bool parse_coordinate(std::string_view token, double& out) {
  if (token.empty()) return false;
  if (token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(out);
}

/// One line of a text input: its number, the content before any comment, and the comment.
struct TextLine {
  std::size_t number = 0;
  std::string_view content;
  std::string_view comment;  // text after '#', empty if none
  bool has_comment = false;
};

std::vector<TextLine> split_lines(std::string_view data) {
  std::vector<TextLine> lines;
  std::size_t number = 0, start = 0;
  while (start <= data.size()) {
    std::size_t end = data.find('\n', start);
    if (end == std::string_view::npos) end = data.size();
    std::string_view raw = data.substr(start, end - start);
    ++number;
    TextLine line;
    line.number = number;
    const std::size_t hash = raw.find('#');
    if (hash != std::string_view::npos) {
      line.has_comment = true;
      line.comment = trim(raw.substr(hash + 1));
      raw = raw.substr(0, hash);
    }
    line.content = trim(raw);
    lines.push_back(line);
    if (end == data.size()) break;
    start = end + 1;
  }
  return lines;
}

std::string quoted(std::string_view s) {
  constexpr std::size_t limit = 60;
  std::string out = "'";
  out += s.size() > limit ? std::string(s.substr(0, limit)) + "..." : std::string(s);
  return out + "'";
}

std::string edge_name(std::uint64_t a, std::uint64_t b) { return std::to_string(a) + "-" + std::to_string(b); }

/// The content of a text file in the edges or coords format, before any graph is built.
struct TextGraph {
  std::vector<std::uint64_t> vertex_ids;  // coords only, declaration order
  std::vector<Point2> positions;          // coords only
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  std::vector<std::size_t> edge_lines;
  std::vector<std::uint64_t> outer;
  std::size_t outer_line = 0;
};

/// Parses a `# outer:` directive if `line` is one; returns whether it was.
bool parse_outer_directive(const TextLine& line, const std::string& source, TextGraph& out) {
  if (!line.has_comment || !line.content.empty()) return false;
  constexpr std::string_view key = "outer:";
  if (line.comment.substr(0, key.size()) != key) return false;
  if (out.outer_line != 0)
    throw GraphInputError(source, line.number, 0,
                          "a second '# outer:' directive was found (the first is on line " +
                              std::to_string(out.outer_line) + "); give the outer face once.");
  const auto tokens = split_blanks(line.comment.substr(key.size()));
  for (std::string_view t : tokens) {
    std::uint64_t id = 0;
    if (!parse_id(t, id))
      throw GraphInputError(source, line.number, 0,
                            "the '# outer:' directive expects non-negative integer vertex ids, found " + quoted(t) +
                                ".");
    out.outer.push_back(id);
  }
  if (out.outer.size() < 3)
    throw GraphInputError(source, line.number, 0,
                          "the '# outer:' directive must list a cycle of at least 3 vertices, found " +
                              std::to_string(out.outer.size()) + ".");
  auto sorted = out.outer;
  std::sort(sorted.begin(), sorted.end());
  const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
  if (dup != sorted.end())
    throw GraphInputError(source, line.number, 0,
                          "the '# outer:' directive lists vertex " + std::to_string(*dup) +
                              " twice; the outer face must be a simple cycle.");
  out.outer_line = line.number;
  return true;
}

void add_edge_line(std::span<const std::string_view> tokens, const TextLine& line, const std::string& source,
                   TextGraph& out) {
  std::uint64_t a = 0, b = 0;
  if (tokens.size() != 2 || !parse_id(tokens[0], a) || !parse_id(tokens[1], b))
    throw GraphInputError(source, line.number, 0,
                          "expected two non-negative integer vertex ids, found " + quoted(line.content) + ".");
  if (a == b)
    throw GraphInputError(source, line.number, 0,
                          "edge " + edge_name(a, b) + " is a self-loop; the graph must be simple.");
  out.edges.emplace_back(a, b);
  out.edge_lines.push_back(line.number);
}

/// Rejects repeated edges (u v and v u are the same edge), naming both lines.
void check_duplicate_edges(const TextGraph& text, const std::string& source) {
  std::vector<std::size_t> order(text.edges.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t i) {
    auto [a, b] = text.edges[i];
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return key(i) < key(j); });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (key(order[k]) == key(order[k - 1])) {
      const std::size_t first = std::min(order[k], order[k - 1]), second = std::max(order[k], order[k - 1]);
      throw GraphInputError(source, text.edge_lines[second], 0,
                            "edge " + edge_name(text.edges[second].first, text.edges[second].second) +
                                " is listed twice (first on line " + std::to_string(text.edge_lines[first]) +
                                "); the graph must be simple.");
    }
}

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

// ---------------------------------------------------------------------------------------------------
// Graph building.

using IndexEdges = std::vector<std::pair<Vertex, Vertex>>;

/// Throws unless the graph on n vertices is connected.
void check_connected(std::size_t n, const IndexEdges& edges, const std::vector<std::uint64_t>& ids,
                     const std::string& source) {
  std::vector<std::vector<Vertex>> adjacency(n);
  for (auto [a, b] : edges) {
    adjacency[a].push_back(b);
    adjacency[b].push_back(a);
  }
  std::vector<std::uint8_t> seen(n, 0);
  std::vector<Vertex> stack{0};
  seen[0] = 1;
  while (!stack.empty()) {
    const Vertex v = stack.back();
    stack.pop_back();
    for (Vertex w : adjacency[v])
      if (!seen[w]) {
        seen[w] = 1;
        stack.push_back(w);
      }
  }
  for (std::size_t v = 0; v < n; ++v)
    if (!seen[v])
      throw GraphInputError(source, 0, 0,
                            "the graph is not connected: vertex " + std::to_string(ids[v]) +
                                " cannot be reached from vertex " + std::to_string(ids[0]) + ".");
}

/// Wraps PlanarGraph::from_rotation, turning its std::invalid_argument into a GraphInputError.
PlanarGraph build_graph(std::vector<std::vector<Vertex>> rotation, std::vector<std::uint64_t> ids,
                        const std::string& source, std::size_t graph_index, Dart outer = none) {
  try {
    return PlanarGraph::from_rotation(std::move(rotation), std::move(ids), outer);
  } catch (const std::invalid_argument& e) {
    std::string message = e.what();
    if (!message.empty() && std::isupper(static_cast<unsigned char>(message[0])))
      message[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(message[0])));
    throw GraphInputError(source, 0, graph_index, message);
  }
}

/// A planar rotation system of the graph by Boyer–Myrvold, or nullopt if the graph is not planar.
std::optional<std::vector<std::vector<Vertex>>> boyer_myrvold_rotation(std::size_t n, const IndexEdges& edges) {
  using BoostGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS,
                                           boost::property<boost::vertex_index_t, int>,
                                           boost::property<boost::edge_index_t, int>>;
  using BoostEdge = boost::graph_traits<BoostGraph>::edge_descriptor;
  BoostGraph bg(n);
  for (auto [a, b] : edges) boost::add_edge(a, b, bg);
  auto edge_index = boost::get(boost::edge_index, bg);
  int next_index = 0;
  for (auto [it, end] = boost::edges(bg); it != end; ++it) boost::put(edge_index, *it, next_index++);
  std::vector<std::vector<BoostEdge>> storage(n);
  auto embedding = boost::make_iterator_property_map(storage.begin(), boost::get(boost::vertex_index, bg));
  const bool planar = boost::boyer_myrvold_planarity_test(boost::boyer_myrvold_params::graph = bg,
                                                          boost::boyer_myrvold_params::embedding = embedding);
  if (!planar) return std::nullopt;
  std::vector<std::vector<Vertex>> rotation(n);
  for (std::size_t v = 0; v < n; ++v) {
    rotation[v].reserve(storage[v].size());
    for (const BoostEdge& e : storage[v]) {
      const auto s = boost::source(e, bg), t = boost::target(e, bg);
      rotation[v].push_back(static_cast<Vertex>(s == v ? t : s));
    }
  }
  return rotation;
}

/// The vertex cycle walked by the face to the left of dart d, starting at tail(d).
std::vector<Vertex> face_walk(const PlanarGraph& g, Dart d) {
  std::vector<Vertex> walk;
  Dart e = d;
  do {
    walk.push_back(g.tail(e));
    e = g.next_in_face(e);
  } while (e != d);
  return walk;
}

void mirror(std::vector<std::vector<Vertex>>& rotation) {
  for (auto& list : rotation) std::reverse(list.begin(), list.end());
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

  GraphInput result;
  result.name = source;
  if (outer.empty()) {
    auto rotation = boyer_myrvold_rotation(n, edges);
    if (!rotation)
      throw GraphInputError(source, 0, 0,
                            "the graph is not planar (the Boyer-Myrvold test found a Kuratowski subgraph).");
    result.graph = build_graph(std::move(*rotation), ids, source, 0);
    return result;
  }
  // Apex trick: a vertex joined to the whole outer cycle forces the cycle to bound a face.
  IndexEdges with_apex = edges;
  const auto apex = static_cast<Vertex>(n);
  for (Vertex v : outer) with_apex.emplace_back(apex, v);
  auto rotation = boyer_myrvold_rotation(n + 1, with_apex);
  if (!rotation) {
    if (!boyer_myrvold_rotation(n, edges))
      throw GraphInputError(source, 0, 0,
                            "the graph is not planar (the Boyer-Myrvold test found a Kuratowski subgraph).");
    throw GraphInputError(source, text.outer_line, 0,
                          "the graph has no planar embedding in which the '# outer:' cycle bounds a face.");
  }
  rotation->pop_back();
  for (auto& list : *rotation) std::erase(list, apex);
  for (int attempt = 0; attempt < 2; ++attempt) {
    PlanarGraph g = build_graph(*rotation, ids, source, 0);
    const Dart d = g.find_dart(outer[0], outer[1]);
    if (face_walk(g, d) == outer) {
      result.graph = g.with_outer_dart(d);
      result.outer_given = true;
      return result;
    }
    mirror(*rotation);  // the face may be there with the other orientation
  }
  throw GraphInputError(source, text.outer_line, 0,
                        "the '# outer:' cycle does not bound a face of the embedding found; the graph must be "
                        "3-connected or a triangulated disc for the outer face to determine the embedding.");
}

/// Half-plane of direction p − o: 0 for angles in [0, π), 1 for [π, 2π). Exact.
int half_plane(Point2 o, Point2 p) { return (p.y > o.y || (p.y == o.y && p.x > o.x)) ? 0 : 1; }

/// Strict counter-clockwise angular order of directions a − o, b − o starting from the positive x axis.
bool angle_less(Point2 o, Point2 a, Point2 b) {
  const int ha = half_plane(o, a), hb = half_plane(o, b);
  if (ha != hb) return ha < hb;
  return orientation(o, a, b) == Sign::positive;
}

std::string point_text(Point2 p) {
  std::ostringstream s;
  s.precision(17);
  s << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

void check_no_crossings(const std::vector<Point2>& pos, const IndexEdges& edges,
                        const std::vector<std::uint64_t>& ids, const std::string& source) {
  struct Box {
    double xmin, xmax, ymin, ymax;
  };
  std::vector<Box> boxes(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Point2 a = pos[edges[i].first], b = pos[edges[i].second];
    boxes[i] = {std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y)};
  }
  std::vector<std::size_t> order(edges.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return std::pair{boxes[i].xmin, i} < std::pair{boxes[j].xmin, j};
  });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    for (std::size_t l = k + 1; l < order.size() && boxes[order[l]].xmin <= boxes[i].xmax; ++l) {
      const std::size_t j = order[l];
      if (boxes[j].ymin > boxes[i].ymax || boxes[i].ymin > boxes[j].ymax) continue;
      const auto [a, b] = edges[i];
      const auto [c, d] = edges[j];
      if (a == c || a == d || b == c || b == d) continue;  // overlaps at a shared end are found by the angle sort
      if (segments_intersect(pos[a], pos[b], pos[c], pos[d]))
        throw GraphInputError(source, 0, 0,
                              "the drawing is not plane: edges " + edge_name(ids[a], ids[b]) + " and " +
                                  edge_name(ids[c], ids[d]) + " cross or touch.");
    }
  }
}

}  // namespace

GraphInput graph_from_drawing(std::vector<std::uint64_t> ids, std::vector<Point2> positions, const IndexEdges& edges,
                              const std::string& source, bool check_crossings) {
  const std::size_t n = ids.size();
  if (positions.size() != n)
    throw std::invalid_argument("graph_from_drawing needs one position per id, got " +
                                std::to_string(positions.size()) + " positions for " + std::to_string(n) + " ids.");
  if (n == 0) throw GraphInputError(source, 0, 0, "the graph has no vertices.");
  for (std::size_t v = 0; v < n; ++v)
    if (!std::isfinite(positions[v].x) || !std::isfinite(positions[v].y))
      throw GraphInputError(source, 0, 0, "vertex " + std::to_string(ids[v]) + " has a non-finite position.");
  {
    std::vector<Vertex> order(n);
    std::iota(order.begin(), order.end(), Vertex{0});
    auto key = [&](Vertex v) { return std::pair{positions[v].x, positions[v].y}; };
    std::sort(order.begin(), order.end(),
              [&](Vertex a, Vertex b) { return std::pair{key(a), a} < std::pair{key(b), b}; });
    for (std::size_t k = 1; k < n; ++k)
      if (key(order[k]) == key(order[k - 1]))
        throw GraphInputError(source, 0, 0,
                              "vertices " + std::to_string(ids[order[k - 1]]) + " and " + std::to_string(ids[order[k]]) +
                                  " are both at " + point_text(positions[order[k]]) + ".");
  }
  std::vector<std::vector<Vertex>> rotation(n);
  for (auto [a, b] : edges) {
    if (a >= n || b >= n) throw std::invalid_argument("graph_from_drawing: an edge has a vertex index out of range.");
    if (a == b)
      throw GraphInputError(source, 0, 0, "edge " + edge_name(ids[a], ids[b]) + " is a self-loop; the graph must be simple.");
    rotation[a].push_back(b);
    rotation[b].push_back(a);
  }
  for (Vertex v = 0; v < n; ++v) {
    auto& list = rotation[v];
    const Point2 o = positions[v];
    std::sort(list.begin(), list.end(),
              [&](Vertex a, Vertex b) { return angle_less(o, positions[a], positions[b]); });
    for (std::size_t k = 0; k < list.size(); ++k) {
      const Vertex a = list[k], b = list[(k + 1) % list.size()];
      if (list.size() > 1 && !angle_less(o, positions[a], positions[b]) && !angle_less(o, positions[b], positions[a])) {
        if (a == b)
          throw GraphInputError(source, 0, 0,
                                "edge " + edge_name(ids[v], ids[a]) + " is listed twice; the graph must be simple.");
        throw GraphInputError(source, 0, 0,
                              "the drawing is not plane: edges " + edge_name(ids[v], ids[a]) + " and " +
                                  edge_name(ids[v], ids[b]) + " overlap.");
      }
    }
  }
  check_connected(n, edges, ids, source);
  if (check_crossings) check_no_crossings(positions, edges, ids, source);

  // The unbounded face: at the lexicographically smallest position v, it is the angular sector from the
  // last neighbour in the upper half-plane [0, π) counter-clockwise to the next one (it contains the
  // direction π). The face to the left of v→w is the sector from w counter-clockwise to the next neighbour.
  Dart outer = none;
  if (!edges.empty()) {
    Vertex v = 0;
    for (Vertex u = 1; u < n; ++u)
      if (std::pair{positions[u].x, positions[u].y} < std::pair{positions[v].x, positions[v].y}) v = u;
    const auto& list = rotation[v];
    std::size_t upper = 0;
    while (upper < list.size() && half_plane(positions[v], positions[list[upper]]) == 0) ++upper;
    const std::size_t pick = upper > 0 ? upper - 1 : list.size() - 1;
    std::size_t first = 0;
    for (Vertex u = 0; u < v; ++u) first += rotation[u].size();
    outer = static_cast<Dart>(first + pick);
  }
  GraphInput result;
  result.graph = build_graph(std::move(rotation), std::move(ids), source, 0, outer);
  result.positions = std::move(positions);
  result.name = source;
  result.outer_given = true;
  return result;
}

namespace {

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

// ---------------------------------------------------------------------------------------------------
// planar_code.

std::vector<GraphInput> read_planar_code(std::string_view data, const std::string& source) {
  bool big_endian = false;
  std::size_t pos = 0;
  if (data.substr(0, planar_code_magic.size()) == planar_code_magic) {
    for (std::string_view header : {">>planar_code<<", ">>planar_code le<<", ">>planar_code be<<"})
      if (data.substr(0, header.size()) == header) {
        pos = header.size();
        big_endian = header == ">>planar_code be<<";
      }
    if (pos == 0)
      throw GraphInputError(source, 0, 0,
                            "the planar_code header is not one of '>>planar_code<<', '>>planar_code le<<' and "
                            "'>>planar_code be<<'.");
  }
  std::vector<GraphInput> graphs;
  std::size_t index = 0;
  while (pos < data.size()) {
    ++index;
    const std::string name = source + "#" + std::to_string(index);
    bool wide = false;
    std::size_t n = 0, done = 0;
    auto truncated = [&]() {
      std::string where = n == 0 ? "while reading its number of vertices"
                                 : "after the neighbours of " + std::to_string(done) + " of its " +
                                       std::to_string(n) + " vertices";
      return GraphInputError(source, 0, index,
                             "the planar_code data ends in the middle of graph " + std::to_string(index) + " (" +
                                 where + ").");
    };
    auto byte_at = [&](std::size_t i) { return static_cast<unsigned>(static_cast<unsigned char>(data[i])); };
    auto read_entry = [&]() -> std::size_t {
      if (!wide) {
        if (pos >= data.size()) throw truncated();
        return byte_at(pos++);
      }
      if (pos + 2 > data.size()) throw truncated();
      const unsigned lo = byte_at(big_endian ? pos + 1 : pos), hi = byte_at(big_endian ? pos : pos + 1);
      pos += 2;
      return lo | (hi << 8);
    };
    n = read_entry();
    if (n == 0) {
      wide = true;
      n = read_entry();
      if (n == 0)
        throw GraphInputError(source, 0, index, "graph " + std::to_string(index) + " has no vertices.");
    }
    std::vector<std::vector<Vertex>> rotation(n);
    for (std::size_t v = 0; v < n; ++v) {
      auto& list = rotation[v];
      const std::size_t vertex = v + 1;  // plantri's number of the vertex being read
      for (;;) {
        const std::size_t w = read_entry();
        if (w == 0) break;
        if (w > n)
          throw GraphInputError(source, 0, index,
                                "vertex " + std::to_string(vertex) + " lists neighbour " + std::to_string(w) +
                                    ", outside 1.." + std::to_string(n) + ".");
        if (w == vertex)
          throw GraphInputError(source, 0, index,
                                "vertex " + std::to_string(vertex) + " lists itself as a neighbour; the graph must be simple.");
        list.push_back(static_cast<Vertex>(w - 1));
      }
      std::reverse(list.begin(), list.end());  // plantri lists clockwise, we store counter-clockwise
      done = vertex;
    }
    // Symmetry and simplicity, with messages in plantri's numbering.
    std::vector<std::pair<Vertex, Vertex>> darts;
    for (Vertex v = 0; v < n; ++v)
      for (Vertex w : rotation[v]) darts.emplace_back(v, w);
    std::sort(darts.begin(), darts.end());
    for (std::size_t k = 0; k < darts.size(); ++k) {
      const auto [v, w] = darts[k];
      if (k > 0 && darts[k - 1] == darts[k])
        throw GraphInputError(source, 0, index,
                              "vertex " + std::to_string(v + 1) + " lists neighbour " + std::to_string(w + 1) +
                                  " twice; the graph must be simple.");
      if (!std::binary_search(darts.begin(), darts.end(), std::pair{w, v}))
        throw GraphInputError(source, 0, index,
                              "the planar_code is inconsistent: vertex " + std::to_string(v + 1) + " lists " +
                                  std::to_string(w + 1) + " as a neighbour but vertex " + std::to_string(w + 1) +
                                  " does not list " + std::to_string(v + 1) + ".");
    }
    std::vector<std::uint64_t> ids(n);
    std::iota(ids.begin(), ids.end(), std::uint64_t{1});
    GraphInput input;
    input.graph = build_graph(std::move(rotation), std::move(ids), source, index);
    input.name = name;
    graphs.push_back(std::move(input));
  }
  return graphs;
}

// ---------------------------------------------------------------------------------------------------
// GraphML and DOT (through Boost.PropertyTree's XML parser and Boost.Graph's read_graphviz).

/// A graph read from GraphML or DOT, with the file's node names, before ids are assigned.
struct NamedGraph {
  std::vector<std::string> names;                     // node names, in file order
  std::vector<std::optional<double>> x, y;            // per node, if given
  std::vector<std::pair<std::size_t, std::size_t>> edges;  // node indices, in file order
  std::vector<std::string> outer;                     // the laguerre 'outer' attribute, as node names
};

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
  {  // connectivity, isolated nodes included
    std::vector<std::vector<std::size_t>> adj(n);
    for (auto [a, b] : ng.edges) {
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
    std::vector<std::uint8_t> reached(n, 0);
    std::vector<std::size_t> stack{0};
    reached[0] = 1;
    while (!stack.empty()) {
      const std::size_t v = stack.back();
      stack.pop_back();
      for (std::size_t w : adj[v])
        if (!reached[w]) reached[w] = 1, stack.push_back(w);
    }
    for (std::size_t v = 0; v < n; ++v)
      if (!reached[v])
        throw GraphInputError(source, 0, 0, "the graph is not connected: node " + node_quoted(ng.names[v]) +
                                                " cannot be reached from node " + node_quoted(ng.names[0]) + ".");
  }
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

std::vector<GraphInput> read_graphml(std::string_view data, const std::string& source) {
  namespace pt = boost::property_tree;
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
  std::vector<GraphInput> out;
  out.push_back(build_named(ng, source));
  return out;
}

/// Vertex properties read from DOT.
struct DotNode {
  std::string name, pos, x, y;
};

std::vector<GraphInput> read_dot(std::string_view data, const std::string& source) {
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
  std::vector<GraphInput> out;
  out.push_back(build_named(ng, source));
  return out;
}

/// Whether the text starts (after a byte-order mark, blanks and comments) with a DOT graph keyword.
bool looks_like_dot(std::string_view data) {
  if (data.substr(0, 3) == "\xEF\xBB\xBF") data.remove_prefix(3);
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

/// Whether the text starts (after a byte-order mark and blanks) with an XML or GraphML tag.
bool looks_like_xml(std::string_view data) {
  if (data.substr(0, 3) == "\xEF\xBB\xBF") data.remove_prefix(3);
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  return data.substr(i, 5) == "<?xml" || data.substr(i, 8) == "<graphml" || data.substr(i, 4) == "<!--";
}

GraphFormat detect_format(std::string_view data) {
  if (data.substr(0, planar_code_magic.size()) == planar_code_magic) return GraphFormat::planar_code;
  if (looks_like_xml(data)) return GraphFormat::graphml;
  if (looks_like_dot(data)) return GraphFormat::dot;
  for (const TextLine& line : split_lines(data))
    if (line.content == "vertices") return GraphFormat::coords;
  return GraphFormat::edges;
}

}  // namespace

GraphFormat parse_graph_format(std::string_view name) {
  for (GraphFormat f : {GraphFormat::automatic, GraphFormat::edges, GraphFormat::planar_code, GraphFormat::coords,
                        GraphFormat::graphml, GraphFormat::dot})
    if (to_string(f) == name) return f;
  throw std::invalid_argument("Unknown graph format '" + std::string(name) +
                              "'; expected one of automatic, edges, planar_code, coords, graphml, dot.");
}

std::string_view to_string(GraphFormat format) {
  switch (format) {
    case GraphFormat::automatic: return "automatic";
    case GraphFormat::edges: return "edges";
    case GraphFormat::planar_code: return "planar_code";
    case GraphFormat::coords: return "coords";
    case GraphFormat::graphml: return "graphml";
    case GraphFormat::dot: return "dot";
  }
  return "unknown";
}

std::vector<GraphInput> read_graphs_from_string(std::string_view data, const std::string& source_name,
                                                GraphFormat format) {
  if (format == GraphFormat::automatic) format = detect_format(data);
  switch (format) {
    case GraphFormat::planar_code: return read_planar_code(data, source_name);
    case GraphFormat::coords: {
      std::vector<GraphInput> out;
      out.push_back(build_from_coords_text(parse_coords_text(data, source_name), source_name));
      return out;
    }
    case GraphFormat::graphml: return read_graphml(data, source_name);
    case GraphFormat::dot: return read_dot(data, source_name);
    case GraphFormat::edges:
    case GraphFormat::automatic: break;
  }
  std::vector<GraphInput> out;
  out.push_back(build_from_edges_text(parse_edges_text(data, source_name), source_name));
  return out;
}

std::vector<GraphInput> read_graphs(const std::string& path, GraphFormat format) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw GraphInputError(path, 0, 0, "the file cannot be opened for reading (" + std::string(std::strerror(errno)) + ").");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw GraphInputError(path, 0, 0, "the file could not be read to the end.");
  return read_graphs_from_string(data, path, format);
}

std::string write_edge_list(const PlanarGraph& g) {
  std::string out = "# laguerre edge list: " + std::to_string(g.num_vertices()) + " vertices, " +
                    std::to_string(g.num_edges()) + " edges\n";
  if (g.outer_face() != none) {
    out += "# outer:";
    for (Vertex v : g.boundary_cycle()) out += " " + std::to_string(g.id(v));
    out += "\n";
  }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  for (Dart d = 0; d < g.num_darts(); ++d)
    if (g.id(g.tail(d)) < g.id(g.head(d))) edges.emplace_back(g.id(g.tail(d)), g.id(g.head(d)));
  std::sort(edges.begin(), edges.end());
  for (auto [a, b] : edges) out += std::to_string(a) + " " + std::to_string(b) + "\n";
  return out;
}

namespace {

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
  if (!positions.empty() && positions.size() != g.num_vertices())
    throw std::invalid_argument(std::string(writer) + " needs no positions or one per vertex, got " +
                                std::to_string(positions.size()) + " for " + std::to_string(g.num_vertices()) + " vertices.");
}

std::string outer_ids(const PlanarGraph& g) {
  std::string out;
  for (Vertex v : g.boundary_cycle()) out += (out.empty() ? "" : " ") + std::to_string(g.id(v));
  return out;
}

}  // namespace

std::string write_graphml(const PlanarGraph& g, const std::vector<Point2>& positions) {
  check_positions(g, positions, "write_graphml");
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<graphml xmlns=\"http://graphml.graphdrawing.org/xmlns\">\n"
      "  <key id=\"outer\" for=\"graph\" attr.name=\"outer\" attr.type=\"string\"/>\n";
  if (!positions.empty())
    out += "  <key id=\"x\" for=\"node\" attr.name=\"x\" attr.type=\"double\"/>\n"
           "  <key id=\"y\" for=\"node\" attr.name=\"y\" attr.type=\"double\"/>\n";
  out += "  <graph id=\"G\" edgedefault=\"undirected\">\n";
  if (g.outer_face() != none) out += "    <data key=\"outer\">" + outer_ids(g) + "</data>\n";
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    out += "    <node id=\"" + std::to_string(g.id(v)) + "\"";
    if (positions.empty()) {
      out += "/>\n";
      continue;
    }
    out += "><data key=\"x\">" + exact_number(positions[v].x) + "</data><data key=\"y\">" +
           exact_number(positions[v].y) + "</data></node>\n";
  }
  for (auto [a, b] : sorted_id_edges(g))
    out += "    <edge source=\"" + std::to_string(a) + "\" target=\"" + std::to_string(b) + "\"/>\n";
  return out + "  </graph>\n</graphml>\n";
}

std::string write_dot(const PlanarGraph& g, const std::vector<Point2>& positions) {
  check_positions(g, positions, "write_dot");
  std::string out = "graph G {\n";
  if (g.outer_face() != none) out += "  outer=\"" + outer_ids(g) + "\";\n";
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    out += "  " + std::to_string(g.id(v));
    if (!positions.empty()) out += " [pos=\"" + exact_number(positions[v].x) + "," + exact_number(positions[v].y) + "\"]";
    out += ";\n";
  }
  for (auto [a, b] : sorted_id_edges(g)) out += "  " + std::to_string(a) + " -- " + std::to_string(b) + ";\n";
  return out + "}\n";
}

std::string write_planar_code(const std::vector<PlanarGraph>& graphs) {
  std::string out = ">>planar_code le<<";
  for (const PlanarGraph& g : graphs) {
    const std::size_t n = g.num_vertices();
    if (n == 0 || n > 65535)
      throw std::invalid_argument("planar_code stores graphs of 1 to 65535 vertices, not " + std::to_string(n) + ".");
    const bool wide = n > 255;
    auto put = [&](std::size_t value) {
      out.push_back(static_cast<char>(value & 0xff));
      if (wide) out.push_back(static_cast<char>(value >> 8));
    };
    if (wide) out.push_back('\0');
    put(n);
    for (Vertex v = 0; v < n; ++v) {
      const auto list = g.neighbours(v);
      for (auto it = list.rbegin(); it != list.rend(); ++it) put(*it + 1);  // clockwise
      put(0);
    }
  }
  return out;
}

}  // namespace laguerre::core
