// Metrics, distortion and metric fields (thesis §2.4, §3.2): closed forms against brute-force
// oracles, the distortion inequality, field definitions, background meshes and their file formats.
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/Metric.hpp"
#include "laguerre/core/meshing/MetricField.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

namespace laguerre::core {
namespace {

Metric random_metric(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.01, 2), angle(-M_PI, M_PI);
  return metric_from_sizes(size(rng), size(rng), angle(rng));
}

Matrix2 multiply(const Matrix2& p, const Matrix2& q) {
  return {p.m00 * q.m00 + p.m01 * q.m10, p.m00 * q.m01 + p.m01 * q.m11, p.m10 * q.m00 + p.m11 * q.m10,
          p.m10 * q.m01 + p.m11 * q.m11};
}

Matrix2 inverse(const Matrix2& f) {
  const double det = f.m00 * f.m11 - f.m01 * f.m10;
  return {f.m11 / det, -f.m01 / det, -f.m10 / det, f.m00 / det};
}

/// The upper-triangular Cholesky-type root R with RᵀR = M (another valid F of thesis §3.2).
Matrix2 cholesky_root(const Metric& m) {
  const double r00 = std::sqrt(m.a), r01 = m.b / r00;
  return {r00, r01, 0, std::sqrt(m.c - r01 * r01)};
}

/// ‖A‖₂ by sampling the unit circle densely (the oracle for the closed form).
double sampled_norm(const Matrix2& a) {
  double best = 0;
  for (int k = 0; k < 20000; ++k) {
    const double t = M_PI * k / 20000;
    const double x = std::cos(t), y = std::sin(t);
    best = std::max(best, std::hypot(a.m00 * x + a.m01 * y, a.m10 * x + a.m11 * y));
  }
  return best;
}

TEST(Metric, SizesRoundTrip) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 200; ++i) {
    const Metric m = random_metric(rng);
    ASSERT_TRUE(is_metric(m));
    const auto [h1, h2, theta] = sizes_of(m);
    EXPECT_GE(h1, h2);
    const Metric back = metric_from_sizes(h1, h2, theta);
    const double scale = std::max({std::abs(m.a), std::abs(m.c)});
    EXPECT_NEAR(back.a, m.a, 1e-10 * scale);
    EXPECT_NEAR(back.b, m.b, 1e-10 * scale);
    EXPECT_NEAR(back.c, m.c, 1e-10 * scale);
    // h1 is the length of the unit ball's long semi-axis: ‖h1·u(θ)‖_M = 1.
    EXPECT_NEAR(metric_length(m, h1 * std::cos(theta), h1 * std::sin(theta)), 1, 1e-10);
  }
}

TEST(Metric, SquareRootIsSymmetricWithPositiveDeterminant) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 200; ++i) {
    const Metric m = random_metric(rng);
    const Matrix2 f = square_root(m);
    EXPECT_DOUBLE_EQ(f.m01, f.m10);
    EXPECT_GT(f.m00 * f.m11 - f.m01 * f.m10, 0);
    const Matrix2 ftf = multiply({f.m00, f.m10, f.m01, f.m11}, f);
    const double scale = std::max(m.a, m.c);
    EXPECT_NEAR(ftf.m00, m.a, 1e-10 * scale);
    EXPECT_NEAR(ftf.m01, m.b, 1e-10 * scale);
    EXPECT_NEAR(ftf.m11, m.c, 1e-10 * scale);
  }
}

TEST(Metric, DistortionMatchesOperatorNormsForAnySquareRoot) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 60; ++i) {
    const Metric m = random_metric(rng), n = random_metric(rng);
    for (bool cholesky : {false, true}) {
      const Matrix2 fm = cholesky ? cholesky_root(m) : square_root(m);
      const Matrix2 fn = cholesky ? cholesky_root(n) : square_root(n);
      const double oracle =
          std::max(sampled_norm(multiply(fm, inverse(fn))), sampled_norm(multiply(fn, inverse(fm))));
      EXPECT_NEAR(distortion(m, n), oracle, 1e-6 * oracle) << "cholesky=" << cholesky;
    }
  }
}

TEST(Metric, DistortionBoundsLengthsAndIsSymmetric) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> coord(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Metric m = random_metric(rng), n = random_metric(rng);
    const double g = distortion(m, n);
    EXPECT_GE(g, 1);
    EXPECT_NEAR(g, distortion(n, m), 1e-12 * g);
    for (int k = 0; k < 20; ++k) {
      const double dx = coord(rng), dy = coord(rng);
      const double lm = metric_length(m, dx, dy), ln = metric_length(n, dx, dy);
      EXPECT_LE(lm, g * ln * (1 + 1e-12));
      EXPECT_LE(ln, g * lm * (1 + 1e-12));
    }
  }
  const Metric m{2, 0.5, 1};
  EXPECT_NEAR(distortion(m, m), 1, 1e-15);
  EXPECT_NEAR(distortion(m, {4 * m.a, 4 * m.b, 4 * m.c}), 2, 1e-14);  // lengths scale by 2
  EXPECT_NEAR(distortion(Metric{1, 0, 1}, Metric{1, 0, 9}), 3, 1e-14);
}

TEST(MetricField, BuiltInsHaveTheirDocumentedValues) {
  const auto shock = shock_layer_field(0.002, 0.1, 0.02, 0.5);
  const Metric at_layer = shock->at(0.5, 0.3);
  EXPECT_NEAR(sizes_of(at_layer)[0], 0.1, 1e-12);   // along the layer (vertical)
  EXPECT_NEAR(sizes_of(at_layer)[1], 0.002, 1e-12);  // across it
  const double far = 0.5 + 0.02 * std::log(2.0);    // 1 − e^{−d/w} = 1/2
  EXPECT_NEAR(1 / std::sqrt(shock->at(far, 0).a), 0.002 + 0.098 / 2, 1e-12);

  const auto thesis = thesis_field(0.05, 4, 0.1, 0.5);
  EXPECT_NEAR(1 / std::sqrt(thesis->at(0.3, 0.9).a), 0.1, 1e-12);   // horizontal size above
  EXPECT_NEAR(1 / std::sqrt(thesis->at(0.3, 0.9).c), 0.025, 1e-12);  // vertical size above
  EXPECT_NEAR(1 / std::sqrt(thesis->at(0.3, 0.1).a), 0.025, 1e-12);  // exchanged below
  EXPECT_NEAR(distortion(thesis->at(0, 0.5), {400, 0, 400}), 1, 1e-12);  // isotropic on the midline
  // Continuity: the distortion between points 1e-6 apart across the band is close to 1.
  for (double y = 0.3; y < 0.7; y += 0.01) EXPECT_LT(distortion(*thesis, 0, y, 0, y + 1e-6), 1 + 1e-4);
}

TEST(MetricField, ExpressionsAgreeWithBuiltIns) {
  const auto expr = parse_metric_field(
      "sizes:h1=0.1;h2=0.002+(0.1-0.002)*(1-exp(-abs(x-0.5)/0.02));theta=pi/2");
  const auto shock = parse_metric_field("shock");
  for (double x = 0; x <= 1; x += 0.05) {
    const Metric a = expr->at(x, 0.2), b = shock->at(x, 0.2);
    EXPECT_NEAR(distortion(a, b), 1, 1e-9) << x;
  }
  const auto abc = parse_metric_field("expr:a=1+x*x;b=x*y;c=2");
  EXPECT_DOUBLE_EQ(abc->at(0.5, 2).a, 1.25);
  EXPECT_DOUBLE_EQ(abc->at(0.5, 2).b, 1.0);
  EXPECT_THROW(abc->at(2, 2), FieldError);  // det = 5·2 − 16 < 0 there
}

// Positive finite sizes whose squares leave the doubles give infinite or zero entries: a FieldError
// naming the field, as for expr fields (fuzz finding metric-2).
TEST(MetricField, SizesBeyondTheDoublesThrowAtThePoint) {
  auto message = [](const MetricField& field, double x, double y) {
    try {
      (void)field.at(x, y);
    } catch (const FieldError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const auto sizes = parse_metric_field("sizes:h1=0.1+x;h2=0.01e-300;theta=atan2(y,x)");
  EXPECT_NE(message(*sizes, 0, 0).find("metric field 'sizes:h1=0.1+x;h2=0.01e-300;theta=atan2(y,x)': the matrix"),
            std::string::npos)
      << message(*sizes, 0, 0);
  EXPECT_TRUE(is_metric(parse_metric_field("sizes:h1=0.1+x;h2=0.01;theta=0")->at(0, 0)));
  const auto shock = shock_layer_field(1e-200, 0.1, 0.02, 0.5);
  EXPECT_NE(message(*shock, 0.5, 0).find("metric field 'shock:1e-200:0.1:0.02:0.5'"), std::string::npos)
      << message(*shock, 0.5, 0);
  EXPECT_TRUE(is_metric(shock->at(0.9, 0)));  // far from the layer the size across is about HMAX
  const auto thesis = thesis_field(1e-160, 4, 0.1, 0.5);
  EXPECT_THROW((void)thesis->at(0, 0.9), FieldError);
  EXPECT_THROW((void)thesis_field(1e160, 4, 0.1, 0.5)->at(0, 0.9), FieldError);  // zero entries
}

// A uniform field's description parses back to the same matrix bit for bit (fuzz finding metric-1).
TEST(MetricField, UniformDescriptionsReadBackExactly) {
  for (const char* spec : {"uniform:065536.2:1844674407370955161601e30", "uniform:617:0.05:30", "uniform:0.1:0.05:30",
                           "uniform:0.3:0.3", "uniform:0.02:0.1:-17.25", "uniform:1e-100:3e-100:1e-300"}) {
    const auto field = parse_metric_field(spec);
    const std::string description = field->describe();
    const auto again = parse_metric_field(description);
    const Metric m = field->at(0, 0), n = again->at(0, 0);
    EXPECT_TRUE(m.a == n.a && m.b == n.b && m.c == n.c) << spec << " -> " << description;
    EXPECT_EQ(again->describe(), description) << spec;
  }
  EXPECT_EQ(parse_metric_field("uniform:065536.2:1844674407370955161601e30")->describe(),
            "uniform:65536.2:1.8446744073709553e+51:0");
  EXPECT_EQ(parse_metric_field("uniform:0.3:0.3")->describe(), "uniform:0.3:0.3:0");  // default THETA filled in
  // Built from a matrix: described by its entries.
  const Metric m{2.5, -0.1, 1.0 / 3};
  const auto field = uniform_field(m);
  const Metric n = parse_metric_field(field->describe())->at(0.5, 0.5);
  EXPECT_TRUE(m.a == n.a && m.b == n.b && m.c == n.c) << field->describe();
}

TEST(MetricField, BadSpecificationsAreExplained) {
  auto message = [](const std::string& spec) {
    try {
      parse_metric_field(spec);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("bogus").find("unknown metric field 'bogus'"), std::string::npos);
  EXPECT_NE(message("uniform:1").find("usage uniform:H1:H2"), std::string::npos);
  EXPECT_NE(message("uniform:1:x").find("parameter 2 is 'x', expected a number"), std::string::npos);
  EXPECT_NE(message("shock:0.1:0.01").find("0 < HMIN <= HMAX"), std::string::npos);
  EXPECT_NE(message("expr:a=1;b=0").find("missing 'c=EXPR'"), std::string::npos);
  EXPECT_NE(message("expr:a=1;b=0;c=(x").find("in c=(x"), std::string::npos);
  EXPECT_NE(message("mesh:/nonexistent.mesh").find("/nonexistent.mesh: no such Medit mesh file"), std::string::npos);
}

class BackgroundMesh : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("laguerre-metric-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(BackgroundMesh, InterpolatesLinearlyAndRoundTrips) {
  TriangleMesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.point_refs = {1, 1, 2, 2};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.triangle_refs = {0, 0};
  mesh.edges = {{0, 1}};
  mesh.edge_refs = {7};
  const std::vector<Metric> metrics = {{1, 0, 1}, {4, 0, 1}, {9, 1, 4}, {1, 0, 16}};
  write_medit_mesh(path("bg.mesh"), mesh);
  write_medit_sol(path("bg.sol"), metrics);

  const TriangleMesh back = read_medit_mesh(path("bg.mesh"));
  EXPECT_EQ(back.points, mesh.points);
  EXPECT_EQ(back.triangles, mesh.triangles);
  EXPECT_EQ(back.edges, mesh.edges);
  EXPECT_EQ(back.edge_refs, mesh.edge_refs);

  const auto field = parse_metric_field("mesh:" + path("bg.mesh"));
  for (std::size_t v = 0; v < 4; ++v) {
    const Metric m = field->at(mesh.points[v][0], mesh.points[v][1]);
    EXPECT_DOUBLE_EQ(m.a, metrics[v].a);
    EXPECT_DOUBLE_EQ(m.c, metrics[v].c);
  }
  const Metric centre = field->at(2.0 / 3, 1.0 / 3);  // centroid of the first triangle
  EXPECT_NEAR(centre.a, (1 + 4 + 9) / 3.0, 1e-12);
  EXPECT_NEAR(centre.b, 1 / 3.0, 1e-12);
  EXPECT_THROW(field->at(1.5, 0.5), FieldError);
  EXPECT_NO_THROW(field->at(1 + 1e-12, 0.5));  // on the boundary up to rounding
}

TEST_F(BackgroundMesh, MalformedFilesNameTheLine) {
  {
    std::ofstream out(path("bad.mesh"));
    out << "MeshVersionFormatted 2\nDimension 2\nVertices\n2\n0 0 0\n1 zero 0\nEnd\n";
  }
  try {
    read_medit_mesh(path("bad.mesh"));
    FAIL() << "accepted a malformed mesh";
  } catch (const MeshInputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.mesh:6: expected a vertex ordinate (a finite number), found 'zero'"),
              std::string::npos)
        << e.what();
  }
  {
    std::ofstream out(path("range.mesh"));
    out << "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 4 0\nEnd\n";
  }
  EXPECT_THROW(
      {
        try {
          read_medit_mesh(path("range.mesh"));
        } catch (const MeshInputError& e) {
          EXPECT_NE(std::string(e.what()).find("range.mesh:10: vertex index 4 is out of range 1..3"), std::string::npos)
              << e.what();
          throw;
        }
      },
      MeshInputError);
  {
    std::ofstream out(path("short.sol"));
    out << "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n2\n1 1\n0.5\n0.25\nEnd\n";
  }
  EXPECT_THROW(read_medit_sol(path("short.sol"), 3), MeshInputError);
  const auto sizes = read_medit_sol(path("short.sol"), 2);
  EXPECT_DOUBLE_EQ(sizes[1].a, 16);  // h = 0.25 ⇒ M = I/h²
}

TEST_F(BackgroundMesh, PlanarMeshesInDimensionThreeAreRead) {
  // gmsh writes a planar mesh as `Dimension 3` with z = 0; a clockwise triangle is turned around.
  {
    std::ofstream out(path("gmsh.mesh"));
    out << " MeshVersionFormatted 2\n Dimension\n 3\n Vertices\n 3\n 0 0 0 1\n 0 1 0 2\n 1 0 0 3\n"
           " Triangles\n 1\n 1 2 3 7\n End\n";
  }
  const TriangleMesh m = read_medit_mesh(path("gmsh.mesh"));
  ASSERT_EQ(m.points.size(), 3u);
  EXPECT_EQ(m.points[1], (std::array<double, 2>{0, 1}));
  EXPECT_EQ(m.point_refs[2], 3);
  ASSERT_EQ(m.triangles.size(), 1u);
  const auto& t = m.triangles[0];
  const double cross = (m.points[t[1]][0] - m.points[t[0]][0]) * (m.points[t[2]][1] - m.points[t[0]][1]) -
                       (m.points[t[1]][1] - m.points[t[0]][1]) * (m.points[t[2]][0] - m.points[t[0]][0]);
  EXPECT_GT(cross, 0);
  EXPECT_EQ(m.triangle_refs[0], 7);
  {
    std::ofstream out(path("lifted.mesh"));
    out << "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 1\n1 0 0.5 1\nEnd\n";
  }
  try {
    read_medit_mesh(path("lifted.mesh"));
    FAIL() << "accepted a vertex off the plane";
  } catch (const MeshInputError& e) {
    EXPECT_NE(std::string(e.what()).find("lifted.mesh:6: vertex 2 has z = 0.5"), std::string::npos) << e.what();
  }
  {
    std::ofstream out(path("three.sol"));
    out << "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 1\n0.5\nEnd\n";
  }
  EXPECT_THROW(read_medit_sol(path("three.sol"), 1), MeshInputError);  // solutions stay planar
}

TEST(MetricField, BoundedDistortionRadius) {
  // Uniform field: the distortion never exceeds 1, the radius is the cap.
  EXPECT_DOUBLE_EQ(bounded_distortion_radius(*parse_metric_field("uniform:1:0.1"), 0.3, 0.3, 1.1, 2.0), 2.0);
  // The thesis field depends on y only: inside the radius every sampled point respects γ₀, and just
  // beyond it some point breaks it.
  const auto field = thesis_field(0.05, 4, 0.1, 0.5);
  const double gamma0 = 1.2;
  const double l = bounded_distortion_radius(*field, 0.5, 0.5, gamma0, 10.0);
  ASSERT_GT(l, 0);
  ASSERT_LT(l, 10.0);
  const Metric mp = field->at(0.5, 0.5);
  double worst_inside = 1, worst_beyond = 1;
  for (double y = 0.0; y <= 1.0; y += 1e-4) {
    const double d = metric_length(mp, 0, y - 0.5);
    const double g = distortion(mp, field->at(0.5, y));
    if (d <= l) worst_inside = std::max(worst_inside, g);
    if (d <= l * 1.01) worst_beyond = std::max(worst_beyond, g);
  }
  EXPECT_LE(worst_inside, gamma0 * (1 + 1e-9));
  EXPECT_GT(worst_beyond, gamma0);
}

}  // namespace
}  // namespace laguerre::core
