// The radical-centre predicates (double stage, intervals, Mpzf) against a slow exact oracle in
// rationals (Boost.Multiprecision, independent of CGAL): the radical centre c is solved for by
// Cramer's rule, and pow(c, t) − pow(c, u) or |c|² − 1 evaluated directly.
//
// The inputs are near-ties built on purpose: t's radius is set so that c lies on the radical axis of
// u and t up to the rounding of that radius, then moved by −3 … 3 ulps; for the unit-disc test c is
// put on the unit circle up to rounding. Scales run from 2^-90 to 2^30, translated by up to 0.3 — the
// regime of uniform random maps, whose circles of radius 1e-25 sit far from the origin — and exact
// ties (dyadic cocircular centres with equal radii) must give zero.

#include <gtest/gtest.h>

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <cstdint>
#include <random>

#include "laguerre/core/geometry/Predicates.hpp"
#include "RadicalCentreOracle.hpp"

using namespace laguerre::core;

namespace {

using namespace laguerre::testing::oracle;  // Q, QCircle, sign, power, the oracle

Q exact(double x) {  // the double's exact value
  if (x == 0) return Q(0);
  int e = 0;
  const double m = std::frexp(x, &e);
  Q q(static_cast<std::int64_t>(std::ldexp(m, 53)));
  e -= 53;
  const Q two(2);
  Q p(1);
  for (int i = 0; i < std::abs(e); ++i) p *= two;
  return e >= 0 ? Q(q * p) : Q(q / p);
}

// The oracle of RadicalCentreOracle.hpp on Circle circles, converted exactly.
QCircle rational(const Circle& c) { return {exact(c.x), exact(c.y), exact(c.r) * exact(c.r)}; }

bool oracle_centre(const Circle& u, const Circle& a, const Circle& b, Q& cx, Q& cy) {
  return radical_centre(rational(u), rational(a), rational(b), cx, cy);
}

int oracle_power_side(const Circle& u, const Circle& a, const Circle& b, const Circle& t) {
  return power_side(rational(u), rational(a), rational(b), rational(t));
}

int oracle_outside(const Circle& u, const Circle& a, const Circle& b) {
  return outside_unit_disc(rational(u), rational(a), rational(b));
}

double ulps(double x, int k) {  // x moved by k units in the last place
  for (; k > 0; --k) x = std::nextafter(x, INFINITY);
  for (; k < 0; ++k) x = std::nextafter(x, -INFINITY);
  return x;
}

}  // namespace

TEST(RadicalCentrePredicates, PowerSideMatchesTheExactOracleOnNearTies) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> unit(-1, 1), pos(0.2, 1);
  const int scales[] = {-90, -60, -40, -20, 0, 30};
  int decided[3] = {0, 0, 0};
  for (int scale : scales)
    for (int rep = 0; rep < 150; ++rep) {
      const double s = std::ldexp(1.0, scale);
      const double ox = rep % 2 ? 0.3 * unit(rng) : 0, oy = rep % 2 ? 0.3 * unit(rng) : 0;  // far from the origin
      auto circle = [&] { return Circle{ox + s * unit(rng), oy + s * unit(rng), s * 0.3 * pos(rng)}; };
      const Circle u = circle(), a = circle(), b = circle();
      Q cx, cy;
      if (!oracle_centre(u, a, b, cx, cy)) continue;
      // t on the tie: r_t² = |c − p_t|² − pow(c, u), if positive (else try another centre).
      Circle t = circle();
      const QCircle qu = rational(u);
      const double pu = static_cast<double>(power(cx, cy, qu));
      const double dx = static_cast<double>(cx - exact(t.x)), dy = static_cast<double>(cy - exact(t.y));
      const double r2 = dx * dx + dy * dy - pu;
      if (!(r2 > 0)) continue;
      for (int k = -3; k <= 3; ++k) {
        t.r = ulps(std::sqrt(r2), k);
        const int want = oracle_power_side(u, a, b, t);
        ASSERT_EQ(static_cast<int>(radical_centre_power_side(u, a, b, t)), want)
            << "scale 2^" << scale << " rep " << rep << " k " << k;
        ++decided[want + 1];
      }
    }
  // Both signs occur among the near-ties (the test would not see a predicate stuck on one answer).
  EXPECT_GT(decided[0], 250);
  EXPECT_GT(decided[2], 250);
}

TEST(RadicalCentrePredicates, PowerSideIsZeroOnExactTies) {
  // Equal radii: the power test is the in-circle test; the centres are on a circle of radius 5
  // (3-4-5 points), scaled and translated by dyadics, so every double is exact.
  const double pts[][2] = {{5, 0}, {3, 4}, {-4, 3}, {0, -5}, {-3, -4}, {4, -3}};
  for (int e : {-80, -40, 0, 20})
    for (double off : {0.0, 0.375, -0.3125}) {
      const double s = std::ldexp(1.0, e), r = std::ldexp(1.0, e - 3);
      if (off != 0 && e < -45) continue;  // off + 5·2^e would round: the centres would not be cocircular
      auto c = [&](int i) { return Circle{off + s * pts[i][0], off / 2 + s * pts[i][1], r}; };
      ASSERT_EQ(oracle_power_side(c(0), c(1), c(2), c(3)), 0);
      EXPECT_EQ(radical_centre_power_side(c(0), c(1), c(2), c(3)), Sign::zero) << e << ' ' << off;
      EXPECT_EQ(radical_centre_power_side(c(5), c(1), c(3), c(4)), Sign::zero) << e << ' ' << off;
      Circle t = c(3);
      t.r = std::nextafter(r, 0.0);  // smaller t: c now strictly inside H_t
      EXPECT_EQ(radical_centre_power_side(c(0), c(1), c(2), t), Sign::positive) << e << ' ' << off;
      EXPECT_EQ(oracle_power_side(c(0), c(1), c(2), t), 1);
    }
}

TEST(RadicalCentrePredicates, OutsideUnitDiscMatchesTheExactOracleNearTheUnitCircle) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586), unit(-1, 1);
  int seen[3] = {0, 0, 0};
  for (int rep = 0; rep < 600; ++rep) {
    // Centres around a point c of the unit circle, radii making pow(c, ·) equal up to rounding.
    const double th = angle(rng), cx = std::cos(th), cy = std::sin(th);
    const double s = std::ldexp(1.0, -(rep % 40));
    const double k = 0.25 * s * s;  // the common power
    Circle w[3];
    for (Circle& c : w) {
      c.x = cx + s * unit(rng);
      c.y = cy + s * unit(rng);
      const double d2 = (c.x - cx) * (c.x - cx) + (c.y - cy) * (c.y - cy);
      c.r = ulps(std::sqrt(std::fabs(d2 + k)), static_cast<int>(rng() % 5) - 2);
    }
    const int want = oracle_outside(w[0], w[1], w[2]);
    ASSERT_EQ(static_cast<int>(radical_centre_outside_unit_disc(w[0], w[1], w[2])), want) << rep;
    ++seen[want + 1];
  }
  EXPECT_GT(seen[0], 100);
  EXPECT_GT(seen[2], 100);
}
