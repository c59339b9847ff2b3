// Star refinement (thesis chapter 3): termination with consistent stars, the merged mesh is a valid
// triangulation of the domain, and the promised bounds hold on every element in its vertices' metrics.
#include "laguerre/core/meshing/MeshQuality.hpp"
#include "laguerre/core/meshing/StarMesher.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace laguerre::core {
namespace {

void expect_good_mesh(const StarMeshResult& r, const Domain& d, const StarMeshOptions& o, double slack) {
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(check_triangulation(r.mesh, d), "");
  // Each triangle is in the stars of its three vertices, so for each vertex's metric it satisfies
  // that star's bounds; across vertices the bounds hold up to the distortion γ₀ (slack).
  const MeshQuality q = measure_quality(r.mesh, r.metrics);
  EXPECT_LE(q.radius_edge.max, o.radius_edge_bound * slack);
  EXPECT_GE(q.smallest_angle.min, std::asin(1 / (2 * o.radius_edge_bound * slack)) * 180 / M_PI - 1e-9);
  EXPECT_LE(q.edge_length.max, 2 * o.size_bound * slack);  // an edge is a chord of the circumcircle
}

TEST(StarMesher, IsotropicSquare) {
  const Domain d = Domain::unit_square();
  const auto field = parse_metric_field("uniform:0.1:0.1");
  StarMeshOptions o;
  const StarMeshResult r = mesh_with_stars(d, *field, o);
  expect_good_mesh(r, d, o, 1 + 1e-9);
  EXPECT_GT(r.mesh.points.size(), 50u);
}

TEST(StarMesher, AnisotropicUniformSquareWithHole) {
  // Axis-aligned anisotropy keeps the square's corners at 90° in the metric (the thesis requires
  // boundary angles of at least 90° in the metric for the encroachment rule to terminate).
  const Domain d({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.4, 0.4}, {0.6, 0.4}, {0.5, 0.6}}});
  const auto field = parse_metric_field("uniform:0.2:0.04:0");
  StarMeshOptions o;
  const StarMeshResult r = mesh_with_stars(d, *field, o);
  expect_good_mesh(r, d, o, 1 + 1e-9);
}

TEST(StarMesher, SmallInputAnglesInTheMetricStopAtTheCap) {
  // A 30°-rotated anisotropy makes two corners of the square acute in the metric: the hypothesis of
  // the termination theorem fails and boundary protection cascades. The cap turns that into a status.
  const auto field = parse_metric_field("uniform:0.2:0.04:30");
  StarMeshOptions o;
  o.max_vertices = 2000;
  const StarMeshResult r = mesh_with_stars(Domain::unit_square(), *field, o);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("max_vertices"), std::string::npos);
}

TEST(StarMesher, ThesisFieldTerminatesConsistent) {
  const Domain d = Domain::unit_square();
  const auto field = parse_metric_field("thesis:0.1:4:0.2:0.5");
  StarMeshOptions o;
  const StarMeshResult r = mesh_with_stars(d, *field, o);
  expect_good_mesh(r, d, o, o.distortion_bound);
  EXPECT_GT(r.stats.shape, 0u);
  EXPECT_GT(r.stats.inconsistency + r.stats.distortion, 0u);  // the exchange of axes needs work
}

TEST(StarMesher, ShockLayer) {
  const Domain d = Domain::unit_square();
  const auto field = parse_metric_field("shock:0.01:0.1:0.05:0.5");
  StarMeshOptions o;
  const StarMeshResult r = mesh_with_stars(d, *field, o);
  expect_good_mesh(r, d, o, o.distortion_bound);
  // Denser in the layer: more vertices within 0.05 of x = 0.5 than in the outer strip of equal width.
  std::size_t in_layer = 0, outside = 0;
  for (const auto& p : r.mesh.points) {
    in_layer += std::abs(p[0] - 0.5) < 0.05;
    outside += p[0] < 0.1;
  }
  EXPECT_GT(in_layer, 3 * outside);
}

TEST(StarMesher, DeterministicPerSeed) {
  const Domain d = Domain::unit_square();
  const auto field = parse_metric_field("thesis:0.1:4:0.2:0.5");
  StarMeshOptions o;
  const auto a = mesh_with_stars(d, *field, o), b = mesh_with_stars(d, *field, o);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  o.seed = 2;
  EXPECT_NE(mesh_with_stars(d, *field, o).mesh.points, a.mesh.points);
}

}  // namespace
}  // namespace laguerre::core
