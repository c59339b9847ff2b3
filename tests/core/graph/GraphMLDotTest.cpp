#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
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

bool same_rotation(const PlanarGraph& a, const PlanarGraph& b) {
  if (a.num_vertices() != b.num_vertices() || a.ids() != b.ids()) return false;
  for (Vertex v = 0; v < a.num_vertices(); ++v) {
    const auto x = a.neighbours(v), y = b.neighbours(v);
    if (!std::equal(x.begin(), x.end(), y.begin(), y.end())) return false;
  }
  return a.boundary_cycle() == b.boundary_cycle();
}

std::string graphml(const std::string& body, const std::string& edgedefault = "undirected") {
  return "<?xml version=\"1.0\"?>\n<graphml>\n<key id=\"x\" for=\"node\" attr.name=\"x\"/>\n"
         "<key id=\"y\" for=\"node\" attr.name=\"y\"/>\n<graph edgedefault=\"" + edgedefault + "\">\n" + body +
         "</graph>\n</graphml>\n";
}

}  // namespace

TEST(GraphMLDot, RoundTripOfDrawingsIsExact) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    for (const GraphInput& in : {random_delaunay_triangulation(40, seed), random_three_connected(40, seed)}) {
      for (GraphFormat f : {GraphFormat::graphml, GraphFormat::dot}) {
        const std::string text = f == GraphFormat::graphml ? write_graphml(in.graph, in.positions) : write_dot(in.graph, in.positions);
        const GraphInput back = read_one(text);  // automatic detection
        EXPECT_TRUE(same_rotation(in.graph, back.graph)) << to_string(f);
        ASSERT_EQ(back.positions.size(), in.positions.size());
        for (std::size_t v = 0; v < in.positions.size(); ++v) {
          EXPECT_EQ(back.positions[v].x, in.positions[v].x);
          EXPECT_EQ(back.positions[v].y, in.positions[v].y);
        }
        EXPECT_EQ(write_edge_list(back.graph), write_edge_list(in.graph));
      }
    }
  }
}

TEST(GraphMLDot, RoundTripWithoutPositionsKeepsEdgesAndOuterFace) {
  for (std::uint64_t seed : {4u, 5u}) {
    for (const GraphInput& in : {random_delaunay_triangulation(30, seed), random_three_connected(30, seed)}) {
      for (const std::string& text : {write_graphml(in.graph), write_dot(in.graph)}) {
        const GraphInput back = read_one(text);
        EXPECT_TRUE(back.positions.empty());
        EXPECT_TRUE(back.outer_given);
        // The edge list (with its '# outer:' line, in boundary order) is the same graph, the same outer face.
        EXPECT_EQ(write_edge_list(back.graph), write_edge_list(in.graph));
        GraphKind a{}, b{};
        prepare_for_packing(in, &a);
        prepare_for_packing(back, &b);
        EXPECT_EQ(a, b);
      }
    }
  }
}

TEST(GraphMLDot, BundledFilesMatchTheirEdgeListTwins) {
  const auto octa = read_graphs(data_path("octahedron.graphml"));
  const auto twin = read_graphs(data_path("octahedron.txt"));
  ASSERT_EQ(octa.size(), 1u);
  EXPECT_EQ(octa[0].graph.ids(), (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5}));  // n0..n5
  EXPECT_EQ(octa[0].graph.num_edges(), 12u);
  EXPECT_TRUE(is_three_connected(octa[0].graph));
  // Same edge set as the edge list (the embedding's outer face may differ: compare without it).
  const auto edges_only = [](const PlanarGraph& g) {
    std::string s = write_edge_list(g);
    return s.substr(s.find('\n', s.find("# outer:")) + 1);
  };
  EXPECT_EQ(edges_only(octa[0].graph), edges_only(twin[0].graph));
  const auto square = read_graphs(data_path("square.coords.txt"));
  for (const char* name : {"wheel.dot", "wheel.graphml"}) {
    const auto wheel = read_graphs(data_path(name));
    ASSERT_EQ(wheel.size(), 1u);
    EXPECT_TRUE(same_rotation(wheel[0].graph, square[0].graph)) << name;
    ASSERT_EQ(wheel[0].positions.size(), 5u) << name;
    EXPECT_EQ(wheel[0].positions[4].x, 0.5);
  }
  EXPECT_EQ(parse_graph_format("graphml"), GraphFormat::graphml);
  EXPECT_EQ(parse_graph_format("dot"), GraphFormat::dot);
  EXPECT_EQ(to_string(GraphFormat::dot), "dot");
}

TEST(GraphMLDot, NodeNamesBecomeIds) {
  // Keys are matched by attr.name, not by their ids.
  const GraphInput keyed = read_one(
      "<graphml><key id=\"k1\" for=\"node\" attr.name=\"y\"/><key id=\"k2\" for=\"node\" attr.name=\"x\"/>"
      "<graph><node id=\"1\"><data key=\"k2\">2</data><data key=\"k1\">3</data></node>"
      "<node id=\"2\"><data key=\"k2\">0</data><data key=\"k1\">0</data></node>"
      "<node id=\"3\"><data key=\"k2\">5</data><data key=\"k1\">0</data></node>"
      "<edge source=\"1\" target=\"2\"/><edge source=\"2\" target=\"3\"/><edge source=\"3\" target=\"1\"/></graph></graphml>");
  ASSERT_EQ(keyed.positions.size(), 3u);
  EXPECT_EQ(keyed.positions[0].x, 2);
  EXPECT_EQ(keyed.positions[0].y, 3);
  // Plain names: ids in file order; prefixed numbers: the numbers; plain numbers: themselves.
  const std::string k4 = "-- b; a -- c; a -- d; b -- c; b -- d; c -- d; }";
  EXPECT_EQ(read_one("graph { a " + k4).graph.ids(), (std::vector<std::uint64_t>{0, 1, 2, 3}));
  EXPECT_EQ(read_one("graph { v7 -- v3; v7 -- v9; v7 -- v11; v3 -- v9; v3 -- v11; v9 -- v11; }").graph.ids(),
            (std::vector<std::uint64_t>{3, 7, 9, 11}));
  EXPECT_EQ(read_one("graph { 10 -- 20; 10 -- 30; 10 -- 40; 20 -- 30; 20 -- 40; 30 -- 40; }").graph.ids(),
            (std::vector<std::uint64_t>{10, 20, 30, 40}));
  const GraphInput mixed = read_one(graphml("<node id=\"s\"/><node id=\"t\"/><node id=\"u\"/>"
                                            "<edge source=\"s\" target=\"t\"/><edge source=\"t\" target=\"u\"/>"
                                            "<edge source=\"u\" target=\"s\"/>"));
  EXPECT_EQ(mixed.graph.ids(), (std::vector<std::uint64_t>{0, 1, 2}));
}

TEST(GraphMLDot, MalformedInputGivesClearErrors) {
  try {
    read_graphs(data_path("malformed.graphml"));
    ADD_FAILURE() << "malformed XML was accepted";
  } catch (const GraphInputError& e) {
    EXPECT_NE(std::string(e.what()).find("malformed.graphml:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is not well-formed XML"), std::string::npos) << e.what();
    EXPECT_GE(e.line(), 5u);
  }
  const std::string tri = "<node id=\"a\"/><node id=\"b\"/><node id=\"c\"/>";
  const std::string ab = "<edge source=\"a\" target=\"b\"/>", bc = "<edge source=\"b\" target=\"c\"/>",
                    ca = "<edge source=\"c\" target=\"a\"/>";
  EXPECT_EQ(read_error(graphml(tri + ab + bc + ca)), "");
  EXPECT_NE(read_error("<?xml version=\"1.0\"?>\n<root/>\n").find("no <graphml> root element"), std::string::npos);
  EXPECT_NE(read_error(graphml(tri + ab + bc + ca, "directed")).find("edge 1 ('a' -> 'b') is directed"), std::string::npos);
  EXPECT_NE(read_error(graphml(tri + ab + "<edge source=\"b\" target=\"c\" directed=\"true\"/>" + ca)).find("edge 2"),
            std::string::npos);
  EXPECT_NE(read_error(graphml(tri + ab + bc + ca + "<edge source=\"b\" target=\"b\"/>")).find("edge 4 ('b' -- 'b') is a self-loop"),
            std::string::npos);
  EXPECT_NE(read_error(graphml(tri + ab + bc + ca + "<edge source=\"b\" target=\"a\"/>")).find("edge 4 ('b' -- 'a') repeats an earlier edge"),
            std::string::npos);
  EXPECT_NE(read_error(graphml(tri + ab + bc + "<edge source=\"c\" target=\"z\"/>")).find("refers to node 'z', which is not declared"),
            std::string::npos);
  EXPECT_NE(read_error(graphml(tri + "<node id=\"a\"/>" + ab + bc + ca)).find("node 'a' is declared twice"), std::string::npos);
  EXPECT_NE(read_error(graphml(tri + "<node id=\"d\"/>" + ab + bc + ca)).find("node 'd' cannot be reached"), std::string::npos);
  EXPECT_NE(read_error(graphml("<node id=\"a\"><data key=\"x\">0</data><data key=\"y\">0</data></node>"
                               "<node id=\"b\"/><node id=\"c\"/>" + ab + bc + ca))
                .find("node 'b' has no position"),
            std::string::npos);
  EXPECT_NE(read_error(graphml("<node id=\"a\"><data key=\"x\">east</data></node><node id=\"b\"/>" + ab))
                .find("the x of node 'a' is 'east'; expected a finite number"),
            std::string::npos);
  EXPECT_NE(read_error(graphml("")).find("no nodes"), std::string::npos);
  // DOT.
  EXPECT_NE(read_error("digraph { a -> b; b -> c; c -> a; }").find("is a digraph"), std::string::npos);
  EXPECT_NE(read_error("graph { a -- b; b - c; }").find("DOT syntax error"), std::string::npos);
  EXPECT_NE(read_error("graph { a -- b; b -- c; c -- a; a -- a; }").find("is a self-loop"), std::string::npos);
  EXPECT_NE(read_error("graph { a -- b; b -- c; c -- a; b -- a; }").find("('b' -- 'a') repeats an earlier edge"),
            std::string::npos);
  EXPECT_NE(read_error("graph { a [pos=\"1;2\"]; a -- b; }").find("node 'a' has pos='1;2'; expected \"x,y\""),
            std::string::npos);
  EXPECT_NE(read_error("graph { outer=\"a b q\"; a -- b; b -- c; c -- a; }").find("lists node 'q', which is not declared"),
            std::string::npos);
  // Not planar: K5 through either reader.
  EXPECT_NE(read_error("graph { 1--2; 1--3; 1--4; 1--5; 2--3; 2--4; 2--5; 3--4; 3--5; 4--5; }").find("not planar"),
            std::string::npos);
}

TEST(GraphMLDot, DeepNestingIsAnErrorNotACrash) {
  // 50,000 nested elements overflowed the stack of the recursive XML parser; the depth limit stops them
  // first, naming the file and the line of the first element too deep.
  std::string deep = "<?xml version=\"1.0\"?>\n<graphml>\n<graph>\n";
  for (int i = 0; i < 50000; ++i) deep += "<a>\n";
  for (int i = 0; i < 50000; ++i) deep += "</a>";
  deep += "</graph></graphml>\n";
  const std::string path = laguerre::testing::scratch_path("deep.graphml");
  std::ofstream(path, std::ios::binary) << deep;
  const auto e = expect_input_error([&] { read_graphs(path); });
  // <graphml> is level 1, <graph> 2, the first <a> (line 4) 3: the first one too deep is on line 2 + limit.
  EXPECT_EQ(e.source(), path);
  EXPECT_EQ(e.line(), graphml_max_depth + 2);
  EXPECT_EQ(e.message(), "the <a> element here is nested " + std::to_string(graphml_max_depth + 1) +
                             " deep; laguerre reads GraphML nested at most " + std::to_string(graphml_max_depth) +
                             " deep.");
  std::remove(path.c_str());

  // Nesting within the limit, with comments, CDATA and quoted '>' the scan must step over, still reads.
  std::string extra = "<data key=\"note\"><!-- <a><a> --><![CDATA[<b><b>]]>";
  for (int i = 0; i < 50; ++i) extra += "<y:n t=\"a>b\">";
  for (int i = 0; i < 50; ++i) extra += "</y:n>";
  extra += "</data>";
  const std::string tri = "<node id=\"a\"/><node id=\"b\"/><node id=\"c\"/><edge source=\"a\" target=\"b\"/>"
                          "<edge source=\"b\" target=\"c\"/><edge source=\"c\" target=\"a\"/>";
  EXPECT_EQ(read_one(graphml(extra + tri)).graph.num_edges(), 3u);
}

TEST(GraphMLDot, AutomaticDetectionKeepsTheOtherFormats) {
  EXPECT_EQ(read_one("# a comment\n1 2\n2 3\n3 1\n").graph.num_edges(), 3u);                     // edges
  EXPECT_EQ(read_one("vertices\n1 0 0\n2 1 0\n3 0 1\nedges\n1 2\n2 3\n3 1\n").positions.size(), 3u);  // coords
  EXPECT_EQ(read_one("// made by hand\n/* a triangle */\n# another comment\nGraph { 1 -- 2 -- 3 -- 1 }").graph.num_edges(), 3u);
  EXPECT_EQ(read_one("strict graph { 1 -- 2 -- 3 -- 1 }").graph.num_edges(), 3u);
  EXPECT_EQ(read_one("\n  <!-- c -->\n<graphml><graph><node id=\"1\"/><node id=\"2\"/><node id=\"3\"/>"
                     "<edge source=\"1\" target=\"2\"/><edge source=\"2\" target=\"3\"/><edge source=\"3\" target=\"1\"/>"
                     "</graph></graphml>").graph.num_edges(), 3u);
  // A DOT text read as an edge list is an error of the edges format, as before.
  EXPECT_NE(read_error("graph { 1 -- 2 }", nullptr, GraphFormat::edges).find("expected two non-negative integer vertex ids"),
            std::string::npos);
  EXPECT_THROW(write_graphml(random_delaunay_triangulation(5, 1).graph, {{0, 0}}), InternalError);
}

TEST(GraphMLDot, EveryWriterReadsBackWhenTheBoundaryIsNoCycle) {
  // Fuzz finding graph-1: a path (boundary walk 0 1 2 3 2 1), one edge (4 5), a pendant vertex b on a
  // graph that is neither 3-connected nor a triangulated disc; and a drawing of a triangle with a
  // pendant vertex outside it (unbounded face 0 1 3 1 2).
  const std::vector<GraphInput> inputs = {
      read_one("0 1\n1 2\n2 3\n"), read_one("4 5\n"),
      read_one("graph { a -- f -- c -- d -- a; a -- c; subgraph s { e; } e -- a; e -- b; }"),
      read_one("vertices\n0 0 0\n1 1 0\n2 0 1\n3 2 0\nedges\n0 1\n1 2\n2 0\n1 3\n")};
  for (const GraphInput& in : inputs) {
    const std::vector<std::pair<GraphFormat, std::string>> written = {
        {GraphFormat::edges, write_edge_list(in.graph)},
        {GraphFormat::graphml, write_graphml(in.graph, in.positions)},
        {GraphFormat::dot, write_dot(in.graph, in.positions)}};
    for (const auto& [format, text] : written) {
      SCOPED_TRACE(text);
      EXPECT_EQ(text.find("outer:"), std::string::npos);  // no '# outer:' line
      EXPECT_EQ(text.find("outer="), std::string::npos);  // no DOT attribute
      EXPECT_EQ(text.find("<data key=\"outer\">"), std::string::npos);
      const GraphInput back = read_one(text, format);
      EXPECT_EQ(back.graph.ids(), in.graph.ids());
      EXPECT_EQ(back.graph.num_faces(), in.graph.num_faces());
      EXPECT_EQ(write_edge_list(back.graph), write_edge_list(in.graph));
      if (format != GraphFormat::edges) {
        EXPECT_EQ(back.positions.size(), in.positions.size());
      }
    }
  }
  // A drawing keeps any simple outer face: here its inner triangle made the outer face.
  const GraphInput& drawn = inputs[3];
  Dart inner_dart = 0;
  while (drawn.graph.face_of(inner_dart) == drawn.graph.outer_face()) ++inner_dart;
  const PlanarGraph inner = drawn.graph.with_outer_dart(inner_dart);
  ASSERT_EQ(inner.boundary_cycle().size(), 3u);
  for (const std::string& text : {write_graphml(inner, drawn.positions), write_dot(inner, drawn.positions)}) {
    const GraphInput back = read_one(text);
    EXPECT_EQ(back.graph.face_of(back.graph.find_dart(inner.boundary_cycle()[0], inner.boundary_cycle()[1])),
              back.graph.outer_face())
        << text;
    EXPECT_EQ(write_edge_list(back.graph), write_edge_list(inner));
  }
  EXPECT_EQ(write_edge_list(inner).find("# outer:"), std::string::npos);  // without the drawing: left out
}
