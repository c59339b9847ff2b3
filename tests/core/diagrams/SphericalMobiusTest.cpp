// Möbius diagrams on S² through the stereographic projection: the projection round trip, the
// projected distance identity, point location against brute force on the sphere, and vertices mapped
// back equidistant from their three sites with no site closer.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "laguerre/core/diagrams/SphericalMobiusDiagram.hpp"

using namespace laguerre::core;

namespace {
Point3 random_on_sphere(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Point3 p{g(rng), g(rng), g(rng)};
  const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return {p[0] / n, p[1] / n, p[2] / n};
}

std::vector<SphereMobiusSite> random_sites(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> l(0.5, 2), m(0, 0.3);
  std::vector<SphereMobiusSite> s;
  for (std::size_t i = 0; i < n; ++i) s.push_back({random_on_sphere(rng), l(rng), m(rng)});
  return s;
}
}  // namespace

TEST(SphericalMobius, ProjectionRoundTripAndDistanceIdentity) {
  std::mt19937_64 rng(1);
  const auto sites = random_sites(10, 2);
  for (int k = 0; k < 200; ++k) {
    const Point3 x = random_on_sphere(rng);
    const Point3 y = inverse_stereographic(stereographic(x));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[static_cast<std::size_t>(c)], y[static_cast<std::size_t>(c)], 1e-9);
    const Point2 q = stereographic(x);
    const double factor = q.x * q.x + q.y * q.y + 1;
    for (const auto& s : sites) {
      const double lhs = sphere_mobius_distance(x, s) * factor, rhs = mobius_distance(q, stereographic_site(s));
      EXPECT_NEAR(lhs, rhs, 1e-8 * (1 + std::fabs(lhs)));
    }
  }
}

TEST(SphericalMobius, LocationAgreesWithBruteForceOnTheSphere) {
  const auto sites = random_sites(40, 3);
  const SphericalMobiusDiagram d(sites, 20);
  ASSERT_TRUE(d.planar().is_valid(true));
  std::mt19937_64 rng(4);
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const Point3 x = random_on_sphere(rng);
    SiteIndex best = 0;
    double b1 = INFINITY, b2 = INFINITY;
    for (SiteIndex i = 0; i < sites.size(); ++i) {
      const double v = sphere_mobius_distance(x, sites[i]);
      if (v < b1) b2 = b1, b1 = v, best = i;
      else if (v < b2) b2 = v;
    }
    if (b2 - b1 < 1e-6) continue;
    EXPECT_EQ(d.locate(x), best);
    // Away from the pole cap outside the window, the computed cells agree too.
    const Point2 q = stereographic(x);
    if (std::fabs(q.x) < 19 && std::fabs(q.y) < 19 && b2 - b1 > 1e-3) {
      EXPECT_EQ(d.planar().locate_in_cells(q).first, best);
    }
    ++checked;
  }
  EXPECT_GT(checked, 2900);
}

TEST(SphericalMobius, VerticesMapBackToEquidistantPoints) {
  const auto sites = random_sites(30, 5);
  const SphericalMobiusDiagram d(sites, 10);
  const auto vs = d.vertices();
  ASSERT_EQ(vs.size(), d.planar().vertices().size());
  ASSERT_FALSE(vs.empty());
  for (std::size_t k = 0; k < vs.size(); ++k) {
    const auto& t = d.planar().vertices()[k].sites;
    const double d0 = sphere_mobius_distance(vs[k], sites[t[0]]);
    EXPECT_NEAR(std::hypot(vs[k][0], vs[k][1], vs[k][2]), 1.0, 1e-12);
    EXPECT_NEAR(sphere_mobius_distance(vs[k], sites[t[1]]), d0, 1e-7);
    EXPECT_NEAR(sphere_mobius_distance(vs[k], sites[t[2]]), d0, 1e-7);
    for (const auto& s : sites) EXPECT_GE(sphere_mobius_distance(vs[k], s), d0 - 1e-7);
  }
  for (const auto& line : d.edge_polylines())
    for (const Point3& p : line) EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), 1.0, 1e-12);
}
