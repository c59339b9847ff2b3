#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"

using namespace laguerre::core;

namespace {

std::vector<std::pair<Vertex, Vertex>> edge_pairs(const PlanarGraph& g) {
  std::vector<std::pair<Vertex, Vertex>> out;
  for (Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) out.emplace_back(g.tail(d), g.head(d));
  return out;
}

/// Rebuilding from the positions with the full plane-drawing check gives the same embedding.
void expect_plane_drawing(const GraphInput& in) {
  const PlanarGraph& g = in.graph;
  ASSERT_EQ(in.positions.size(), g.num_vertices());
  const GraphInput again = graph_from_drawing(g.ids(), in.positions, edge_pairs(g), "check", true);
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    const auto a = g.neighbours(v), b = again.graph.neighbours(v);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
  }
  EXPECT_EQ(again.graph.boundary_cycle(), g.boundary_cycle());
}

/// The outer face is the convex hull, walked clockwise with strict right turns.
void expect_convex_hull_boundary(const GraphInput& in) {
  const auto b = in.graph.boundary_cycle();
  ASSERT_GE(b.size(), 3u);
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Point2 p = in.positions[b[i]], q = in.positions[b[(i + 1) % b.size()]], r = in.positions[b[(i + 2) % b.size()]];
    EXPECT_EQ(orientation(p, q, r), Sign::negative);
  }
  for (Vertex v = 0; v < in.graph.num_vertices(); ++v) {
    if (in.graph.is_boundary(v)) continue;
    for (std::size_t i = 0; i < b.size(); ++i)
      EXPECT_EQ(orientation(in.positions[b[i]], in.positions[b[(i + 1) % b.size()]], in.positions[v]), Sign::negative);
  }
}

bool same_graph(const GraphInput& a, const GraphInput& b) {
  if (a.graph.num_vertices() != b.graph.num_vertices() || a.graph.num_edges() != b.graph.num_edges()) return false;
  for (std::size_t v = 0; v < a.positions.size(); ++v)
    if (a.positions[v].x != b.positions[v].x || a.positions[v].y != b.positions[v].y) return false;
  for (Vertex v = 0; v < a.graph.num_vertices(); ++v) {
    const auto x = a.graph.neighbours(v), y = b.graph.neighbours(v);
    if (!std::equal(x.begin(), x.end(), y.begin(), y.end())) return false;
  }
  return true;
}

}  // namespace

TEST(RandomGraphs, DelaunayTriangulationIsATriangulatedDiscOnTheHull) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const GraphInput in = random_delaunay_triangulation(200, seed);
    const PlanarGraph& g = in.graph;
    EXPECT_EQ(in.name, "random_delaunay_triangulation(n=200, seed=" + std::to_string(seed) + ")");
    EXPECT_TRUE(in.outer_given);
    EXPECT_TRUE(g.is_valid(true));
    ASSERT_EQ(g.num_vertices(), 200u);
    for (Vertex v = 0; v < 200; ++v) {
      EXPECT_EQ(g.id(v), v);
      EXPECT_LT(in.positions[v].x * in.positions[v].x + in.positions[v].y * in.positions[v].y, 1.0);
    }
    EXPECT_TRUE(g.inner_faces_are_triangles());
    const std::size_t hull = g.boundary_cycle().size();
    EXPECT_EQ(g.num_edges(), 3 * 200 - 3 - hull);  // Euler for a triangulated disc
    expect_plane_drawing(in);
    expect_convex_hull_boundary(in);
    GraphKind kind = GraphKind::three_connected;
    prepare_for_packing(in, &kind);
    EXPECT_EQ(kind, GraphKind::triangulated_disc);
  }
}

TEST(RandomGraphs, DeterministicBySeed) {
  EXPECT_TRUE(same_graph(random_delaunay_triangulation(100, 7), random_delaunay_triangulation(100, 7)));
  EXPECT_FALSE(same_graph(random_delaunay_triangulation(100, 7), random_delaunay_triangulation(100, 8)));
  EXPECT_TRUE(same_graph(random_three_connected(100, 7), random_three_connected(100, 7)));
  EXPECT_FALSE(same_graph(random_three_connected(100, 7), random_three_connected(100, 8)));
  // Golden values: mt19937_64 is fixed by the standard and the mapping to doubles is ours, so these hold
  // on every platform.
  const GraphInput golden = random_delaunay_triangulation(10, 1);
  EXPECT_EQ(golden.positions[0].x, -0x1.8fa5c310a338p-4);
  EXPECT_EQ(golden.positions[0].y, -0x1.ea789fea1b29p-1);
  EXPECT_EQ(golden.graph.num_edges(), 22u);
  EXPECT_EQ(random_three_connected(60, 1).graph.num_edges(), 121u);
}

TEST(RandomGraphs, ThreeConnectedGraphsAreThreeConnectedAndThinned) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const std::size_t n = 60;
    const GraphInput in = random_three_connected(n, seed);
    const PlanarGraph& g = in.graph;
    SCOPED_TRACE(write_edge_list(g));
    EXPECT_TRUE(g.is_valid(true));
    EXPECT_TRUE(in.outer_given);
    ASSERT_EQ(g.num_vertices(), n);
    EXPECT_TRUE(is_three_connected(g));
    expect_plane_drawing(in);
    expect_convex_hull_boundary(in);
    const std::size_t hull = g.boundary_cycle().size();
    const std::size_t triangulation_edges = 3 * n - 3 - hull;
    EXPECT_LE(g.num_edges(), triangulation_edges - 30);  // most of the 45 requested deletions happen
    EXPECT_GE(g.num_edges(), triangulation_edges - 45);
    for (Face f = 0; f < g.num_faces(); ++f)
      if (f != g.outer_face()) {
        EXPECT_LE(g.face_size(f), 8u);
      }
    GraphKind kind = GraphKind::triangulated_disc;
    const PlanarGraph p = prepare_for_packing(in, &kind);
    EXPECT_EQ(kind, GraphKind::three_connected);
    EXPECT_EQ(p.boundary_cycle(), g.boundary_cycle());
  }
}

TEST(RandomGraphs, ThreeConnectedParameters) {
  const GraphInput k4 = random_three_connected(4, 3);
  EXPECT_EQ(k4.graph.num_edges(), 6u);
  EXPECT_TRUE(is_three_connected(k4.graph));
  const GraphInput none_deleted = random_three_connected(50, 3, 0.0);
  EXPECT_TRUE(none_deleted.graph.inner_faces_are_triangles());
  const GraphInput many = random_three_connected(50, 3, 10.0, 4);
  for (Face f = 0; f < many.graph.num_faces(); ++f)
    if (f != many.graph.outer_face()) {
      EXPECT_LE(many.graph.face_size(f), 4u);
    }
  EXPECT_TRUE(is_three_connected(many.graph));
  EXPECT_THROW(random_delaunay_triangulation(2, 1), GraphInputError);
  EXPECT_THROW(random_three_connected(3, 1), GraphInputError);
  EXPECT_THROW(random_three_connected(10, 1, -1.0), GraphInputError);
  EXPECT_THROW(random_three_connected(10, 1, 0.5, 3), GraphInputError);
  try {
    random_delaunay_triangulation(2, 7);
    ADD_FAILURE() << "no GraphInputError";
  } catch (const GraphInputError& e) {
    EXPECT_STREQ(e.what(), "random_delaunay_triangulation(n=2, seed=7): a random Delaunay triangulation needs at least 3 "
                           "vertices, not 2.");
  }
}

TEST(RandomGraphs, LargeGraphsStayValid) {
  const GraphInput tri = random_delaunay_triangulation(5000, 11);
  EXPECT_TRUE(tri.graph.is_valid());
  EXPECT_TRUE(tri.graph.inner_faces_are_triangles());
  const GraphInput three = random_three_connected(5000, 11);
  EXPECT_TRUE(three.graph.is_valid());
  EXPECT_TRUE(is_three_connected(three.graph));
  EXPECT_LT(three.graph.num_edges(), tri.graph.num_edges());
}
