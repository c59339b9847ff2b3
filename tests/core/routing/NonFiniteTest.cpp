// An embedding with a NaN or infinite circle (an unrepresentable layout) is refused with the vertex
// named, and the exact predicates refuse non-finite inputs instead of aborting inside GMP.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "DrawingGraph.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

namespace laguerre::core {
namespace {

TEST(NonFinite, RoutingRefusesTheEmbeddingNamingTheVertex) {
  CircleEmbedding phi = {{0, 0, 0.1}, {1, 0, 0.1}, {0, 1, 0.1}, {1, 1, 0.1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 3}, {3, 2}, {2, 0}, {0, 3}});
  phi[2].x = std::numeric_limits<double>::quiet_NaN();
  try {
    (void)evaluate_routing(g, phi, Scheme::greedy_power, {});
    FAIL() << "routed on a NaN circle";
  } catch (const laguerre::core::InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 2 is not finite"), std::string::npos) << e.what();
  }
  phi[2].x = 0;
  phi[1].r = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)route(g, phi, Scheme::gfg, 0, 3), laguerre::core::InternalError);
}

TEST(NonFinite, ExactPredicatesThrowInsteadOfAborting) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)compare_power({nan, 0}, {0, 0, 1}, {1, 0, 2}), std::domain_error);
  EXPECT_THROW((void)orientation({0, 0}, {1, 0}, {nan, 1}), std::domain_error);
  EXPECT_THROW((void)compare_distance({0, 0}, {INFINITY, 0}, {1, 1}), std::domain_error);
  EXPECT_EQ(orientation({0, 0}, {1, 0}, {0, 1}), Sign::positive);  // finite inputs are unaffected
}

}  // namespace
}  // namespace laguerre::core
