// The outer rule of a triangulated sphere (core::prepare_input): keep a face, or puncture the vertex of
// largest degree so that its link becomes the boundary of a triangulated disc.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "laguerre/core/graph/GraphError.hpp"
#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"

using namespace laguerre::core;

namespace {

GraphInput read_edges(const std::string& text) { return read_graphs_from_string(text, "<input>", GraphFormat::edges).at(0); }

/// A triangulated sphere as an edge list without `# outer:`: a random Delaunay triangulation of n points
/// plus an apex (id n) joined to every hull vertex.
std::string sphere_edges(std::size_t n, std::uint64_t seed) {
  const GraphInput disc = random_delaunay_triangulation(n, seed);
  const PlanarGraph& g = disc.graph;
  std::ostringstream os;
  for (Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) os << g.id(g.tail(d)) << ' ' << g.id(g.head(d)) << '\n';
  for (Vertex v : g.boundary_cycle()) os << g.id(v) << ' ' << n << '\n';
  return os.str();
}

/// The ids of `cycle` rotated to start at its smallest id, read in the direction of its smaller second id.
std::vector<std::uint64_t> canonical_cycle(std::vector<std::uint64_t> cycle) {
  std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
  if (cycle.size() > 2 && cycle.back() < cycle[1]) std::reverse(cycle.begin() + 1, cycle.end());
  return cycle;
}

/// The vertex with user id `id`, or none.
Vertex vertex_of(const PlanarGraph& g, std::uint64_t id) {
  for (Vertex v = 0; v < g.num_vertices(); ++v)
    if (g.id(v) == id) return v;
  return none;
}

const std::string octahedron = "0 1\n0 2\n0 3\n0 4\n1 2\n2 3\n3 4\n4 1\n5 1\n5 2\n5 3\n5 4\n";

}  // namespace

TEST(OuterRule, NamesRoundTrip) {
  for (const auto& e : outer_rule_names) EXPECT_EQ(parse_name(outer_rule_names, name_of(outer_rule_names, e.value)), e.value);
  try {
    (void)parse_name(outer_rule_names, "hole", "--outer");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--outer"), std::string::npos) << what;
    EXPECT_NE(what.find("'hole'"), std::string::npos) << what;
    EXPECT_NE(what.find("face or puncture"), std::string::npos) << what;
  }
}

TEST(OuterRule, PunctureGivesTheDiscBoundedByTheRemovedVertexsLink) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const GraphInput sphere = read_edges(sphere_edges(40, seed));
    const PlanarGraph& s = sphere.graph;
    ASSERT_TRUE(is_triangulated_sphere(s));
    // The oracle for the removed vertex: largest degree, then smallest id, by a scan of its own.
    std::uint32_t best_degree = 0;
    std::uint64_t best_id = 0;
    for (Vertex v = 0; v < s.num_vertices(); ++v)
      if (s.degree(v) > best_degree || (s.degree(v) == best_degree && s.id(v) < best_id)) {
        best_degree = s.degree(v);
        best_id = s.id(v);
      }
    const Vertex hub = vertex_of(s, best_id);
    std::vector<std::uint64_t> link;
    for (Vertex w : s.neighbours(hub)) link.push_back(s.id(w));

    GraphInput in = sphere;
    const PreparedInput prepared = prepare_input(in, OuterRule::puncture);
    const PlanarGraph& disc = in.graph;
    ASSERT_TRUE(disc.is_valid());
    EXPECT_EQ(prepared.kind, GraphKind::triangulated_disc);
    EXPECT_EQ(prepared.removed, std::vector<std::uint64_t>{best_id});
    EXPECT_EQ(disc.num_vertices(), s.num_vertices() - 1);
    EXPECT_EQ(disc.num_edges(), s.num_edges() - best_degree);
    EXPECT_EQ(vertex_of(disc, best_id), none);
    // The boundary is the link, in its cyclic order; every other face is a triangle.
    std::vector<std::uint64_t> boundary;
    for (Vertex v : disc.boundary_cycle()) boundary.push_back(disc.id(v));
    EXPECT_EQ(canonical_cycle(boundary), canonical_cycle(link)) << "seed " << seed;
    for (Face f = 0; f < disc.num_faces(); ++f)
      if (f != disc.outer_face()) {
        EXPECT_EQ(disc.face_size(f), 3u);
      }
    // Deterministic: the same input gives the same rotation and the same outer face.
    GraphInput again = sphere;
    (void)prepare_input(again, OuterRule::puncture);
    ASSERT_EQ(again.graph.num_vertices(), disc.num_vertices());
    for (Vertex v = 0; v < disc.num_vertices(); ++v) {
      EXPECT_EQ(again.graph.id(v), disc.id(v));
      const auto a = again.graph.neighbours(v), b = disc.neighbours(v);
      EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
    }
    EXPECT_EQ(again.graph.boundary_cycle(), disc.boundary_cycle());
    // It packs to LPD.
    const PackResult r = pack(disc, PackOptions{});
    EXPECT_EQ(r.status, PackStatus::converged) << "seed " << seed;
    EXPECT_EQ(r.local_ok, disc.num_vertices());
  }
}

TEST(OuterRule, PunctureBreaksDegreeTiesByTheSmallestIdAndDropsThePosition) {
  // Every vertex of the octahedron has degree 4; relabelled, the smallest id goes.
  std::string text;
  std::istringstream in(octahedron);
  for (std::uint64_t a, b; in >> a >> b;) text += std::to_string(70 - 10 * a) + " " + std::to_string(70 - 10 * b) + "\n";
  GraphInput g = read_edges(text);
  for (Vertex v = 0; v < g.graph.num_vertices(); ++v) g.positions.push_back({static_cast<double>(g.graph.id(v)), 0.0});
  const PreparedInput p = prepare_input(g, OuterRule::puncture);
  EXPECT_EQ(p.removed, std::vector<std::uint64_t>{20});
  EXPECT_EQ(g.graph.num_vertices(), 5u);
  EXPECT_EQ(g.graph.boundary_cycle().size(), 4u);
  ASSERT_EQ(g.positions.size(), 5u);
  for (Vertex v = 0; v < g.graph.num_vertices(); ++v) EXPECT_EQ(g.positions[v].x, static_cast<double>(g.graph.id(v)));
}

TEST(OuterRule, FaceKeepsPrepareForPackingAndPunctureLeavesOtherGraphsAlone) {
  const GraphInput sphere = read_edges(sphere_edges(30, 5));
  GraphInput face = sphere;
  const PreparedInput p = prepare_input(face, OuterRule::face);
  EXPECT_TRUE(p.removed.empty());
  const PlanarGraph expected = prepare_for_packing(sphere);
  EXPECT_EQ(face.graph.boundary_cycle(), expected.boundary_cycle());
  EXPECT_EQ(face.graph.num_vertices(), sphere.graph.num_vertices());
  // A disc (Delaunay, hull outside) and a 3-connected graph are not spheres: puncture changes nothing.
  for (const GraphInput& other : {random_delaunay_triangulation(30, 3), random_three_connected(30, 3)}) {
    if (is_triangulated_sphere(other.graph)) continue;
    GraphInput copy = other;
    GraphKind kind{};
    const PlanarGraph reference = prepare_for_packing(other, &kind);
    const PreparedInput q = prepare_input(copy, OuterRule::puncture);
    EXPECT_TRUE(q.removed.empty());
    EXPECT_EQ(q.kind, kind);
    EXPECT_EQ(copy.graph.boundary_cycle(), reference.boundary_cycle());
    EXPECT_EQ(copy.positions.size(), other.positions.size());
  }
}

TEST(OuterRule, PuncturingATriangleIsAClearError) {
  GraphInput triangle = read_edges("1 2\n2 3\n3 1\n");
  ASSERT_TRUE(is_triangulated_sphere(triangle.graph));
  try {
    (void)prepare_input(triangle, OuterRule::puncture);
    FAIL() << "no error";
  } catch (const GraphInputError& e) {
    EXPECT_NE(std::string(e.what()).find("at least 4"), std::string::npos) << e.what();
  }
  GraphInput k4 = read_edges("1 2\n1 3\n1 4\n2 3\n2 4\n3 4\n");
  const PreparedInput p = prepare_input(k4, OuterRule::puncture);
  EXPECT_EQ(p.removed, std::vector<std::uint64_t>{1});
  EXPECT_EQ(k4.graph.num_vertices(), 3u);
  EXPECT_TRUE(k4.graph.is_valid());
}
