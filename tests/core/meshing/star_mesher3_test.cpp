// The 3D star mesher: outputs are checked tetrahedralizations of the bundled domains (is_valid-style
// invariants: orientation, facets shared by two tetrahedra on opposite sides, boundary covered once,
// volume), every merged tetrahedron is in the star of each of its vertices (locally uniform),
// runs are deterministic, and the Medit writer round-trips the result.
#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/MeshQuality.hpp"
#include "laguerre/core/meshing/StarMesher3.hpp"

#include "../../../core/src/meshing/detail/LocalDelaunay3.hpp"
#include "../../support/Scratch.hpp"

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

TEST(LocalDelaunay3, MetricInSphereFilterDefersOnNearlyCosphericalPoints) {
  // The floating-point filter either answers the exact sign or defers (kUndecided): it must defer on
  // exactly cospherical points (determinant 0) and on points perturbed off the sphere by far less than
  // its error bound, agree with the unfiltered exact predicate whenever it answers, and answer almost
  // always on random (well-separated) points, which is what makes it worth having.
  using detail::kUndecided;
  using P = std::array<double, 3>;
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> u(0, 1), w(-1, 1);
  const auto check = [](const P& p, const P& q, const P& r, const P& s, const P& t, const std::array<double, 6>& m) {
    const int f = detail::metric_in_sphere_filter(p, q, r, s, t, m);
    const int e = detail::metric_in_sphere_unfiltered(p, q, r, s, t, m);
    if (f != kUndecided) {
      EXPECT_EQ(f, e);
    }
    EXPECT_EQ(detail::metric_in_sphere(p, q, r, s, t, m), e);
    return f;
  };
  // Random points and random SPD metrics (AᵀA + I/10), also translated far from the origin (the
  // differences are then small against the coordinates: the filter's scaling).
  std::size_t decided = 0, total = 0;
  for (int k = 0; k < 20000; ++k) {
    double a[9];
    for (double& x : a) x = w(rng);
    const std::array<double, 6> m{a[0] * a[0] + a[3] * a[3] + a[6] * a[6] + 0.1, a[0] * a[1] + a[3] * a[4] + a[6] * a[7],
                                  a[0] * a[2] + a[3] * a[5] + a[6] * a[8],     a[1] * a[1] + a[4] * a[4] + a[7] * a[7] + 0.1,
                                  a[1] * a[2] + a[4] * a[5] + a[7] * a[8],     a[2] * a[2] + a[5] * a[5] + a[8] * a[8] + 0.1};
    const double offset = k % 2 ? 1000 : 0, size = k % 2 ? 1e-3 : 1;
    std::array<P, 5> p;
    for (P& x : p) x = {offset + size * u(rng), offset + size * u(rng), offset + size * u(rng)};
    if (detail::orientation3(p[0], p[1], p[2], p[3]) < 0) std::swap(p[2], p[3]);
    decided += check(p[0], p[1], p[2], p[3], p[4], m) != kUndecided;
    ++total;
  }
  EXPECT_GT(decided, total * 99 / 100);
  // Exactly cospherical: the corners of a box inscribed in an M-sphere (M = diag(4, 16, 64), the box
  // [0, 1/2] × [0, 1/4] × [0, 1/8], exact in binary), and the same perturbed by 2^-k, k = 50…70: a
  // decision there must be right, and from 2^-56 on (far below the bound) there must be none.
  const std::array<double, 6> diagonal{4, 0, 0, 16, 0, 64};
  const P c0{0, 0, 0}, c1{0.5, 0, 0}, c2{0, 0.25, 0}, c3{0, 0, 0.125}, corner{0.5, 0.25, 0.125};
  ASSERT_EQ(detail::orientation3(c0, c1, c2, c3), 1);
  EXPECT_EQ(detail::metric_in_sphere_unfiltered(c0, c1, c2, c3, corner, diagonal), 0);
  EXPECT_EQ(check(c0, c1, c2, c3, corner, diagonal), kUndecided);
  for (const P& t : {P{0.5, 0.25, 0}, P{0, 0.25, 0.125}, P{0.5, 0, 0.125}})
    EXPECT_EQ(check(c0, c1, c2, c3, t, diagonal), kUndecided);
  for (int k = 50; k <= 70; ++k)
    for (const P& direction : {P{1, 0, 0}, P{-1, 1, 0}, P{1, 1, 1}, P{0, 0, -1}}) {
      const double e = std::ldexp(1.0, -k);
      const P t{corner[0] + e * direction[0], corner[1] + e * direction[1], corner[2] + e * direction[2]};
      const int f = check(c0, c1, c2, c3, t, diagonal);
      if (k >= 56) {
        EXPECT_EQ(f, kUndecided) << "perturbation 2^-" << k;
      }
    }
  // Nearly cospherical under general metrics: five points c + F⁻¹v on the unit M-sphere (rounded), so
  // the determinant is rounding noise: every answer right, and nearly all deferred.
  std::size_t deferred = 0;
  for (int k = 0; k < 500; ++k) {
    const Metric3 m = metric3_from_sizes(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng),
                                         square_root({1 + u(rng), 0.3 * w(rng), 0.3 * w(rng), 1 + u(rng), 0.3 * w(rng), 1 + u(rng)}));
    const Matrix3 f = square_root(m);
    std::array<P, 5> p;
    for (P& x : p) {
      P v{w(rng), w(rng), w(rng)};
      const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      const P d = solve(f, {v[0] / n, v[1] / n, v[2] / n});
      x = {0.5 + d[0], 0.5 + d[1], 0.5 + d[2]};
    }
    if (detail::orientation3(p[0], p[1], p[2], p[3]) < 0) std::swap(p[2], p[3]);
    deferred += check(p[0], p[1], p[2], p[3], p[4], {m.xx, m.xy, m.xz, m.yy, m.yz, m.zz}) == kUndecided;
  }
  EXPECT_GT(deferred, 450u);
}

void expect_locally_delaunay(const StarMesh3Result& r);

/// The run stopped by itself (every star consistent) with a checked tetrahedralization of `domain`,
/// locally Delaunay in each vertex's metric, with the bounds the rules enforce in every star (thesis
/// §3.4): radius–edge ≤ ρ₀ and sliverity ≥ σ₀ in the metric of each vertex (no sliver counted),
/// distortion < γ₀ between the vertices of each tetrahedron, and above `least_distortion` (the field
/// does vary).
void expect_converged_with_the_thesis_bounds(const StarMesh3Result& r, const PolyhedralDomain& domain,
                                             const StarMesh3Options& options, double least_distortion) {
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(r.status, "converged");
  EXPECT_EQ(r.stats.last_sweep_inconsistent, 0u);
  EXPECT_EQ(check_tetrahedralization(r.mesh, domain), "");
  expect_locally_delaunay(r);
  const MeshQuality q = measure_quality(r.mesh, r.metrics, options.sliver_bound);
  EXPECT_LE(q.radius_edge.max, options.radius_edge_bound * (1 + 1e-9));
  EXPECT_GE(q.sliverity.min, options.sliver_bound * (1 - 1e-9));
  EXPECT_EQ(q.slivers, 0u);
  EXPECT_LT(q.distortion.max, options.distortion_bound);
  EXPECT_GT(q.distortion.max, least_distortion);
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
  const auto dir = laguerre::testing::scratch_folder() / "laguerre_star3_test";
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
  expect_converged_with_the_thesis_bounds(r, cube, options, 1.01);  // the metrics do differ between neighbours
}

TEST(StarMesher3, CurvedSphereShockLayerAcrossTheCubeConvergesChecked) {
  // The bench's sphere field (tools/bench/mesh3.sh): a shock layer around a sphere of radius 2 centred
  // below the cube, crossing it as a curved sheet, so the metrics rotate by ~0.2 rad per element (the
  // thesis's hypothesis; docs/star-mesher3.md). At the default γ₀ = 1.5 the run stops by itself with
  // every star consistent and a checked tetrahedralization, locally Delaunay in each vertex's metric,
  // with the bounds the rules enforce.
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  const auto field = parse_metric_field3("sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5");
  StarMesh3Options options;
  options.max_vertices = 4000;
  const StarMesh3Result r = mesh_with_stars(cube, *field, options);
  expect_converged_with_the_thesis_bounds(r, cube, options, 1.05);  // the metrics do rotate between neighbours
  // Both sides of the curved layer are meshed: vertices above and below the sheet near the centre.
  std::size_t above = 0, below = 0;
  for (const auto& p : r.mesh.points) {
    const double d = std::sqrt((p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] + 1.5) * (p[2] + 1.5));
    (d > 2 ? above : below) += 1;
  }
  EXPECT_GT(above, 100u);
  EXPECT_GT(below, 100u);
}

}  // namespace
}  // namespace laguerre::core
