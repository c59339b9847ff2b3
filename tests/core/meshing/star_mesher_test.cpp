// Star refinement (thesis chapter 3): termination with consistent stars, the merged mesh is a valid
// triangulation of the domain, and the promised bounds hold on every element in its vertices' metrics.
#include "laguerre/core/meshing/StarMesher.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace laguerre::core {
namespace {

/// The largest M-radius–edge ratio and M-circumradius of triangle t over the metrics of its vertices.
std::pair<double, double> worst_quality(const StarMeshResult& r, std::size_t t) {
  double ratio = 0, radius = 0;
  const auto& tri = r.mesh.triangles[t];
  for (std::size_t k = 0; k < 3; ++k) {
    const Matrix2 f = square_root(r.metrics[tri[k]]);
    std::array<std::array<double, 2>, 3> q{};
    for (std::size_t i = 0; i < 3; ++i) {
      const auto& p = r.mesh.points[tri[i]];
      q[i] = {f.m00 * p[0] + f.m01 * p[1], f.m10 * p[0] + f.m11 * p[1]};
    }
    const double ax = q[1][0] - q[0][0], ay = q[1][1] - q[0][1], bx = q[2][0] - q[0][0], by = q[2][1] - q[0][1];
    const double d = 2 * (ax * by - ay * bx);
    const double ux = (by * (ax * ax + ay * ay) - ay * (bx * bx + by * by)) / d;
    const double uy = (ax * (bx * bx + by * by) - bx * (ax * ax + ay * ay)) / d;
    const double R = std::hypot(ux, uy);
    const double shortest = std::min({std::hypot(ax, ay), std::hypot(bx, by), std::hypot(bx - ax, by - ay)});
    ratio = std::max(ratio, R / shortest);
    radius = std::max(radius, R);
  }
  return {ratio, radius};
}

void expect_good_mesh(const StarMeshResult& r, const Domain& d, const StarMeshOptions& o, double slack) {
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(check_triangulation(r.mesh, d), "");
  // Each triangle is in the stars of its three vertices, so for each vertex's metric it satisfies
  // that star's bounds; across vertices the bounds hold up to the distortion γ₀ (slack).
  double worst_ratio = 0, worst_radius = 0;
  for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t) {
    const auto [ratio, radius] = worst_quality(r, t);
    worst_ratio = std::max(worst_ratio, ratio);
    worst_radius = std::max(worst_radius, radius);
  }
  EXPECT_LE(worst_ratio, o.radius_edge_bound * slack);
  EXPECT_LE(worst_radius, o.size_bound * slack);
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
