// Embedding graphs given by their edges: Boyer–Myrvold for abstract graphs (with the apex trick that
// makes a given cycle a face), the exact angular order for straight-line drawings, and the drawing's
// plane check.
#include "laguerre/core/graph/Embedding.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
// Boyer–Myrvold's embedding stored in std::lists instead of its default recursive lazy lists, whose
// shared_ptr bookkeeping was a third of the time of reading a 10^6-vertex edge list.
#define BOOST_GRAPH_PREFER_STD_LIB
#include <boost/graph/boyer_myrvold_planar_test.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
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

struct Box {
  double xmin, xmax, ymin, ymax;
};

// The sweep by the left ends of the boxes: throws on the first crossing in its order. Used for the
// error message (the same pair is named whichever search found that there is one) and when the grid
// below would be too large (edges of very different lengths).
void sweep_for_crossings(const std::vector<Point2>& pos, const IndexEdges& edges, const std::vector<Box>& boxes,
                          const std::vector<std::uint64_t>& ids, const std::string& source) {
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

// Whether two edges that share no vertex cross or touch (exact), over the pairs whose closed boxes
// overlap. The candidates come from a uniform grid of about one cell per edge: each edge is listed in
// every cell its box meets, and a pair is tested only in the cell of the lower-left corner of the
// intersection of its boxes — a point of both boxes, so both edges are listed there (the cell index
// is a non-decreasing function of each coordinate), and a single cell, so each pair is tested once.
// Linear time for edges of comparable lengths (a random drawing of 10^6 vertices: 3·10^6 edges), where
// the sweep by the left ends of the boxes tested every pair within an edge's x-range (~E^1.5).
void check_no_crossings(const std::vector<Point2>& pos, const IndexEdges& edges,
                        const std::vector<std::uint64_t>& ids, const std::string& source) {
  const std::size_t m = edges.size();
  if (m < 2) return;
  std::vector<Box> boxes(m);
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  double sum_w = 0, sum_h = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const Point2 a = pos[edges[i].first], b = pos[edges[i].second];
    boxes[i] = {std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y)};
    x0 = std::min(x0, boxes[i].xmin), x1 = std::max(x1, boxes[i].xmax);
    y0 = std::min(y0, boxes[i].ymin), y1 = std::max(y1, boxes[i].ymax);
    sum_w += boxes[i].xmax - boxes[i].xmin, sum_h += boxes[i].ymax - boxes[i].ymin;
  }
  // Cells about the size of a typical box, at most ~2 per edge in total.
  const double w = x1 - x0, h = y1 - y0;
  const double cell_w = std::max(sum_w / static_cast<double>(m), w / 4096), cell_h = std::max(sum_h / static_cast<double>(m), h / 4096);
  auto cells_along = [&](double extent, double cell) {
    const double c = cell > 0 && extent > 0 ? std::floor(extent / cell) + 1 : 1;
    return static_cast<std::size_t>(std::clamp(c, 1.0, 4096.0));
  };
  std::size_t gx = cells_along(w, cell_w), gy = cells_along(h, cell_h);
  while (gx * gy > 2 * m && (gx > 1 || gy > 1)) {  // keep the grid no larger than the edge list
    gx = std::max<std::size_t>(1, gx / 2);
    gy = std::max<std::size_t>(1, gy / 2);
  }
  const double sx = w > 0 ? static_cast<double>(gx) / w : 0, sy = h > 0 ? static_cast<double>(gy) / h : 0;
  auto cx = [&](double x) { return std::min(gx - 1, static_cast<std::size_t>(std::max(0.0, (x - x0) * sx))); };
  auto cy = [&](double y) { return std::min(gy - 1, static_cast<std::size_t>(std::max(0.0, (y - y0) * sy))); };
  // Cell lists in compressed form: count, prefix sums, fill. Long boxes among short ones could list an
  // edge in very many cells: then the sweep does the work.
  std::size_t entries = 0;
  for (const Box& b : boxes) entries += (cx(b.xmax) - cx(b.xmin) + 1) * (cy(b.ymax) - cy(b.ymin) + 1);
  if (entries > 16 * m + 1024) return sweep_for_crossings(pos, edges, boxes, ids, source);
  std::vector<std::size_t> start(gx * gy + 1, 0);
  for (const Box& b : boxes)
    for (std::size_t j = cy(b.ymin); j <= cy(b.ymax); ++j)
      for (std::size_t i = cx(b.xmin); i <= cx(b.xmax); ++i) ++start[j * gx + i + 1];
  for (std::size_t c = 0; c < gx * gy; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t> list(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t e = 0; e < m; ++e) {
      const Box& b = boxes[e];
      for (std::size_t j = cy(b.ymin); j <= cy(b.ymax); ++j)
        for (std::size_t i = cx(b.xmin); i <= cx(b.xmax); ++i) list[fill[j * gx + i]++] = static_cast<std::uint32_t>(e);
    }
  }
  for (std::size_t c = 0; c < gx * gy; ++c)
    for (std::size_t p = start[c]; p < start[c + 1]; ++p)
      for (std::size_t q = p + 1; q < start[c + 1]; ++q) {
        const Box &bi = boxes[list[p]], &bj = boxes[list[q]];
        if (bj.xmin > bi.xmax || bi.xmin > bj.xmax || bj.ymin > bi.ymax || bi.ymin > bj.ymax) continue;
        if (cy(std::max(bi.ymin, bj.ymin)) * gx + cx(std::max(bi.xmin, bj.xmin)) != c) continue;  // tested elsewhere
        const auto [a, b] = edges[list[p]];
        const auto [u, v] = edges[list[q]];
        if (a == u || a == v || b == u || b == v) continue;  // overlaps at a shared end are found by the angle sort
        if (segments_intersect(pos[a], pos[b], pos[u], pos[v])) {
          sweep_for_crossings(pos, edges, boxes, ids, source);  // names the first crossing in its order
          throw GraphInputError(source, 0, 0, "the drawing is not plane: edges " + edge_name(ids[a], ids[b]) + " and " +
                                                  edge_name(ids[u], ids[v]) + " cross or touch.");
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
