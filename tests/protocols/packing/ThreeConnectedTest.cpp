// 3-connected graphs: the synchronous protocol on K = G′ (face vertices emulated by their hosts,
// messages relayed along faces) equals core::pack bit for bit, and the G-face-local GLPD check equals
// core::check_glpd. The wide sweep is in tests/protocols/property.

#include <gtest/gtest.h>

#include "laguerre/core/Error.hpp"
#include "../NullRuntime.hpp"
#include "../SyncCompare.hpp"
#include "../TestGraphs.hpp"
#include "laguerre/protocols/LocalChecks.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

// check_glpd_local at every vertex of g, fed from g as a node would gather it.
void expect_local_glpd_equals_core(const core::PlanarGraph& g, const core::CircleEmbedding& phi) {
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const LocalKnowledge k = local_knowledge(g, v);
    const std::size_t deg = k.neighbours.size();
    std::vector<core::Circle> nb;
    std::vector<std::uint64_t> nid;
    for (core::Vertex w : g.neighbours(v)) {
      nb.push_back(phi[w]);
      nid.push_back(g.id(w));
    }
    std::vector<std::vector<core::Circle>> fc(deg);
    std::vector<std::vector<std::uint64_t>> fid(deg);
    std::vector<GlpdWedge> wedges(deg);
    for (std::size_t i = 0; i < deg; ++i) {
      const core::Dart d = g.first_dart(v) + static_cast<core::Dart>(i);
      if (g.face_of(d) == g.outer_face()) {
        wedges[i].outer = true;
        continue;
      }
      core::Dart e = d;
      do {
        fc[i].push_back(phi[g.tail(e)]);
        fid[i].push_back(g.id(g.tail(e)));
        e = g.next_in_face(e);
      } while (e != d);
      wedges[i].circles = fc[i];
      wedges[i].ids = fid[i];
    }
    EXPECT_EQ(check_glpd_local(phi[v], g.id(v), nb, nid, k.boundary, k.outer_gap, wedges), core::check_glpd(g, phi, v))
        << "vertex " << v;
  }
}
}  // namespace

TEST(ThreeConnected, LocalKnowledgeListsPolygonFaces) {
  const core::PlanarGraph g = three_connected(40, 3);
  ASSERT_FALSE(g.inner_faces_are_triangles());
  std::size_t polygons = 0;
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const LocalKnowledge k = local_knowledge(g, v);
    if (k.faces.empty()) continue;
    ASSERT_EQ(k.faces.size(), k.neighbours.size());
    for (std::size_t i = 0; i < k.faces.size(); ++i) {
      if (k.faces[i].empty()) continue;
      ++polygons;
      EXPECT_GT(k.faces[i].size(), 3u);
      EXPECT_EQ(k.faces[i][0], k.id);
      EXPECT_EQ(k.faces[i][1], k.neighbours[i]);
      EXPECT_EQ(k.faces[i].back(), k.neighbours[(i + 1) % k.neighbours.size()]);
    }
  }
  EXPECT_GT(polygons, 0u);
}

TEST(ThreeConnected, LocalGlpdEqualsCoreOnEveryIterate) {
  // Early iterates fail GLPD for every reason; later ones hold: the outcome and its first reason agree.
  std::size_t seen_fail = 0, seen_hold = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const core::PlanarGraph g = three_connected(20 + 10 * seed, seed);
    for (int cap : {0, 2, 10, 40, 200}) {
      core::PackOptions o;
      o.stop = core::StopRule::cap;
      o.max_iterations = cap;
      const core::PackResult r = core::pack(g, o);
      expect_local_glpd_equals_core(g, r.circles);
      for (core::LocalCondition c : r.local) (c == core::LocalCondition::holds ? seen_hold : seen_fail)++;
    }
  }
  EXPECT_GT(seen_fail, 0u);
  EXPECT_GT(seen_hold, 0u);
}

TEST(ThreeConnected, SyncEqualsCoreBitForBitFifo) {
  for (std::size_t n : {5, 6, 8, 12, 20, 35})
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
      for (int steps : {1, 3}) {
        const core::PlanarGraph g = three_connected(n, 100 * n + seed);
        PackingParams p;
        p.steps_per_check = steps;
        expect_sync_equals_core(g, p, 0, "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(steps));
        if (::testing::Test::HasFailure()) return;
      }
}

TEST(ThreeConnected, SyncEqualsCoreUnderRandomDeliveryOrder) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const core::PlanarGraph g = three_connected(15 + 5 * seed, seed + 7);
    PackingParams p;
    p.steps_per_check = static_cast<int>(seed % 3) + 1;
    p.root = seed % 2 ? core::RootRule::deepest : core::RootRule::smallest_id;
    expect_sync_equals_core(g, p, seed, "shuffled seed=" + std::to_string(seed));
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(ThreeConnected, IterationCapAndExactUpdate) {
  expect_cap_and_exact_update_equal_core(three_connected(30, 11), 4, 5);
}

TEST(ThreeConnected, RejectsInconsistentFaces) {
  laguerre::protocols::testing::NullRuntime rt;
  auto knowledge = [](std::vector<std::vector<NodeId>> faces) {
    return LocalKnowledge{1, {2, 3, 4}, false, LocalKnowledge::no_gap, {}, std::move(faces)};
  };
  EXPECT_NO_THROW(PackingNode(rt, knowledge({{1, 2, 7, 3}, {}, {}}), {}));
  EXPECT_THROW(PackingNode(rt, knowledge({{1, 2, 7, 3}}), {}), laguerre::core::InternalError);         // not per wedge
  EXPECT_THROW(PackingNode(rt, knowledge({{1, 3, 7, 2}, {}, {}}), {}), laguerre::core::InternalError); // wrong wedge
  EXPECT_THROW(PackingNode(rt, knowledge({{1, 2, 3}, {}, {}}), {}), laguerre::core::InternalError);    // a triangle
  EXPECT_THROW(PackingNode(rt, knowledge({{1, 2, NodeId{1} << 40, 3}, {}, {}}), {}), laguerre::core::InputError);
}

TEST(ThreeConnected, ForgedEnvelopesAreCountedNotTrusted) {
  const core::PlanarGraph g = three_connected(30, 4);
  DequeHost host(g, PackingParams{});
  // A node with a polygon face that it does not host, and its walk's predecessor.
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const LocalKnowledge k = local_knowledge(g, v);
    std::size_t i = 0;
    while (i < k.faces.size() && (k.faces[i].empty() || *std::min_element(k.faces[i].begin(), k.faces[i].end()) == k.id)) ++i;
    if (i == k.faces.size()) continue;
    const std::vector<NodeId>& walk = k.faces[i];
    const NodeId host_id = *std::min_element(walk.begin(), walk.end());
    const auto h = std::find(walk.begin(), walk.end(), host_id);
    const NodeId face = face_vertex_id(host_id, h + 1 == walk.end() ? walk.front() : *(h + 1));
    PackingNode& n = host.node(v);
    n.on_start();
    const std::vector<std::byte> payload = encode(ReportMsg{0, true});
    const PackingCounters before = n.counters();
    n.on_message(walk.back(), encode(RelayMsg{face + 1, face + 1, k.id, false, payload}));  // unknown face
    n.on_message(walk[1], encode(RelayMsg{face, face, k.id, false, payload}));            // wrong direction
    n.on_message(walk.back(), encode(RelayMsg{face, face, 987654, false, payload}));      // not a member
    EXPECT_EQ(n.counters().unexpected, before.unexpected + 3);
    n.on_message(walk.back(), encode(RelayMsg{face, face, k.id, false, {std::byte{1}, std::byte{99}}}));  // bad payload
    EXPECT_EQ(n.counters().bad_payload, before.bad_payload + 1);
    n.on_message(walk.back(), encode(RelayMsg{face, face, k.id, false, encode(RelayMsg{face, face, k.id, false, payload})}));
    EXPECT_EQ(n.counters().bad_payload, before.bad_payload + 2);  // envelopes never nest: not a PackingMessage
    EXPECT_EQ(n.counters().unexpected, before.unexpected + 3);
    return;
  }
  FAIL() << "no node with a polygon face it does not host";
}

TEST(ThreeConnected, ConvergesWhenIdsDoNotFollowIndices) {
  // With ids in another order than vertex indices, a face vertex sums its star from another corner
  // than core (and ties may break differently), so the run is no longer core's bit for bit; it must
  // still end with GLPD holding everywhere, checked here by core on the circles the nodes hold.
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const core::PlanarGraph g0 = three_connected(25 + 5 * seed, seed + 40);
    const std::size_t n = g0.num_vertices();
    std::vector<std::vector<core::Vertex>> rotation(n);
    std::vector<std::uint64_t> ids(n);
    for (core::Vertex v = 0; v < n; ++v) {
      rotation[v].assign(g0.neighbours(v).begin(), g0.neighbours(v).end());
      ids[v] = 1000 + (static_cast<std::uint64_t>(v) * 7919 + seed) % n;  // a permutation (7919 is prime, n < 7919)
    }
    const core::PlanarGraph g =
        core::PlanarGraph::from_rotation(rotation, ids, g0.face_darts(g0.outer_face()).front());
    DequeHost host(g, PackingParams{});
    host.run(seed);
    core::CircleEmbedding phi(n);
    for (core::Vertex v = 0; v < n; ++v) {
      const PackingNode& node = host.node(v);
      ASSERT_EQ(node.phase(), PackingPhase::finished) << "seed " << seed;
      EXPECT_EQ(node.outcome(), PackingOutcome::converged);
      EXPECT_EQ(node.counters().unexpected, 0u);
      phi[v] = node.placement().circle;
    }
    for (core::LocalCondition c : core::check_all(g, phi)) EXPECT_EQ(c, core::LocalCondition::holds) << "seed " << seed;
  }
}
