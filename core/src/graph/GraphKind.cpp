#include "laguerre/core/graph/GraphKind.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

namespace laguerre::core {

namespace {

/// Whether x and y are joined by an edge whose two sides are the faces f and g.
bool is_shared_edge(const PlanarGraph& g, Vertex x, Vertex y, Face f, Face h) {
  const Dart d = g.find_dart(x, y);
  if (d == none) return false;
  const Face a = g.face_of(d), b = g.face_of(g.twin(d));
  return (a == f && b == h) || (a == h && b == f);
}

std::vector<Vertex> sorted_pair(Vertex a, Vertex b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

std::string_view to_string(GraphKind kind) {
  switch (kind) {
    case GraphKind::triangulated_disc: return "triangulated_disc";
    case GraphKind::three_connected: return "three_connected";
  }
  return "unknown";
}

std::vector<Vertex> find_small_separator(const PlanarGraph& g) {
  const std::size_t n = g.num_vertices();
  if (n < 4) return {};
  // 2-connectivity: a repeated vertex on a face walk is a cut vertex.
  std::vector<Face> seen_on(n, none);
  for (Face f = 0; f < g.num_faces(); ++f)
    for (Dart d : g.face_darts(f)) {
      const Vertex x = g.tail(d);
      if (seen_on[x] == f) return {x};
      seen_on[x] = f;
    }
  // Two faces meeting in two vertices that are not the ends of an edge separating exactly these faces.
  const std::size_t nf = g.num_faces();
  std::vector<Face> stamp(nf, none);
  std::vector<std::array<Vertex, 2>> shared(nf);
  std::vector<std::uint8_t> count(nf, 0);
  for (Face f = 0; f < nf; ++f) {
    for (Dart d : g.face_darts(f)) {
      const Vertex x = g.tail(d);
      const Dart first = g.first_dart(x);
      for (Dart e = first; e < first + g.degree(x); ++e) {
        const Face h = g.face_of(e);
        if (h <= f) continue;  // each unordered pair once; h == f is f itself
        if (stamp[h] != f) {
          stamp[h] = f;
          count[h] = 1;
          shared[h][0] = x;
          continue;
        }
        if (count[h] == 1) {
          count[h] = 2;
          shared[h][1] = x;
          if (!is_shared_edge(g, shared[h][0], x, f, h)) return sorted_pair(shared[h][0], x);
          continue;
        }
        // A third common vertex: with n ≥ 4 at most one of the three pairs is the shared edge.
        const Vertex a = shared[h][0], b = shared[h][1];
        if (!is_shared_edge(g, a, x, f, h)) return sorted_pair(a, x);
        return sorted_pair(b, x);
      }
    }
  }
  return {};
}

bool is_three_connected(const PlanarGraph& g) { return g.num_vertices() >= 4 && find_small_separator(g).empty(); }

PlanarGraph prepare_for_packing(const PlanarGraph& g, bool outer_given, GraphKind* kind_out,
                                const std::string& source) {
  const std::size_t n = g.num_vertices();
  if (n < 3)
    throw GraphInputError(source, 0, 0,
                          "the graph has " + std::to_string(n) + " vertices; circle packing needs at least 3.");
  auto set_kind = [&](GraphKind k) {
    if (kind_out) *kind_out = k;
  };
  std::size_t non_triangles = 0;
  Face odd_face = none;
  for (Face f = 0; f < g.num_faces(); ++f)
    if (g.face_size(f) != 3) {
      ++non_triangles;
      odd_face = f;
    }
  if (non_triangles == 0) {
    set_kind(GraphKind::triangulated_disc);
    return outer_given ? g : g.with_outer_dart(g.default_outer_dart());
  }
  if (non_triangles == 1 && (!outer_given || odd_face == g.outer_face())) {
    const auto darts = g.face_darts(odd_face);
    std::vector<std::uint8_t> seen(n, 0);
    for (Dart d : darts) {
      const Vertex x = g.tail(d);
      if (seen[x])
        throw GraphInputError(source, 0, 0,
                              "every face but one is a triangle, but the remaining face visits vertex " +
                                  std::to_string(g.id(x)) +
                                  " twice; the boundary of a triangulated disc must be a simple cycle.");
      seen[x] = 1;
    }
    set_kind(GraphKind::triangulated_disc);
    return g.with_outer_dart(darts.front());
  }
  const std::vector<Vertex> separator = find_small_separator(g);
  if (separator.empty()) {
    set_kind(GraphKind::three_connected);
    if (outer_given) return g;
    // Largest face; ties broken by the sorted list of its (min id, max id) edge keys, which starts with
    // its smallest edge and, unlike a dart, does not depend on the orientation of the embedding.
    using Keys = std::vector<std::pair<std::uint64_t, std::uint64_t>>;
    auto keys_of = [&](Face f) {
      Keys keys;
      for (Dart d : g.face_darts(f)) {
        const std::uint64_t a = g.id(g.tail(d)), b = g.id(g.head(d));
        keys.emplace_back(std::min(a, b), std::max(a, b));
      }
      std::sort(keys.begin(), keys.end());
      return keys;
    };
    Face best = 0;
    Keys best_keys = keys_of(0);
    for (Face f = 1; f < g.num_faces(); ++f) {
      if (g.face_size(f) < g.face_size(best)) continue;
      Keys keys = keys_of(f);
      if (g.face_size(f) > g.face_size(best) || keys < best_keys) {
        best = f;
        best_keys = std::move(keys);
      }
    }
    return g.with_outer_dart(g.face_darts(best).front());
  }
  std::string why = separator.size() == 1
                        ? "removing vertex " + std::to_string(g.id(separator[0])) + " disconnects it"
                        : "removing vertices " + std::to_string(g.id(separator[0])) + " and " +
                              std::to_string(g.id(separator[1])) + " disconnects it";
  throw GraphInputError(source, 0, 0,
                        "the graph is neither a triangulated disc (every face but the outer one a triangle) nor "
                        "3-connected: " + why + " (" + std::to_string(non_triangles) +
                            " faces of the embedding are not triangles). If it is a triangulated disc, give its "
                            "boundary cycle with a '# outer: a b c ...' line.");
}

PlanarGraph prepare_for_packing(const GraphInput& input, GraphKind* kind_out) {
  return prepare_for_packing(input.graph, input.outer_given, kind_out, input.name);
}

bool is_triangulated_sphere(const PlanarGraph& g) {
  for (Face f = 0; f < g.num_faces(); ++f)
    if (g.face_size(f) != 3) return false;
  return true;
}

Vertex puncture_vertex(const PlanarGraph& g) {
  LAGUERRE_PRECONDITION(g.num_vertices() > 0, "puncture_vertex needs a vertex");
  Vertex hub = 0;
  for (Vertex v = 1; v < g.num_vertices(); ++v)
    if (g.degree(v) > g.degree(hub) || (g.degree(v) == g.degree(hub) && g.id(v) < g.id(hub))) hub = v;
  return hub;
}

PlanarGraph puncture(const PlanarGraph& g, Vertex hub) {
  LAGUERRE_PRECONDITION(g.num_vertices() >= 4, "puncturing needs at least 4 vertices");
  std::vector<std::vector<Vertex>> rotation;
  std::vector<std::uint64_t> ids;
  auto renumber = [hub](Vertex v) { return v > hub ? v - 1 : v; };
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    if (v == hub) continue;
    std::vector<Vertex> around;
    for (Vertex w : g.neighbours(v))
      if (w != hub) around.push_back(renumber(w));
    rotation.push_back(std::move(around));
    ids.push_back(g.id(v));
  }
  const PlanarGraph punctured = PlanarGraph::from_rotation(std::move(rotation), std::move(ids));
  // The hub's link is now one face; pick the dart between two consecutive link vertices whose left face
  // has the link's length.
  const auto link = g.neighbours(hub);
  for (const auto& [a, b] : {std::pair{link[0], link[1]}, std::pair{link[1], link[0]}}) {
    const Dart d = punctured.find_dart(renumber(a), renumber(b));
    if (punctured.face_darts(punctured.face_of(d)).size() == link.size()) return punctured.with_outer_dart(d);
  }
  throw InternalError("puncture: the link of the removed vertex is not a face (a face around it is not a triangle)");
}

PreparedInput prepare_input(GraphInput& input, OuterRule rule) {
  PreparedInput out;
  if (rule == OuterRule::puncture && is_triangulated_sphere(input.graph)) {
    const PlanarGraph& g = input.graph;
    if (g.num_vertices() < 4)
      throw GraphInputError(input.name, 0, 0,
                            "--outer puncture: the triangulated sphere has " + std::to_string(g.num_vertices()) +
                                " vertices; removing one needs at least 4 (use --outer face).");
    const Vertex hub = puncture_vertex(g);
    out.removed.push_back(g.id(hub));
    PlanarGraph disc = puncture(g, hub);
    if (!input.positions.empty()) input.positions.erase(input.positions.begin() + static_cast<std::ptrdiff_t>(hub));
    input.graph = std::move(disc);
    input.outer_given = true;
  }
  input.graph = prepare_for_packing(input, &out.kind);
  return out;
}

}  // namespace laguerre::core
