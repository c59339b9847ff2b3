#include "laguerre/scenarios/fields/FieldGraph.hpp"

#include "laguerre/core/Error.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/biconnected_components.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <numeric>
#include <optional>
#include <sstream>
#include <utility>

namespace laguerre::scenarios {

using core::GraphInput;
using core::Point2;
using core::Sign;
using core::Vertex;

namespace {

constexpr std::pair<FieldGraphType, std::string_view> type_names[] = {
    {FieldGraphType::delaunay, "delaunay"},
    {FieldGraphType::unit_disk, "unit-disk"},
    {FieldGraphType::gabriel, "gabriel"},
    {FieldGraphType::relative_neighbourhood, "rng"},
    {FieldGraphType::local_delaunay, "local-delaunay"}};

constexpr std::pair<RepairPolicy, std::string_view> policy_names[] = {
    {RepairPolicy::fail, "fail"},
    {RepairPolicy::largest_block, "largest-block"},
    {RepairPolicy::three_connected_core, "three-connected-core"},
    {RepairPolicy::triangulate_faces, "triangulate-faces"}};

/// The value called `name` in `names`, else core::InputError listing the names.
template <class E, std::size_t N>
E value_named(const std::pair<E, std::string_view> (&names)[N], std::string_view name, const char* what) {
  std::string expected;
  for (const auto& [value, text] : names) {
    if (text == name) return value;
    expected += (expected.empty() ? "" : ", ") + std::string(text);
  }
  throw core::InputError("unknown " + std::string(what) + " '" + std::string(name) + "'; expected one of " + expected +
                         ".");
}

/// The name of `value` in `names`, or "unknown".
template <class E, std::size_t N>
std::string_view name_of(const std::pair<E, std::string_view> (&names)[N], E value) {
  const auto* it = std::find_if(std::begin(names), std::end(names), [&](const auto& entry) { return entry.first == value; });
  return it == std::end(names) ? std::string_view("unknown") : it->second;
}

/// Connected components by union–find: component label per vertex (labels by smallest member order).
std::vector<std::size_t> component_labels(std::size_t n, const EdgeList& edges) {
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (auto [a, b] : edges) {
    const std::size_t ra = find(a), rb = find(b);
    if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  std::vector<std::size_t> label(n);
  for (std::size_t v = 0; v < n; ++v) label[v] = find(v);
  return label;
}

/// The edges of the largest 2-connected block (most vertices, ties to the first found), or empty.
EdgeList largest_block(std::size_t n, const EdgeList& edges) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                      boost::property<boost::edge_index_t, std::size_t>>;
  Graph g(n);
  for (std::size_t i = 0; i < edges.size(); ++i) boost::add_edge(edges[i].first, edges[i].second, i, g);
  std::vector<std::size_t> block(edges.size());
  const std::size_t blocks =
      boost::biconnected_components(g, boost::make_iterator_property_map(block.begin(), boost::get(boost::edge_index, g)));
  std::vector<std::vector<Vertex>> members(blocks);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    members[block[i]].push_back(edges[i].first);
    members[block[i]].push_back(edges[i].second);
  }
  std::size_t best = blocks, best_size = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    auto& m = members[b];
    std::sort(m.begin(), m.end());
    m.erase(std::unique(m.begin(), m.end()), m.end());
    if (m.size() > best_size) {
      best = b;
      best_size = m.size();
    }
  }
  EdgeList out;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (block[i] == best) out.push_back(edges[i]);
  return out;
}

/// The drawing of `edges` on the points they use (ids = point indices). The edges must be connected.
GraphInput drawing(std::span<const Point2> points, const EdgeList& edges, const std::string& source, bool check) {
  std::vector<Vertex> used;
  for (auto [a, b] : edges) {
    used.push_back(a);
    used.push_back(b);
  }
  if (edges.empty()) used.push_back(0);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<std::uint64_t> ids(used.begin(), used.end());
  std::vector<Point2> positions;
  for (Vertex v : used) positions.push_back(points[v]);
  const auto index = [&](Vertex v) { return static_cast<Vertex>(std::lower_bound(used.begin(), used.end(), v) - used.begin()); };
  std::vector<std::pair<Vertex, Vertex>> local;
  for (auto [a, b] : edges) local.emplace_back(index(a), index(b));
  return core::graph_from_drawing(std::move(ids), std::move(positions), local, source, check);
}

struct Classification {
  bool triangulated_disc = false;
  bool three_connected = false;
  std::size_t non_triangular_faces = 0;
  std::optional<std::uint64_t> repeated_boundary_vertex;
  std::vector<std::uint64_t> separator;
};

Classification classify(const core::PlanarGraph& g) {
  Classification c;
  for (core::Face f = 0; f < g.num_faces(); ++f)
    if (f != g.outer_face() && g.face_size(f) != 3) ++c.non_triangular_faces;
  auto boundary = g.boundary_cycle();
  std::sort(boundary.begin(), boundary.end());
  const auto dup = std::adjacent_find(boundary.begin(), boundary.end());
  if (dup != boundary.end()) c.repeated_boundary_vertex = g.id(*dup);
  c.triangulated_disc = g.num_vertices() >= 3 && c.non_triangular_faces == 0 && !c.repeated_boundary_vertex;
  const std::vector<Vertex> separator = core::find_small_separator(g);
  for (Vertex v : separator) c.separator.push_back(g.id(v));
  c.three_connected = g.num_vertices() >= 4 && separator.empty();  // core::is_three_connected, without a second pass
  return c;
}

std::string neither_message(const Classification& c, std::size_t n) {
  std::string why = "neither a triangulated disc (";
  if (n < 3)
    why += "it has fewer than 3 vertices";
  else if (c.non_triangular_faces > 0)
    why += std::to_string(c.non_triangular_faces) + " inner face" + (c.non_triangular_faces == 1 ? " is" : "s are") +
           " not triangles";
  else
    why += "its outer boundary passes twice through point " + std::to_string(*c.repeated_boundary_vertex);
  why += ") nor 3-connected";
  if (c.separator.size() == 1)
    why += ": removing point " + std::to_string(c.separator[0]) + " disconnects it";
  else if (c.separator.size() == 2)
    why += ": removing points " + std::to_string(c.separator[0]) + " and " + std::to_string(c.separator[1]) +
           " disconnects it";
  else
    why += " (it has fewer than 4 vertices)";
  return why;
}

/// Ear clipping of a simple polygon (vertex indices, counter-clockwise) with exact predicates; appends
/// the chords. An ear is a strictly convex corner whose closed triangle holds no other polygon vertex.
void ear_clip(std::vector<Vertex> poly, std::span<const Point2> p, EdgeList& chords) {
  while (poly.size() > 3) {
    const std::size_t k = poly.size();
    bool clipped = false;
    for (std::size_t i = 0; i < k && !clipped; ++i) {
      const Vertex a = poly[(i + k - 1) % k], b = poly[i], c = poly[(i + 1) % k];
      if (core::orientation(p[a], p[b], p[c]) != Sign::positive) continue;
      bool empty = true;
      for (Vertex x : poly) {
        if (x == a || x == b || x == c) continue;
        if (core::orientation(p[a], p[b], p[x]) != Sign::negative && core::orientation(p[b], p[c], p[x]) != Sign::negative &&
            core::orientation(p[c], p[a], p[x]) != Sign::negative) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      chords.emplace_back(std::min(a, c), std::max(a, c));
      poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) throw std::logic_error("ear clipping found no ear: the face is not a simple polygon.");
  }
}


/// Edges among `keep` (a 0/1 flag per point).
EdgeList induced(const EdgeList& edges, const std::vector<std::uint8_t>& keep) {
  EdgeList out;
  for (auto [a, b] : edges)
    if (keep[a] && keep[b]) out.emplace_back(a, b);
  return out;
}

/// The three-connected-core policy (see the header): largest component, deletion of vertices of degree
/// ≤ 2, then the largest side of each separating set of 1–2 vertices, separator included.
EdgeList three_connected_core(std::size_t n, EdgeList edges, const std::function<GraphInput(const EdgeList&)>& draw) {
  std::vector<std::uint8_t> keep(n, 1);
  const auto keep_largest_component = [&] {
    const auto label = component_labels(n, edges);
    std::vector<std::size_t> size(n, 0);
    for (std::size_t v = 0; v < n; ++v) size[label[v]] += keep[v];
    const std::size_t best = static_cast<std::size_t>(std::max_element(size.begin(), size.end()) - size.begin());
    for (std::size_t v = 0; v < n; ++v) keep[v] = keep[v] && label[v] == best;
    edges = induced(edges, keep);
  };
  for (;;) {
    keep_largest_component();
    std::vector<std::vector<Vertex>> adj(n);
    for (auto [a, b] : edges) {
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
    std::vector<std::size_t> degree(n);
    std::vector<Vertex> queue;
    std::size_t alive = 0;
    for (Vertex v = 0; v < n; ++v) {
      degree[v] = adj[v].size();
      alive += keep[v];
      if (keep[v] && degree[v] <= 2) queue.push_back(v);
    }
    while (!queue.empty() && alive > 3) {
      const Vertex v = queue.back();
      queue.pop_back();
      if (!keep[v]) continue;
      keep[v] = 0;
      --alive;
      for (Vertex w : adj[v])
        if (keep[w] && --degree[w] == 2) queue.push_back(w);
    }
    edges = induced(edges, keep);
    keep_largest_component();  // deleting a vertex of degree 2 may disconnect the graph
    if (edges.size() < 3) return edges;
    const GraphInput input = draw(edges);
    const core::PlanarGraph& g = input.graph;
    const Classification c = classify(g);
    if (c.triangulated_disc || c.three_connected) return edges;
    const std::vector<Vertex> sep = core::find_small_separator(g);
    if (sep.empty()) return edges;
    // Components of g − sep; keep the largest and the separator.
    std::vector<std::size_t> comp(g.num_vertices(), n);
    for (Vertex s : sep) comp[s] = n + 1;
    std::vector<std::size_t> sizes;
    for (Vertex r = 0; r < g.num_vertices(); ++r) {
      if (comp[r] != n) continue;
      const std::size_t id = sizes.size();
      sizes.push_back(0);
      std::vector<Vertex> stack{r};
      comp[r] = id;
      while (!stack.empty()) {
        const Vertex v = stack.back();
        stack.pop_back();
        ++sizes[id];
        for (Vertex w : g.neighbours(v))
          if (comp[w] == n) {
            comp[w] = id;
            stack.push_back(w);
          }
      }
    }
    const std::size_t best = static_cast<std::size_t>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
    std::fill(keep.begin(), keep.end(), 0);
    for (Vertex v = 0; v < g.num_vertices(); ++v)
      if (comp[v] == best || comp[v] == n + 1) keep[g.id(v)] = 1;
    edges = induced(edges, keep);
  }
}

}  // namespace

FieldGraphType parse_field_graph_type(std::string_view name) { return value_named(type_names, name, "field graph"); }

std::string_view to_string(FieldGraphType type) { return name_of(type_names, type); }

RepairPolicy parse_repair_policy(std::string_view name) { return value_named(policy_names, name, "repair policy"); }

std::string_view to_string(RepairPolicy policy) { return name_of(policy_names, policy); }

std::string FieldGraphReport::summary(std::string_view name) const {
  std::string s = std::string(name) + ": " + std::to_string(points) + " points, " + std::to_string(edges) + " edges, ";
  if (components != 1) {
    s += "not connected (" + std::to_string(components) + " components, the largest with " +
         std::to_string(largest_component) + " points)";
  } else {
    s += "connected, ";
    s += triangulated_disc ? "a triangulated disc"
                           : "not a triangulated disc (" + std::to_string(non_triangular_faces) + " non-triangular inner face" +
                                 (non_triangular_faces == 1 ? ")" : "s)");
    s += three_connected ? ", 3-connected" : ", not 3-connected";
    if (separator.size() == 1) s += " (point " + std::to_string(separator[0]) + " separates)";
    if (separator.size() == 2)
      s += " (points " + std::to_string(separator[0]) + " and " + std::to_string(separator[1]) + " separate)";
  }
  if (repaired)
    s += "; repair removed " + std::to_string(removed_points) + " points and added " + std::to_string(added_chords) +
         " chords";
  s += ": ";
  s += core::to_string(kind);
  return s;
}

double radius_for_mean_degree(const core::Domain& domain, std::size_t n, double degree) {
  LAGUERRE_PRECONDITION(n > 0 && degree > 0 && std::isfinite(degree),
                        "radius_for_mean_degree needs n > 0 and a positive finite degree.");
  return std::sqrt(degree * domain.area() / (3.141592653589793 * static_cast<double>(n)));
}

EdgeList field_edges(const core::Domain& domain, std::span<const Point2> points, const FieldGraphOptions& options) {
  switch (options.type) {
    case FieldGraphType::delaunay: return restricted_delaunay_edges(domain, points);
    case FieldGraphType::unit_disk: return unit_disk_edges(points, options.radius);
    case FieldGraphType::gabriel: return gabriel_edges(points, options.radius);
    case FieldGraphType::relative_neighbourhood: return relative_neighbourhood_edges(points, options.radius);
    case FieldGraphType::local_delaunay: return local_delaunay_edges(points, options.radius, options.hops);
  }
  throw core::InternalError("unknown field graph type.");  // unreachable: every FieldGraphType is handled
}

FieldGraph build_field_graph(const core::Domain& domain, std::span<const Point2> points, const FieldGraphOptions& options) {
  const EdgeList edges = field_edges(domain, points, options);
  std::string name(to_string(options.type));
  if (options.type != FieldGraphType::delaunay) {
    std::ostringstream r;
    r.precision(6);
    r << " graph (R = " << options.radius << ")";
    name += r.str();
    if (options.type == FieldGraphType::local_delaunay) name = "LDel^(" + std::to_string(options.hops) + ")" + r.str();
  } else {
    name += " triangulation";
  }
  // Restricted Delaunay, Gabriel and RNG drawings are plane by construction (subgraphs of a Delaunay
  // triangulation), LDel^(k) for k >= 2 by Li et al.'s theorem (and the tests check it); the unit-disk
  // graph and LDel^(1) are checked exactly.
  const bool check = options.type == FieldGraphType::unit_disk ||
                     (options.type == FieldGraphType::local_delaunay && options.hops < 2);
  return field_graph_from_edges(points, edges, options.repair, options.source, name, check);
}

FieldGraph field_graph_from_edges(std::span<const Point2> points, const EdgeList& edges, RepairPolicy repair,
                                  const std::string& source, std::string_view type_name, bool check_crossings) {
  const std::size_t n = points.size();
  FieldGraph result;
  FieldGraphReport& report = result.report;
  report.points = n;
  report.edges = edges.size();
  const std::string what = source + ": the " + std::string(type_name) + " of " + std::to_string(n) + " points";
  const auto fail = [&](const std::string& why) -> FieldGraphError {
    return FieldGraphError(what + " is " + why + ".", report);
  };
  const auto build = [&](const EdgeList& e, bool check) {
    try {
      return drawing(points, e, source, check);
    } catch (const core::GraphInputError& error) {
      throw FieldGraphError(what + " cannot be drawn as a plane graph: " + error.message() +
                                (check_crossings ? " Use a planar spanner (gabriel, rng, local-delaunay with hops >= 2)." : ""),
                            report);
    }
  };

  const auto label = component_labels(n, edges);
  std::vector<std::size_t> size(n, 0);
  for (std::size_t v = 0; v < n; ++v) ++size[label[v]];
  report.components = static_cast<std::size_t>(std::count_if(size.begin(), size.end(), [](std::size_t s) { return s > 0; }));
  report.largest_component = n == 0 ? 0 : *std::max_element(size.begin(), size.end());

  std::string problem;
  if (report.components != 1) {
    std::size_t stray = 0;
    while (stray < n && label[stray] == label[0]) ++stray;
    problem = "not connected: " + std::to_string(report.components) + " components, the largest has " +
              std::to_string(report.largest_component) + " of the " + std::to_string(n) + " points (point " +
              std::to_string(stray) + " cannot be reached from point 0)";
  } else {
    result.input = build(edges, check_crossings);
    const Classification c = classify(result.input.graph);
    report.triangulated_disc = c.triangulated_disc;
    report.three_connected = c.three_connected;
    report.non_triangular_faces = c.non_triangular_faces;
    report.separator = c.separator;
    if (c.triangulated_disc || c.three_connected) {
      result.input.graph = core::prepare_for_packing(result.input, &result.kind);
      report.kind = result.kind;
      return result;
    }
    problem = neither_message(c, result.input.graph.num_vertices());
  }
  if (repair == RepairPolicy::fail)
    throw fail(problem + "; choose repair: largest-block, three-connected-core or triangulate-faces to use part of it");

  EdgeList kept;
  std::string part;
  if (repair == RepairPolicy::three_connected_core) {
    kept = three_connected_core(n, edges, [&](const EdgeList& e) { return build(e, check_crossings); });
    part = "its three-connected core";
  } else {
    kept = largest_block(n, edges);
    part = "its largest 2-connected block";
  }
  if (kept.size() < 3) throw fail(problem + ", and " + part + " has fewer than 3 points");
  result.input = build(kept, check_crossings);
  report.repaired = true;
  report.removed_points = n - result.input.graph.num_vertices();
  if (repair == RepairPolicy::triangulate_faces) {
    const core::PlanarGraph& g = result.input.graph;
    EdgeList chords;
    for (core::Face f = 0; f < g.num_faces(); ++f) {
      if (f == g.outer_face() || g.face_size(f) == 3) continue;
      std::vector<Vertex> poly;
      for (core::Dart d : g.face_darts(f)) poly.push_back(static_cast<Vertex>(g.id(g.tail(d))));
      ear_clip(std::move(poly), points, chords);
    }
    report.added_chords = chords.size();
    kept.insert(kept.end(), chords.begin(), chords.end());
    std::sort(kept.begin(), kept.end());
    result.input = build(kept, false);  // chords lie inside their faces: still plane
  }
  const Classification c = classify(result.input.graph);
  if (!c.triangulated_disc && !c.three_connected)
    throw fail(problem + "; " + part + " (" + std::to_string(result.input.graph.num_vertices()) +
               " points) is " + neither_message(c, result.input.graph.num_vertices()));
  result.input.graph = core::prepare_for_packing(result.input, &result.kind);
  report.kind = result.kind;
  return result;
}

}  // namespace laguerre::scenarios
