// The exact predicates on binary128 inputs (Circle128) against a slow exact oracle in rationals
// (Boost.Multiprecision, independent of CGAL and of the predicates' three-double split: each binary128
// number is decoded from its bits). As RadicalCentreTest.cpp does for doubles: near-ties built on
// purpose (t's radius set so that the radical centre lies on the radical axis of u and t up to the
// rounding of that radius, then moved by −3 … 3 binary128 ulps), at scales 2^-120 … 2^0, centres of
// both signs and translated by up to 0.3 with binary128 tails no double carries; exact ties must give
// zero. And LPD on binary128 circles: the same answers as on doubles where the circles are doubles,
// and a flower of circles of radius ~1e-33 far from the origin, which binary128 carries and doubles do
// not.

#include <gtest/gtest.h>

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "RadicalCentreOracle.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

using namespace laguerre::core;

namespace {

__extension__ typedef unsigned __int128 U128;
using namespace laguerre::testing::oracle;  // Q, QCircle, sign, power, the oracle
using I = boost::multiprecision::cpp_int;

Q exact(Float128 x) {  // decoded from the IEEE binary128 bits: sign, 15-bit exponent, 112-bit fraction
  U128 bits = 0;
  static_assert(sizeof bits == sizeof x);
  std::memcpy(&bits, &x, sizeof x);
  const bool negative = (bits >> 127) != 0;
  const int biased = static_cast<int>((bits >> 112) & 0x7fff);
  U128 frac = bits & ((static_cast<U128>(1) << 112) - 1);
  int e = biased == 0 ? 1 - 16383 - 112 : biased - 16383 - 112;
  if (biased != 0) frac |= static_cast<U128>(1) << 112;
  I m = I(static_cast<std::uint64_t>(frac >> 64));
  m <<= 64;
  m += I(static_cast<std::uint64_t>(frac));
  Q q(m);
  if (e >= 0) q *= Q(I(1) << e);
  else q /= Q(I(1) << -e);
  return negative ? Q(-q) : q;
}

// The oracle of RadicalCentreOracle.hpp on Circle128 circles, converted exactly.
QCircle rational(const Circle128& c) { return {exact(c.x), exact(c.y), exact(c.r) * exact(c.r)}; }

bool oracle_centre(const Circle128& u, const Circle128& a, const Circle128& b, Q& cx, Q& cy) {
  return radical_centre(rational(u), rational(a), rational(b), cx, cy);
}

int oracle_power_side(const Circle128& u, const Circle128& a, const Circle128& b, const Circle128& t) {
  return power_side(rational(u), rational(a), rational(b), rational(t));
}

int oracle_outside(const Circle128& u, const Circle128& a, const Circle128& b) {
  return outside_unit_disc(rational(u), rational(a), rational(b));
}

Float128 ulps(Float128 x, int k) {  // a positive x moved by k binary128 units in the last place
  U128 bits = 0;
  std::memcpy(&bits, &x, sizeof x);
  bits = k >= 0 ? bits + static_cast<unsigned>(k) : bits - static_cast<unsigned>(-k);
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

Float128 sqrt128(Float128 a) {  // double estimate, then Newton in binary128 (to within an ulp or two)
  Float128 y = std::sqrt(static_cast<double>(a));
  for (int i = 0; i < 3; ++i) y = y + (a - y * y) / (2 * y);
  return y;
}

Float128 to_quad(const Q& q) {  // nearest-ish binary128 of a rational (double head plus a double tail)
  const double hi = static_cast<double>(q);
  const double lo = static_cast<double>(Q(q - Q(exact(Float128(hi)))));
  return Float128(hi) + Float128(lo);
}

}  // namespace

TEST(RadicalCentrePredicates128, PowerSideMatchesTheExactOracleOnNearTies) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> unit(-1, 1), pos(0.2, 1);
  const int scales[] = {-120, -100, -80, -60, -40, -20, 0};
  int decided[3] = {0, 0, 0};
  for (int scale : scales)
    for (int rep = 0; rep < 120; ++rep) {
      const Float128 s = std::ldexp(1.0, scale);
      // Each coordinate a double plus a binary128 tail 2^-70 below it: not a double.
      auto q = [&](double v) { return Float128(v) + Float128(v) * Float128(std::ldexp(unit(rng), -70)); };
      const Float128 ox = rep % 2 ? q(0.3 * unit(rng)) : 0, oy = rep % 2 ? q(0.3 * unit(rng)) : 0;
      auto circle = [&] { return Circle128{ox + s * q(unit(rng)), oy + s * q(unit(rng)), s * q(0.3 * pos(rng))}; };
      const Circle128 u = circle(), a = circle(), b = circle();
      Q cx, cy;
      if (!oracle_centre(u, a, b, cx, cy)) continue;
      Circle128 t = circle();
      const Q r2 = (cx - exact(t.x)) * (cx - exact(t.x)) + (cy - exact(t.y)) * (cy - exact(t.y)) - power(cx, cy, rational(u));
      if (!(r2 > 0)) continue;
      const Float128 r = sqrt128(to_quad(r2));
      for (int k = -3; k <= 3; ++k) {
        t.r = ulps(r, k);
        const int want = oracle_power_side(u, a, b, t);
        ASSERT_EQ(static_cast<int>(radical_centre_power_side(u, a, b, t)), want)
            << "scale 2^" << scale << " rep " << rep << " k " << k;
        ++decided[want + 1];
      }
    }
  EXPECT_GT(decided[0], 250);
  EXPECT_GT(decided[2], 250);
}

TEST(RadicalCentrePredicates128, PowerSideIsZeroOnExactTies) {
  // Equal radii, centres on a circle of radius 5 (3-4-5 points), scaled and translated by dyadics so
  // that every binary128 coordinate is exact (the translated ones at 2^-100 are not doubles).
  const double pts[][2] = {{5, 0}, {3, 4}, {-4, 3}, {0, -5}, {-3, -4}, {4, -3}};
  for (int e : {-120, -100, -60, 0})
    for (double off : {0.0, 0.375, -0.3125}) {
      if (off != 0 && e < -105) continue;  // off + 5·2^e would need more than 113 bits
      const Float128 s = std::ldexp(1.0, e), r = std::ldexp(1.0, e - 3);
      auto c = [&](int i) { return Circle128{off + s * pts[i][0], off / 2 + s * pts[i][1], r}; };
      ASSERT_EQ(oracle_power_side(c(0), c(1), c(2), c(3)), 0);
      EXPECT_EQ(radical_centre_power_side(c(0), c(1), c(2), c(3)), Sign::zero) << e << ' ' << off;
      EXPECT_EQ(radical_centre_power_side(c(5), c(1), c(3), c(4)), Sign::zero) << e << ' ' << off;
      Circle128 t = c(3);
      t.r = ulps(r, -1);  // smaller t: c now strictly inside H_t
      EXPECT_EQ(radical_centre_power_side(c(0), c(1), c(2), t), Sign::positive) << e << ' ' << off;
      EXPECT_EQ(oracle_power_side(c(0), c(1), c(2), t), 1);
      // The degree-2 predicates on the same exact points: cocircular, so orientation is non-zero and
      // compare_distance from the common centre is zero.
      const Point128 o{off, off / 2};
      EXPECT_EQ(compare_distance(o, centre(c(0)), centre(c(2))), Sign::zero);
      EXPECT_EQ(compare_power(o, c(1), c(4)), Sign::zero);
      EXPECT_EQ(orientation(centre(c(0)), centre(c(1)), centre(c(2))), Sign::positive);
      EXPECT_EQ(orientation(centre(c(0)), centre(c(0)), centre(c(2))), Sign::zero);
    }
}

TEST(RadicalCentrePredicates128, OutsideUnitDiscMatchesTheExactOracleNearTheUnitCircle) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586), unit(-1, 1);
  int seen[3] = {0, 0, 0};
  for (int rep = 0; rep < 400; ++rep) {
    const double th = angle(rng);
    const Float128 cx = std::cos(th), cy = std::sin(th);
    const Float128 s = std::ldexp(1.0, -(rep % 100));
    const Float128 k = Float128(0.25) * s * s;
    Circle128 w[3];
    for (Circle128& c : w) {
      c.x = cx + s * Float128(unit(rng));
      c.y = cy + s * Float128(unit(rng));
      const Float128 d2 = (c.x - cx) * (c.x - cx) + (c.y - cy) * (c.y - cy);
      c.r = ulps(sqrt128(d2 + k), static_cast<int>(rng() % 5) - 2);
    }
    const int want = oracle_outside(w[0], w[1], w[2]);
    ASSERT_EQ(static_cast<int>(radical_centre_outside_unit_disc(w[0], w[1], w[2])), want) << rep;
    ++seen[want + 1];
  }
  EXPECT_GT(seen[0], 60);
  EXPECT_GT(seen[2], 60);
}

TEST(RadicalCentrePredicates128, DegreeTwoPredicatesMatchTheOracleOnNearTies) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  int seen[3] = {0, 0, 0};
  for (int rep = 0; rep < 600; ++rep) {
    const Float128 s = std::ldexp(1.0, -(rep % 121));
    const Float128 o = Float128(0.3 * unit(rng));
    const Point128 a{o + s * Float128(unit(rng)), o + s * Float128(unit(rng))};
    const Point128 b{o + s * Float128(unit(rng)), o + s * Float128(unit(rng))};
    // c on line ab up to rounding, then moved by a few ulps in y.
    const Float128 lambda = Float128(unit(rng));
    Point128 c{a.x + lambda * (b.x - a.x), a.y + lambda * (b.y - a.y)};
    c.y = c.y > 0 ? ulps(c.y, static_cast<int>(rng() % 5) - 2) : c.y;
    const Q ax = exact(a.x), ay = exact(a.y), bx = exact(b.x), by = exact(b.y), qx = exact(c.x), qy = exact(c.y);
    const int want = sign((bx - ax) * (qy - ay) - (by - ay) * (qx - ax));
    ASSERT_EQ(static_cast<int>(orientation(a, b, c)), want) << rep;
    ++seen[want + 1];
    // compare_power at c between circles a and b of radii making the powers equal up to rounding.
    const Circle128 ca{a.x, a.y, s / 4};
    const Q pa = (qx - ax) * (qx - ax) + (qy - ay) * (qy - ay) - exact(ca.r) * exact(ca.r);
    const Q d2b = (qx - bx) * (qx - bx) + (qy - by) * (qy - by);
    if (d2b - pa > 0) {
      const Circle128 cb{b.x, b.y, ulps(sqrt128(to_quad(Q(d2b - pa))), static_cast<int>(rng() % 5) - 2)};
      const int wp = sign(pa - (d2b - exact(cb.r) * exact(cb.r)));
      ASSERT_EQ(static_cast<int>(compare_power(c, ca, cb)), wp) << rep;
    }
  }
  EXPECT_GT(seen[0], 50);
  EXPECT_GT(seen[2], 50);
}

TEST(Lpd128, AgreesWithTheDoubleCheckOnDoubleCircles) {
  // A flower of perturbed tangent circles: where the binary128 circles are the same numbers as the
  // doubles, both checks answer the same (the same exact predicates on the same exact values).
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-1, 1);
  int outcomes[2] = {0, 0};
  for (int rep = 0; rep < 400; ++rep) {
    const int deg = 4 + rep % 5;
    const double r = 0.1, amp = rep % 3 == 0 ? 0.0 : 0.05 * r;
    const double cx = 0.3 * jitter(rng), cy = 0.3 * jitter(rng);
    std::vector<Circle> nb;
    const double rw = r * std::sin(3.141592653589793 / deg) / (1 - std::sin(3.141592653589793 / deg));
    for (int i = 0; i < deg; ++i) {
      const double th = 2 * 3.141592653589793 * i / deg + amp * jitter(rng);
      nb.push_back({cx + (r + rw) * std::cos(th), cy + (r + rw) * std::sin(th), rw * (1 + amp * jitter(rng))});
    }
    const Circle v{cx, cy, r * (1 + amp * jitter(rng))};
    std::vector<Circle128> nb128;
    for (const Circle& c : nb) nb128.push_back({c.x, c.y, c.r});
    const Circle128 v128{v.x, v.y, v.r};
    for (bool boundary : {false, true}) {
      const LocalCondition want = check_lpd_at(v, nb, boundary);
      ASSERT_EQ(check_lpd_at(v128, nb128, boundary), want) << rep << ' ' << boundary;
      ++outcomes[want == LocalCondition::holds];
    }
  }
  EXPECT_GT(outcomes[0], 20);
  EXPECT_GT(outcomes[1], 20);
}

TEST(Lpd128, DecidesTinyCirclesFarFromTheOriginThatDoublesCollapse) {
  // Seven tangent circles of radius 1e-33 (a hexagonal flower) around (0.3, −0.2): binary128 carries
  // them (its ulp there is ~6e-35), doubles do not (ulp ~6e-17: all centres round to one point).
  const Float128 r = 1e-33, sq3 = sqrt128(3);
  const Float128 cx = 0.3, cy = -0.2;
  const Float128 dx[] = {2, 1, -1, -2, -1, 1}, dy[] = {0, 1, 1, 0, -1, -1};
  std::vector<Circle128> nb;
  std::vector<Circle> nb_double;
  for (int i = 0; i < 6; ++i) {
    nb.push_back({cx + r * dx[i], cy + r * dy[i] * sq3, r});
    nb_double.push_back(to_double(nb.back()));
  }
  const Circle128 v{cx, cy, r};
  EXPECT_EQ(check_lpd_at(v, nb, false), LocalCondition::holds);
  EXPECT_NE(check_lpd_at(to_double(v), nb_double, false), LocalCondition::holds);
}
