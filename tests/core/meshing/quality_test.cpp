// Mesh quality in the metrics of the vertices: known shapes, the worst-over-vertices rule, summaries.
#include "laguerre/core/meshing/MeshQuality.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace laguerre::core {
namespace {

TEST(MeshQuality, KnownShapes) {
  TriangleMesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}, {0, 1}};
  mesh.triangles = {{0, 1, 2}, {0, 1, 3}};
  const std::vector<Metric> identity(4, Metric{1, 0, 1});
  const MeshQuality q = measure_quality(mesh, identity);
  EXPECT_NEAR(q.elements[0].radius_edge, 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(q.elements[0].smallest_angle, 60, 1e-9);
  EXPECT_NEAR(q.elements[1].radius_edge, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.elements[1].smallest_angle, 45, 1e-9);
  EXPECT_DOUBLE_EQ(q.elements[1].distortion, 1);

  // Stretching y by 2 at one vertex only: that vertex's metric sees the right triangle (0,0),(1,0),(0,2),
  // whose smallest angle is atan(1/2); the element reports the worst over its vertices.
  std::vector<Metric> metrics = identity;
  metrics[3] = {1, 0, 4};
  const MeshQuality s = measure_quality(mesh, metrics);
  EXPECT_NEAR(s.elements[1].smallest_angle, std::atan(0.5) * 180 / M_PI, 1e-9);
  EXPECT_NEAR(s.elements[1].distortion, 2, 1e-12);
  EXPECT_NEAR(s.elements[0].smallest_angle, 60, 1e-9);  // untouched triangle
  // Five distinct edges, each measured at both ends.
  EXPECT_EQ(q.edge_lengths.size(), 10u);
}

TEST(MeshQuality, SummaryPercentilesAndHistogram) {
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  const QualitySummary s = summarize(v, 0, 100, 10);
  EXPECT_EQ(s.count, 100u);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.max, 100);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
  EXPECT_EQ(s.p5, 5);   // nearest rank: ceil(0.05·100) = 5th value
  EXPECT_EQ(s.p95, 95);
  std::size_t total = 0;
  for (std::size_t c : s.histogram) total += c;
  EXPECT_EQ(total, 100u);
  EXPECT_EQ(s.histogram.front(), 9u);  // 1..9 (10 goes to the second bin)
  EXPECT_EQ(s.histogram.back(), 11u);  // 90..100, the last value clamped into the last bin
}

}  // namespace
}  // namespace laguerre::core
