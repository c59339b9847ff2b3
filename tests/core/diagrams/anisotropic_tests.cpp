// Anisotropic (flower power) diagrams: conic intersections, the regular complex in R⁵ against brute
// force over all triples, the raster oracle, and the reduction M_i = λ_i·I to the Möbius diagram.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"
#include "laguerre/core/diagrams/MinimizationDiagram.hpp"
#include "laguerre/core/diagrams/MobiusDiagram.hpp"
#include "../../support/Scratch.hpp"

namespace laguerre::core {
namespace {

/// Random sites in the unit square with metrics of eigenvalues in [1, ratio] and random axes.
std::vector<AnisotropicSite> random_sites(unsigned seed, std::size_t n, double ratio) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), e(1, ratio), angle(0, 3.14159);
  std::vector<AnisotropicSite> s;
  for (std::size_t i = 0; i < n; ++i) {
    const double l1 = e(rng), l2 = e(rng), t = angle(rng), c = std::cos(t), sn = std::sin(t);
    s.push_back({u(rng), u(rng), l1 * c * c + l2 * sn * sn, (l1 - l2) * c * sn, l1 * sn * sn + l2 * c * c});
  }
  return s;
}

TEST(Anisotropic, ConicIntersectionKnownAnswer) {
  // Unit circle ∩ the two diagonals x² − y² = 0: four points (±1/√2, ±1/√2).
  const auto pts = intersect_conics({1, 0, 1, 0, 0, -1}, {1, 0, -1, 0, 0, 0});
  ASSERT_EQ(pts.size(), 4u);
  for (Point2 p : pts) {
    EXPECT_NEAR(std::abs(p.x), std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(std::abs(p.y), std::sqrt(0.5), 1e-12);
  }
  // Two ellipses crossing in four points, far from the origin (conditioning by centre and scale).
  const Conic e1{1, 0, 4, -2000, -8000, 1000000 + 4000000 - 4}, e2{4, 0, 1, -8000, -2000, 4000000 + 1000000 - 4};
  const auto far = intersect_conics(e1, e2, {1000, 1000}, 2);
  ASSERT_EQ(far.size(), 4u);
  for (Point2 p : far) {
    EXPECT_NEAR(std::abs(p.x - 1000), std::sqrt(0.8), 1e-9);
    EXPECT_NEAR(std::abs(p.y - 1000), std::sqrt(0.8), 1e-9);
  }
  // Disjoint circles: nothing; the same circle twice: nothing (a common component).
  EXPECT_TRUE(intersect_conics({1, 0, 1, 0, 0, -1}, {1, 0, 1, -10, 0, 24}).empty());
  EXPECT_TRUE(intersect_conics({1, 0, 1, 0, 0, -1}, {2, 0, 2, 0, 0, -2}).empty());
}

TEST(Anisotropic, NearlyLinearBisectorsOfAlmostEqualMetrics) {
  // Sites whose metrics differ by ~1e-11 relatively (a field that is constant up to rounding, as the
  // shock layer far from its line): the bisectors are lines up to a tiny quadratic part. Their bounded
  // intersection must be found, and accurately (found by the meshing of thesis Part II).
  const double eps = 1e-9;
  const AnisotropicSite a{1.09375, 1, 100 + 3 * eps, 0, 100}, b{1.078125, 1, 100 + 1 * eps, 0, 100},
      c{1.072509, 0.942038, 100 + 7 * eps, 0, 100}, d{1.2, 0.9, 100 + 2 * eps, 0, 100 + eps};
  for (const auto& [p, q, r] : {std::array{a, b, c}, std::array{a, c, d}, std::array{b, c, d}}) {
    const Point2 centre{(p.x + q.x + r.x) / 3, (p.y + q.y + r.y) / 3};
    double scale = 0;
    for (const AnisotropicSite* s : {&p, &q, &r}) scale = std::max(scale, std::hypot(s->x - centre.x, s->y - centre.y));
    const auto pts = intersect_conics(bisector_conic(p, q), bisector_conic(q, r), centre, scale);
    // The circumcentre of the three points (the metrics are 100·I up to 1e-11).
    const double ax = p.x, ay = p.y, bx = q.x, by = q.y, cx = r.x, cy = r.y;
    const double den = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
    const Point2 o{((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / den,
                   ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / den};
    bool near = false;
    for (Point2 x : pts) near = near || std::hypot(x.x - o.x, x.y - o.y) < 1e-7;
    EXPECT_TRUE(near) << pts.size() << " points, expected one near (" << o.x << ", " << o.y << ")";
  }
}

TEST(Anisotropic, RegularComplexFindsEveryVertexOfBruteForce) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const auto sites = random_sites(seed, 14 + seed, seed % 2 ? 4.0 : 16.0);
    const AnisotropicDiagram fast = anisotropic_diagram(sites), slow = anisotropic_diagram(sites, {true, 1e-9});
    EXPECT_EQ(fast.lifted_dimension, 5);
    EXPECT_LT(fast.candidate_triangles, slow.candidate_triangles);
    ASSERT_EQ(fast.vertices.size(), slow.vertices.size()) << "seed " << seed;
    for (std::size_t i = 0; i < fast.vertices.size(); ++i) {
      EXPECT_EQ(fast.vertices[i].sites, slow.vertices[i].sites) << "seed " << seed;
      EXPECT_NEAR(fast.vertices[i].position.x, slow.vertices[i].position.x, 1e-9);
      EXPECT_NEAR(fast.vertices[i].position.y, slow.vertices[i].position.y, 1e-9);
    }
    EXPECT_GT(fast.vertices.size(), sites.size());  // about 2n for a diagram of the plane
    // Every vertex: its three sites equidistant and no site closer (brute force).
    for (const AnisotropicVertex& v : fast.vertices) {
      for (SiteIndex s : v.sites) EXPECT_NEAR(anisotropic_distance(v.position, sites[s]), v.distance, 1e-8 * (1 + v.distance));
      for (const auto& s : sites) EXPECT_GE(anisotropic_distance(v.position, s), v.distance * (1 - 1e-8));
    }
  }
}

/// Field-for-field equality of two diagrams, doubles compared exactly.
void expect_same_diagram(const AnisotropicDiagram& a, const AnisotropicDiagram& b, const std::string& what) {
  EXPECT_EQ(a.hidden, b.hidden) << what;
  EXPECT_EQ(a.lifted_dimension, b.lifted_dimension) << what;
  EXPECT_EQ(a.candidate_triangles, b.candidate_triangles) << what;
  EXPECT_EQ(a.dual_triangles, b.dual_triangles) << what;
  EXPECT_EQ(a.dual_edges, b.dual_edges) << what;
  ASSERT_EQ(a.vertices.size(), b.vertices.size()) << what;
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    EXPECT_EQ(a.vertices[i].sites, b.vertices[i].sites) << what << ", vertex " << i;
    EXPECT_EQ(a.vertices[i].position.x, b.vertices[i].position.x) << what << ", vertex " << i;
    EXPECT_EQ(a.vertices[i].position.y, b.vertices[i].position.y) << what << ", vertex " << i;
    EXPECT_EQ(a.vertices[i].distance, b.vertices[i].distance) << what << ", vertex " << i;
  }
}

TEST(Anisotropic, UpdaterEqualsTheRebuiltDiagramAfterEveryBatch) {
  // Random metrics (lifted dimension 5), one isotropic metric on a grid (lifted dimension 2, every grid
  // square cocircular: the degenerate case CGAL's perturbation decides), and repeated sites.
  std::vector<std::pair<std::string, std::vector<AnisotropicSite>>> inputs;
  inputs.push_back({"random", random_sites(7, 120, 9.0)});
  std::vector<AnisotropicSite> grid;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) grid.push_back({(i * 5 % 9) / 8.0, (j * 7 % 9) / 8.0, 4, 0, 4});
  inputs.push_back({"grid", grid});
  std::vector<AnisotropicSite> repeated = random_sites(8, 40, 4.0);
  for (std::size_t i = 0; i < 40; i += 3) repeated.push_back(repeated[i]);
  inputs.push_back({"repeated", repeated});
  for (const auto& [name, sites] : inputs) {
    AnisotropicDiagramUpdater updater;
    std::size_t done = 0;
    for (std::size_t batch = 1; done < sites.size(); batch = batch * 2 % 13 + 1) {
      const std::size_t end = std::min(sites.size(), done + batch);
      updater.add({sites.begin() + static_cast<std::ptrdiff_t>(done), sites.begin() + static_cast<std::ptrdiff_t>(end)});
      done = end;
      const std::vector<AnisotropicSite> prefix(sites.begin(), sites.begin() + static_cast<std::ptrdiff_t>(done));
      expect_same_diagram(updater.diagram(), anisotropic_diagram(prefix), name + " after " + std::to_string(done) + " sites");
      EXPECT_TRUE(updater.diagram().is_valid(true)) << name;
    }
  }
}

TEST(Anisotropic, UpdaterRecomputesOnlyAroundTheNewSite) {
  const auto sites = random_sites(9, 301, 4.0);
  AnisotropicDiagramUpdater updater;
  updater.add({sites.begin(), sites.end() - 1});
  EXPECT_EQ(updater.intersected_triangles(), updater.diagram().candidate_triangles);  // the first add: all
  EXPECT_EQ(updater.filtered_triangles(), updater.diagram().candidate_triangles);
  updater.add({sites.back()});
  // The new triangles all have the new site; the filtered ones a site of its star.
  EXPECT_GT(updater.intersected_triangles(), 0u);
  EXPECT_LT(updater.intersected_triangles() * 10, updater.diagram().candidate_triangles);
  EXPECT_LE(updater.intersected_triangles(), updater.filtered_triangles());
  EXPECT_LT(updater.filtered_triangles(), updater.diagram().candidate_triangles);
  expect_same_diagram(updater.diagram(), anisotropic_diagram(sites), "one more site");
  // Bad input is refused before anything changes.
  EXPECT_THROW(updater.add({{0.5, 0.5, 1, 2, 1}}), InputError);
  EXPECT_EQ(updater.diagram().sites.size(), sites.size());
  EXPECT_THROW(AnisotropicDiagramUpdater({true, 1e-9}), InputError);
}

TEST(Anisotropic, AgreesWithRasterOracle) {
  const auto sites = random_sites(21, 30, 6.0);
  const AnisotropicDiagram d = anisotropic_diagram(sites);
  const Box box{0, 0, 1, 1};
  const int res = 400;
  const MinimizationDiagram raster(box, res, res, sites.size(),
                                   [&](SiteIndex i, Point2 x) { return anisotropic_distance(x, sites[i]); });
  const double step = box.width() / res;
  // (i) Every 2×2 block of pixels with three labels has a vertex of those labels within 6 pixels (edges
  // may meet at a small angle, so the three labels can stay adjacent a few pixels away from it).
  std::size_t blocks = 0;
  for (int row = 0; row + 1 < res; ++row)
    for (int col = 0; col + 1 < res; ++col) {
      std::set<SiteIndex> labels{raster.label(col, row), raster.label(col + 1, row), raster.label(col, row + 1),
                                 raster.label(col + 1, row + 1)};
      if (labels.size() != 3) continue;
      ++blocks;
      const std::array<SiteIndex, 3> t{*labels.begin(), *std::next(labels.begin()), *labels.rbegin()};
      const Point2 c{raster.pixel_centre(col, row).x + step / 2, raster.pixel_centre(col, row).y - step / 2};
      bool found = false;
      for (const AnisotropicVertex& v : d.vertices)
        found = found || (v.sites == t && std::hypot(v.position.x - c.x, v.position.y - c.y) < 6 * step);
      EXPECT_TRUE(found) << "no vertex " << t[0] << " " << t[1] << " " << t[2] << " near " << c.x << " " << c.y;
    }
  EXPECT_GT(blocks, 20u);
  // (ii) Every vertex well inside the box shows its three labels in the 7×7 pixels around it.
  std::size_t inside = 0;
  for (const AnisotropicVertex& v : d.vertices) {
    if (!box.expanded(-6 * step).contains(v.position)) continue;
    ++inside;
    const int col = static_cast<int>((v.position.x - box.xmin) / step), row = static_cast<int>((box.ymax - v.position.y) / step);
    std::set<SiteIndex> seen;
    for (int dr = -3; dr <= 3; ++dr)
      for (int dc = -3; dc <= 3; ++dc) seen.insert(raster.label(col + dc, row + dr));
    for (SiteIndex s : v.sites) EXPECT_EQ(seen.count(s), 1u) << "vertex at " << v.position.x << " " << v.position.y;
  }
  EXPECT_GT(inside, 20u);
  // (iii) Labels of neighbouring pixels clearly away from a third cell (third smallest distance above
  // the smallest by more than twice the variation of d over a pixel step: |∇d| ≤ 2·6·√2 < 17.5 here)
  // are the two ends of a dual edge (every edge of this diagram ends at a vertex).
  const std::set<std::pair<SiteIndex, SiteIndex>> dual(d.dual_edges.begin(), d.dual_edges.end());
  auto third_gap = [&](Point2 q) {
    std::vector<double> v;
    for (const auto& s : sites) v.push_back(anisotropic_distance(q, s));
    std::partial_sort(v.begin(), v.begin() + 3, v.end());
    return v[2] - v[0];
  };
  std::size_t pairs = 0;
  for (int row = 0; row < res; ++row)
    for (int col = 0; col + 1 < res; ++col) {
      const SiteIndex l = raster.label(col, row), r = raster.label(col + 1, row);
      if (l == r || third_gap(raster.pixel_centre(col, row)) < 35 * step || third_gap(raster.pixel_centre(col + 1, row)) < 35 * step)
        continue;
      ++pairs;
      EXPECT_EQ(dual.count(std::minmax(l, r)), 1u) << l << " " << r;
    }
  EXPECT_GT(pairs, 50u);
  // The sampled edges lie on their bisectors, and the restriction keeps the vertices inside the box.
  const RestrictedAnisotropicDiagram r = restrict_anisotropic(d, box.corners(), 128);
  EXPECT_EQ(r.vertices.size(), static_cast<std::size_t>(std::count_if(d.vertices.begin(), d.vertices.end(), [&](const AnisotropicVertex& v) { return box.contains(v.position); })));
  std::size_t points = 0;
  for (const SampledEdge& e : r.edges)
    for (const auto& line : e.polylines)
      for (Point2 x : line) {
        const double da = anisotropic_distance(x, sites[e.a]), db = anisotropic_distance(x, sites[e.b]);
        EXPECT_NEAR(da, db, 1e-6 * (1 + da));
        ++points;
      }
  EXPECT_GT(points, 200u);
}

TEST(Anisotropic, ScalarMetricsGiveTheMobiusDiagram) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1), lam(1, 3);
  std::vector<AnisotropicSite> sites;
  std::vector<MobiusSite> mobius;
  for (int i = 0; i < 25; ++i) {
    const double x = u(rng), y = u(rng), l = lam(rng);
    sites.push_back({x, y, l, 0, l});
    mobius.push_back({x, y, l, 0});
  }
  const AnisotropicDiagram d = anisotropic_diagram(sites);
  EXPECT_LE(d.lifted_dimension, 3);  // the lifted centres span a 3-flat
  const MobiusDiagram m(mobius, {-1, -1, 2, 2});
  std::multiset<std::array<SiteIndex, 3>> a, b;
  for (const auto& v : d.vertices) a.insert(v.sites);
  for (const auto& v : m.vertices()) b.insert(v.sites);
  EXPECT_EQ(a, b);
  for (const auto& v : d.vertices) {
    double best = 1e300;
    for (const auto& w : m.vertices())
      if (w.sites == v.sites) best = std::min(best, std::hypot(w.point.x - v.position.x, w.point.y - v.position.y));
    EXPECT_LT(best, 1e-7);
  }
}

TEST(Anisotropic, DegenerateInputs) {
  // Equal metrics: the Euclidean Voronoi diagram (lifted dimension 2); a square's four cocircular
  // sites give the centre for each of the triangles that carry it.
  const AnisotropicDiagram sq = anisotropic_diagram({{0, 0, 1, 0, 1}, {1, 0, 1, 0, 1}, {1, 1, 1, 0, 1}, {0, 1, 1, 0, 1}});
  EXPECT_EQ(sq.lifted_dimension, 2);
  ASSERT_FALSE(sq.vertices.empty());
  for (const auto& v : sq.vertices) {
    EXPECT_NEAR(v.position.x, 0.5, 1e-12);
    EXPECT_NEAR(v.position.y, 0.5, 1e-12);
  }
  // Duplicates are hidden; non-positive-definite metrics are rejected.
  const AnisotropicDiagram dup = anisotropic_diagram({{0, 0, 1, 0, 2}, {0, 0, 1, 0, 2}, {1, 0, 1, 0, 1}, {0, 1, 3, 1, 1}});
  EXPECT_EQ(dup.hidden, (std::vector<SiteIndex>{1}));
  EXPECT_THROW(anisotropic_diagram({{0, 0, 1, 2, 1}}), InputError);
}

TEST(Anisotropic, ReaderReportsFileAndLine) {
  const std::string path = laguerre::testing::scratch_path("anisotropic-bad.txt");
  std::ofstream(path) << "# x y a b c\n0 0 1 0 1\n\n1 1 1 2 1\n";
  try {
    read_anisotropic_sites(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":4:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("positive definite"), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), 4u);
  }
}

TEST(Anisotropic, IsValidDetectsBrokenInvariants) {
  const auto sites = read_anisotropic_sites(std::string(LAGUERRE_TEST_DATA) + "/../../tools/examples/diagrams/anisotropic-flowers.txt");
  const AnisotropicDiagram good = anisotropic_diagram(sites);
  ASSERT_TRUE(good.is_valid(true));
  ASSERT_FALSE(good.vertices.empty());
  AnisotropicDiagram moved = good;  // a vertex off its bisectors
  moved.vertices[0].position.x += 0.01;
  EXPECT_FALSE(moved.is_valid());
  AnisotropicDiagram closer = good;  // a vertex claiming a distance smaller than its sites'
  closer.vertices[0].distance *= 0.5;
  EXPECT_FALSE(closer.is_valid());
  AnisotropicDiagram extra = good;  // a dual triangle that carries no vertex
  extra.dual_triangles.push_back({sites.size() + 0, sites.size() + 1, sites.size() + 2});
  EXPECT_FALSE(extra.is_valid());
  AnisotropicDiagram edges = good;  // dual edges that are not the triangles' sides
  edges.dual_edges.pop_back();
  EXPECT_FALSE(edges.is_valid());
  AnisotropicDiagram hidden = good;  // a site hidden without being a duplicate
  hidden.hidden = {0};
  EXPECT_FALSE(hidden.is_valid());
  // A duplicate is hidden, and the diagram is still valid.
  std::vector<AnisotropicSite> twice = sites;
  twice.push_back(sites[3]);
  const AnisotropicDiagram dup = anisotropic_diagram(twice);
  EXPECT_EQ(dup.hidden, (std::vector<SiteIndex>{sites.size()}));
  EXPECT_TRUE(dup.is_valid(true));
}

TEST(Anisotropic, BundledExamples) {
  for (const char* name : {"anisotropic-flowers.txt", "anisotropic-random-100.txt"}) {
    const auto sites = read_anisotropic_sites(std::string(LAGUERRE_TEST_DATA) + "/../../tools/examples/diagrams/" + name);
    ASSERT_GE(sites.size(), 12u) << name;
    const AnisotropicDiagram d = anisotropic_diagram(sites);
    EXPECT_FALSE(d.vertices.empty()) << name;
    for (const AnisotropicVertex& v : d.vertices) {
      const SiteIndex nearest = anisotropic_nearest(sites, v.position);
      EXPECT_NEAR(anisotropic_distance(v.position, sites[nearest]), v.distance, 1e-8 * (1 + v.distance)) << name;
    }
  }
}

}  // namespace
}  // namespace laguerre::core
