// Embedding graphs given by their edges: Boyer–Myrvold for abstract graphs (with the apex trick that
// makes a given cycle a face), the exact angular order for straight-line drawings, and the drawing's
// plane check.
#include "laguerre/core/graph/Embedding.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boyer_myrvold_planar_test.hpp>
#include <cctype>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "detail/EmbeddingDetail.hpp"
#include "laguerre/core/Error.hpp"

namespace laguerre::core {

namespace detail {

void check_connected(std::size_t n, const IndexEdges& edges, const std::vector<std::uint64_t>& ids,
                     const std::string& source) {
  const std::size_t v = first_unreached_by_edges(n, edges);
  if (v < n)
    throw GraphInputError(source, 0, 0,
                          "the graph is not connected: vertex " + std::to_string(ids[v]) +
                              " cannot be reached from vertex " + std::to_string(ids[0]) + ".");
}

PlanarGraph build_graph(std::vector<std::vector<Vertex>> rotation, std::vector<std::uint64_t> ids,
                        const std::string& source, std::size_t graph_index, Dart outer) {
  try {
    return PlanarGraph::from_rotation(std::move(rotation), std::move(ids), outer);
  } catch (const InputError& e) {
    std::string message = e.what();
    if (!message.empty() && std::isupper(static_cast<unsigned char>(message[0])))
      message[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(message[0])));
    throw GraphInputError(source, 0, graph_index, message);
  }
}

std::vector<Vertex> face_walk(const PlanarGraph& g, Dart d) {
  std::vector<Vertex> walk;
  Dart e = d;
  do {
    walk.push_back(g.tail(e));
    e = g.next_in_face(e);
  } while (e != d);
  return walk;
}

}  // namespace detail

namespace {

using detail::build_graph;
using detail::check_connected;
using detail::edge_name;
using detail::face_walk;
using detail::IndexEdges;

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

void mirror(std::vector<std::vector<Vertex>>& rotation) {
  for (auto& list : rotation) std::reverse(list.begin(), list.end());
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

GraphInput detail::embed_combinatorial(const IndexEdges& edges, const std::vector<std::uint64_t>& ids,
                                       const std::vector<Vertex>& outer, const std::string& source, std::size_t outer_line) {
  const std::size_t n = ids.size();
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
    throw GraphInputError(source, outer_line, 0,
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
  throw GraphInputError(source, outer_line, 0,
                        "the '# outer:' cycle does not bound a face of the embedding found; the graph must be "
                        "3-connected or a triangulated disc for the outer face to determine the embedding.");
}

GraphInput graph_from_drawing(std::vector<std::uint64_t> ids, std::vector<Point2> positions, const IndexEdges& edges,
                              const std::string& source, bool check_crossings) {
  const std::size_t n = ids.size();
  LAGUERRE_PRECONDITION(positions.size() == n, "graph_from_drawing needs one position per id, got " +
                                                   std::to_string(positions.size()) + " positions for " +
                                                   std::to_string(n) + " ids.");
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
    LAGUERRE_PRECONDITION(a < n && b < n, "graph_from_drawing: an edge has a vertex index out of range.");
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

}  // namespace laguerre::core
