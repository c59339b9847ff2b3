#pragma once
// Runs the protocol on the deque host and core::pack on the same graph, and compares bit for bit.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "SyncHost.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

namespace laguerre::protocols::testing {

inline std::uint64_t bits(double d) { return std::bit_cast<std::uint64_t>(d); }

// Hop distance from the boundary (core's rule for RootRule::deepest; on K for 3-connected graphs).
inline std::vector<std::uint32_t> boundary_depths(const core::PlanarGraph& g) {
  std::vector<std::uint32_t> depth(g.num_vertices(), core::none);
  std::deque<core::Vertex> q;
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)
    if (g.is_boundary(v)) depth[v] = 0, q.push_back(v);
  while (!q.empty()) {
    const core::Vertex v = q.front();
    q.pop_front();
    for (core::Vertex w : g.neighbours(v))
      if (depth[w] == core::none) depth[w] = depth[v] + 1, q.push_back(w);
  }
  return depth;
}

// The protocol id of each vertex of K: G's ids, then face_vertex_id(host, successor) per face vertex.
inline std::vector<NodeId> protocol_ids(const core::PlanarGraph& g, const core::PackingComplex& k) {
  std::vector<NodeId> ids(g.ids().begin(), g.ids().end());
  for (core::Face f : k.face_of_vertex) {
    core::Dart best = core::none;
    for (core::Dart d : g.face_darts(f))
      if (best == core::none || g.id(g.tail(d)) < g.id(g.tail(best))) best = d;
    ids.push_back(face_vertex_id(g.id(g.tail(best)), g.id(g.head(best))));
  }
  return ids;
}

inline void expect_same_circle(const core::PlacedCircle& a, const core::Layout& l, core::Vertex v) {
  EXPECT_EQ(bits(a.circle.x), bits(l.circles[v].x));
  EXPECT_EQ(bits(a.circle.y), bits(l.circles[v].y));
  EXPECT_EQ(bits(a.circle.r), bits(l.circles[v].r));
  EXPECT_EQ(bits(a.centre.real()), bits(l.centre[v].real()));
  EXPECT_EQ(bits(a.centre.imag()), bits(l.centre[v].imag()));
}

// The state of face vertex `fid` at its host (node ids are vertex indices here), if it is hosted there.
template <class Host>
std::optional<VertexState> hosted_state(Host& host, NodeId fid) {
  const PackingNode& h = host.node(static_cast<core::Vertex>((fid >> 31) & max_face_node_id));
  for (std::size_t j = 0; j < h.hosted_faces(); ++j)
    if (h.hosted_face_state(j).id == fid) return h.hosted_face_state(j);
  return std::nullopt;
}


// Compares one protocol run with core::pack (Jacobi, stop = lpd) on g, vertex by vertex of K; returns
// core's iteration count.
inline int expect_sync_equals_core(const core::PlanarGraph& g, const PackingParams& params, std::uint64_t shuffle_seed,
                                    const std::string& label) {
  SCOPED_TRACE(label);
  int iterations = -1;
  [&] {
  const core::PackResult r = core::pack(g, reference_options(params));
  iterations = r.iterations;
  const core::PackingComplex k = core::PackingComplex::from_graph(g);
  const core::Vertex root = core::choose_root(k, params.root);
  ASSERT_NE(root, core::none) << "test graphs must have an interior vertex";
  const auto depth = boundary_depths(k.graph);
  const auto ids = protocol_ids(g, k);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)
    ASSERT_EQ(g.id(v), v) << "face vertices list their neighbours as core does when ids follow indices";

  DequeHost host(g, params);
  host.run(shuffle_seed);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const PackingNode& n = host.node(v);
    SCOPED_TRACE("vertex " + std::to_string(v));
    ASSERT_EQ(n.phase(), PackingPhase::finished);
    EXPECT_EQ(n.depth(), depth[v]);
    EXPECT_EQ(n.is_root(), v == root);
    EXPECT_EQ(n.wave(), r.layout.wave[v]);
    EXPECT_EQ(n.parent(), v == root ? g.id(v) : ids[r.layout.parent[v]]);
    EXPECT_EQ(n.polygon_faces(), k.has_face_vertices());
    EXPECT_EQ(n.steps(), static_cast<std::uint32_t>(r.iterations));
    EXPECT_EQ(bits(n.h()), bits(r.radii[v])) << n.h() << " vs " << r.radii[v];
    expect_same_circle(n.placement(), r.layout, v);
    EXPECT_EQ(n.local_condition(), r.local[v]) << to_string(n.local_condition()) << " vs " << to_string(r.local[v]);
    const auto& c = n.counters();
    EXPECT_EQ(c.unexpected, 0u);
    EXPECT_EQ(c.not_a_neighbour, 0u);
    EXPECT_EQ(c.bad_payload, 0u);
    EXPECT_EQ(c.decode[0], c.received);
    if (r.status == core::PackStatus::converged) {
      EXPECT_EQ(n.outcome(), PackingOutcome::converged);
    } else if (r.status == core::PackStatus::iteration_cap) {
      EXPECT_EQ(n.outcome(), PackingOutcome::cap);
    }
  }
  // Face vertices, at their hosts.
  std::size_t hosted = 0;
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) hosted += host.node(v).hosted_faces();
  ASSERT_EQ(hosted, k.face_of_vertex.size());
  for (std::size_t i = 0; i < k.face_of_vertex.size(); ++i) {
    const core::Vertex fv = static_cast<core::Vertex>(g.num_vertices() + i);
    const NodeId fid = ids[fv];
    SCOPED_TRACE("face vertex " + std::to_string(i));
    const std::optional<VertexState> st = hosted_state(host, fid);
    ASSERT_TRUE(st.has_value());
    EXPECT_EQ(st->phase, PackingPhase::finished);
    EXPECT_EQ(st->depth, depth[fv]);
    EXPECT_EQ(st->wave, r.layout.wave[fv]);
    EXPECT_EQ(st->parent, ids[r.layout.parent[fv]]);
    EXPECT_EQ(st->steps, static_cast<std::uint32_t>(r.iterations));
    EXPECT_EQ(bits(st->h), bits(r.radii[fv])) << st->h << " vs " << r.radii[fv];
    expect_same_circle(st->placement, r.layout, fv);
  }
  }();
  return iterations;
}

// With the iteration cap `cap`, then with the exact update (N = 2, no cap, delivery order `shuffle`):
// both runs equal core::pack's.
inline void expect_cap_and_exact_update_equal_core(const core::PlanarGraph& g, int cap, std::uint64_t shuffle) {
  PackingParams p;
  p.max_iterations = cap;
  expect_sync_equals_core(g, p, 0, "cap " + std::to_string(cap));
  p.max_iterations = 100000;
  p.update = core::UpdateRule::exact;
  p.steps_per_check = 2;
  expect_sync_equals_core(g, p, shuffle, "exact update");
}

}  // namespace laguerre::protocols::testing
