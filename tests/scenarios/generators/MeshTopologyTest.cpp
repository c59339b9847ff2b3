// The `mesh` topology of a domain with holes: the corner rule makes it a 3-connected network whose
// outer face is the outer boundary and whose holes are inner faces; without the rule it is refused
// (naming the separating pair) unless a repair policy applies.
#include "laguerre/scenarios/Topology.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace laguerre::scenarios {
namespace {

const std::string holes_domain = std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/domains/square-with-holes.txt";

TopologyParams mesh_params(const std::string& metric) {
  TopologyParams p;
  p.set("domain", holes_domain);
  p.set("metric", metric);
  return p;
}

TEST(MeshTopology, DomainWithHolesIsThreeConnectedWithTheOuterBoundaryOutside) {
  for (const char* metric : {"uniform:0.1:0.1", "uniform:0.25:0.25", "shock:0.02:0.15:0.05:0.5"}) {
    SCOPED_TRACE(metric);
    const Topology t = build_topology("mesh", mesh_params(metric), 7, 0);
    EXPECT_EQ(t.kind, core::GraphKind::three_connected);
    ASSERT_EQ(t.positions.size(), t.graph.num_vertices());
    for (core::Vertex v = 0; v < t.graph.num_vertices(); ++v) EXPECT_GE(t.graph.degree(v), 3u) << v;
    // Every outer-face vertex lies on the unit square's boundary, and every vertex there is outside.
    std::size_t on_square = 0;
    for (core::Vertex v = 0; v < t.graph.num_vertices(); ++v) {
      const core::Point2 p = t.positions[v];
      const bool on = p.x == 0 || p.x == 1 || p.y == 0 || p.y == 1;
      on_square += on;
      EXPECT_EQ(t.graph.is_boundary(v), on) << v;
    }
    EXPECT_EQ(t.graph.face_size(t.graph.outer_face()), on_square);
    // Euler: V − E + F = 2 with F = triangles + outer face + 2 holes; the square hole has ≥ 4 vertices.
    std::size_t larger = 0;
    for (core::Face f = 0; f < t.graph.num_faces(); ++f) larger += f != t.graph.outer_face() && t.graph.face_size(f) > 3;
    EXPECT_GE(larger, 1u);
    EXPECT_LE(larger, 2u);
    EXPECT_NE(t.note.find("lonely corner(s) refined"), std::string::npos) << t.note;
  }
}

TEST(MeshTopology, WithoutTheCornerRuleTheSeparatingPairIsNamed) {
  TopologyParams p = mesh_params("uniform:0.25:0.25");  // three square corners keep a single triangle
  p.set("refine_corners", false);
  try {
    (void)build_topology("mesh", p, 7, 0);
    FAIL() << "a mesh with lonely corners was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("is neither a triangulated disc"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("disconnects it; choose repair"), std::string::npos) << e.what();
  }
  // The field's repair policies apply: the 3-connected core drops the lonely corners, the holes stay.
  p.set("repair", std::string("three-connected-core"));
  const Topology t = build_topology("mesh", p, 7, 0);
  EXPECT_EQ(t.kind, core::GraphKind::three_connected);
  EXPECT_NE(t.note.find("repair removed 3 points"), std::string::npos) << t.note;
  std::size_t larger = 0;
  for (core::Face f = 0; f < t.graph.num_faces(); ++f) larger += f != t.graph.outer_face() && t.graph.face_size(f) > 3;
  EXPECT_GE(larger, 1u);
}

}  // namespace
}  // namespace laguerre::scenarios
