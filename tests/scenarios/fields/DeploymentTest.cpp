// Sensor deployments in a domain with holes (core::Domain): strictly inside, distinct, deterministic,
// uniform or clustered. (The domain's own tests are in tests/core/meshing/domain_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/scenarios/fields/Deployment.hpp"

using namespace laguerre::scenarios;
using laguerre::core::Domain;
using laguerre::core::DomainSide;
using laguerre::core::Point2;

namespace {

Domain square_with_hole() { return Domain({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}}); }

}  // namespace

TEST(Deployment, UniformPointsAreStrictlyInsideDistinctAndDeterministic) {
  const Domain d = square_with_hole();
  const auto a = deploy_uniform(d, 2000, 7), b = deploy_uniform(d, 2000, 7), c = deploy_uniform(d, 2000, 8);
  ASSERT_EQ(a.size(), 2000u);
  std::set<std::pair<double, double>> distinct;
  std::size_t in_hole_quarter = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(d.locate(a[i]), DomainSide::inside);
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
      EXPECT_EQ(d.locate(a[i]), DomainSide::inside);
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
  EXPECT_THROW(deploy_clustered(d, 10, {0, 0.1, ClusterShape::disc}, 1), laguerre::core::InternalError);
  EXPECT_THROW(deploy_clustered(d, 10, {3, -1, ClusterShape::disc}, 1), laguerre::core::InternalError);
  EXPECT_THROW(deploy_uniform(d, 0, 1), laguerre::core::InternalError);
}
