// Refinement of the anisotropic Voronoi diagram (thesis Part II): the primitives against brute-force
// oracles, the priority of the rules, and the guarantees at termination (a triangulation of Ω with
// every constraint subsegment, every Voronoi vertex well shaped), determinism.
#include "laguerre/core/meshing/MeshQuality.hpp"
#include "laguerre/core/meshing/StarMesher.hpp"
#include "laguerre/core/meshing/VoronoiMesher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace laguerre::core {
namespace {

AnisotropicSite site(double x, double y, double h1, double h2, double theta) {
  const Metric m = metric_from_sizes(h1, h2, theta);
  return {x, y, m.a, m.b, m.c};
}

/// The guarantees of a converged run, checked independently of the mesher's own bookkeeping.
void expect_guarantees(const VoronoiMeshResult& r, const Domain& d, double shape_bound) {
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(check_triangulation(r.mesh, d), "");
  // Every constraint subsegment is an edge of a triangle (interior walls too, which
  // check_triangulation does not see).
  std::set<std::pair<std::size_t, std::size_t>> edges;
  for (const auto& t : r.mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::size_t u = t[static_cast<std::size_t>(k)], v = t[static_cast<std::size_t>((k + 1) % 3)];
      edges.insert({std::min(u, v), std::max(u, v)});
    }
  for (const auto& e : r.mesh.edges) EXPECT_TRUE(edges.count({std::min(e[0], e[1]), std::max(e[0], e[1])}));
  // Every constraint is covered by subsegments: their total length is the constraints' total length.
  double covered = 0, constraints = 0;
  for (const auto& e : r.mesh.edges)
    covered += std::hypot(r.mesh.points[e[1]][0] - r.mesh.points[e[0]][0], r.mesh.points[e[1]][1] - r.mesh.points[e[0]][1]);
  for (const auto& c : d.constraints()) constraints += std::hypot(c[1].x - c[0].x, c[1].y - c[0].y);
  EXPECT_NEAR(covered, constraints, 1e-9 * constraints);
  // β ≤ B at every triangle's Voronoi vertex, recomputed from the vertex: equidistant from the three
  // sites in their metrics, inside Ω.
  ASSERT_EQ(r.centres.size(), r.mesh.triangles.size());
  for (std::size_t i = 0; i < r.mesh.triangles.size(); ++i) {
    std::array<AnisotropicSite, 3> s;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t v = r.mesh.triangles[i][k];
      s[k] = {r.mesh.points[v][0], r.mesh.points[v][1], r.metrics[v].a, r.metrics[v].b, r.metrics[v].c};
    }
    const Point2 c = r.centres[i];
    const double d0 = anisotropic_distance(c, s[0]);
    EXPECT_NEAR(anisotropic_distance(c, s[1]), d0, 1e-6 * d0);
    EXPECT_NEAR(anisotropic_distance(c, s[2]), d0, 1e-6 * d0);
    if (d.locate(c) == DomainSide::outside) {  // allowed only on ∂Ω up to rounding (boundary_tolerance)
      double gap = INFINITY;
      for (const auto& [p, q] : d.constraints()) {
        const double ux = q.x - p.x, uy = q.y - p.y;
        const double t = std::clamp(((c.x - p.x) * ux + (c.y - p.y) * uy) / (ux * ux + uy * uy), 0.0, 1.0);
        gap = std::min(gap, std::hypot(c.x - p.x - t * ux, c.y - p.y - t * uy));
      }
      EXPECT_LT(gap, 1e-9) << "triangle " << i;
    }
    EXPECT_LE(radius_edge_ratio(s[0], s[1], s[2], c), shape_bound * (1 + 1e-12)) << "triangle " << i;
  }
}

/// Meshes `d` for the field `spec` with the default options but `size_bound` (0: rule 6 off) and checks
/// the guarantees.
VoronoiMeshResult mesh_checked(const Domain& d, const std::string& spec, double size_bound) {
  const auto field = parse_metric_field(spec);
  VoronoiMeshOptions o;
  o.size_bound = size_bound;
  VoronoiMeshResult r = mesh_with_voronoi(d, *field, o);
  expect_guarantees(r, d, o.shape_bound);
  return r;
}

// --- primitives ------------------------------------------------------------------------------------

TEST(VoronoiPrimitives, EncroachmentAgreesWithSampling) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1), size(0.05, 0.5), angle(0, M_PI);
  int encroached = 0, clear = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const AnisotropicSite a = site(u(rng), u(rng), size(rng), size(rng), angle(rng));
    const AnisotropicSite b = site(u(rng), u(rng), size(rng), size(rng), angle(rng));
    const AnisotropicSite p = site(u(rng), u(rng), size(rng), size(rng), angle(rng));
    // Oracle: the largest sampled min(d_a², d_b²) − d_p² over 20001 points of [a, b].
    double best = -INFINITY, scale = 0;
    for (int k = 0; k <= 20000; ++k) {
      const double t = k / 20000.0;
      const Point2 z{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
      const double m = std::min(anisotropic_distance(z, a), anisotropic_distance(z, b));
      best = std::max(best, m - anisotropic_distance(z, p));
      scale = std::max(scale, m);
    }
    const double margin = encroachment_margin(a, b, p)[0];
    EXPECT_GE(margin, best - 1e-12 * scale);                   // the exact maximum is at least the sampled one
    EXPECT_LE(margin, best + 1e-3 * scale);                    // and close to it
    if (std::abs(best) < 1e-3 * scale) continue;               // too close to call by sampling
    EXPECT_EQ(encroaches(a, b, p), best > 0) << "trial " << trial;
    (best > 0 ? encroached : clear)++;
  }
  EXPECT_GT(encroached, 40);
  EXPECT_GT(clear, 40);
}

TEST(VoronoiPrimitives, IsotropicEncroachmentIsTheDiametralDisc) {
  // Equal isotropic metrics: p encroaches iff it lies strictly inside the diametral circle.
  const AnisotropicSite a{0, 0, 1, 0, 1}, b{2, 0, 1, 0, 1};
  EXPECT_TRUE(encroaches(a, b, {1, 0.99, 1, 0, 1}));
  EXPECT_FALSE(encroaches(a, b, {1, 1.01, 1, 0, 1}));
  EXPECT_FALSE(encroaches(a, b, {1, 1, 1, 0, 1}));  // on the circle: touching only
  EXPECT_FALSE(encroaches(a, b, {3, 0.1, 1, 0, 1}));
}

TEST(VoronoiPrimitives, MidpointIsEquidistantInTheEndpointsMetrics) {
  const AnisotropicSite a = site(0.1, 0.2, 0.3, 0.05, 0.4), b = site(0.9, 0.7, 0.1, 0.1, 0);
  const double t = midpoint_parameter(a, b);
  ASSERT_GT(t, 0);
  ASSERT_LT(t, 1);
  const Point2 z{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
  EXPECT_NEAR(anisotropic_distance(z, a), anisotropic_distance(z, b), 1e-12 * anisotropic_distance(z, a));
}

TEST(VoronoiPrimitives, BreakpointLiesOnTheSegmentOutsideTheEndpointCells) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1), size(0.05, 0.5), angle(0, M_PI);
  int at_midpoint = 0, on_bisector = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const AnisotropicSite a = site(0, 0, size(rng), size(rng), angle(rng)), b = site(1, 0, size(rng), size(rng), angle(rng));
    std::vector<AnisotropicSite> others;
    for (int k = 0; k < 3; ++k) others.push_back(site(u(rng), u(rng) - 0.5, size(rng), size(rng), angle(rng)));
    bool any = false;
    for (const auto& s : others) any = any || encroaches(a, b, s);
    const auto t = breakpoint_parameter(a, b, others);
    ASSERT_EQ(t.has_value(), any);
    if (!t) {
      EXPECT_FALSE(breakpoint_parameter(a, b, {}).has_value());
      continue;
    }
    ASSERT_GE(*t, 0);
    ASSERT_LE(*t, 1);
    const Point2 z{*t, 0};
    const double da = anisotropic_distance(z, a), db = anisotropic_distance(z, b);
    double ds = INFINITY;
    for (const auto& s : others) ds = std::min(ds, anisotropic_distance(z, s));
    // In the closure of [a, b] \ (Vor(a) ∪ Vor(b)): some other site at most as close as a and b.
    EXPECT_LE(ds, std::min(da, db) * (1 + 1e-9)) << "trial " << trial;
    const double tm = midpoint_parameter(a, b);
    if (*t == tm) {
      ++at_midpoint;
      continue;
    }
    // Not at the midpoint: on the boundary of an encroaching cell (equidistant from s and a or b), and
    // no sampled point between it and the midpoint is outside Vor(a) ∪ Vor(b).
    EXPECT_NEAR(ds, std::min(da, db), 1e-9 * std::min(da, db));
    for (int k = 1; k < 200; ++k) {
      const double w = *t + (tm - *t) * k / 200.0;
      const Point2 y{w, 0};
      const double m = std::min(anisotropic_distance(y, a), anisotropic_distance(y, b));
      for (const auto& s : others) EXPECT_GE(anisotropic_distance(y, s), m * (1 - 1e-9)) << "trial " << trial;
    }
    ++on_bisector;
  }
  EXPECT_GT(at_midpoint, 5);
  EXPECT_GT(on_bisector, 5);
}

TEST(VoronoiPrimitives, RadiusEdgeRatioOfTheEquilateralTriangle) {
  const AnisotropicSite a{0, 0, 1, 0, 1}, b{1, 0, 1, 0, 1}, c{0.5, std::sqrt(3) / 2, 1, 0, 1};
  EXPECT_NEAR(radius_edge_ratio(a, b, c, {0.5, std::sqrt(3) / 6}), 1 / std::sqrt(3), 1e-12);
  // Unsquared distances: scaling the metric by 4 leaves the ratio unchanged.
  const AnisotropicSite a4{0, 0, 4, 0, 4}, b4{1, 0, 4, 0, 4}, c4{0.5, std::sqrt(3) / 2, 4, 0, 4};
  EXPECT_NEAR(radius_edge_ratio(a4, b4, c4, {0.5, std::sqrt(3) / 6}), 1 / std::sqrt(3), 1e-12);
}

// --- the rules -------------------------------------------------------------------------------------

TEST(VoronoiMesher, RulesFireInPriorityOrder) {
  // A site close to the bottom edge encroaches it (rule 1) while a Voronoi vertex is badly shaped (rule
  // 3): the first round must split the edge, and no round may apply a rule while an earlier one has
  // requests.
  const Domain d = Domain::unit_square();
  const auto field = parse_metric_field("uniform:0.3:0.3");
  VoronoiMeshOptions o;
  o.extra_sites = {{0.5, 0.05}, {0.3, 0.3}, {0.6, 0.3}};
  std::vector<VoronoiRound> rounds;
  o.on_round = [&](const VoronoiRound& r) { rounds.push_back(r); };
  const VoronoiMeshResult r = mesh_with_voronoi(d, *field, o);
  expect_guarantees(r, d, o.shape_bound);
  ASSERT_FALSE(rounds.empty());
  EXPECT_EQ(rounds[0].rule, 1);
  EXPECT_GT(rounds[0].requests[3], 0u);
  std::set<int> applied;
  for (const VoronoiRound& k : rounds) {
    int first = 0;
    for (int i = 6; i >= 1; --i)
      if (k.requests[static_cast<std::size_t>(i)] > 0) first = i;
    EXPECT_EQ(k.rule, first) << "round " << k.round;
    if (k.rule) applied.insert(k.rule);
  }
  EXPECT_TRUE(applied.count(1));
  EXPECT_TRUE(applied.count(3));
  EXPECT_GT(r.stats.redirected, 0u);  // some rule-3 vertices encroached and became breakpoints
  EXPECT_EQ(rounds.back().rule, 0);
  EXPECT_EQ(r.stats.rounds, rounds.size());
}

TEST(VoronoiMesher, WallWithAFreeEndpoint) {
  // The L-shaped domain with a wall of scenarios/domains/l-shape-with-wall.txt, the wall's free endpoint
  // (0.6, 1.5) where the thesis field changes its axes (the configuration of rule 2, thesis Fig. 2.6).
  // Pure thesis rules (no size rule): the wall is in the mesh, split into edges.
  const Domain d({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {}, {{Point2{0, 1.5}, Point2{0.6, 1.5}}});
  const auto field = parse_metric_field("thesis:0.2:4:0.2:1.5");
  VoronoiMeshOptions o;
  const VoronoiMeshResult r = mesh_with_voronoi(d, *field, o);
  expect_guarantees(r, d, o.shape_bound);
}

// --- meshes ----------------------------------------------------------------------------------------

TEST(VoronoiMesher, IsotropicSquare) {
  const VoronoiMeshResult r = mesh_checked(Domain::unit_square(), "uniform:0.1:0.1", 1);
  EXPECT_GT(r.mesh.points.size(), 40u);
  // β ≤ 1 in an isotropic metric is a smallest angle of at least 30°.
  const MeshQuality q = measure_quality(r.mesh, r.metrics);
  EXPECT_GE(q.smallest_angle.min, 30 - 1e-6);
}

TEST(VoronoiMesher, AnisotropicSquare) {
  const VoronoiMeshResult r = mesh_checked(Domain::unit_square(), "uniform:0.2:0.04:0", 1);
  const MeshQuality q = measure_quality(r.mesh, r.metrics);
  EXPECT_GE(q.smallest_angle.min, 30 - 1e-6);  // one metric: the isotropic case after a linear map
}

TEST(VoronoiMesher, SquareWithHole) {
  const Domain d({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}}});
  mesh_checked(d, "uniform:0.15:0.05:0", 1);
}

TEST(VoronoiMesher, ThesisField) {
  const Domain d = Domain::unit_square();
  const VoronoiMeshResult pure = mesh_checked(d, "thesis:0.15:4:0.2:0.5", 0);  // rules 1–5 only
  const VoronoiMeshResult sized = mesh_checked(d, "thesis:0.15:4:0.2:0.5", 1);
  EXPECT_GT(sized.stats.size, 0u);
  EXPECT_GT(sized.mesh.points.size(), 2 * pure.mesh.points.size());
}

TEST(VoronoiMesher, SharpHoleCornersUseShells) {
  // A hole with a 20° corner: without shells the breakpoints of its two sides cascade into the corner.
  const Domain d({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.3, 0.4}, {0.7, 0.4}, {0.3, 0.4 + 0.4 * std::tan(20 * M_PI / 180)}}});
  const auto field = parse_metric_field("uniform:0.1:0.1");
  VoronoiMeshOptions o;
  o.size_bound = 1;
  const VoronoiMeshResult r = mesh_with_voronoi(d, *field, o);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(check_triangulation(r.mesh, d), "");
  // β ≤ B except at the triangle(s) at the 20° corner (0.7, 0.4).
  for (std::size_t i = 0; i < r.mesh.triangles.size(); ++i) {
    if (r.shape[i] <= o.shape_bound) continue;
    bool at_corner = false;
    for (std::size_t v : r.mesh.triangles[i]) at_corner = at_corner || (r.mesh.points[v][0] == 0.7 && r.mesh.points[v][1] == 0.4);
    EXPECT_TRUE(at_corner) << "triangle " << i << " β = " << r.shape[i];
  }
  o.corner_shells = false;
  o.max_vertices = 400;
  EXPECT_FALSE(mesh_with_voronoi(d, *field, o).converged());
}

TEST(VoronoiMesher, Deterministic) {
  const Domain d = Domain::unit_square();
  const auto field = parse_metric_field("thesis:0.15:4:0.2:0.5");
  VoronoiMeshOptions o;
  o.size_bound = 2;
  const auto a = mesh_with_voronoi(d, *field, o), b = mesh_with_voronoi(d, *field, o);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.stats.rounds, b.stats.rounds);
}

TEST(VoronoiMesher, UpdatedDiagramGivesTheRebuiltMesh) {
  // The diagram kept across rounds (the default) against the whole diagram rebuilt every round: the
  // same mesh bit for bit, and the same rounds. Isotropic (degenerate, cocircular sites), anisotropic,
  // a hole with a sharp corner (shells), the L shape with its wall.
  struct Case {
    Domain domain;
    std::string field;
    double size_bound;
  };
  const std::vector<Case> cases = {
      {Domain::unit_square(), "uniform:0.2:0.2", 1},
      {Domain::unit_square(), "thesis:0.15:4:0.2:0.5", 2},
      {Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.3, 0.4}, {0.7, 0.4}, {0.3, 0.4 + 0.4 * std::tan(20 * M_PI / 180)}}}),
       "uniform:0.15:0.1:0.3", 1},
      {Domain({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {}, {{Point2{0, 1.5}, Point2{0.6, 1.5}}}),
       "thesis:0.2:4:0.2:1.5", 0},
  };
  for (const Case& c : cases) {
    const auto field = parse_metric_field(c.field);
    VoronoiMeshOptions o;
    o.size_bound = c.size_bound;
    const VoronoiMeshResult updated = mesh_with_voronoi(c.domain, *field, o);
    o.rebuild_diagram = true;
    const VoronoiMeshResult rebuilt = mesh_with_voronoi(c.domain, *field, o);
    EXPECT_GT(updated.mesh.points.size(), 20u) << c.field;
    EXPECT_EQ(updated.status, rebuilt.status) << c.field;
    EXPECT_EQ(updated.message, rebuilt.message) << c.field;
    EXPECT_EQ(updated.mesh.points, rebuilt.mesh.points) << c.field;
    EXPECT_EQ(updated.mesh.triangles, rebuilt.mesh.triangles) << c.field;
    EXPECT_EQ(updated.mesh.edges, rebuilt.mesh.edges) << c.field;
    EXPECT_EQ(updated.shape, rebuilt.shape) << c.field;
    ASSERT_EQ(updated.centres.size(), rebuilt.centres.size()) << c.field;
    for (std::size_t i = 0; i < updated.centres.size(); ++i) {
      EXPECT_EQ(updated.centres[i].x, rebuilt.centres[i].x) << c.field;
      EXPECT_EQ(updated.centres[i].y, rebuilt.centres[i].y) << c.field;
    }
    EXPECT_EQ(updated.stats.rounds, rebuilt.stats.rounds) << c.field;
    EXPECT_EQ(updated.stats.bad_shape, rebuilt.stats.bad_shape) << c.field;
    EXPECT_EQ(updated.stats.redirected, rebuilt.stats.redirected) << c.field;
  }
}

TEST(VoronoiMesher, StopsAtTheCap) {
  const auto field = parse_metric_field("uniform:0.05:0.05");
  VoronoiMeshOptions o;
  o.size_bound = 1;
  o.max_vertices = 60;
  const VoronoiMeshResult r = mesh_with_voronoi(Domain::unit_square(), *field, o);
  EXPECT_EQ(r.status, VoronoiMeshStatus::max_vertices);
  EXPECT_LE(r.mesh.points.size(), 60u);
  EXPECT_NE(r.message.find("max_vertices"), std::string::npos);
}

}  // namespace
}  // namespace laguerre::core
