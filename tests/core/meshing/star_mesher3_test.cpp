// The 3D star mesher: outputs are checked tetrahedralizations of the bundled domains (is_valid-style
// invariants: orientation, facets shared by two tetrahedra on opposite sides, boundary covered once,
// volume), every merged tetrahedron is in the star of each of its vertices (locally uniform),
// runs are deterministic, and the Medit writer round-trips the result.
#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/MeshQuality.hpp"
#include "laguerre/core/meshing/StarMesher3.hpp"

#include "../../../core/src/meshing/detail/LocalDelaunay3.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace laguerre::core {
namespace {

const std::string domains = std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/domains/";

TEST(LocalDelaunay3, MetricInSphereIsTheStretchedEuclideanOne) {
  // In the metric diag(1, 4, 9) the point t is inside the M-circumsphere iff F·t is inside the
  // Euclidean circumsphere of the F-images, F = diag(1, 2, 3).
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::array<double, 6> m{1, 0, 0, 4, 0, 9};
  const std::array<double, 6> id{1, 0, 0, 1, 0, 1};
  for (int k = 0; k < 300; ++k) {
    std::array<std::array<double, 3>, 5> p, s;
    for (int i = 0; i < 5; ++i) {
      p[i] = {u(rng), u(rng), u(rng)};
      s[i] = {p[i][0], 2 * p[i][1], 3 * p[i][2]};
    }
    if (detail::orientation3(p[0], p[1], p[2], p[3]) < 0) std::swap(p[2], p[3]), std::swap(s[2], s[3]);
    EXPECT_EQ(detail::metric_in_sphere(p[0], p[1], p[2], p[3], p[4], m),
              detail::metric_in_sphere(s[0], s[1], s[2], s[3], s[4], id));
  }
  // Exactly cospherical: a cube corner on the circumsphere of four others.
  EXPECT_EQ(detail::metric_in_sphere({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, id), 0);
  EXPECT_EQ(detail::orientation3({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
}

TEST(LocalDelaunay3, StarsAreDelaunayForTheirMetricOnGridsAndRandomPoints) {
  // Grid points (many cospherical and coplanar ties) under a diagonal metric, where the stretching is
  // an exact scaling, and random points under a general one; each star tetrahedron is positively
  // oriented and has an empty M-circumsphere (brute force, exact metric in-sphere).
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  for (const std::array<double, 6>& m : {std::array<double, 6>{4, 0, 0, 11, 0, 25}, std::array<double, 6>{4, 1, 0.5, 11, 2, 25}}) {
    std::vector<std::array<double, 3>> points;
    const bool diagonal = m[1] == 0 && m[2] == 0 && m[4] == 0;
    for (int z = 0; z < (diagonal ? 4 : 0); ++z)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) points.push_back({x / 3.0, y / 3.0, z / 3.0});
    for (int k = 0; k < 30; ++k) points.push_back({u(rng), u(rng), u(rng)});
    for (std::size_t centre : {0, 5, 21, 29}) {
      std::vector<std::array<std::size_t, 3>> star;
      bool on_hull = false;
      ASSERT_TRUE(detail::delaunay_star3(points, centre, m, star, on_hull));
      EXPECT_FALSE(star.empty());
      for (const auto& t : star) {
        const auto& p = points[centre];
        ASSERT_EQ(detail::orientation3(p, points[t[0]], points[t[1]], points[t[2]]), 1);
        for (std::size_t w = 0; w < points.size(); ++w)
          EXPECT_LE(detail::metric_in_sphere(p, points[t[0]], points[t[1]], points[t[2]], points[w], m), 0);
      }
    }
  }
}

/// Every merged tetrahedron is in the star of each vertex: its M_v-circumball holds no vertex of the
/// mesh strictly inside, for each of its four vertices v (brute force over all vertices).
void expect_locally_delaunay(const StarMesh3Result& r) {
  const auto& p = r.mesh.points;
  std::size_t violations = 0;
  for (const auto& t : r.mesh.tetrahedra)
    for (std::size_t i = 0; i < 4; ++i) {
      const Metric3& m = r.metrics[t[i]];
      const std::array<double, 6> e{m.xx, m.xy, m.xz, m.yy, m.yz, m.zz};
      for (std::size_t w = 0; w < p.size(); ++w)
        if (w != t[0] && w != t[1] && w != t[2] && w != t[3] &&
            detail::metric_in_sphere(p[t[0]], p[t[1]], p[t[2]], p[t[3]], p[w], e) > 0)
          ++violations;
    }
  EXPECT_EQ(violations, 0u);
}

TEST(StarMesher3, CubeUnderAnisotropicUniformMetricIsACheckedTetrahedralization) {
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  const auto field = parse_metric_field3("uniform:0.5:0.3:0.2");
  const StarMesh3Result r = mesh_with_stars(cube, *field);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(check_tetrahedralization(r.mesh, cube), "");
  EXPECT_GT(r.mesh.tetrahedra.size(), 20u);
  expect_locally_delaunay(r);
  // Quality in the metric: the bounds the rules enforce hold for every tetrahedron in its vertices' metric
  // (uniform metric: every star uses the same one).
  const MeshQuality q = measure_quality(r.mesh, r.metrics);
  EXPECT_LE(q.radius_edge.max, StarMesh3Options{}.radius_edge_bound * (1 + 1e-9));
  EXPECT_NEAR(q.distortion.max, 1, 1e-12);
}

TEST(StarMesher3, BoxWithHoleIsACheckedTetrahedralizationWithNothingInTheHole) {
  const PolyhedralDomain holed = read_polyhedral_domain(domains + "box-with-hole.off");
  const auto uniform = parse_metric_field3("uniform:0.3:0.3:0.4");
  const StarMesh3Result h = mesh_with_stars(holed, *uniform);
  ASSERT_TRUE(h.converged) << h.status;
  EXPECT_EQ(check_tetrahedralization(h.mesh, holed), "");
  expect_locally_delaunay(h);
  for (const auto& t : h.mesh.tetrahedra) {
    Point3 g{0, 0, 0};
    for (std::size_t v : t)
      for (std::size_t k = 0; k < 3; ++k) g[k] += h.mesh.points[v][k] / 4;
    EXPECT_EQ(holed.locate(g), DomainSide::inside);
  }
}

TEST(StarMesher3, DeterministicAndRoundTripsThroughMedit) {
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  const auto field = parse_metric_field3("uniform:0.4:0.4:0.25");
  const StarMesh3Result a = mesh_with_stars(cube, *field);
  const StarMesh3Result b = mesh_with_stars(cube, *field);
  ASSERT_TRUE(a.converged) << a.status;
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.tetrahedra, b.mesh.tetrahedra);
  StarMesh3Options other;
  other.seed = 7;
  const StarMesh3Result c = mesh_with_stars(cube, *field, other);
  EXPECT_TRUE(c.converged) << c.status;
  const auto dir = std::filesystem::temp_directory_path() / "laguerre_star3_test";
  std::filesystem::create_directories(dir);
  write_medit_mesh((dir / "cube.mesh").string(), a.mesh);
  write_medit_sol((dir / "cube.sol").string(), a.metrics);
  const TetMesh back = read_medit_tet_mesh((dir / "cube.mesh").string());
  EXPECT_EQ(back.points, a.mesh.points);  // 17 significant digits: exact
  EXPECT_EQ(back.tetrahedra, a.mesh.tetrahedra);
  EXPECT_EQ(back.triangles, a.mesh.triangles);
  EXPECT_EQ(check_tetrahedralization(back, cube), "");
  const auto metrics = read_medit_sol3((dir / "cube.sol").string(), back.points.size());
  EXPECT_EQ(metrics[3].zz, a.metrics[3].zz);
}

TEST(StarMesher3, CheckRejectsBrokenMeshes) {
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  const auto field = parse_metric_field3("uniform:0.5:0.5:0.5");
  const StarMesh3Result r = mesh_with_stars(cube, *field);
  ASSERT_TRUE(r.converged) << r.status;
  TetMesh missing = r.mesh;
  missing.tetrahedra.pop_back();
  EXPECT_NE(check_tetrahedralization(missing, cube), "");
  TetMesh flipped = r.mesh;
  std::swap(flipped.tetrahedra[0][0], flipped.tetrahedra[0][1]);
  EXPECT_NE(check_tetrahedralization(flipped, cube).find("not positively oriented"), std::string::npos);
  TetMesh doubled = r.mesh;
  doubled.tetrahedra.push_back(doubled.tetrahedra.front());
  EXPECT_NE(check_tetrahedralization(doubled, cube), "");
  TetMesh open = r.mesh;
  open.triangles.pop_back();
  EXPECT_NE(check_tetrahedralization(open, cube), "");
}

TEST(StarMesher3, SphereShockFieldTerminatesCheckedWithTheThesisBounds) {
  // Non-diagonal metrics that rotate with the radial direction (a shock layer around a sphere inside
  // the unit cube). The run must stop by itself (not at the cap) with every star consistent and a
  // checked tetrahedralization, and the merged mesh has the bounds the rules enforce in every star
  // (thesis §3.4): radius–edge ≤ ρ₀ and sliverity ≥ σ₀ in the metric of each vertex (no sliver
  // counted), distortion < γ₀ between the vertices of each tetrahedron.
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  const auto field = parse_metric_field3("sphere:0.25:0.5:0.05:0.25:0.5:0.5:0.5");
  StarMesh3Options options;
  options.max_vertices = 2000;
  const StarMesh3Result r = mesh_with_stars(cube, *field, options);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(check_tetrahedralization(r.mesh, cube), "");
  expect_locally_delaunay(r);
  const MeshQuality q = measure_quality(r.mesh, r.metrics, options.sliver_bound);
  EXPECT_LE(q.radius_edge.max, options.radius_edge_bound * (1 + 1e-9));
  EXPECT_GE(q.sliverity.min, options.sliver_bound * (1 - 1e-9));
  EXPECT_EQ(q.slivers, 0u);
  EXPECT_LT(q.distortion.max, options.distortion_bound);
  EXPECT_GT(q.distortion.max, 1.01);  // the metrics do differ between neighbours
}

}  // namespace
}  // namespace laguerre::core
