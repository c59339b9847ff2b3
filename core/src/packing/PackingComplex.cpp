#include "laguerre/core/packing/PackingComplex.hpp"

namespace laguerre::core {

PackingComplex PackingComplex::from_graph(const PlanarGraph& g) {
  PackingComplex k;
  k.num_original = g.num_vertices();
  const std::size_t n = g.num_vertices();
  // Face vertices for inner non-triangle faces, numbered in face order.
  std::vector<Vertex> face_vertex(g.num_faces(), none);
  for (Face f = 0; f < g.num_faces(); ++f)
    if (f != g.outer_face() && g.face_size(f) > 3) {
      face_vertex[f] = static_cast<Vertex>(n + k.face_of_vertex.size());
      k.face_of_vertex.push_back(f);
    }
  const std::size_t nk = n + k.face_of_vertex.size();
  std::vector<std::vector<Vertex>> rotation(nk);
  std::vector<std::vector<std::uint8_t>> orthogonal(nk);
  // Around an original vertex v: the face to the left of dart v→a is the wedge between a and the next
  // neighbour counter-clockwise, so the face vertex of that face goes right after a.
  for (Vertex v = 0; v < n; ++v) {
    const Dart first = g.first_dart(v);
    for (Dart d = first; d < first + g.degree(v); ++d) {
      rotation[v].push_back(g.head(d));
      orthogonal[v].push_back(0);
      const Face f = g.face_of(d);
      if (face_vertex[f] != none) {
        rotation[v].push_back(face_vertex[f]);
        orthogonal[v].push_back(1);
      }
    }
  }
  // Around a face vertex: the face's vertices in counter-clockwise order (inner faces are ccw walks).
  for (std::size_t i = 0; i < k.face_of_vertex.size(); ++i) {
    const Vertex fv = static_cast<Vertex>(n + i);
    for (Dart d : g.face_darts(k.face_of_vertex[i])) {
      rotation[fv].push_back(g.tail(d));
      orthogonal[fv].push_back(1);
    }
  }
  std::vector<std::uint64_t> ids(g.ids());
  std::uint64_t next_id = 0;
  for (auto id : ids) next_id = std::max(next_id, id + 1);
  for (std::size_t i = 0; i < k.face_of_vertex.size(); ++i) ids.push_back(next_id + i);
  // Keep G's outer face: its first dart u→w exists in K too.
  const Dart outer_g = g.face_darts(g.outer_face()).front();
  const Vertex ou = g.tail(outer_g), ow = g.head(outer_g);
  // Build once to find the dart index in K, then again with that outer dart.
  PlanarGraph tmp = PlanarGraph::from_rotation(rotation, ids);
  k.graph = tmp.with_outer_dart(tmp.find_dart(ou, ow));
  k.cos_angle.resize(k.graph.num_darts());
  for (Vertex v = 0; v < nk; ++v)
    for (std::uint32_t j = 0; j < k.graph.degree(v); ++j)
      k.cos_angle[k.graph.first_dart(v) + j] = orthogonal[v][j] ? 0.0 : 1.0;
  k.tangent_only.assign(nk, 1);
  for (Vertex v = 0; v < nk; ++v)
    for (Vertex w : k.graph.neighbours(v))
      if (w >= n) {  // v touches a face vertex: v itself, or every neighbour of a face vertex
        k.tangent_only[v] = 0;
        break;
      }
  for (Vertex v = static_cast<Vertex>(n); v < nk; ++v) k.tangent_only[v] = 0;
  return k;
}

}  // namespace laguerre::core
