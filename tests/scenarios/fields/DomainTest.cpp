#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/Domain.hpp"

using namespace laguerre::scenarios;
using laguerre::core::orientation;
using laguerre::core::Point2;
using laguerre::core::Sign;

namespace {

/// The message of the std::invalid_argument thrown by making a Domain, or "" if none.
std::string domain_error(Polygon outer, std::vector<Polygon> holes = {}) {
  try {
    Domain d(std::move(outer), std::move(holes));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

Polygon square(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

double signed_area(const Polygon& p) {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) s += p[i].x * p[(i + 1) % p.size()].y - p[i].y * p[(i + 1) % p.size()].x;
  return s / 2;
}

Domain square_with_hole() { return Domain(square(0, 0, 4, 4), {square(1, 1, 2, 2)}); }

}  // namespace

TEST(Domain, ValidationErrorsNameThePolygonAndTheProblem) {
  EXPECT_NE(domain_error({{0, 0}, {1, 0}}).find("the outer polygon has 2 vertices"), std::string::npos);
  EXPECT_NE(domain_error({{0, 0}, {1, 0}, {1, 1}, {1, 0}}).find("vertices 1 and 3 of the outer polygon are both at"),
            std::string::npos);
  // A bow tie: edges 0 and 2 cross.
  EXPECT_NE(domain_error({{0, 0}, {1, 1}, {1, 0}, {0, 1}}).find("edges 0 (") , std::string::npos);
  EXPECT_NE(domain_error({{0, 0}, {1, 1}, {1, 0}, {0, 1}}).find("cross or touch"), std::string::npos);
  // A spike: the boundary goes out to (3, 0) and back along the same line.
  EXPECT_NE(domain_error({{0, 0}, {3, 0}, {2, 0}, {2, 2}}).find("overlap"), std::string::npos);
  EXPECT_NE(domain_error({{0, 0}, {1, 0}, {2, 0}}).find("overlap"), std::string::npos);  // collinear triangle
  EXPECT_NE(domain_error(square(0, 0, 4, 4), {square(5, 5, 6, 6)}).find("hole 1 lies outside the outer polygon"),
            std::string::npos);
  EXPECT_NE(domain_error(square(0, 0, 4, 4), {square(1, 1, 2, 2), square(3, 3, 5, 5)}).find("hole 2 meets the boundary"),
            std::string::npos);
  EXPECT_NE(domain_error(square(0, 0, 4, 4), {square(0, 1, 1, 2)}).find("hole 1 meets the boundary"),  // shares an edge line
            std::string::npos);
  EXPECT_NE(domain_error(square(0, 0, 9, 9), {square(1, 1, 5, 5), square(2, 2, 3, 3)}).find("hole 1 and hole 2 overlap"),
            std::string::npos);
  EXPECT_NE(domain_error(square(0, 0, 9, 9), {square(1, 1, 3, 3), square(3, 1, 5, 3)}).find("hole 1 and hole 2 meet"),
            std::string::npos);
  EXPECT_NE(domain_error({{0, 0}, {1, 0}, {1, std::nan("")}}).find("non-finite"), std::string::npos);
  EXPECT_EQ(domain_error(square(0, 0, 4, 4), {square(1, 1, 2, 2), square(2.5, 2.5, 3, 3)}), "");
  EXPECT_THROW(Domain::rectangle(1, 0, 1, 2), std::invalid_argument);
}

TEST(Domain, OrientationIsNormalized) {
  Polygon cw = square(0, 0, 4, 4);
  std::reverse(cw.begin(), cw.end());
  const Domain d(cw, {square(1, 1, 2, 2)});  // the hole given counter-clockwise
  EXPECT_GT(signed_area(d.outer()), 0);
  EXPECT_LT(signed_area(d.holes()[0]), 0);
  EXPECT_DOUBLE_EQ(d.area(), 15.0);
}

TEST(Domain, LocateKnownAnswers) {
  const Domain d = square_with_hole();
  using L = Domain::Location;
  EXPECT_EQ(d.locate({0.5, 0.5}), L::inside);
  EXPECT_EQ(d.locate({3, 1.5}), L::inside);
  EXPECT_EQ(d.locate({1.5, 1.5}), L::outside);  // in the hole
  EXPECT_EQ(d.locate({5, 1}), L::outside);
  EXPECT_EQ(d.locate({-1, 1}), L::outside);
  EXPECT_EQ(d.locate({4, 2}), L::boundary);
  EXPECT_EQ(d.locate({0, 0}), L::boundary);
  EXPECT_EQ(d.locate({1.5, 2}), L::boundary);  // hole edge
  EXPECT_EQ(d.locate({1, 1}), L::boundary);    // hole corner
  // A point a hair inside the hole's edge, where rounding would matter: exact.
  EXPECT_EQ(d.locate({1.5, std::nextafter(2.0, 0.0)}), L::outside);
  EXPECT_EQ(d.locate({1.5, std::nextafter(2.0, 3.0)}), L::inside);
  // Rays towards +x through the hole's corners (1, 1) and (2, 1), and along its edge y = 2.
  EXPECT_EQ(d.locate({0.5, 1}), L::inside);
  EXPECT_EQ(d.locate({0.5, 2}), L::inside);
}

TEST(Domain, TriangleInside) {
  const Domain d = square_with_hole();
  EXPECT_TRUE(d.triangle_inside({0.5, 0.5}, {3.5, 0.5}, {3.5, 0.9}));
  EXPECT_FALSE(d.triangle_inside({0.5, 0.5}, {3.5, 0.5}, {3.5, 3.5}));   // cuts through the hole
  EXPECT_FALSE(d.triangle_inside({0.5, 0.5}, {3.5, 0.5}, {1.5, 1.5}));   // a vertex in the hole
  EXPECT_FALSE(d.triangle_inside({0.5, 1.5}, {1.5, 0.5}, {2.5, 1.5}));  // pokes into the hole
  EXPECT_TRUE(d.triangle_inside({0.5, 0.5}, {1, 0.5}, {1, 1}));          // touches the hole's corner only
  const Domain l({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});      // an L: a reflex corner at (1, 1)
  EXPECT_FALSE(l.triangle_inside({1.6, 0.6}, {0.6, 1.6}, {0.5, 0.5}));  // the reflex corner is inside it
  EXPECT_FALSE(l.triangle_inside({1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}));  // a vertex outside
  EXPECT_FALSE(l.triangle_inside({1.5, 0.5}, {1.9, 0.9}, {1.2, 1.3}));  // a vertex outside
  EXPECT_TRUE(l.triangle_inside({1.5, 0.5}, {0.5, 1.5}, {0.5, 0.5}));
}

TEST(Deployment, UniformPointsAreStrictlyInsideDistinctAndDeterministic) {
  const Domain d = square_with_hole();
  const auto a = deploy_uniform(d, 2000, 7), b = deploy_uniform(d, 2000, 7), c = deploy_uniform(d, 2000, 8);
  ASSERT_EQ(a.size(), 2000u);
  std::set<std::pair<double, double>> distinct;
  std::size_t in_hole_quarter = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(d.locate(a[i]), Domain::Location::inside);
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].y, b[i].y);
    distinct.emplace(a[i].x, a[i].y);
    if (a[i].x < 2 && a[i].y < 2) ++in_hole_quarter;
  }
  EXPECT_EQ(distinct.size(), a.size());
  EXPECT_NE(a[0].x, c[0].x);
  // Uniformity: the quarter [0, 2]² minus the hole has area 3 of 15, expectation 400, sd ≈ 17.9.
  EXPECT_NEAR(static_cast<double>(in_hole_quarter), 400.0, 5 * 17.9);
}

TEST(Deployment, ClusteredPointsAreInsideDeterministicAndClustered) {
  const Domain d({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{4, 4}, {6, 4}, {6, 6}, {4, 6}}});
  for (ClusterShape shape : {ClusterShape::gaussian, ClusterShape::disc}) {
    const ClusterOptions options{5, 0.2, shape};
    const auto a = deploy_clustered(d, 1000, options, 3), b = deploy_clustered(d, 1000, options, 3);
    const auto u = deploy_uniform(d, 1000, 3);
    ASSERT_EQ(a.size(), 1000u);
    double nn_clustered = 0, nn_uniform = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(d.locate(a[i]), Domain::Location::inside);
      EXPECT_EQ(a[i].x, b[i].x);
      double best_c = 1e300, best_u = 1e300;
      for (std::size_t j = 0; j < a.size(); ++j)
        if (j != i) {
          best_c = std::min(best_c, std::hypot(a[i].x - a[j].x, a[i].y - a[j].y));
          best_u = std::min(best_u, std::hypot(u[i].x - u[j].x, u[i].y - u[j].y));
        }
      nn_clustered += best_c;
      nn_uniform += best_u;
    }
    // 1000 points in 5 clusters of radius ~0.2 are far denser than 1000 points over area 96.
    EXPECT_LT(nn_clustered, 0.25 * nn_uniform);
  }
  EXPECT_THROW(deploy_clustered(d, 10, {0, 0.1, ClusterShape::disc}, 1), std::invalid_argument);
  EXPECT_THROW(deploy_clustered(d, 10, {3, -1, ClusterShape::disc}, 1), std::invalid_argument);
  EXPECT_THROW(deploy_uniform(d, 0, 1), std::invalid_argument);
}
