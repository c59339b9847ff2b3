#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

using namespace laguerre::core;

namespace {
// Reference: hyperbolic law of cosines on finite radii, straight from the definitions.
double law_of_cosines_angle(double hx, double hy, double hz, double cxy, double cxz, double cyz) {
  auto dist = [](double a, double b, double c) {
    return std::acosh(std::cosh(a) * std::cosh(b) + c * std::sinh(a) * std::sinh(b));
  };
  const double c = dist(hx, hy, cxy), b = dist(hx, hz, cxz), a = dist(hy, hz, cyz);
  return std::acos((std::cosh(b) * std::cosh(c) - std::cosh(a)) / (std::sinh(b) * std::sinh(c)));
}
}  // namespace

TEST(HyperbolicTriangle, TangentAngleMatchesLawOfCosines) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> h(0.05, 4.0);
  for (int i = 0; i < 2000; ++i) {
    const double hx = h(rng), hy = h(rng), hz = h(rng);
    const double ref = law_of_cosines_angle(hx, hy, hz, 1, 1, 1);
    EXPECT_NEAR(tangent_angle(x_of_radius(hx), x_of_radius(hy), x_of_radius(hz)), ref, 1e-9);
  }
}

TEST(HyperbolicTriangle, OverlapAngleMatchesLawOfCosinesForAllAnglePatterns) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> h(0.05, 3.0);
  for (int i = 0; i < 4000; ++i) {
    const double hx = h(rng), hy = h(rng), hz = h(rng);
    // In G′ a triangle has either three tangencies or one tangency and two right angles.
    const int pattern = i % 4;
    const double cxy = pattern == 1 ? 1 : (pattern == 0 ? 1 : 0);
    const double cxz = pattern == 2 ? 1 : (pattern == 0 ? 1 : 0);
    const double cyz = pattern == 3 ? 1 : (pattern == 0 ? 1 : 0);
    const double ref = law_of_cosines_angle(hx, hy, hz, cxy, cxz, cyz);
    EXPECT_NEAR(overlap_angle(x_of_radius(hx), x_of_radius(hy), x_of_radius(hz), cxy, cxz, cyz), ref, 1e-8)
        << "pattern " << pattern << " radii " << hx << ' ' << hy << ' ' << hz;
  }
}

TEST(HyperbolicTriangle, OverlapAngleReducesToTangentAngle) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 0.95);
  for (int i = 0; i < 1000; ++i) {
    const double X = u(rng) + 0.01, Y = u(rng), Z = u(rng);
    // The generic expression (all tangencies) carries some cancellation; G′ patterns are factored.
    EXPECT_NEAR(overlap_angle(X, Y, Z, 1, 1, 1), tangent_angle(X, Y, Z), 1e-10);
  }
}

TEST(HyperbolicTriangle, HorocycleLimitsAreContinuous) {
  // Y, Z → 0 (horocycles): the formulas must have the limit at 0, not a singularity.
  for (double X : {0.01, 0.3, 0.8}) {
    for (double c : {0.0, 1.0}) {
      const double at0 = overlap_angle(X, 0, 0.4, c, 1, c);
      const double near0 = overlap_angle(X, 1e-13, 0.4, c, 1, c);
      EXPECT_NEAR(at0, near0, 1e-9);
      // Also matches the law of cosines at a huge but finite radius.
      const double ref = law_of_cosines_angle(radius_of(X), 14.0, radius_of(0.4), c, 1, c);
      EXPECT_NEAR(at0, ref, 1e-6);
    }
    // Known closed form: two horocycle neighbours, all tangent: sin²(α/2) = X.
    EXPECT_NEAR(tangent_angle(X, 0, 0), 2 * std::asin(std::sqrt(X)), 1e-14);
    EXPECT_NEAR(overlap_angle(X, 0, 0, 1, 1, 1), 2 * std::asin(std::sqrt(X)), 1e-12);
  }
}

TEST(HyperbolicTriangle, SmallAnglesKeepTheirRelativePrecision) {
  // A huge circle (X tiny) sees its neighbours under tiny angles; acos would return 0.
  const double X = 1e-20;
  const double a = overlap_angle(X, 0.5, 0.5, 1, 1, 1);
  const double ref = 2 * std::sqrt(X) * (1 - 0.5);  // sin(α/2) ≈ √X (1−Y) for X → 0
  EXPECT_NEAR(a / ref, 1.0, 1e-9);
  EXPECT_GT(overlap_angle(X, 0.5, 0.5, 0, 0, 1), 0.0);
}

TEST(HyperbolicTriangle, UniformNeighbourUpdateSolvesTheUniformFlower) {
  for (int k = 3; k <= 12; ++k) {
    for (double U : {0.0, 0.2, 0.7}) {
      for (double X : {0.05, 0.4, 0.9}) {
        const double theta = k * tangent_angle(X, U, U);
        const double Xp = uniform_neighbour_update(X, theta, k);
        // With the neighbours actually equal to U, one update lands exactly on 2π.
        EXPECT_NEAR(k * tangent_angle(Xp, U, U), 2 * std::numbers::pi, 1e-10) << k << ' ' << U << ' ' << X;
      }
    }
  }
}
