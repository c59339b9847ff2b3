// Voronoi and power diagrams against the raster oracle, plus known answers and degenerate inputs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "laguerre/core/diagrams/MinimizationDiagram.hpp"
#include "laguerre/core/diagrams/PowerDiagram.hpp"
#include "laguerre/core/diagrams/VoronoiDiagram.hpp"

using namespace laguerre::core;

namespace {

std::vector<WeightedPoint> random_weighted(std::size_t n, unsigned seed, double wmax) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 10), w(0, wmax);
  std::vector<WeightedPoint> s(n);
  for (auto& p : s) p = {u(rng), u(rng), w(rng)};
  return s;
}

bool in_convex(const Polygon& poly, Point2 q) {
  if (poly.size() < 3) return false;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point2 a = poly[k], b = poly[(k + 1) % poly.size()];
    if ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x) < 0) return false;
  }
  return true;
}

// Every pixel clearly inside one oracle cell (margin > tol) is located in that site, and lies in that
// site's clipped cell polygon.
template <class Diagram, class Distance>
void check_against_oracle(const Diagram& d, std::size_t n, const Distance& dist, double tol) {
  const MinimizationDiagram oracle(d.box(), 120, 120, n, dist);
  int checked = 0;
  for (int row = 0; row < oracle.height(); ++row)
    for (int col = 0; col < oracle.width(); ++col) {
      if (oracle.margin(col, row) <= tol) continue;
      const Point2 x = oracle.pixel_centre(col, row);
      const SiteIndex s = oracle.label(col, row);
      ASSERT_EQ(d.locate(x), s) << "at " << x.x << ", " << x.y;
      ASSERT_TRUE(in_convex(d.cell(s), x)) << "pixel not in the cell of " << s;
      ++checked;
    }
  EXPECT_GT(checked, 120 * 120 * 9 / 10);
}

}  // namespace

TEST(PowerDiagram, AgreesWithTheRasterOracle) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto sites = random_weighted(60, seed, 4.0);
    const PowerDiagram d(sites, {-1, -1, 11, 11});
    ASSERT_TRUE(d.is_valid(true));
    check_against_oracle(d, sites.size(), [&](SiteIndex i, Point2 x) { return power_distance(x, sites[i]); }, 1e-6);
    // Hidden sites label no pixel of a dense raster, and only hidden sites have empty cells in the box.
    for (SiteIndex i : d.hidden_sites()) EXPECT_TRUE(d.cell(i).empty());
  }
}

TEST(PowerDiagram, HiddenSiteIsReported) {
  // A small circle well inside the power cell of a big one is hidden.
  const PowerDiagram d({{0, 0, 100}, {1, 0, 0.1}, {20, 0, 1}}, {-30, -30, 30, 30});
  EXPECT_EQ(d.hidden_sites(), (std::vector<SiteIndex>{1}));
  EXPECT_TRUE(d.cell(1).empty());
  EXPECT_EQ(d.locate({1, 0}), 0u);
  EXPECT_TRUE(d.is_valid(true));
}

TEST(PowerDiagram, TwoSitesKnownRadicalAxis) {
  // pow_0 = pow_1  ⇔  x² − 4 = (x − 4)² − 0  ⇔  x = 2.5 (y free).
  const PowerDiagram d({{0, 0, 4}, {4, 0, 0}}, {-10, -10, 10, 10});
  ASSERT_EQ(d.edges().size(), 1u);
  EXPECT_NEAR(d.edges()[0].p.x, 2.5, 1e-12);
  EXPECT_NEAR(d.edges()[0].q.x, 2.5, 1e-12);
  EXPECT_NEAR(std::fabs(d.edges()[0].p.y - d.edges()[0].q.y), 20, 1e-12);
  EXPECT_NEAR(signed_area(d.cell(0)), 12.5 * 20, 1e-9);
  EXPECT_EQ(d.dimension(), 1);
  EXPECT_TRUE(d.vertices().empty());
}

TEST(PowerDiagram, ZeroWeightsGiveTheVoronoiDiagram) {
  const auto w = random_weighted(80, 7, 0.0);
  std::vector<Point2> p;
  for (const auto& s : w) p.push_back({s.x, s.y});
  const PowerDiagram pd(w, {0, 0, 10, 10});
  const VoronoiDiagram vd(p, {0, 0, 10, 10});
  EXPECT_EQ(pd.dual_edges(), vd.dual_edges());
  for (SiteIndex i = 0; i < p.size(); ++i) EXPECT_NEAR(signed_area(pd.cell(i)), signed_area(vd.cell(i)), 1e-9);
}

TEST(VoronoiDiagram, AgreesWithTheRasterOracle) {
  const auto w = random_weighted(100, 11, 0.0);
  std::vector<Point2> p;
  for (const auto& s : w) p.push_back({s.x, s.y});
  const VoronoiDiagram d(p, {-2, -2, 12, 12});
  ASSERT_TRUE(d.is_valid(true));
  check_against_oracle(d, p.size(), [&](SiteIndex i, Point2 x) { return squared_distance(x, p[i]); }, 1e-9);
  // Euler for a triangulation of n points: edges − triangles = n − 1.
  const std::size_t n = p.size(), t = d.vertices().size(), e = d.dual_edges().size();
  EXPECT_EQ(e - t, n - 1);
}

TEST(VoronoiDiagram, CocircularSquare) {
  // Four cocircular points: the Delaunay triangulation picks one diagonal; the two Voronoi vertices
  // coincide at the centre and the diagonal's dual edge has length zero (so it is not in edges()).
  const VoronoiDiagram d({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {-1, -1, 2, 2});
  EXPECT_EQ(d.dual_edges().size(), 5u);
  EXPECT_EQ(d.vertices().size(), 2u);
  for (const auto& v : d.vertices()) {
    EXPECT_NEAR(v.point.x, 0.5, 1e-12);
    EXPECT_NEAR(v.point.y, 0.5, 1e-12);
  }
  EXPECT_EQ(d.edges().size(), 4u);
  for (SiteIndex i = 0; i < 4; ++i) EXPECT_NEAR(signed_area(d.cell(i)), 9.0 / 4, 1e-12);
  EXPECT_TRUE(d.is_valid(true));
}

TEST(VoronoiDiagram, CollinearAndDuplicatePoints) {
  const VoronoiDiagram d({{0, 0}, {1, 0}, {2, 0}, {1, 0}}, {-1, -1, 3, 1});
  EXPECT_EQ(d.dimension(), 1);
  EXPECT_EQ(d.hidden_sites().size(), 1u);
  EXPECT_EQ(d.dual_edges().size(), 2u);
  EXPECT_TRUE(d.vertices().empty());
  // Strips of widths 1.5, 1, 1.5 (the box is [−1, 3] × [−1, 1]).
  const SiteIndex kept = d.is_hidden(1) ? 3 : 1;
  EXPECT_NEAR(signed_area(d.cell(0)), 3.0, 1e-12);
  EXPECT_NEAR(signed_area(d.cell(kept)), 2.0, 1e-12);
  EXPECT_NEAR(signed_area(d.cell(2)), 3.0, 1e-12);
  EXPECT_TRUE(d.is_valid(true));
}

TEST(VoronoiDiagram, EmptyAndSingleSite) {
  const VoronoiDiagram none({}, {0, 0, 1, 1});
  EXPECT_EQ(none.locate({0.5, 0.5}), no_site);
  const VoronoiDiagram one({{0.3, 0.3}}, {0, 0, 1, 1});
  EXPECT_EQ(one.locate({0.9, 0.9}), 0u);
  EXPECT_NEAR(signed_area(one.cell(0)), 1.0, 1e-15);
  EXPECT_TRUE(one.is_valid(true));
}

TEST(AffineDiagrams, RejectBadInput) {
  EXPECT_THROW(PowerDiagram({{0, 0, NAN}}, {0, 0, 1, 1}), InputError);
  EXPECT_THROW(VoronoiDiagram({{0, 0}}, {0, 0, -1, 1}), InputError);
}

// Fuzz finding sites-4: (0.15, 0.2), (0.5, 0.1), (0.85, 0) are a proper triangle for the exact
// orientation predicate, but the inexact weighted circumcentre divides by a determinant that rounds to 0.
// The vertex is then computed in exact rational arithmetic: finite, far outside the box, and the
// diagram is valid (it was a [null, null] vertex and "valid": false).
TEST(PowerDiagram, NearlyCollinearSitesGetAFiniteVertex) {
  const std::vector<WeightedPoint> sites{{0.15, 0.2, 0.01}, {0.5, 0.1, 0.004}, {0.85, 0.0, 0.025},
                                         {0.3, 0.5, 0.03},  {0.62, 0.45, 0.002}, {0.5, 0.8, 0.004}};
  std::vector<Point2> points;
  for (const auto& s : sites) points.push_back({s.x, s.y});
  const PowerDiagram d(sites, bounding_box(points, 0.15));
  EXPECT_TRUE(d.is_valid(true));
  bool far = false;
  for (const auto& v : d.vertices()) {
    EXPECT_TRUE(std::isfinite(v.point.x) && std::isfinite(v.point.y));
    far = far || std::abs(v.point.x) > 1e6;
  }
  EXPECT_TRUE(far) << "the nearly flat triangle's vertex lies far away";
}

// A small box far from the origin: the area check sums cell areas relative to a box corner, not in
// absolute coordinates, whose rounding (~1e-17 · 0.5²) is far above 1e-7 of a ~4e-13 box (fuzz finding
// sites-3). In the far cluster the vertices themselves are rounded to ~1e-7 of the box's side.
TEST(AffineDiagrams, SmallBoxesFarFromTheOriginAreValid) {
  const std::vector<Point2> pair{{0.5, 0.500001}, {0.5, 0.5}};
  const VoronoiDiagram tiny(pair, bounding_box(pair, 0.15));
  EXPECT_TRUE(tiny.is_valid(true));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1e-6);
  std::vector<Point2> cluster;
  std::vector<WeightedPoint> weighted;
  for (int k = 0; k < 30; ++k) {
    cluster.push_back({1e3 + u(rng), -2e3 + u(rng)});
    weighted.push_back({cluster.back().x, cluster.back().y, 1e-14 * u(rng)});
  }
  const Box box = bounding_box(cluster, 0.15);
  EXPECT_TRUE(VoronoiDiagram(cluster, box).is_valid(true));
  EXPECT_TRUE(PowerDiagram(weighted, box).is_valid(true));
  double total = 0;
  const VoronoiDiagram d(cluster, box);
  for (SiteIndex i = 0; i < cluster.size(); ++i) total += signed_area(d.cell(i), {box.xmin, box.ymin});
  EXPECT_NEAR(total, box.width() * box.height(), 1e-7 * box.width() * box.height());  // is_valid's tolerance
}

// Nearly collinear sites on the hull make a sliver face whose circumcentre the doubles compute as
// inf or 0/0: it is then constructed exactly (found by the sites fuzz harness).
TEST(AffineDiagrams, SliverFacesHaveFiniteVertices) {
  const std::vector<Point2> sites{{0.15, 0.2}, {0.5, 0.1}, {0.85, 0}, {0.62, 0.45}, {0.9, 0.6},
                                  {0.12, 0.82}, {0.5, 0.8}, {0.78, 0.9}};
  const VoronoiDiagram d(sites, bounding_box(sites, 0.15));
  for (const DiagramVertex& v : d.vertices()) EXPECT_TRUE(std::isfinite(v.point.x) && std::isfinite(v.point.y));
  EXPECT_TRUE(d.is_valid(true));
  std::vector<WeightedPoint> weighted;
  for (const Point2& p : sites) weighted.push_back({p.x, p.y, 0.0});
  EXPECT_TRUE(PowerDiagram(weighted, bounding_box(sites, 0.15)).is_valid(true));
}

// One site ten decades away from the others leaves thin cells whose rounded vertices have a shoelace
// area at the rounding level of the box, of either sign: degenerate, not clockwise (fuzz finding sites-3).
TEST(AffineDiagrams, CellsAcrossTenDecadesAreValid) {
  std::vector<Point2> sites{{0.15, 0.2}, {0.5, 0.1}, {0.85, 0.25}, {0.3, 42949672960.5}, {0.62, 0.45},
                            {0.9, 0.6}, {0.12, 0.82}, {0.5, 0.8}, {0.78, 0.9}};
  EXPECT_TRUE(VoronoiDiagram(sites, bounding_box(sites, 0.15)).is_valid(true));
  std::vector<WeightedPoint> weighted;
  for (const Point2& p : sites) weighted.push_back({p.x, p.y, 0.0});
  EXPECT_TRUE(PowerDiagram(weighted, bounding_box(sites, 0.15)).is_valid(true));
}

// Far from the origin a margin of 1 (or 15% of a small span) is lost to rounding: the box still has a
// positive width and height (fuzz finding sites-3, a single site at 2^64).
TEST(AffineDiagrams, BoundingBoxesFarFromTheOriginAreNotFlat) {
  for (const std::vector<Point2>& points : {std::vector<Point2>{{0.5, 0x1p64}},
                                            std::vector<Point2>{{0, 1e19}, {1, 1e19}}}) {
    const Box b = bounding_box(points, 0.15);
    EXPECT_LT(b.xmin, b.xmax);
    EXPECT_LT(b.ymin, b.ymax);
    EXPECT_TRUE(VoronoiDiagram(points, b).is_valid(true));
  }
  const Box unit = bounding_box(std::vector<Point2>{{0, 0}, {1, 1}}, 0.1);  // unchanged near the origin
  EXPECT_DOUBLE_EQ(unit.xmin, -0.1);
  EXPECT_DOUBLE_EQ(unit.ymax, 1.1);
}
