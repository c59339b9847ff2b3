// Every sensor routed: quasi-unit-disk links, the attachment rule and all-pairs routing
// (scenarios/fields/SensorNetwork.hpp), checked against independent oracles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "laguerre/core/geometry/Delaunay.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/scenarios/Topology.hpp"
#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/SensorNetwork.hpp"

using namespace laguerre::scenarios;
namespace core = laguerre::core;
using core::Vertex;

namespace {

const std::string domains = std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/domains/";

/// Hop distances from `s` in the edge list (a plain BFS on an adjacency matrix of lists, the oracle).
std::vector<std::uint32_t> hop_distances(std::size_t n, const EdgeList& edges, Vertex s) {
  std::vector<std::vector<Vertex>> adj(n);
  for (auto [a, b] : edges) adj[a].push_back(b), adj[b].push_back(a);
  std::vector<std::uint32_t> d(n, std::numeric_limits<std::uint32_t>::max());
  std::vector<Vertex> q{s};
  d[s] = 0;
  for (std::size_t i = 0; i < q.size(); ++i)
    for (Vertex w : adj[q[i]])
      if (d[w] == std::numeric_limits<std::uint32_t>::max()) d[w] = d[q[i]] + 1, q.push_back(w);
  return d;
}

Topology field(std::size_t n, double radius, const std::string& domain, const std::string& links, std::uint64_t seed) {
  TopologyParams p;
  p.set("n", std::int64_t(n));
  p.set("radius", radius);
  p.set("graph", std::string("local-delaunay"));
  p.set("repair", std::string("three-connected-core"));
  p.set("attach", true);
  p.set("links", links);
  p.set("domain_file", domains + domain);
  return build_topology("field", p, seed);
}

core::CircleEmbedding packed(const core::PlanarGraph& g) {
  core::PackOptions opt;
  opt.stop = core::StopRule::lpd;
  opt.acceleration = core::Acceleration::newton;
  opt.max_iterations = 200;
  core::PackResult r = core::pack(g, opt);
  EXPECT_EQ(r.status, core::PackStatus::converged);
  return r.circles;
}

}  // namespace

TEST(QuasiUnitDiskLinks, SureInsideNoneOutsideAndTheAnnulusAtItsProbability) {
  const auto points = deploy_uniform(core::Domain::unit_square(), 600, 5);
  const double R = 0.08;
  const EdgeList udg = unit_disk_edges(points, R);
  const EdgeList q = link_edges(points, {true, R, 0.6, 0.5, 99});
  EXPECT_TRUE(std::includes(udg.begin(), udg.end(), q.begin(), q.end()));  // nothing beyond R
  std::size_t annulus = 0, kept = 0;
  for (auto [a, b] : udg) {
    const bool in = std::binary_search(q.begin(), q.end(), std::pair{a, b});
    if (core::compare_length(points[a], points[b], 0.6 * R) != core::Sign::positive) {
      EXPECT_TRUE(in) << a << "-" << b;  // every short pair is a link
    } else {
      ++annulus;
      kept += in;
    }
  }
  ASSERT_GT(annulus, 1000u);
  EXPECT_NEAR(static_cast<double>(kept) / static_cast<double>(annulus), 0.5, 0.05);
  EXPECT_EQ(q, link_edges(points, {true, R, 0.6, 0.5, 99}));   // deterministic
  EXPECT_NE(q, link_edges(points, {true, R, 0.6, 0.5, 100}));  // the seed decides the annulus
  EXPECT_EQ(link_edges(points, {true, R, 0.6, 1.0, 1}), udg);
  EXPECT_EQ(link_edges(points, {false, R, 0.6, 0.0, 1}), udg);
  EXPECT_EQ(link_edges(points, {true, R, 0.6, 0.0, 1}), unit_disk_edges(points, 0.6 * R));
}

// Every sensor is in the network; the trees follow the documented rule: a sensor one hop farther from
// the core than its parent, the parent a link and the smallest such neighbour, the anchor inherited;
// depth = hop distance to the core (the oracle: a BFS from every core sensor).
TEST(Attachment, EverySensorHangsOnTheCoreByTheDocumentedRule) {
  for (const char* links : {"unit-disk", "quasi-unit-disk"}) {
    const Topology t = field(400, 0.1, "one-large-hole.txt", links, 3);
    ASSERT_TRUE(t.sensors) << links;
    const SensorNetwork& net = *t.sensors;
    const Attachment& a = net.attachment;
    const std::size_t n = net.points.size();
    ASSERT_EQ(n, 400u);
    ASSERT_LT(t.graph.num_vertices(), n) << "the test wants sensors outside the core";
    // On this deployment the hole (a square of side 0.5, perimeter 2) is an inner face of the
    // 3-connected core (the repair may also cut it open: docs/sensor-attachment.md), and a cycle of
    // links no longer than R = 0.1 around it has at least 2 / 0.1 = 20 vertices.
    EXPECT_EQ(t.kind, core::GraphKind::three_connected);
    std::size_t largest = 0;
    for (core::Face f = 0; f < t.graph.num_faces(); ++f)
      if (f != t.graph.outer_face()) largest = std::max<std::size_t>(largest, t.graph.face_size(f));
    EXPECT_GE(largest, 20u) << links;
    EXPECT_EQ(t.graph.num_vertices() + a.attached + a.stray, n);
    std::vector<std::vector<Vertex>> adj(n);
    for (auto [u, v] : net.links) adj[u].push_back(v), adj[v].push_back(u);
    for (auto& row : adj) std::sort(row.begin(), row.end());
    std::vector<std::uint32_t> to_core(n, std::numeric_limits<std::uint32_t>::max());
    for (Vertex c = 0; c < t.graph.num_vertices(); ++c) {
      const auto d = hop_distances(n, net.links, static_cast<Vertex>(t.graph.id(c)));
      for (std::size_t v = 0; v < n; ++v) to_core[v] = std::min(to_core[v], d[v]);
    }
    std::size_t stray = 0;
    for (Vertex v = 0; v < n; ++v) {
      const bool in_core = a.core_vertex[v] != core::none;
      if (in_core) {
        EXPECT_EQ(t.graph.id(a.core_vertex[v]), v);
        EXPECT_EQ(a.depth[v], 0u);
        EXPECT_EQ(a.anchor[v], v);
        continue;
      }
      if (to_core[v] == std::numeric_limits<std::uint32_t>::max()) {
        ++stray;
        EXPECT_EQ(a.core_vertex[a.anchor[v]], core::none);  // a tree of its own component
      } else {
        EXPECT_EQ(a.depth[v], to_core[v]) << v;
        EXPECT_NE(a.core_vertex[a.anchor[v]], core::none) << v;
      }
      if (a.depth[v] == 0) continue;  // the root of a stray component
      const Vertex p = a.parent[v];
      EXPECT_TRUE(std::binary_search(adj[v].begin(), adj[v].end(), p)) << v << " -> " << p;
      EXPECT_EQ(a.depth[p] + 1, a.depth[v]);
      EXPECT_EQ(a.anchor[p], a.anchor[v]);
      EXPECT_EQ(a.component[p], a.component[v]);
      for (Vertex w : adj[v]) {
        if (w < p) {
          EXPECT_NE(a.depth[w] + 1, a.depth[v]) << "a smaller parent exists for " << v;
        }
      }
    }
    EXPECT_EQ(stray, a.stray) << links;
  }
}

// Over all ordered pairs of a small field: greedy power with the attachment delivers every connected
// pair; every delivered route of every scheme walks links from s to t in at least the BFS hop count;
// disconnected pairs are exactly those the BFS oracle cannot join; the evaluation is deterministic.
TEST(AllPairs, GreedyPowerWithAttachmentDeliversEveryConnectedPair) {
  for (const char* links : {"unit-disk", "quasi-unit-disk"}) {
    const Topology t = field(220, 0.13, "square-with-holes.txt", links, 8);
    ASSERT_TRUE(t.sensors);
    const SensorNetwork& net = *t.sensors;
    const std::size_t n = net.points.size();
    const core::CircleEmbedding phi = packed(t.graph);
    const PlanarizationRouter planar(net);
    const std::vector<SensorRouter> routers{attached_router(net, t.graph, phi), planar.router(core::Scheme::greedy_euclid),
                                            planar.router(core::Scheme::compass), planar.router(core::Scheme::gfg)};
    const auto stats = evaluate_all_pairs(net, routers, {});
    std::size_t disconnected = 0;
    for (Vertex s = 0; s < n; ++s) {
      const auto d = hop_distances(n, net.links, s);
      for (Vertex v = 0; v < n; ++v) disconnected += v != s && d[v] == std::numeric_limits<std::uint32_t>::max();
      for (Vertex v = (s * 7) % 11; v < n; v += 11) {  // a slice of the targets, every scheme, routes checked hop by hop
        if (v == s || d[v] == std::numeric_limits<std::uint32_t>::max()) continue;
        for (const SensorRouter& r : routers) {
          const core::Route route = r(s, v);
          if (route.outcome != core::RouteOutcome::delivered) continue;
          ASSERT_EQ(route.path.front(), s);
          ASSERT_EQ(route.path.back(), v);
          EXPECT_GE(route.hops(), d[v]);
          for (std::size_t i = 0; i + 1 < route.path.size(); ++i)
            EXPECT_TRUE(std::binary_search(net.links.begin(), net.links.end(),
                                           std::pair{std::min(route.path[i], route.path[i + 1]),
                                                     std::max(route.path[i], route.path[i + 1])}));
        }
      }
    }
    ASSERT_EQ(stats.size(), 4u);
    for (const AllPairsStats& st : stats) {
      EXPECT_EQ(st.pairs, n * (n - 1));
      EXPECT_EQ(st.disconnected, disconnected);
      EXPECT_EQ(st.invalid_routes, 0u);
      EXPECT_GE(st.stretch_mean, 1.0);
      EXPECT_GE(st.stretch_p95, st.stretch_mean > 0 ? 1.0 : 0.0);
      EXPECT_GE(st.stretch_max, st.stretch_p95);
    }
    EXPECT_EQ(stats[0].delivered, n * (n - 1) - disconnected) << links << ": greedy power with attachment";
    EXPECT_EQ(stats[0].delivery_rate, 1.0);
    const auto again = evaluate_all_pairs(net, routers, {});
    for (std::size_t k = 0; k < stats.size(); ++k) {
      EXPECT_EQ(again[k].delivered, stats[k].delivered);
      EXPECT_EQ(again[k].stretch_mean, stats[k].stretch_mean);
    }
  }
}

// The same seed builds the same network (deployment, links, core, attachment).
TEST(Attachment, IsDeterministic) {
  const Topology a = field(300, 0.11, "many-small-holes.txt", "quasi-unit-disk", 4);
  const Topology b = field(300, 0.11, "many-small-holes.txt", "quasi-unit-disk", 4);
  ASSERT_TRUE(a.sensors && b.sensors);
  EXPECT_EQ(a.sensors->links, b.sensors->links);
  EXPECT_EQ(a.sensors->planar, b.sensors->planar);
  EXPECT_EQ(a.sensors->attachment.parent, b.sensors->attachment.parent);
  EXPECT_EQ(a.graph.ids(), b.graph.ids());
  EXPECT_EQ(a.note, b.note);
}
