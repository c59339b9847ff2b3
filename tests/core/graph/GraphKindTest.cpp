#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"

using namespace laguerre::core;

namespace {

PlanarGraph from_edges(const std::string& text) {
  return read_graphs_from_string(text, "<input>", GraphFormat::edges).at(0).graph;
}

/// Brute force: no set of at most 2 vertices disconnects the graph, and n ≥ 4.
bool brute_force_three_connected(const PlanarGraph& g) {
  const std::size_t n = g.num_vertices();
  if (n < 4) return false;
  // Union-find over the edges avoiding a and b: an oracle independent of the traversal under test.
  auto connected_without = [&](Vertex a, Vertex b) {
    std::vector<Vertex> parent(n);
    std::iota(parent.begin(), parent.end(), Vertex{0});
    const auto root = [&](Vertex v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    std::size_t components = n - (a == b ? 1 : 2);
    for (Dart d = 0; d < g.num_darts(); ++d) {
      const Vertex u = g.tail(d), w = g.head(d);
      if (u == a || u == b || w == a || w == b) continue;
      const Vertex ru = root(u), rw = root(w);
      if (ru != rw) parent[ru] = rw, --components;
    }
    return components == 1;
  };
  for (Vertex a = 0; a < n; ++a)
    for (Vertex b = a; b < n; ++b)
      if (!connected_without(a, b)) return false;
  return true;
}

std::vector<std::uint64_t> boundary_ids(const PlanarGraph& g) {
  std::vector<std::uint64_t> ids;
  for (Vertex v : g.boundary_cycle()) ids.push_back(g.id(v));
  std::sort(ids.begin(), ids.end());
  return ids;
}

/// The kind prepare_for_packing decides for a graph and the (sorted) ids of the outer face it chooses.
using Packed = std::pair<GraphKind, std::vector<std::uint64_t>>;
Packed packed(const std::string& edges_text) {
  GraphKind kind{};
  const PlanarGraph p = prepare_for_packing(read_graphs_from_string(edges_text, "<input>", GraphFormat::edges).at(0), &kind);
  return {kind, boundary_ids(p)};
}

const std::string cube = "0 1\n1 2\n2 3\n3 0\n4 5\n5 6\n6 7\n7 4\n0 4\n1 5\n2 6\n3 7\n";
const std::string prism = "0 1\n1 2\n2 0\n3 4\n4 5\n5 3\n0 3\n1 4\n2 5\n";
const std::string octahedron = "0 1\n0 2\n0 3\n0 4\n1 2\n2 3\n3 4\n4 1\n5 1\n5 2\n5 3\n5 4\n";
const std::string k4 = "1 2\n1 3\n1 4\n2 3\n2 4\n3 4\n";
const std::string wheel = "0 1\n0 2\n0 3\n0 4\n0 5\n1 2\n2 3\n3 4\n4 5\n5 1\n";
// Two K4s {1,2,3,4} and {3,4,5,6} glued along the edge 3-4: {3, 4} separates.
const std::string two_k4_on_an_edge = "1 2\n1 3\n1 4\n2 3\n2 4\n3 4\n3 5\n3 6\n4 5\n4 6\n5 6\n";
// Two cubes sharing the edge 0-1: {0, 1} is the only separating pair, and many faces are squares.
const std::string two_cubes = cube + "1 9\n9 8\n8 0\n10 11\n11 12\n12 13\n13 10\n0 10\n1 11\n9 12\n8 13\n";
// Two K4s sharing vertex 4: a cut vertex.
const std::string two_k4_on_a_vertex = "1 2\n1 3\n1 4\n2 3\n2 4\n3 4\n4 5\n4 6\n4 7\n5 6\n5 7\n6 7\n";

}  // namespace

TEST(GraphKind, Names) {
  EXPECT_EQ(to_string(GraphKind::triangulated_disc), "triangulated_disc");
  EXPECT_EQ(to_string(GraphKind::three_connected), "three_connected");
}

TEST(GraphKind, ThreeConnectivityKnownAnswers) {
  for (const std::string* text : {&cube, &prism, &octahedron, &k4, &wheel}) {
    const PlanarGraph g = from_edges(*text);
    EXPECT_TRUE(is_three_connected(g)) << *text;
    EXPECT_TRUE(find_small_separator(g).empty());
  }
  EXPECT_FALSE(is_three_connected(from_edges("1 2\n2 3\n3 4\n4 5\n5 1\n")));  // a cycle
  EXPECT_FALSE(is_three_connected(from_edges("1 2\n2 3\n3 1\n")));           // too small
  EXPECT_FALSE(is_three_connected(from_edges("1 2\n1 3\n1 4\n2 3\n3 4\n")));  // K4 minus an edge
  EXPECT_FALSE(is_three_connected(from_edges("1 2\n2 3\n3 4\n")));            // a path

  const PlanarGraph glued = from_edges(two_k4_on_an_edge);
  EXPECT_FALSE(is_three_connected(glued));
  const auto pair = find_small_separator(glued);
  ASSERT_EQ(pair.size(), 2u);
  EXPECT_EQ(glued.id(pair[0]), 3u);
  EXPECT_EQ(glued.id(pair[1]), 4u);

  EXPECT_FALSE(is_three_connected(from_edges(two_cubes)));
  const PlanarGraph pinched = from_edges(two_k4_on_a_vertex);
  const auto cut = find_small_separator(pinched);
  ASSERT_EQ(cut.size(), 1u);
  EXPECT_EQ(pinched.id(cut[0]), 4u);
}

TEST(GraphKind, AgreesWithBruteForceOnRandomSubgraphs) {
  std::mt19937_64 engine(17);
  int yes = 0, no = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 5 + engine() % 20;
    const GraphInput base = random_delaunay_triangulation(n, engine());
    const PlanarGraph& g = base.graph;
    std::vector<std::pair<Vertex, Vertex>> edges;
    const std::uint64_t drop_one_in = 3 + engine() % 8;
    for (Dart d = 0; d < g.num_darts(); ++d)
      if (g.tail(d) < g.head(d) && engine() % drop_one_in != 0) edges.emplace_back(g.tail(d), g.head(d));
    GraphInput sub;
    try {
      sub = graph_from_drawing(g.ids(), base.positions, edges, "sub");
    } catch (const GraphInputError&) {
      continue;  // disconnected
    }
    const bool expected = brute_force_three_connected(sub.graph);
    EXPECT_EQ(is_three_connected(sub.graph), expected) << write_edge_list(sub.graph);
    EXPECT_EQ(find_small_separator(sub.graph).empty(), expected || n < 4);
    (expected ? yes : no)++;
  }
  EXPECT_GT(yes, 10);
  EXPECT_GT(no, 10);
}

TEST(GraphKind, SphereTriangulationIsADiscWithATriangularBoundary) {
  const PlanarGraph g = from_edges(octahedron);
  GraphKind kind = GraphKind::three_connected;
  const PlanarGraph p = prepare_for_packing(g, false, &kind);
  EXPECT_EQ(kind, GraphKind::triangulated_disc);
  EXPECT_EQ(p.outer_face(), p.face_of(p.default_outer_dart()));
  EXPECT_EQ(p.boundary_cycle().size(), 3u);
  // An explicit outer face is kept.
  EXPECT_EQ(packed("# outer: 5 2 3\n" + octahedron), (Packed{GraphKind::triangulated_disc, {2, 3, 5}}));
}

TEST(GraphKind, TheOnlyNonTriangleBecomesTheOuterFace) {
  EXPECT_EQ(packed(wheel), (Packed{GraphKind::triangulated_disc, {1, 2, 3, 4, 5}}));
  EXPECT_FALSE(prepare_for_packing(from_edges(wheel), false).is_boundary(0));
  // Octahedron minus the edge 1-2: the quadrilateral 0 1 5 2 is the disc's boundary.
  const std::string no12 = "0 1\n0 2\n0 3\n0 4\n2 3\n3 4\n4 1\n5 1\n5 2\n5 3\n5 4\n";
  EXPECT_EQ(packed(no12), (Packed{GraphKind::triangulated_disc, {0, 1, 2, 5}}));
  // With a triangle given as the outer face, the graph is packed as 3-connected instead.
  EXPECT_EQ(packed("# outer: 0 3 4\n" + no12), (Packed{GraphKind::three_connected, {0, 3, 4}}));
}

TEST(GraphKind, ThreeConnectedOuterFaceRule) {
  GraphKind kind{};
  // Cube: all faces are squares; the face with edge list {0-1, 0-3, 1-2, 2-3} beats {0-1, 0-4, …}.
  EXPECT_EQ(packed(cube), (Packed{GraphKind::three_connected, {0, 1, 2, 3}}));
  // Prism: the largest faces are the squares; {0-1, 0-3, 1-4, 3-4} is the smallest.
  EXPECT_EQ(packed(prism), (Packed{GraphKind::three_connected, {0, 1, 3, 4}}));
  // An explicit outer face is kept.
  const GraphInput top = read_graphs_from_string("# outer: 4 5 6 7\n" + cube).at(0);
  EXPECT_EQ(boundary_ids(prepare_for_packing(top, &kind)), (std::vector<std::uint64_t>{4, 5, 6, 7}));
  // The rule does not depend on the mirror image.
  const GraphInput mirrored = read_graphs_from_string("# outer: 7 6 5 4\n" + cube).at(0);
  EXPECT_EQ(boundary_ids(prepare_for_packing(mirrored.graph, false, &kind)), (std::vector<std::uint64_t>{0, 1, 2, 3}));
}

TEST(GraphKind, RejectsGraphsOfNeitherKind) {
  try {
    prepare_for_packing(from_edges(two_cubes), false, nullptr, "glued.txt");
    FAIL() << "no exception";
  } catch (const GraphInputError& e) {
    EXPECT_EQ(e.source(), "glued.txt");
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("glued.txt: the graph is neither a triangulated disc", 0), 0u) << what;
    EXPECT_NE(what.find("removing vertices 0 and 1 disconnects it"), std::string::npos) << what;
    EXPECT_NE(what.find("'# outer: a b c ...'"), std::string::npos) << what;
  }
  try {
    // Whichever face the second K4 sits in, that face is the only non-triangle and visits 4 twice.
    prepare_for_packing(from_edges(two_k4_on_a_vertex), false);
    FAIL() << "no exception";
  } catch (const GraphInputError& e) {
    EXPECT_NE(std::string(e.what()).find("visits vertex 4 twice"), std::string::npos) << e.what();
  }
  try {
    prepare_for_packing(from_edges("1 2\n"), false);
    FAIL() << "no exception";
  } catch (const GraphInputError& e) {
    EXPECT_STREQ(e.what(), "<input>: the graph has 2 vertices; circle packing needs at least 3.");
  }
  // A cycle: two faces of length 5, neither a disc nor 3-connected.
  EXPECT_THROW(prepare_for_packing(from_edges("1 2\n2 3\n3 4\n4 5\n5 1\n"), false), GraphInputError);
}

TEST(GraphKind, RandomThreeConnectedGraphsPassTheBruteForceTest) {
  for (std::uint64_t seed = 0; seed < 150; ++seed) {
    const std::size_t n = 4 + seed % 37;
    const GraphInput in = random_three_connected(n, seed, 2.0, 4 + seed % 6);
    EXPECT_TRUE(brute_force_three_connected(in.graph)) << in.name << "\n" << write_edge_list(in.graph);
  }
}
