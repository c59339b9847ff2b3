#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

using namespace laguerre::core;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();

// Oracle: the hyperbolic law of cosines straight from the definitions, in 256-bit MPFR arithmetic
// on the exact double inputs (h ≥ 10^-12 keeps ~50 significant digits of cosh h − 1):
//   cosh l_ab = cosh h_a cosh h_b + c_ab sinh h_a sinh h_b,
//   cos α = (cosh l_xy cosh l_xz − cosh l_yz) / (sinh l_xy sinh l_xz).
class Mp {
public:
  Mp() { mpfr_init2(v, 256); }
  explicit Mp(double d) : Mp() { mpfr_set_d(v, d, MPFR_RNDN); }
  Mp(const Mp&) = delete;
  Mp& operator=(const Mp&) = delete;
  ~Mp() { mpfr_clear(v); }
  mpfr_t v;
};

void lifted_cosh(Mp& out, const Mp& a, const Mp& b, double c) {
  Mp ca, cb, sa, sb, t;
  mpfr_cosh(ca.v, a.v, MPFR_RNDN);
  mpfr_cosh(cb.v, b.v, MPFR_RNDN);
  mpfr_sinh(sa.v, a.v, MPFR_RNDN);
  mpfr_sinh(sb.v, b.v, MPFR_RNDN);
  mpfr_mul(out.v, ca.v, cb.v, MPFR_RNDN);
  mpfr_mul(t.v, sa.v, sb.v, MPFR_RNDN);
  mpfr_mul_d(t.v, t.v, c, MPFR_RNDN);
  mpfr_add(out.v, out.v, t.v, MPFR_RNDN);
}

double oracle_angle(double hx, double hy, double hz, double cxy, double cxz, double cyz) {
  Mp x(hx), y(hy), z(hz), lxy, lxz, lyz, num, t, sxy, sxz;
  lifted_cosh(lxy, x, y, cxy);
  lifted_cosh(lxz, x, z, cxz);
  lifted_cosh(lyz, y, z, cyz);
  mpfr_mul(num.v, lxy.v, lxz.v, MPFR_RNDN);
  mpfr_sub(num.v, num.v, lyz.v, MPFR_RNDN);
  for (auto [s, l] : {std::pair<Mp*, Mp*>{&sxy, &lxy}, {&sxz, &lxz}}) {
    mpfr_sqr(s->v, l->v, MPFR_RNDN);
    mpfr_sub_ui(s->v, s->v, 1, MPFR_RNDN);
    mpfr_sqrt(s->v, s->v, MPFR_RNDN);
  }
  mpfr_mul(t.v, sxy.v, sxz.v, MPFR_RNDN);
  mpfr_div(num.v, num.v, t.v, MPFR_RNDN);
  mpfr_acos(num.v, num.v, MPFR_RNDN);
  return mpfr_get_d(num.v, MPFR_RNDN);
}

// Radii log-uniform over [10^lo, 10^hi].
double draw_radius(std::mt19937_64& rng, double lo, double hi) {
  return std::pow(10.0, std::uniform_real_distribution<double>(lo, hi)(rng));
}
}  // namespace

TEST(HyperbolicTriangle, LiftKeepsBothEndsExact) {
  EXPECT_EQ(lift(inf).x, 0.0);
  EXPECT_EQ(lift(inf).xbar, 1.0);
  // A vanishing circle: X̄ = 1 − e^{-2h} ≈ 2h to full relative precision (X alone would round to 1).
  EXPECT_NEAR(lift(1e-20).xbar / 2e-20, 1.0, 1e-15);
  EXPECT_EQ(lift(1e-20).x, 1.0);
  // A near-horocycle: X = e^{-2h} keeps its relative precision far below the double epsilon.
  EXPECT_NEAR(lift(100).x / std::exp(-200.0), 1.0, 1e-15);
}

TEST(HyperbolicTriangle, TangentAngleMatchesTheHighPrecisionOracle) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 3000; ++i) {
    const double hx = draw_radius(rng, -10, 1.3), hy = draw_radius(rng, -10, 1.3), hz = draw_radius(rng, -10, 1.3);
    const double ref = oracle_angle(hx, hy, hz, 1, 1, 1);
    EXPECT_NEAR(tangent_angle(lift(hx), lift(hy), lift(hz)), ref, 2e-14) << hx << ' ' << hy << ' ' << hz;
  }
}

TEST(HyperbolicTriangle, OverlapAngleMatchesTheOracleForEveryPatternOfGPrime) {
  // In G′ a triangle has either three tangencies or one tangency and two right angles; the angle at
  // a vertex of G, or at the face vertex, must stay exact down to vanishing circles (h = 10^-10).
  std::mt19937_64 rng(11);
  for (int i = 0; i < 8000; ++i) {
    const double hx = draw_radius(rng, -10, 1.3), hy = draw_radius(rng, -10, 1.3), hz = draw_radius(rng, -10, 1.3);
    const int pattern = i % 4;
    const double cxy = pattern == 0 || pattern == 1 ? 1 : 0;
    const double cxz = pattern == 0 || pattern == 2 ? 1 : 0;
    const double cyz = pattern == 0 || pattern == 3 ? 1 : 0;
    const double ref = oracle_angle(hx, hy, hz, cxy, cxz, cyz);
    EXPECT_NEAR(overlap_angle(lift(hx), lift(hy), lift(hz), cxy, cxz, cyz), ref, 2e-14)
        << "pattern " << pattern << " radii " << hx << ' ' << hy << ' ' << hz;
  }
}

TEST(HyperbolicTriangle, GeneralCosinesFollowTheLawOfCosines) {
  // Patterns that G′ never produces go through the general formula (moderate radii only).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> c(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const double hx = draw_radius(rng, -1, 0.5), hy = draw_radius(rng, -1, 0.5), hz = draw_radius(rng, -1, 0.5);
    const double cxy = c(rng), cxz = c(rng), cyz = c(rng);
    EXPECT_NEAR(overlap_angle(lift(hx), lift(hy), lift(hz), cxy, cxz, cyz), oracle_angle(hx, hy, hz, cxy, cxz, cyz), 1e-9);
  }
}

TEST(HyperbolicTriangle, HorocycleLimitsAreContinuous) {
  // h → ∞ (horocycles): the formulas must take the limit at ∞, not a singularity; at h = 40 a circle
  // differs from a horocycle by e^{-80}.
  for (double hx : {1e-7, 0.3, 2.0}) {
    for (double c : {0.0, 1.0}) {
      const double at_inf = overlap_angle(lift(hx), lift(inf), lift(0.4), c, 1, c);
      EXPECT_NEAR(at_inf, overlap_angle(lift(hx), lift(40.0), lift(0.4), c, 1, c), 1e-15);
      EXPECT_NEAR(at_inf, oracle_angle(hx, 40.0, 0.4, c, 1, c), 2e-14);
    }
    // Known closed form: two horocycle neighbours, all tangent: sin²(α/2) = X, cos²(α/2) = 1 − X.
    EXPECT_NEAR(tangent_angle(lift(hx), lift(inf), lift(inf)), 2 * std::atan2(std::exp(-hx), std::sqrt(-std::expm1(-2 * hx))), 1e-15);
  }
}

TEST(HyperbolicTriangle, SmallAnglesKeepTheirRelativePrecision) {
  // A huge circle (X tiny) sees its neighbours under tiny angles; acos would return 0.
  const double h = 23.0;  // X = e^{-46} ≈ 1e-20
  const double a = tangent_angle(lift(h), lift(radius_of(0.5)), lift(radius_of(0.5)));
  const double ref = 2 * std::exp(-h) * (1 - 0.5);  // sin(α/2) ≈ √X (1−Y) for X → 0
  EXPECT_NEAR(a / ref, 1.0, 1e-9);
  // At a huge face circle: the right-triangle parts tanh h_y / sinh h_f are tiny but positive.
  const double f = overlap_angle(lift(h), lift(0.5), lift(0.5), 0, 0, 1);
  EXPECT_NEAR(f / (2 * std::tanh(0.5) / std::sinh(h)), 1.0, 1e-12);
}

TEST(HyperbolicTriangle, VanishingCircleSeesHalfTurnsAtItsNeighbours) {
  // As h_x → 0 the angle of a tangency triangle tends to π and that of a G′ triangle to π/2 (x sits
  // on a point where its two neighbours meet): the defect shrinks like √h_x, not to a rounding error.
  for (double hx : {1e-6, 1e-9, 1e-12}) {
    const double t = tangent_angle(lift(hx), lift(0.7), lift(1.1));
    EXPECT_LT(t, std::numbers::pi);
    EXPECT_NEAR(t, oracle_angle(hx, 0.7, 1.1, 1, 1, 1), 2e-14);
    EXPECT_GT(std::numbers::pi - t, 0.5 * std::sqrt(hx));
    const double r = overlap_angle(lift(hx), lift(0.7), lift(1.1), 1, 0, 0);
    EXPECT_NEAR(r, std::numbers::pi / 2 - std::atan(std::sinh(hx) / std::tanh(1.1)), 1e-15);
  }
}

TEST(HyperbolicTriangle, UniformNeighbourUpdateSolvesTheUniformFlower) {
  for (int k = 3; k <= 12; ++k) {
    for (double hu : {inf, 3.0, 0.2, 1e-3, 1e-7}) {
      for (double h : {1e-9, 1e-3, 0.05, 1.0, 6.0}) {
        const double theta = k * tangent_angle(lift(h), lift(hu), lift(hu));
        const double hp = uniform_neighbour_update(h, theta, k);
        ASSERT_TRUE(hp > 0 && std::isfinite(hp)) << k << ' ' << hu << ' ' << h;
        // With the neighbours actually equal to U, one update lands on 2π. From h = 10^-9 the input
        // θ ≈ kπ − O(√h) carries only ~10^-11 of relative information on the defect kπ − θ.
        EXPECT_NEAR(k * tangent_angle(lift(hp), lift(hu), lift(hu)), 2 * std::numbers::pi, h < 1e-6 ? 1e-10 : 1e-12)
            << k << ' ' << hu << ' ' << h;
      }
    }
  }
}

TEST(HyperbolicTriangle, RadiusAndXAreInverse) {
  for (double h : {1e-3, 0.5, 1.0, 20.0}) EXPECT_NEAR(radius_of(x_of_radius(h)) / h, 1.0, 1e-12);
  EXPECT_EQ(radius_of(0.0), inf);
  EXPECT_EQ(x_of_radius(inf), 0.0);
}
