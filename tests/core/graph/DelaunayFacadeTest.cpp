// The Delaunay facade's exact predicates (core/geometry/Delaunay.hpp) against 128-bit integer
// arithmetic on integer coordinates, near-degenerate on purpose so that the double filters must defer
// to the exact stage.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "laguerre/core/geometry/Delaunay.hpp"

using namespace laguerre::core;

namespace {

__extension__ typedef __int128 Int;  // GCC and Clang; exact for the magnitudes below

Sign sign_of(Int v) { return v > 0 ? Sign::positive : v < 0 ? Sign::negative : Sign::zero; }

Int in_circle_exact(Point2 a, Point2 b, Point2 c, Point2 d) {
  const Int ax = Int(std::int64_t(a.x)) - Int(std::int64_t(d.x)), ay = Int(std::int64_t(a.y)) - Int(std::int64_t(d.y));
  const Int bx = Int(std::int64_t(b.x)) - Int(std::int64_t(d.x)), by = Int(std::int64_t(b.y)) - Int(std::int64_t(d.y));
  const Int cx = Int(std::int64_t(c.x)) - Int(std::int64_t(d.x)), cy = Int(std::int64_t(c.y)) - Int(std::int64_t(d.y));
  return (ax * ax + ay * ay) * (bx * cy - by * cx) - (bx * bx + by * by) * (ax * cy - ay * cx) +
         (cx * cx + cy * cy) * (ax * by - ay * bx);
}

}  // namespace

TEST(DelaunayFacade, PredicatesAreExactOnNearDegenerateInputs) {
  std::mt19937_64 engine(42);
  const double radius = 0x1p24;  // points rounded to integers near a circle of radius 2^24
  const auto on_circle = [&](double shift) {
    const double t = static_cast<double>(engine() >> 11) * 0x1p-53 * 6.283185307179586;
    return Point2{std::round(radius * std::cos(t)) + shift, std::round(radius * std::sin(t)) + shift};
  };
  // The images of p under the symmetries of the square centred at o (k = 1..7; 0 is p itself): all on
  // the circle about o through p, so four distinct ones are exactly cocircular.
  const auto image = [](Point2 o, Point2 p, int k) {
    double u = p.x - o.x, v = p.y - o.y;
    if (k & 4) std::swap(u, v);
    return Point2{o.x + ((k & 1) ? -u : u), o.y + ((k & 2) ? -v : v)};
  };
  int zeros = 0, positives = 0, negatives = 0;
  for (int i = 0; i < 20000; ++i) {
    const double shift = (i % 2) ? 0x1p26 : 0;  // far from the origin: the filters lose more bits
    Point2 a = on_circle(shift), b = on_circle(shift), c = on_circle(shift), d = on_circle(shift);
    if (i % 4 >= 2) {  // exactly cocircular: a and three of its images
      std::array<int, 7> k{1, 2, 3, 4, 5, 6, 7};
      std::shuffle(k.begin(), k.end(), engine);
      const Point2 o{shift, shift};
      b = image(o, a, k[0]), c = image(o, a, k[1]), d = image(o, a, k[2]);
    }
    const Sign expected = sign_of(in_circle_exact(a, b, c, d));
    ASSERT_EQ(in_circle(a, b, c, d), expected) << i;
    zeros += expected == Sign::zero;
    positives += expected == Sign::positive;
    negatives += expected == Sign::negative;
    // Diametral side and length, exact in doubles for these magnitudes only through the exact stage.
    const Int dot = (Int(std::int64_t(a.x)) - Int(std::int64_t(c.x))) * (Int(std::int64_t(b.x)) - Int(std::int64_t(c.x))) +
                    (Int(std::int64_t(a.y)) - Int(std::int64_t(c.y))) * (Int(std::int64_t(b.y)) - Int(std::int64_t(c.y)));
    ASSERT_EQ(diametral_side(a, b, c), sign_of(dot));
    const Int dx = Int(std::int64_t(a.x)) - Int(std::int64_t(b.x)), dy = Int(std::int64_t(a.y)) - Int(std::int64_t(b.y));
    const double r = std::round(std::sqrt(static_cast<double>(dx * dx + dy * dy)));
    ASSERT_EQ(compare_length(a, b, r), sign_of(dx * dx + dy * dy - Int(std::int64_t(r)) * Int(std::int64_t(r))));
  }
  EXPECT_GT(positives, 1000);
  EXPECT_GT(negatives, 1000);
  EXPECT_GE(zeros, 10000);  // every one of the 10,000 cocircular quadruples
  // Exactly cocircular: the four corners of a rectangle, far from the origin.
  EXPECT_EQ(in_circle({0x1p40, 0x1p40}, {0x1p40 + 3, 0x1p40}, {0x1p40 + 3, 0x1p40 + 7}, {0x1p40, 0x1p40 + 7}), Sign::zero);
  EXPECT_EQ(in_circle({0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}), Sign::positive);
  EXPECT_EQ(in_circle({0, 0}, {1, 0}, {0, 1}, {2, 2}), Sign::negative);
  EXPECT_EQ(diametral_side({0, 0}, {2, 0}, {1, 1}), Sign::zero);  // on the circle (right angle)
  EXPECT_EQ(diametral_side({0, 0}, {2, 0}, {1, 0.5}), Sign::negative);
  EXPECT_EQ(compare_length({0, 0}, {3, 4}, 5), Sign::zero);
  EXPECT_EQ(compare_length({0, 0}, {0.1, 0}, 0.1), Sign::zero);
  EXPECT_EQ(compare_length({0, 0}, {0.1, 0.0}, std::nextafter(0.1, 1.0)), Sign::negative);
}
