#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "GraphTestSupport.hpp"
#include "../../support/Scratch.hpp"

using namespace laguerre::core;
using namespace laguerre::core::test;

namespace {

std::string bytes(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) out.push_back(static_cast<char>(v));
  return out;
}

std::vector<std::uint64_t> ids_of(const PlanarGraph& g, const std::vector<Vertex>& vertices) {
  std::vector<std::uint64_t> out;
  for (Vertex v : vertices) out.push_back(g.id(v));
  return out;
}

/// Whether b is a cyclic rotation of a.
template <class T>
bool cyclic_equal(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  if (a.empty()) return true;
  for (std::size_t s = 0; s < a.size(); ++s) {
    bool same = true;
    for (std::size_t i = 0; i < a.size() && same; ++i) same = a[(s + i) % a.size()] == b[i];
    if (same) return true;
  }
  return false;
}

/// Neighbour ids of every vertex, keyed by the vertex's id, for comparing embeddings across readers.
std::vector<std::vector<std::uint64_t>> id_rotation(const PlanarGraph& g) {
  std::vector<std::vector<std::uint64_t>> out(g.num_vertices());
  for (Vertex v = 0; v < g.num_vertices(); ++v)
    for (Vertex w : g.neighbours(v)) out[v].push_back(g.id(w));
  return out;
}

bool same_embedding(const PlanarGraph& a, const PlanarGraph& b) {
  if (a.ids() != b.ids()) return false;
  const auto ra = id_rotation(a), rb = id_rotation(b);
  for (std::size_t v = 0; v < ra.size(); ++v)
    if (!cyclic_equal(ra[v], rb[v])) return false;
  return true;
}

bool mirror_embedding(const PlanarGraph& a, const PlanarGraph& b) {
  if (a.ids() != b.ids()) return false;
  auto ra = id_rotation(a);
  const auto rb = id_rotation(b);
  for (std::size_t v = 0; v < ra.size(); ++v) {
    std::reverse(ra[v].begin(), ra[v].end());
    if (!cyclic_equal(ra[v], rb[v])) return false;
  }
  return true;
}

// K4 drawn with 1 at the centre (0, 0), 2 at (0, 1), 3 at (-1, -1), 4 at (1, -1), encoded by hand in
// planar_code from that drawing: each vertex's neighbours clockwise, then 0.
//   1: 2 4 3   2: 4 1 3   3: 2 1 4   4: 3 1 2
const std::initializer_list<int> k4_narrow = {4, 2, 4, 3, 0, 4, 1, 3, 0, 2, 1, 4, 0, 3, 1, 2, 0};

GraphInput k4_drawing() {
  return graph_from_drawing({1, 2, 3, 4}, {{0, 0}, {0, 1}, {-1, -1}, {1, -1}}, {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}},
                            "k4");
}

}  // namespace

// ---------------------------------------------------------------------------------------------------
// Formats.

TEST(GraphIO, ParsesFormatNames) {
  EXPECT_EQ(parse_graph_format("automatic"), GraphFormat::automatic);
  EXPECT_EQ(parse_graph_format("edges"), GraphFormat::edges);
  EXPECT_EQ(parse_graph_format("planar_code"), GraphFormat::planar_code);
  EXPECT_EQ(parse_graph_format("coords"), GraphFormat::coords);
  for (GraphFormat f : {GraphFormat::automatic, GraphFormat::edges, GraphFormat::planar_code, GraphFormat::coords,
                        GraphFormat::graphml, GraphFormat::dot})
    EXPECT_EQ(parse_graph_format(to_string(f)), f);
  const auto e = expect_input_error([] { parse_graph_format("gml"); });
  EXPECT_STREQ(e.what(),
               "format: unknown graph format 'gml'; expected one of automatic, edges, planar_code, coords, graphml, dot.");
}

TEST(GraphIO, GraphInputErrorIsAnInputErrorWithTheSameText) {
  const GraphInputError e("g.pc", 0, 3, "graph 3 has no vertices.");
  const InputError& base = e;
  EXPECT_STREQ(base.what(), "g.pc#3: graph 3 has no vertices.");
  EXPECT_EQ(base.source(), "g.pc");
  EXPECT_EQ(base.message(), "graph 3 has no vertices.");
  EXPECT_EQ(e.graph_index(), 3u);
  EXPECT_STREQ(GraphInputError("g.txt", 12, 0, "bad.").what(), "g.txt:12: bad.");
}

// ---------------------------------------------------------------------------------------------------
// Edge lists.

TEST(GraphIO, ReadsOctahedronEdgeListWithBoyerMyrvoldEmbedding) {
  const auto graphs = read_graphs(data_path("octahedron.txt"));
  ASSERT_EQ(graphs.size(), 1u);
  const GraphInput& in = graphs[0];
  const PlanarGraph& g = in.graph;
  EXPECT_EQ(in.name, data_path("octahedron.txt"));
  EXPECT_FALSE(in.outer_given);
  EXPECT_TRUE(in.positions.empty());
  EXPECT_TRUE(g.is_valid(true));
  EXPECT_EQ(g.num_vertices(), 6u);
  EXPECT_EQ(g.num_edges(), 12u);
  EXPECT_EQ(g.num_faces(), 8u);  // Euler: 6 - 12 + 8 = 2
  for (Face f = 0; f < g.num_faces(); ++f) EXPECT_EQ(g.face_size(f), 3u);
  EXPECT_EQ(g.outer_face(), g.face_of(g.default_outer_dart()));
}

TEST(GraphIO, KeepsUserIdsInIncreasingOrder) {
  const GraphInput cube = read_graphs(data_path("cube.txt")).at(0);
  ASSERT_EQ(cube.graph.num_vertices(), 8u);
  for (Vertex v = 0; v < 8; ++v) EXPECT_EQ(cube.graph.id(v), 100u + v);
  EXPECT_EQ(cube.graph.num_faces(), 6u);
  for (Face f = 0; f < 6; ++f) EXPECT_EQ(cube.graph.face_size(f), 4u);

  const GraphInput big = read_one("18446744073709551615 5\n5 7\n7 18446744073709551615\n");
  EXPECT_EQ(big.graph.ids(), (std::vector<std::uint64_t>{5, 7, 18446744073709551615u}));
  EXPECT_EQ(big.graph.vertex_of_id(18446744073709551615u), Vertex{2});
}

TEST(GraphIO, IgnoresCommentsBlankLinesAndCarriageReturns) {
  const GraphInput in = read_one("# a triangle\r\n\r\n1 2   # first edge\r\n  2\t3\r\n3 1\r\n# done\r\n");
  EXPECT_EQ(in.graph.num_vertices(), 3u);
  EXPECT_EQ(in.graph.num_edges(), 3u);
}

TEST(GraphIO, OuterDirectiveForcesTheOuterFaceOfATriangulatedDisc) {
  const GraphInput in = read_graphs(data_path("disc_with_ears.txt")).at(0);
  const PlanarGraph& g = in.graph;
  EXPECT_TRUE(in.outer_given);
  EXPECT_TRUE(g.is_valid(true));
  EXPECT_TRUE(g.inner_faces_are_triangles());
  // Oriented so that boundary_cycle() follows the order of the directive.
  EXPECT_TRUE(cyclic_equal(ids_of(g, g.boundary_cycle()), {1, 7, 2, 3, 8, 4, 5, 6}));
  EXPECT_FALSE(g.is_boundary(*g.vertex_of_id(0)));
  GraphKind kind{};
  const PlanarGraph prepared = prepare_for_packing(in, &kind);
  EXPECT_EQ(kind, GraphKind::triangulated_disc);
  EXPECT_TRUE(cyclic_equal(ids_of(prepared, prepared.boundary_cycle()), {1, 7, 2, 3, 8, 4, 5, 6}));
}

TEST(GraphIO, OuterDirectiveOrderFixesTheMirrorImage) {
  const std::string edges = "0 1\n0 2\n0 3\n0 4\n1 2\n2 3\n3 4\n4 1\n5 1\n5 2\n5 3\n5 4\n";
  const GraphInput forward = read_one("# outer: 1 2 5\n" + edges);
  const GraphInput backward = read_one("# outer: 5 2 1\n" + edges);
  EXPECT_TRUE(cyclic_equal(ids_of(forward.graph, forward.graph.boundary_cycle()), {1, 2, 5}));
  EXPECT_TRUE(cyclic_equal(ids_of(backward.graph, backward.graph.boundary_cycle()), {5, 2, 1}));
  EXPECT_TRUE(mirror_embedding(forward.graph, backward.graph));
}

TEST(GraphIO, EdgeListRoundTrips) {
  for (const char* file : {"cube.txt", "disc_with_ears.txt", "octahedron.txt"}) {
    SCOPED_TRACE(file);
    const GraphInput first = read_graphs(data_path(file)).at(0);
    const std::string text = write_edge_list(first.graph);
    const GraphInput second = read_one(text);
    EXPECT_TRUE(second.outer_given);  // the writer always gives the outer face
    EXPECT_EQ(second.graph.ids(), first.graph.ids());
    EXPECT_EQ(second.graph.num_edges(), first.graph.num_edges());
    EXPECT_EQ(ids_of(second.graph, second.graph.boundary_cycle()).size(), first.graph.boundary_cycle().size());
    EXPECT_TRUE(cyclic_equal(ids_of(second.graph, second.graph.boundary_cycle()),
                             ids_of(first.graph, first.graph.boundary_cycle())));
    // These graphs have a unique embedding once the outer face and its orientation are fixed.
    EXPECT_TRUE(same_embedding(first.graph, second.graph));
    EXPECT_EQ(write_edge_list(second.graph), text);
  }
  EXPECT_EQ(write_edge_list(read_one("# outer: 1 2 3\n3 1\n1 2\n2 3\n").graph),
            "# laguerre edge list: 3 vertices, 3 edges\n# outer: 1 2 3\n1 2\n1 3\n2 3\n");
}

TEST(GraphIO, EdgeListErrorsNameTheLine) {
  auto e = expect_input_error([] { read_one("1 2\n2 x\n3 1\n"); });
  EXPECT_EQ(e.line(), 2u);
  EXPECT_EQ(e.source(), "<input>");
  EXPECT_STREQ(e.what(), "<input>:2: expected two non-negative integer vertex ids, found '2 x'.");

  EXPECT_EQ(read_error("1 2\n2 3 4\n"),
            "<input>:2: expected two non-negative integer vertex ids, found '2 3 4'.");
  e = expect_input_error([] { read_one("-1 2\n"); });
  EXPECT_EQ(e.line(), 1u);
  e = expect_input_error([] { read_one("1 2\n2 99999999999999999999\n"); });
  EXPECT_EQ(e.line(), 2u);

  EXPECT_EQ(read_error("1 2\n\n2 2\n"),
            "<input>:3: edge 2-2 is a self-loop; the graph must be simple.");

  e = expect_input_error([] { read_one("1 2\n2 3\n3 1\n# again\n2 1\n"); });
  EXPECT_EQ(e.line(), 5u);
  EXPECT_STREQ(e.what(), "<input>:5: edge 2-1 is listed twice (first on line 1); the graph must be simple.");

  e = expect_input_error([] { read_one("1 2\n3 4\n"); });
  EXPECT_EQ(e.line(), 0u);
  EXPECT_STREQ(e.what(), "<input>: the graph is not connected: vertex 3 cannot be reached from vertex 1.");

  EXPECT_EQ(read_error("# nothing here\n\n"),
            "<input>: the input contains no edges.");

  e = expect_input_error([] { read_graphs(data_path("k5.txt")); });
  EXPECT_EQ(e.source(), data_path("k5.txt"));
  EXPECT_EQ(e.message(), "the graph is not planar (the Boyer-Myrvold test found a Kuratowski subgraph).");
  e = expect_input_error([] { read_one("1 4\n1 5\n1 6\n2 4\n2 5\n2 6\n3 4\n3 5\n3 6\n"); });  // K3,3
  EXPECT_EQ(e.message(), "the graph is not planar (the Boyer-Myrvold test found a Kuratowski subgraph).");

  // Missing files and directories: core::open_input_file's sentences.
  e = expect_input_error([] { read_graphs(data_path("no-such-file.txt")); });
  EXPECT_EQ(e.source(), data_path("no-such-file.txt"));
  EXPECT_EQ(e.message(), "no such graph file (the file does not exist).");
  e = expect_input_error([] { read_graphs(std::string(LAGUERRE_TEST_DATA) + "/graphs"); });
  EXPECT_STREQ(e.what(), (std::string(LAGUERRE_TEST_DATA) + "/graphs: is a directory; expected a graph file.").c_str());
}

TEST(GraphIO, OuterDirectiveErrors) {
  const std::string octahedron = "0 1\n0 2\n0 3\n0 4\n1 2\n2 3\n3 4\n4 1\n5 1\n5 2\n5 3\n5 4\n";
  auto e = expect_input_error([] { read_one("1 2\n# outer: 1 2\n2 3\n3 1\n"); });
  EXPECT_STREQ(e.what(), "<input>:2: the '# outer:' directive must list a cycle of at least 3 vertices, found 2.");
  EXPECT_EQ(read_error("# outer: 1 2 9\n1 2\n2 3\n3 1\n"),
            "<input>:1: the '# outer:' directive lists vertex 9, which is on no edge.");
  e = expect_input_error([] { read_one("# outer: 1 2 1\n1 2\n2 3\n3 1\n"); });
  EXPECT_EQ(e.line(), 1u);
  EXPECT_NE(e.message().find("twice"), std::string::npos);
  EXPECT_EQ(read_error("# outer: 1 x 3\n1 2\n2 3\n3 1\n"),
            "<input>:1: the '# outer:' directive expects non-negative integer vertex ids, found 'x'.");
  EXPECT_EQ(read_error(octahedron + "# outer: 0 1 5\n"),
            "<input>:13: the '# outer:' cycle uses 5-0, which is not an edge of the graph.");
  e = expect_input_error([&] { read_one(octahedron + "# outer: 1 2 3 4\n"); });  // the equator is no face
  EXPECT_STREQ(e.what(),
               "<input>:13: the graph has no planar embedding in which the '# outer:' cycle bounds a face.");
  e = expect_input_error([&] { read_one("# outer: 0 1 2\n" + octahedron + "# outer: 0 1 2\n"); });
  EXPECT_EQ(e.line(), 14u);
}

// ---------------------------------------------------------------------------------------------------
// Straight-line drawings.

TEST(GraphIO, ReadsCoordsWithExactAngularOrder) {
  const GraphInput in = read_graphs(data_path("square.coords.txt")).at(0);
  const PlanarGraph& g = in.graph;
  EXPECT_TRUE(g.is_valid(true));
  EXPECT_TRUE(in.outer_given);
  ASSERT_EQ(in.positions.size(), 5u);
  EXPECT_EQ(in.positions[4].x, 0.5);
  // Around the centre, counter-clockwise from the positive x axis: (1,1), (0,1), (0,0), (1,0).
  EXPECT_EQ(ids_of(g, {g.neighbours(4).begin(), g.neighbours(4).end()}), (std::vector<std::uint64_t>{3, 4, 1, 2}));
  // The outer face is the unbounded one, walked clockwise.
  EXPECT_TRUE(cyclic_equal(ids_of(g, g.boundary_cycle()), {1, 4, 3, 2}));
  EXPECT_TRUE(g.inner_faces_are_triangles());
  EXPECT_EQ(read_one("vertices\n1 0 0\n2 1 0\n3 0 1\nedges\n1 2\n2 3\n3 1\n", GraphFormat::coords).positions.size(), 3u);
}

TEST(GraphIO, CoordsOuterDirectiveMayNameAnInnerFace) {
  std::ifstream file(data_path("square.coords.txt"));
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  for (const char* directive : {"# outer: 5 1 2\n", "# outer: 2 1 5\n"}) {
    const GraphInput in = read_one(directive + text);
    EXPECT_EQ(in.graph.boundary_cycle().size(), 3u);
    EXPECT_TRUE(in.graph.is_boundary(4));
    EXPECT_FALSE(in.graph.is_boundary(2));
  }
  const auto e = expect_input_error([&] { read_one("# outer: 1 2 3\n" + text); });
  EXPECT_STREQ(e.what(), "<input>:1: the '# outer:' cycle is not a face of the drawing.");
}

TEST(GraphIO, CoordsErrors) {
  auto e = expect_input_error([] { read_one("vertices\n1 0 0\n2 1 1\n3 1 0\n4 0 1\nedges\n1 2\n3 4\n1 3\n"); });
  EXPECT_STREQ(e.what(), "<input>: the drawing is not plane: edges 1-2 and 3-4 cross or touch.");
  e = expect_input_error([] { read_one("vertices\n1 0 0\n2 1 0\n3 2 0\n4 0 1\nedges\n1 2\n1 3\n1 4\n2 4\n"); });
  EXPECT_NE(e.message().find("overlap"), std::string::npos) << e.what();
  // (drawing, the error it gets), read as coords.
  const std::pair<const char*, const char*> cases[] = {
      {"vertices\n1 0 0\n2 2 0\n3 1 0\n4 1 1\nedges\n1 2\n3 4\n1 4\n",  // 3 lies on 1-2
       "<input>: the drawing is not plane: edges 1-2 and 3-4 cross or touch."},
      {"vertices\n1 0 0\n2 1 0\n3 0 0\nedges\n1 2\n2 3\n", "<input>: vertices 1 and 3 are both at (0, 0)."},
      {"1 2\n", "<input>:1: expected the section header 'vertices' before any data, found '1 2'."},
      {"vertices\n1 0 0\n2 1 0\nedges\n1 3\n",
       "<input>:5: edge 1-3 uses vertex 3, which the 'vertices' section does not declare."},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(read_error(text, nullptr, GraphFormat::coords), expected);
  e = expect_input_error([] { read_one("# drawing\nvertices\n1 0 0\n2 1 nan\nedges\n1 2\n"); });
  EXPECT_EQ(e.line(), 4u);
  EXPECT_NE(e.message().find("expected a vertex line 'id x y'"), std::string::npos);
  EXPECT_EQ(read_error("vertices\n1 0 0\n1 1 0\n"),
            "<input>:3: vertex 1 is declared twice (first on line 2).");
  e = expect_input_error([] { read_one("vertices\n1 0 0\n2 1 0\nedges\n1 2\n2 1\n"); });
  EXPECT_EQ(e.line(), 6u);
  e = expect_input_error([] { read_one("edges\n1 2\nvertices\n", GraphFormat::coords); });
  EXPECT_EQ(e.line(), 1u);
}

// ---------------------------------------------------------------------------------------------------
// planar_code.

TEST(GraphIO, HandEncodedPlanarCodeListsNeighboursClockwise) {
  const GraphInput drawn = k4_drawing();
  for (const std::string& header : {std::string(">>planar_code<<"), std::string(">>planar_code le<<"), std::string()}) {
    const auto graphs = read_graphs_from_string(header + bytes(k4_narrow), "k4.pc", GraphFormat::planar_code);
    ASSERT_EQ(graphs.size(), 1u);
    EXPECT_EQ(graphs[0].name, "k4.pc#1");
    EXPECT_FALSE(graphs[0].outer_given);
    EXPECT_EQ(graphs[0].graph.ids(), (std::vector<std::uint64_t>{1, 2, 3, 4}));
    // The same counter-clockwise rotation as the drawing the bytes were encoded from (not its mirror).
    EXPECT_TRUE(same_embedding(graphs[0].graph, drawn.graph));
  }
}

TEST(GraphIO, HandEncodedWidePlanarCodeInBothByteOrders) {
  const PlanarGraph narrow = read_one(">>planar_code<<" + bytes(k4_narrow)).graph;
  std::initializer_list<int> le = {0, 4, 0, 2, 0, 4, 0, 3, 0, 0, 0, 4, 0, 1, 0, 3, 0, 0, 0,
                                   2, 0, 1, 0, 4, 0, 0, 0, 3, 0, 1, 0, 2, 0, 0, 0};
  std::initializer_list<int> be = {0, 0, 4, 0, 2, 0, 4, 0, 3, 0, 0, 0, 4, 0, 1, 0, 3, 0, 0,
                                   0, 2, 0, 1, 0, 4, 0, 0, 0, 3, 0, 1, 0, 2, 0, 0};
  EXPECT_TRUE(same_embedding(read_one(">>planar_code le<<" + bytes(le)).graph, narrow));
  EXPECT_TRUE(same_embedding(read_one(">>planar_code<<" + bytes(le)).graph, narrow));
  EXPECT_TRUE(same_embedding(read_one(">>planar_code be<<" + bytes(be)).graph, narrow));
}

TEST(GraphIO, PlanarCodeRoundTripsSeveralGraphsThroughAFile) {
  std::vector<PlanarGraph> graphs;
  graphs.push_back(read_graphs(data_path("octahedron.txt")).at(0).graph);
  graphs.push_back(read_graphs(data_path("cube.txt")).at(0).graph);
  graphs.push_back(random_delaunay_triangulation(300, 5).graph);  // needs the 2-byte entries
  graphs.push_back(k4_drawing().graph);
  const std::string code = write_planar_code(graphs);
  EXPECT_EQ(code.substr(0, 18), ">>planar_code le<<");
  const std::string path = laguerre::testing::scratch_path("laguerre_graph_io_roundtrip.pc");
  {
    std::ofstream out(path, std::ios::binary);
    out << code;
  }
  const auto back = read_graphs(path);
  std::remove(path.c_str());
  ASSERT_EQ(back.size(), graphs.size());
  for (std::size_t i = 0; i < graphs.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(back[i].name, path + "#" + std::to_string(i + 1));
    const PlanarGraph& g = back[i].graph;
    ASSERT_EQ(g.num_vertices(), graphs[i].num_vertices());
    for (Vertex v = 0; v < g.num_vertices(); ++v) {
      EXPECT_EQ(g.id(v), v + 1u);  // planar_code numbers vertices 1..n
      const auto a = g.neighbours(v), b = graphs[i].neighbours(v);
      EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
    }
  }
  EXPECT_EQ(write_planar_code({back[0].graph, back[1].graph, back[2].graph, back[3].graph}), code);
  EXPECT_TRUE(read_graphs_from_string(">>planar_code<<").empty());
}

TEST(GraphIO, PlanarCodeErrorsNameTheGraph) {
  const std::string k4 = bytes(k4_narrow);
  auto e = expect_input_error([&] { read_graphs_from_string(">>planar_code<<" + k4 + bytes({4, 2, 4, 3, 0, 4}), "t.pc"); });
  EXPECT_EQ(e.graph_index(), 2u);
  EXPECT_EQ(e.line(), 0u);
  EXPECT_STREQ(e.what(), "t.pc#2: the planar_code data ends in the middle of graph 2 (after the neighbours of 1 of "
                         "its 4 vertices).");
  e = expect_input_error([&] { read_graphs_from_string(">>planar_code<<" + k4 + bytes({0, 4}), "t.pc"); });
  EXPECT_EQ(e.graph_index(), 2u);
  EXPECT_NE(e.message().find("while reading its number of vertices"), std::string::npos);

  // Vertex 4 forgets vertex 2.
  e = expect_input_error([] {
    read_graphs_from_string(">>planar_code<<" + bytes({4, 2, 4, 3, 0, 4, 1, 3, 0, 2, 1, 4, 0, 3, 1, 0}), "t.pc");
  });
  EXPECT_EQ(e.graph_index(), 1u);
  EXPECT_STREQ(e.what(), "t.pc#1: the planar_code is inconsistent: vertex 2 lists 4 as a neighbour but vertex 4 "
                         "does not list 2.");
  e = expect_input_error([] {
    read_graphs_from_string(">>planar_code<<" + bytes({4, 2, 4, 3, 0, 4, 1, 3, 0, 2, 1, 4, 0, 3, 1, 5, 0}), "t.pc");
  });
  EXPECT_STREQ(e.what(), "t.pc#1: vertex 4 lists neighbour 5, outside 1..4.");
  e = expect_input_error([] {
    read_graphs_from_string(">>planar_code<<" + bytes({3, 2, 3, 0, 1, 1, 3, 0, 1, 2, 0}), "t.pc");
  });
  EXPECT_NE(e.message().find("twice"), std::string::npos) << e.what();
  // Symmetric but not planar: K4 with every vertex listing its neighbours in increasing order.
  e = expect_input_error([] {
    read_graphs_from_string(">>planar_code<<" + bytes({4, 2, 3, 4, 0, 1, 3, 4, 0, 1, 2, 4, 0, 1, 2, 3, 0}), "t.pc");
  });
  EXPECT_EQ(e.graph_index(), 1u);
  EXPECT_NE(e.message().find("not a planar embedding"), std::string::npos) << e.what();
  e = expect_input_error([] { read_graphs_from_string(">>planar_code xx<<" + bytes({3}), "t.pc"); });
  EXPECT_EQ(e.graph_index(), 0u);
  EXPECT_NE(e.message().find("header"), std::string::npos);
}

TEST(GraphIO, PlanarCodeWriterRefusesMoreThan65535Vertices) {
  std::vector<std::vector<Vertex>> star(65537);  // a star: one centre, 65536 leaves
  for (Vertex v = 1; v < star.size(); ++v) {
    star[0].push_back(v);
    star[v] = {0};
  }
  const auto e = expect_input_error([&] { write_planar_code({PlanarGraph::from_rotation(star)}); });
  EXPECT_STREQ(e.what(), "planar_code output: a graph has 65537 vertices; planar_code stores 1 to 65535.");
  star.resize(65535);  // the largest planar_code stores
  star[0].resize(65534);
  EXPECT_EQ(read_graphs_from_string(write_planar_code({PlanarGraph::from_rotation(star)})).at(0).graph.num_vertices(),
            65535u);
}

TEST(GraphIO, PlanarCodeRequestedForATextFileSaysSo) {
  auto e = expect_input_error([] { read_graphs_from_string("# a triangle\n1 2\n2 3\n3 1\n", "tri.txt", GraphFormat::planar_code); });
  EXPECT_STREQ(e.what(), "tri.txt: expected a planar_code file (header '>>planar_code<<'), found '# a triangle' (no "
                         "header, and none of the 0 bytes that end every vertex's neighbour list).");
  e = expect_input_error([] { read_graphs(data_path("k5.txt"), GraphFormat::planar_code); });
  EXPECT_EQ(e.source(), data_path("k5.txt"));
  EXPECT_EQ(e.message().rfind("expected a planar_code file (header '>>planar_code<<'), found '", 0), 0u) << e.what();
  // Headerless binary planar_code is still read when requested.
  EXPECT_EQ(read_graphs_from_string(bytes({3, 2, 3, 0, 3, 1, 0, 1, 2, 0}), "tri.pc", GraphFormat::planar_code).size(), 1u);
}

TEST(GraphIO, AutomaticDetection) {
  EXPECT_FALSE(read_one("1 2\n2 3\n3 1\n").outer_given);
  EXPECT_EQ(read_one("vertices\n1 0 0\n2 1 0\n3 0 1\nedges\n1 2\n2 3\n3 1\n").positions.size(), 3u);
  EXPECT_EQ(read_one(">>planar_code<<" + bytes(k4_narrow)).graph.num_edges(), 6u);
}
