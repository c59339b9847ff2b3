// Metrics of space and 3D metric fields: square roots against their definition, distortion against
// a sampled oracle, the built-in fields' known values, SPD-ness everywhere sampled, background
// tetrahedral meshes and the 3D Medit solution format.
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/Metric3.hpp"
#include "laguerre/core/meshing/MetricField.hpp"
#include "../../support/Scratch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

namespace laguerre::core {
namespace {

/// A random rotation (Gram–Schmidt of random vectors) and random sizes.
Metric3 random_metric(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.01, 2), u(-1, 1);
  std::array<std::array<double, 3>, 3> v{};
  for (int i = 0; i < 3; ++i) {
    for (double& c : v[i]) c = u(rng);
    for (int j = 0; j < i; ++j) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += v[i][k] * v[j][k];
      for (int k = 0; k < 3; ++k) v[i][k] -= d * v[j][k];
    }
    const double n = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    for (double& c : v[i]) c /= n;
  }
  Matrix3 r{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[static_cast<std::size_t>(3 * k + i)] = v[i][k];  // columns
  return metric3_from_sizes(size(rng), size(rng), size(rng), r);
}

TEST(Metric3, SquareRootSquaresToTheMetricAndGivesItsLengths) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const Metric3 m = random_metric(rng);
    ASSERT_TRUE(is_metric(m));
    const Matrix3 f = square_root(m);
    // FᵀF = M entry by entry (F symmetric).
    auto ftf = [&](int i, int j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += f[static_cast<std::size_t>(3 * k + i)] * f[static_cast<std::size_t>(3 * k + j)];
      return s;
    };
    const double scale = std::max({m.xx, m.yy, m.zz});
    EXPECT_NEAR(ftf(0, 0), m.xx, 1e-12 * scale);
    EXPECT_NEAR(ftf(0, 1), m.xy, 1e-12 * scale);
    EXPECT_NEAR(ftf(0, 2), m.xz, 1e-12 * scale);
    EXPECT_NEAR(ftf(1, 1), m.yy, 1e-12 * scale);
    EXPECT_NEAR(ftf(1, 2), m.yz, 1e-12 * scale);
    EXPECT_NEAR(ftf(2, 2), m.zz, 1e-12 * scale);
    const std::array<double, 3> v{0.3, -0.7, 0.2};
    const auto fv = multiply(f, v);
    EXPECT_NEAR(std::sqrt(fv[0] * fv[0] + fv[1] * fv[1] + fv[2] * fv[2]), metric_length(m, v), 1e-12 * std::sqrt(scale));
    const auto back = solve(f, fv);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[static_cast<std::size_t>(k)], v[static_cast<std::size_t>(k)], 1e-9);
  }
}

TEST(Metric3, SizesAreRecovered) {
  const Metric3 m = metric3_from_sizes(0.1, 0.5, 0.02);
  EXPECT_DOUBLE_EQ(m.xx, 100);
  EXPECT_DOUBLE_EQ(m.yy, 4);
  EXPECT_DOUBLE_EQ(m.zz, 2500);
  const auto s = sizes_of(m);
  EXPECT_NEAR(s[0], 0.5, 1e-12);
  EXPECT_NEAR(s[1], 0.1, 1e-12);
  EXPECT_NEAR(s[2], 0.02, 1e-12);
  EXPECT_FALSE(is_metric(Metric3{1, 2, 0, 1, 0, 1}));  // indefinite
  EXPECT_FALSE(is_metric(Metric3{1, 0, 0, 1, 0, 0}));  // singular
  EXPECT_THROW(metric3_from_sizes(0.1, -1, 0.1), InputError);
}

TEST(Metric3, DistortionMatchesSampledOracleAndIsSymmetric) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 30; ++trial) {
    const Metric3 m = random_metric(rng), n = random_metric(rng);
    const double gamma = distortion(m, n);
    EXPECT_NEAR(gamma, distortion(n, m), 1e-9 * gamma);
    // γ = max over directions of max(‖v‖_M/‖v‖_N, ‖v‖_N/‖v‖_M): sampling gives a lower bound that
    // gets close.
    double sampled = 1;
    for (int k = 0; k < 20000; ++k) {
      const std::array<double, 3> v{g(rng), g(rng), g(rng)};
      const double r = metric_length(m, v) / metric_length(n, v);
      sampled = std::max({sampled, r, 1 / r});
    }
    EXPECT_LE(sampled, gamma * (1 + 1e-9));
    EXPECT_GE(sampled, gamma * 0.97);
  }
  const Metric3 m = metric3_from_sizes(0.1, 0.2, 0.3);
  EXPECT_NEAR(distortion(m, m), 1, 1e-12);
  EXPECT_NEAR(distortion(m, metric3_from_sizes(0.2, 0.2, 0.3)), 2, 1e-12);
}

TEST(MetricField3, BuiltInFieldsHaveTheirKnownValues) {
  const auto uniform = parse_metric_field3("uniform:0.1:0.2:0.4");
  const Metric3 u = uniform->at(3, -2, 7);
  EXPECT_DOUBLE_EQ(u.xx, 100);
  EXPECT_DOUBLE_EQ(u.yy, 25);
  EXPECT_DOUBLE_EQ(u.zz, 6.25);
  EXPECT_EQ(u.xy, 0);
  EXPECT_EQ(uniform->describe(), "uniform:0.1:0.2:0.4");

  const auto shock = parse_metric_field3("shock:0.01:0.1:0.05:0.5");
  // On the plane the size across is HMIN; far away it tends to HMAX; along it is HMAX everywhere.
  EXPECT_NEAR(shock->at(0.5, 0.3, 0.9).xx, 1e4, 1e-8);
  EXPECT_NEAR(shock->at(0.5, 0.3, 0.9).yy, 100, 1e-10);
  const double h = 0.01 + 0.09 * (1 - std::exp(-0.2 / 0.05));
  EXPECT_NEAR(shock->at(0.7, 0, 0).xx, 1 / (h * h), 1e-9);
  EXPECT_NEAR(shock->at(0.3, 0, 0).xx, 1 / (h * h), 1e-9);
  EXPECT_NEAR(shock->at(0.3, 0, 0).zz, 100, 1e-10);

  const auto sphere = parse_metric_field3("sphere:0.01:0.1:0.05:0.3:0.5:0.5:0.5");
  // On the sphere, radially 1/HMIN², tangentially 1/HMAX²: at (0.8, 0.5, 0.5) the radius is x.
  const Metric3 s = sphere->at(0.8, 0.5, 0.5);
  EXPECT_NEAR(s.xx, 1e4, 1e-7);
  EXPECT_NEAR(s.yy, 100, 1e-9);
  EXPECT_NEAR(s.zz, 100, 1e-9);
  EXPECT_NEAR(s.xy, 0, 1e-9);
  // Along a diagonal radius the radial direction n = (1, 1, 0)/√2: nᵀMn = 1/HMIN², and the
  // tangential direction (1, −1, 0)/√2 has 1/HMAX².
  const double t = 0.3 / std::sqrt(2.0);
  const Metric3 d = sphere->at(0.5 + t, 0.5 + t, 0.5);
  EXPECT_NEAR(metric_length(d, {1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0}), 100, 1e-6);
  EXPECT_NEAR(metric_length(d, {1 / std::sqrt(2.0), -1 / std::sqrt(2.0), 0}), 10, 1e-7);
  EXPECT_NEAR(sphere->at(0.5, 0.5, 0.5).xx, 100, 1e-12);  // the centre: isotropic HMAX

  const auto expr = parse_metric_field3("expr:xx=1+x*x;xy=0.1;xz=0;yy=2+y;yz=z;zz=3");
  const Metric3 e = expr->at(2, 1, 0.5);
  EXPECT_DOUBLE_EQ(e.xx, 5);
  EXPECT_DOUBLE_EQ(e.xy, 0.1);
  EXPECT_DOUBLE_EQ(e.yy, 3);
  EXPECT_DOUBLE_EQ(e.yz, 0.5);
  EXPECT_DOUBLE_EQ(e.zz, 3);
}

TEST(MetricField3, FieldsAreSpdWhereSampled) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> c(-0.5, 1.5);
  for (const char* spec : {"shock", "sphere", "sphere:0.001:1:0.01:0.4:0:0:0", "shock:0.001:1:0.001:0"}) {
    const auto f = parse_metric_field3(spec);
    for (int k = 0; k < 2000; ++k) EXPECT_TRUE(is_metric(f->at(c(rng), c(rng), c(rng)))) << spec;
  }
}

TEST(MetricField3, BadSpecificationsAreRejected) {
  for (const char* spec : {"uniform:0.1:0.2", "uniform:0.1:-1:0.2", "shock:0.1:0.01", "sphere:0.01:0.1:0.05:-1",
                           "expr:xx=1;xy=0;xz=0;yy=1;yz=0", "expr:xx=1;xy=0;xz=0;yy=1;yz=0;zz=1;ww=2",
                           "expr:xx=1+;xy=0;xz=0;yy=1;yz=0;zz=1", "thesis", "mesh:"})
    EXPECT_THROW(parse_metric_field3(spec), FieldError) << spec;
  // Parsed, but not a metric where evaluated: the message names the point.
  const auto f = parse_metric_field3("expr:xx=x;xy=0;xz=0;yy=1;yz=0;zz=1");
  try {
    f->at(-1, 0, 0);
    FAIL();
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("(-1, 0, 0)"), std::string::npos) << e.what();
  }
}

TEST(MetricField3, BackgroundTetMeshInterpolatesLinearlyAndRoundTrips) {
  // One tetrahedron with a metric per vertex; inside, the field is the barycentric blend.
  const auto dir = laguerre::testing::scratch_folder() / "laguerre_metric3_test";
  std::filesystem::create_directories(dir);
  TetMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.point_refs = {0, 0, 0, 0};
  mesh.tetrahedra = {{0, 1, 2, 3}};
  mesh.tetrahedron_refs = {0};
  const std::vector<Metric3> metrics = {metric3_from_sizes(1, 1, 1), metric3_from_sizes(0.5, 1, 1),
                                        metric3_from_sizes(1, 0.5, 1), Metric3{4, 1, 0.5, 3, 0.2, 2}};
  write_medit_mesh((dir / "bg.mesh").string(), mesh);
  write_medit_sol((dir / "bg.sol").string(), metrics);
  const TetMesh back = read_medit_tet_mesh((dir / "bg.mesh").string());
  ASSERT_EQ(back.points, mesh.points);
  ASSERT_EQ(back.tetrahedra, mesh.tetrahedra);
  const auto read = read_medit_sol3((dir / "bg.sol").string(), 4);
  EXPECT_DOUBLE_EQ(read[3].xz, 0.5);
  EXPECT_DOUBLE_EQ(read[3].yz, 0.2);
  const auto field = parse_metric_field3("mesh:" + (dir / "bg.mesh").string());
  const Metric3 centre = field->at(0.25, 0.25, 0.25);
  Metric3 expected{0, 0, 0, 0, 0, 0};
  for (const Metric3& m : metrics) expected = {expected.xx + m.xx / 4, expected.xy + m.xy / 4, expected.xz + m.xz / 4,
                                               expected.yy + m.yy / 4, expected.yz + m.yz / 4, expected.zz + m.zz / 4};
  EXPECT_NEAR(centre.xx, expected.xx, 1e-12);
  EXPECT_NEAR(centre.xz, expected.xz, 1e-12);
  EXPECT_NEAR(centre.zz, expected.zz, 1e-12);
  EXPECT_NEAR(field->at(0, 0, 1).xy, 1, 1e-12);  // a vertex gets its own metric
  EXPECT_THROW(field->at(1, 1, 1), FieldError);  // outside the background mesh
  // A .sol for another vertex count, and a 2D mesh, are refused with the file named.
  EXPECT_THROW(read_medit_sol3((dir / "bg.sol").string(), 5), MeshInputError);
  EXPECT_EQ(medit_dimension((dir / "bg.mesh").string()), 3);
}

}  // namespace
}  // namespace laguerre::core
