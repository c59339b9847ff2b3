#include "laguerre/core/graph/PlanarGraph.hpp"

#include <algorithm>
#include <iostream>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "laguerre/core/Error.hpp"
#include "detail/Connectivity.hpp"

namespace laguerre::core {

namespace {
[[noreturn]] void fail(const std::string& what) { throw InputError(what); }
}  // namespace

PlanarGraph PlanarGraph::from_rotation(std::vector<std::vector<Vertex>> rotation,
                                       std::vector<std::uint64_t> ids, Dart outer) {
  PlanarGraph g;
  const std::size_t n = rotation.size();
  if (n == 0) fail("The graph has no vertices.");
  if (ids.empty()) {
    ids.resize(n);
    std::iota(ids.begin(), ids.end(), std::uint64_t{0});
  }
  if (ids.size() != n) fail("The id list has " + std::to_string(ids.size()) + " entries for " +
                            std::to_string(n) + " vertices.");
  g.ids_ = std::move(ids);
  g.offset_.assign(n + 1, 0);
  for (std::size_t v = 0; v < n; ++v) g.offset_[v + 1] = g.offset_[v] + static_cast<std::uint32_t>(rotation[v].size());
  const std::size_t nd = g.offset_[n];
  g.head_.resize(nd);
  g.tail_.resize(nd);
  // Per vertex, its darts sorted by head: loops and repeated edges are adjacent there, and the twin
  // of v→w is found by a binary search in w's block (O(E log deg), local in memory).
  std::vector<Dart> by_head(nd);
  for (Vertex v = 0; v < n; ++v) {
    const auto& list = rotation[v];
    for (std::size_t i = 0; i < list.size(); ++i) {
      g.head_[g.offset_[v] + i] = list[i];
      g.tail_[g.offset_[v] + i] = v;
    }
    const auto first = by_head.begin() + g.offset_[v], last = by_head.begin() + g.offset_[v + 1];
    std::iota(first, last, g.offset_[v]);
    std::sort(first, last, [&](Dart a, Dart b) { return g.head_[a] < g.head_[b]; });
    for (auto it = first; it != last; ++it) {
      const Vertex w = g.head_[*it];
      if (w >= n) fail("Vertex " + std::to_string(g.ids_[v]) + " lists a neighbour index out of range.");
      if (w == v) fail("Vertex " + std::to_string(g.ids_[v]) + " has a loop; the graph must be simple.");
      if (it != first && w == g.head_[*(it - 1)])
        fail("Edge " + std::to_string(g.ids_[v]) + "-" + std::to_string(g.ids_[w]) +
             " appears twice; the graph must be simple.");
    }
  }
  g.twin_.assign(nd, none);
  for (Dart d = 0; d < nd; ++d) {
    const Vertex v = g.tail_[d], w = g.head_[d];
    const auto first = by_head.begin() + g.offset_[w], last = by_head.begin() + g.offset_[w + 1];
    const auto it = std::lower_bound(first, last, v, [&](Dart a, Vertex k) { return g.head_[a] < k; });
    if (it == last || g.head_[*it] != v)
      fail("Vertex " + std::to_string(g.ids_[v]) + " lists " + std::to_string(g.ids_[w]) +
           " as a neighbour but not the other way round.");
    g.twin_[d] = *it;
  }
  // Connectivity.
  const auto neighbours = [&](std::size_t v) { return g.neighbours(static_cast<Vertex>(v)); };
  if (const std::size_t lost = detail::first_unreached(n, neighbours); lost < n)
    fail("The graph is not connected: vertex " + std::to_string(g.ids_[lost]) + " cannot be reached from vertex " +
         std::to_string(g.ids_[0]) + ".");
  g.build_faces();
  const long long euler = static_cast<long long>(n) - static_cast<long long>(g.num_edges()) +
                          static_cast<long long>(g.num_faces());
  if (n > 1 && euler != 2)
    fail("The rotation system is not a planar embedding: V - E + F = " + std::to_string(euler) + " instead of 2.");
  g.boundary_.assign(n, 0);
  if (nd == 0) {  // a single vertex
    g.outer_ = none;
    return g;
  }
  const Dart od = outer == none ? g.default_outer_dart() : outer;
  if (od >= nd) fail("The outer dart index is out of range.");
  g.outer_ = g.face_of_[od];
  for (Dart d : g.face_darts(g.outer_)) g.boundary_[g.tail_[d]] = 1;
  return g;
}

void PlanarGraph::build_faces() {
  const std::size_t nd = head_.size();
  face_of_.assign(nd, none);
  face_offset_.assign(1, 0);
  face_dart_.clear();
  face_dart_.reserve(nd);
  non_triangles_ = 0;
  for (Dart start = 0; start < nd; ++start) {
    if (face_of_[start] != none) continue;
    const Face f = static_cast<Face>(face_offset_.size() - 1);
    Dart d = start;
    do {
      face_of_[d] = f;
      face_dart_.push_back(d);
      d = next_in_face(d);
    } while (d != start);
    face_offset_.push_back(static_cast<std::uint32_t>(face_dart_.size()));
    if (face_size(f) != 3) ++non_triangles_;
  }
}

Dart PlanarGraph::find_dart(Vertex u, Vertex v) const {
  for (Dart d = offset_[u]; d < offset_[u + 1]; ++d)
    if (head_[d] == v) return d;
  return none;
}

std::vector<Vertex> PlanarGraph::boundary_cycle() const {
  std::vector<Vertex> cycle;
  if (outer_ == none) return cycle;
  for (Dart d : face_darts(outer_)) cycle.push_back(tail_[d]);
  return cycle;
}

PlanarGraph PlanarGraph::with_outer_dart(Dart d) const {
  PlanarGraph g = *this;
  g.outer_ = face_of_[d];
  std::fill(g.boundary_.begin(), g.boundary_.end(), 0);
  for (Dart e : g.face_darts(g.outer_)) g.boundary_[g.tail_[e]] = 1;
  return g;
}

Dart PlanarGraph::default_outer_dart() const {
  Dart best = none;
  std::pair<std::uint64_t, std::uint64_t> best_key{};
  for (Dart d = 0; d < head_.size(); ++d) {
    const std::uint64_t a = ids_[tail_[d]], b = ids_[head_[d]];
    if (a > b) continue;
    const std::pair key{a, b};
    if (best == none || key < best_key) {
      best = d;
      best_key = key;
    }
  }
  return best;
}

std::optional<Vertex> PlanarGraph::vertex_of_id(std::uint64_t id) const {
  for (Vertex v = 0; v < ids_.size(); ++v)
    if (ids_[v] == id) return v;
  return std::nullopt;
}

bool PlanarGraph::inner_faces_are_triangles() const {
  const bool outer_is_polygon = outer_ != none && face_size(outer_) != 3;
  return non_triangles_ == (outer_is_polygon ? 1u : 0u);
}

bool PlanarGraph::is_valid(bool verbose) const {
  auto bad = [&](const std::string& why) {
    if (verbose) std::cerr << "PlanarGraph::is_valid: " << why << '\n';
    return false;
  };
  const std::size_t n = num_vertices();
  if (ids_.size() != n || boundary_.size() != n) return bad("per-vertex arrays have the wrong size");
  for (Dart d = 0; d < num_darts(); ++d) {
    if (twin_[twin_[d]] != d) return bad("twin is not an involution at dart " + std::to_string(d));
    if (head_[twin_[d]] != tail_[d]) return bad("twin does not reverse dart " + std::to_string(d));
    if (face_of_[next_in_face(d)] != face_of_[d]) return bad("face walk leaves its face at dart " + std::to_string(d));
  }
  if (n > 1 && static_cast<long long>(n) - static_cast<long long>(num_edges()) +
                       static_cast<long long>(num_faces()) != 2)
    return bad("Euler's formula fails");
  std::uint32_t non_triangles = 0;
  for (Face f = 0; f < num_faces(); ++f) non_triangles += face_size(f) != 3 ? 1 : 0;
  if (non_triangles != non_triangles_) return bad("the count of non-triangular faces is stale");
  std::vector<std::uint64_t> sorted = ids_;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return bad("duplicate user ids");
  return true;
}

}  // namespace laguerre::core
