#include <gtest/gtest.h>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

using namespace laguerre::core;

namespace {
// Octahedron: vertices 0..5, 0 and 5 are poles, 1..4 the equator (counter-clockwise seen from 0).
PlanarGraph octahedron() {
  return PlanarGraph::from_rotation({{1, 2, 3, 4}, {0, 4, 5, 2}, {0, 1, 5, 3}, {0, 2, 5, 4}, {0, 3, 5, 1}, {1, 4, 3, 2}});
}
}  // namespace

TEST(PlanarGraph, OctahedronHasEightTriangles) {
  const PlanarGraph g = octahedron();
  EXPECT_TRUE(g.is_valid(true));
  EXPECT_EQ(g.num_vertices(), 6u);
  EXPECT_EQ(g.num_edges(), 12u);
  EXPECT_EQ(g.num_faces(), 8u);
  for (Face f = 0; f < g.num_faces(); ++f) EXPECT_EQ(g.face_size(f), 3u);
  // Default outer face: at the smallest-id edge 0-1, a triangle.
  EXPECT_EQ(g.boundary_cycle().size(), 3u);
  EXPECT_TRUE(g.is_boundary(0));
  EXPECT_TRUE(g.is_boundary(1));
}

TEST(PlanarGraph, FaceWalkTurnsAroundTwinsConsistently) {
  const PlanarGraph g = octahedron();
  for (Dart d = 0; d < g.num_darts(); ++d) {
    EXPECT_EQ(g.tail(g.next_in_face(d)), g.head(d));
    EXPECT_EQ(g.next_cw(g.next_ccw(d)), d);
    EXPECT_EQ(g.find_dart(g.tail(d), g.head(d)), d);
  }
}

TEST(PlanarGraph, RejectsAsymmetricAndNonPlanarRotations) {
  EXPECT_THROW(PlanarGraph::from_rotation({{1}, {}}), laguerre::core::InputError);
  EXPECT_THROW(PlanarGraph::from_rotation({{1, 1}, {0, 0}}), laguerre::core::InputError);
  // K4 with a rotation that is not planar (genus 1): Euler characteristic 0.
  EXPECT_THROW(PlanarGraph::from_rotation({{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}), laguerre::core::InputError);
  EXPECT_THROW(PlanarGraph::from_rotation({{1}, {0}, {3}, {2}}), laguerre::core::InputError);  // disconnected
}
