#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/FieldGraph.hpp"

using namespace laguerre::scenarios;
using laguerre::core::Domain;
using laguerre::core::Point2;
using laguerre::core::Vertex;
namespace core = laguerre::core;

namespace {

std::vector<std::pair<Vertex, Vertex>> index_edges(const core::PlanarGraph& g) {
  std::vector<std::pair<Vertex, Vertex>> out;
  for (core::Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) out.emplace_back(g.tail(d), g.head(d));
  return out;
}

/// The drawing is plane (full exact crossing check) and every inner face is a triangle.
void expect_plane_triangulated_disc(const FieldGraph& fg) {
  const auto& g = fg.input.graph;
  EXPECT_NO_THROW(core::graph_from_drawing(g.ids(), fg.input.positions, index_edges(g), "check", true));
  EXPECT_TRUE(g.inner_faces_are_triangles());
  auto b = g.boundary_cycle();
  std::sort(b.begin(), b.end());
  EXPECT_EQ(std::adjacent_find(b.begin(), b.end()), b.end());
  EXPECT_EQ(fg.kind, core::GraphKind::triangulated_disc);
}

std::string failure(const Domain& d, const std::vector<Point2>& p, FieldGraphOptions o) {
  try {
    build_field_graph(d, p, o);
  } catch (const FieldGraphError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(FieldGraph, DelaunayOfASquareIsATriangulatedDiscWithPointIds) {
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  const auto p = deploy_uniform(d, 300, 1);
  const FieldGraph fg = build_field_graph(d, p, {});
  expect_plane_triangulated_disc(fg);
  EXPECT_EQ(fg.input.graph.num_vertices(), 300u);
  EXPECT_TRUE(fg.input.outer_given);
  for (Vertex v = 0; v < 300; ++v) {
    EXPECT_EQ(fg.input.graph.id(v), v);
    EXPECT_EQ(fg.input.positions[v].x, p[v].x);
  }
  EXPECT_EQ(fg.report.components, 1u);
  EXPECT_TRUE(fg.report.triangulated_disc);
  EXPECT_FALSE(fg.report.repaired);
}

TEST(FieldGraph, FailPolicyNamesTheProblemAndAWitness) {
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  const auto p = deploy_uniform(d, 200, 4);
  const std::string disconnected = failure(d, p, {FieldGraphType::gabriel, 0.05, 2, RepairPolicy::fail, "sparse.yaml"});
  EXPECT_EQ(disconnected.rfind("sparse.yaml: the gabriel graph (R = 0.05) of 200 points is not connected: ", 0), 0u)
      << disconnected;
  EXPECT_NE(disconnected.find("cannot be reached from point 0"), std::string::npos);
  EXPECT_NE(disconnected.find("choose repair: largest-block"), std::string::npos);
  // Dense enough to be connected, but Gabriel faces are not all triangles and some vertex has degree ≤ 2.
  const std::string neither = failure(d, p, {FieldGraphType::gabriel, 0.5, 2, RepairPolicy::fail, "dense.yaml"});
  EXPECT_NE(neither.find("is neither a triangulated disc ("), std::string::npos) << neither;
  EXPECT_NE(neither.find("inner faces are not triangles) nor 3-connected: removing point"), std::string::npos) << neither;
  try {
    build_field_graph(d, p, {FieldGraphType::relative_neighbourhood, 0.5, 2, RepairPolicy::fail, "x"});
    ADD_FAILURE() << "an RNG is never packable as built";
  } catch (const FieldGraphError& e) {
    EXPECT_EQ(e.report().components, 1u);
    EXPECT_FALSE(e.report().triangulated_disc);
    EXPECT_FALSE(e.report().separator.empty());
  }
}

TEST(FieldGraph, UnitDiskGraphWithCrossingsIsRefused) {
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  const auto p = deploy_uniform(d, 200, 4);
  const std::string message = failure(d, p, {FieldGraphType::unit_disk, 0.3, 2, RepairPolicy::triangulate_faces, "udg"});
  EXPECT_NE(message.find("cannot be drawn as a plane graph"), std::string::npos) << message;
  EXPECT_NE(message.find("Use a planar spanner"), std::string::npos) << message;
}

TEST(FieldGraph, RepairPoliciesGivePackableGraphs) {
  const Domain d({{0, 0}, {3, 0}, {3, 3}, {0, 3}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  const auto p = deploy_uniform(d, 800, 12);
  for (FieldGraphType type : {FieldGraphType::gabriel, FieldGraphType::relative_neighbourhood,
                              FieldGraphType::local_delaunay, FieldGraphType::delaunay}) {
    SCOPED_TRACE(std::string(to_string(type)));
    const FieldGraphOptions base{type, 0.25, 2, RepairPolicy::fail, "field"};
    auto o = base;
    o.repair = RepairPolicy::triangulate_faces;
    const FieldGraph tri = build_field_graph(d, p, o);
    if (type == FieldGraphType::delaunay && !tri.report.repaired) {  // the hole as a face, and 3-connected
      EXPECT_TRUE(tri.report.three_connected);
      EXPECT_EQ(tri.kind, core::GraphKind::three_connected);
    } else {
      expect_plane_triangulated_disc(tri);
      EXPECT_TRUE(tri.report.repaired);
      EXPECT_GT(tri.report.added_chords, 0u);
    }
    o.repair = RepairPolicy::largest_block;
    try {
      const FieldGraph block = build_field_graph(d, p, o);
      EXPECT_TRUE(core::is_three_connected(block.input.graph) || block.kind == core::GraphKind::triangulated_disc);
      EXPECT_NE(core::find_small_separator(block.input.graph).size(), 1u);  // 2-connected
    } catch (const FieldGraphError& e) {
      EXPECT_NE(std::string(e.what()).find("its largest 2-connected block ("), std::string::npos) << e.what();
    }
    o.repair = RepairPolicy::three_connected_core;
    if (type == FieldGraphType::relative_neighbourhood) {  // nearly a forest: peeling low degrees leaves nothing
      try {
        build_field_graph(d, p, o);
        ADD_FAILURE() << "expected the RNG's three-connected core to be empty";
      } catch (const FieldGraphError& e) {
        EXPECT_NE(std::string(e.what()).find("three-connected core has fewer than 3 points"), std::string::npos) << e.what();
      }
      continue;
    }
    const FieldGraph core3 = build_field_graph(d, p, o);
    EXPECT_TRUE(core::is_three_connected(core3.input.graph) || core3.kind == core::GraphKind::triangulated_disc);
    EXPECT_EQ(core3.input.graph.num_vertices() + core3.report.removed_points, 800u);
    EXPECT_NO_THROW(core::graph_from_drawing(core3.input.graph.ids(), core3.input.positions,
                                             index_edges(core3.input.graph), "check", true));
    if (type == FieldGraphType::delaunay || type == FieldGraphType::local_delaunay) {  // dense: most points stay
      EXPECT_GT(core3.input.graph.num_vertices(), 700u);
    }
  }
}

TEST(FieldGraph, DeterministicPerSeed) {
  const Domain d({{0, 0}, {4, 0}, {4, 2}, {0, 2}}, {{{1, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {1, 1.5}}});
  const ClusterOptions clusters{6, 0.3, ClusterShape::gaussian};
  const FieldGraphOptions o{FieldGraphType::local_delaunay, 0.3, 2, RepairPolicy::three_connected_core, "f"};
  const auto a = build_field_graph(d, deploy_clustered(d, 500, clusters, 77), o);
  const auto b = build_field_graph(d, deploy_clustered(d, 500, clusters, 77), o);
  EXPECT_EQ(core::write_edge_list(a.input.graph), core::write_edge_list(b.input.graph));
  EXPECT_EQ(a.report.summary("f"), b.report.summary("f"));
  const auto c = build_field_graph(d, deploy_clustered(d, 500, clusters, 78), o);
  EXPECT_NE(core::write_edge_list(a.input.graph), core::write_edge_list(c.input.graph));
}

TEST(FieldGraph, NonPlaneLocalDelaunayOneIsRefusedOrPlane) {
  // LDel^(1) may have crossing edges; the builder checks it exactly: either a plane graph or the message.
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto p = deploy_uniform(d, 400, seed);
    try {
      const FieldGraph fg = build_field_graph(d, p, {FieldGraphType::local_delaunay, 0.12, 1, RepairPolicy::triangulate_faces, "l1"});
      EXPECT_NO_THROW(core::graph_from_drawing(fg.input.graph.ids(), fg.input.positions, index_edges(fg.input.graph), "c", true));
    } catch (const FieldGraphError& e) {
      EXPECT_NE(std::string(e.what()).find("cannot be drawn as a plane graph"), std::string::npos) << e.what();
    }
  }
}

TEST(FieldGraph, RadiusForMeanDegree) {
  const Domain d = Domain::rectangle(0, 0, 2, 2);
  const auto p = deploy_uniform(d, 4000, 3);
  const double r = radius_for_mean_degree(d, p.size(), 10);
  const double mean = 2.0 * static_cast<double>(unit_disk_edges(p, r).size()) / static_cast<double>(p.size());
  EXPECT_GT(mean, 9.0);  // boundary effects lower it by about 4 R / side ≈ 6% here
  EXPECT_LT(mean, 10.3);
  EXPECT_THROW(radius_for_mean_degree(d, 0, 10), laguerre::core::InternalError);
}

TEST(FieldGraph, NamesRoundTrip) {
  for (auto t : {FieldGraphType::delaunay, FieldGraphType::unit_disk, FieldGraphType::gabriel,
                 FieldGraphType::relative_neighbourhood, FieldGraphType::local_delaunay})
    EXPECT_EQ(parse_field_graph_type(to_string(t)), t);
  for (auto r : {RepairPolicy::fail, RepairPolicy::largest_block, RepairPolicy::three_connected_core,
                 RepairPolicy::triangulate_faces})
    EXPECT_EQ(parse_repair_policy(to_string(r)), r);
  EXPECT_THROW(parse_field_graph_type("voronoi"), laguerre::core::InputError);
  EXPECT_THROW(parse_repair_policy("ignore"), laguerre::core::InputError);
}
