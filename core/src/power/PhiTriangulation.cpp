// The φ-triangulation G(φ) (thesis Def. 5.2.3): each non-triangle inner face, strictly convex, is
// triangulated by the regular triangulation (dual of the power diagram) of its vertices' circles,
// computed exactly on the perturbed embedding of LocalPowerDiagram.hpp.

#include <algorithm>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"
#include "PowerDetail.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

namespace laguerre::core {

std::vector<std::pair<std::uint32_t, std::uint32_t>> regular_triangulation_diagonals(
    std::span<const Circle> poly, std::span<const std::uint64_t> pr) {
  // The regular triangulation is the projection of the lower hull of the lifted points
  // (p, |p|² − σ²). For a convex polygon every corner is on it (Lemma 5.2.1) and every sub-polygon
  // cut off by a lower-hull edge is again triangulated by the lower hull of its own corners, so we
  // peel triangles: the range [i, j] of consecutive corners, closed by the edge (i, j), receives the
  // lower-hull triangle (i, c, j) on that edge, then [i, c] and [c, j] are done the same way.
  // After the perturbation the lower hull is a triangulation (no four lifted points coplanar), hence
  // unique: the result does not depend on where the polygon starts. O(m²) power tests.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  const auto m = static_cast<std::uint32_t>(poly.size());
  if (m <= 3) return out;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0, m - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    const std::uint32_t c = detail::lower_hull_apex(poly, pr, i, j, i + 1, j - 1);
    if (c - i >= 2) {
      out.emplace_back(i, c);
      todo.emplace_back(i, c);
    }
    if (j - c >= 2) {
      out.emplace_back(c, j);
      todo.emplace_back(c, j);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

// Visits every non-triangle inner face: fn(face, its vertices in walk order, local diagonals).
template <class Fn>
void for_each_triangulated_face(const PlanarGraph& g, const CircleEmbedding& phi, Fn&& fn) {
  std::vector<Circle> circles;
  std::vector<std::uint64_t> ids;
  std::vector<Vertex> verts;
  for (Face f = 0; f < g.num_faces(); ++f) {
    if (f == g.outer_face() || g.face_size(f) <= 3) continue;
    circles.clear();
    ids.clear();
    verts.clear();
    for (Dart d : g.face_darts(f)) {
      verts.push_back(g.tail(d));
      circles.push_back(phi[g.tail(d)]);
      ids.push_back(g.id(g.tail(d)));
    }
    if (!is_strictly_convex(circles)) {
      std::string list;
      for (Vertex u : verts) list += (list.empty() ? "" : ", ") + std::to_string(g.id(u));
      throw InternalError("precondition failed: The face (" + list +
                          ") is not strictly convex in the embedding, so it has no φ-triangulation.");
    }
    fn(f, verts, regular_triangulation_diagonals(circles, ids));
  }
}

}  // namespace

std::vector<std::pair<Vertex, Vertex>> phi_triangulation_diagonals(const PlanarGraph& g, const CircleEmbedding& phi) {
  std::vector<std::pair<Vertex, Vertex>> out;
  for_each_triangulated_face(g, phi, [&](Face, const std::vector<Vertex>& verts, const auto& diagonals) {
    const std::size_t start = out.size();
    for (auto [i, j] : diagonals) out.emplace_back(std::min(verts[i], verts[j]), std::max(verts[i], verts[j]));
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
  });
  return out;
}

PlanarGraph phi_triangulation(const PlanarGraph& g, const CircleEmbedding& phi) {
  if (g.outer_face() == none) return g;
  // extra[d]: (offset along the face, target) of the diagonals leaving tail(d) inside face_of(d).
  // In a face (f0 … f_{m−1}) a diagonal f_i f_j leaves f_i at face offset (j − i) mod m; at f_i these
  // diagonals sit between f_{i+1} and f_{i−1} in the rotation, counter-clockwise by increasing offset.
  std::vector<std::vector<std::pair<std::uint32_t, Vertex>>> extra(g.num_darts());
  for_each_triangulated_face(g, phi, [&](Face f, const std::vector<Vertex>& verts, const auto& diagonals) {
    const auto darts = g.face_darts(f);
    const auto m = static_cast<std::uint32_t>(verts.size());
    for (auto [i, j] : diagonals) {
      extra[darts[i]].emplace_back(j - i, verts[j]);
      extra[darts[j]].emplace_back(m - (j - i), verts[i]);
    }
  });
  std::vector<std::vector<Vertex>> rotation(g.num_vertices());
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    for (Dart d = g.first_dart(v); d < g.first_dart(v) + g.degree(v); ++d) {
      rotation[v].push_back(g.head(d));
      auto& e = extra[d];
      std::sort(e.begin(), e.end());
      for (const auto& [offset, u] : e) rotation[v].push_back(u);
    }
  }
  // Keep the outer face: locate one of its darts in the new numbering (darts of v are contiguous).
  const Dart od = g.face_darts(g.outer_face())[0];
  const Vertex ou = g.tail(od), ow = g.head(od);
  Dart outer = 0;
  for (Vertex v = 0; v < ou; ++v) outer += static_cast<Dart>(rotation[v].size());
  outer += static_cast<Dart>(std::find(rotation[ou].begin(), rotation[ou].end(), ow) - rotation[ou].begin());
  return PlanarGraph::from_rotation(std::move(rotation), g.ids(), outer);
}

}  // namespace laguerre::core
