// check_lpd_at against a slow, independent, exact oracle on seeded random configurations.
//
// The configurations have integer centres and radii divided by a power of two D, so the doubles are
// exact and the oracle can work in integers: the local cell C = ∩ {x : a_i·x ≤ b_i}, with
// a_i = 2 (p(w_i) − p(v)) and b_i = z(w_i) − z(v), z = |p|² − r², is computed facet by facet: the
// part of each line a_i·x = b_i inside C is an interval found by clipping against every other
// constraint (rational bounds compared by cross-multiplication in __int128). The oracle then reads
// the definition directly: p(v) ∈ C; every facet of positive length; facets in counter-clockwise
// order of their normals; for an interior vertex a bounded cell whose cyclic facet order is w1 … wn;
// for a boundary vertex either a bounded cell with that cyclic order and outer corner L_n ∩ L_1
// strictly outside the unit disc, or an unbounded cell whose facets run w1 … wn between its two rays.
// Small coordinates make exact degeneracies (concurrent bisectors, collinear centres) frequent.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <numeric>
#include <random>
#include <iostream>
#include <vector>

#include "laguerre/core/power/LocalPowerDiagram.hpp"

using namespace laguerre::core;

namespace {

__extension__ typedef __int128 i128;  // GCC/Clang extension; magnitudes here stay below 2^100

struct ICircle {
  std::int64_t x, y, r;
};

struct Fraction {  // num / den with den > 0
  i128 num, den;
};
bool less(const Fraction& a, const Fraction& b) { return a.num * b.den < b.num * a.den; }

// Half-plane class of a non-zero direction: upper = angle in [0, π).
bool upper(std::int64_t dx, std::int64_t dy) { return dy > 0 || (dy == 0 && dx > 0); }
i128 cross(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by) {
  return static_cast<i128>(ax) * by - static_cast<i128>(ay) * bx;
}

bool oracle_lpd(const ICircle& v, const std::vector<ICircle>& w, bool boundary, std::int64_t disc) {
  const std::size_t n = w.size();
  auto z = [](const ICircle& c) { return c.x * c.x + c.y * c.y - c.r * c.r; };
  std::vector<std::int64_t> ax(n), ay(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    ax[i] = 2 * (w[i].x - v.x);
    ay[i] = 2 * (w[i].y - v.y);
    b[i] = z(w[i]) - z(v);
  }
  // p(v) in the closed cell.
  for (std::size_t i = 0; i < n; ++i)
    if (static_cast<i128>(ax[i]) * v.x + static_cast<i128>(ay[i]) * v.y > b[i]) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (ax[i] == 0 && ay[i] == 0) return false;  // no bisector: no edge
  // Every facet has positive length.
  for (std::size_t i = 0; i < n; ++i) {
    const i128 norm2 = static_cast<i128>(ax[i]) * ax[i] + static_cast<i128>(ay[i]) * ay[i];
    bool has_lo = false, has_hi = false;
    Fraction lo{0, 1}, hi{0, 1};
    bool empty = false;
    for (std::size_t j = 0; j < n && !empty; ++j) {
      if (j == i) continue;
      // x = x0 + s d, d = (−ay_i, ax_i), σ = s |a_i|²: constraint σ α ≤ β.
      const i128 alpha = -static_cast<i128>(ax[j]) * ay[i] + static_cast<i128>(ay[j]) * ax[i];
      const i128 dot = static_cast<i128>(ax[j]) * ax[i] + static_cast<i128>(ay[j]) * ay[i];
      const i128 beta = static_cast<i128>(b[j]) * norm2 - dot * b[i];
      if (alpha == 0) {
        if (beta < 0) empty = true;
        continue;
      }
      const Fraction bound = alpha > 0 ? Fraction{beta, alpha} : Fraction{-beta, -alpha};
      if (alpha > 0) {
        if (!has_hi || less(bound, hi)) hi = bound;
        has_hi = true;
      } else {
        if (!has_lo || less(lo, bound)) lo = bound;
        has_lo = true;
      }
    }
    if (empty) return false;
    if (has_lo && has_hi && !less(lo, hi)) return false;  // empty or a single point
  }
  if (n == 1) return boundary;
  // Facets sorted counter-clockwise by normal angle; equal angles are not allowed.
  std::vector<std::size_t> s(n);
  std::iota(s.begin(), s.end(), 0);
  auto angle_less = [&](std::size_t i, std::size_t j) {
    const bool ui = upper(ax[i], ay[i]), uj = upper(ax[j], ay[j]);
    if (ui != uj) return ui;
    return cross(ax[i], ay[i], ax[j], ay[j]) > 0;
  };
  std::sort(s.begin(), s.end(), angle_less);
  for (std::size_t k = 0; k + 1 < n; ++k)
    if (!angle_less(s[k], s[k + 1])) return false;
  // Gaps between cyclically consecutive normals: < π iff the cross product is positive.
  std::size_t big_gaps = 0, big_at = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = s[k], j = s[(k + 1) % n];
    if (cross(ax[i], ay[i], ax[j], ay[j]) <= 0) {
      ++big_gaps;
      big_at = k;
    }
  }
  auto runs_from = [&](std::size_t k0) {  // the sorted order, read from position k0, is 0, 1, …, n−1
    for (std::size_t t = 0; t < n; ++t)
      if (s[(k0 + t) % n] != t) return false;
    return true;
  };
  if (big_gaps == 0) {  // bounded
    bool cyclic = false;
    for (std::size_t k0 = 0; k0 < n; ++k0) cyclic = cyclic || runs_from(k0);
    if (!cyclic) return false;
    if (!boundary) return true;
    // Outer corner L_{n} ∩ L_{1} strictly outside the disc of radius `disc` (integer units).
    const std::size_t a = n - 1, c = 0;
    const i128 det = cross(ax[a], ay[a], ax[c], ay[c]);
    const i128 X = static_cast<i128>(b[a]) * ay[c] - static_cast<i128>(b[c]) * ay[a];
    const i128 Y = static_cast<i128>(ax[a]) * b[c] - static_cast<i128>(ax[c]) * b[a];
    return X * X + Y * Y > static_cast<i128>(disc) * disc * det * det;
  }
  if (!boundary || big_gaps > 1) return false;  // unbounded interior cell, or a strip
  return runs_from((big_at + 1) % n);
}

struct Config {
  ICircle v;
  std::vector<ICircle> w;
  bool boundary;
  std::int64_t disc;  // doubles = integers / disc; the unit disc has radius `disc`
};

Circle to_circle(const ICircle& c, std::int64_t disc) {
  const double s = 1.0 / static_cast<double>(disc);
  return {static_cast<double>(c.x) * s, static_cast<double>(c.y) * s, static_cast<double>(c.r) * s};
}

// Flower-like: neighbours roughly tangent around v, with jitter, occasional swaps.
Config flower_config(std::mt19937_64& rng) {
  auto uni = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  Config c;
  c.boundary = uni(0, 2) == 0;
  c.disc = 64;
  c.v = {uni(-40, 40), uni(-40, 40), uni(4, 30)};
  const auto n = static_cast<std::size_t>(c.boundary ? uni(2, 8) : uni(3, 9));
  const double span = c.boundary ? std::uniform_real_distribution<double>(1.0, 4.5)(rng) : 2 * std::numbers::pi;
  const double start = std::uniform_real_distribution<double>(0, 2 * std::numbers::pi)(rng);
  const double step = span / static_cast<double>(c.boundary ? n - 1 : n);
  for (std::size_t i = 0; i < n; ++i) {
    const double angle = start + step * (static_cast<double>(i) + std::uniform_real_distribution<double>(-0.35, 0.35)(rng));
    const std::int64_t r = uni(3, 30);
    const double dist = static_cast<double>(c.v.r + r + uni(-6, 10));
    c.w.push_back({c.v.x + std::llround(dist * std::cos(angle)), c.v.y + std::llround(dist * std::sin(angle)), r});
  }
  if (uni(0, 9) == 0) std::swap(c.w[0], c.w[static_cast<std::size_t>(uni(1, static_cast<std::int64_t>(n) - 1))]);
  return c;
}

// Small integers: many exact degeneracies.
Config tiny_config(std::mt19937_64& rng) {
  auto uni = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  Config c;
  c.boundary = uni(0, 1) == 0;
  c.disc = 4;
  c.v = {0, 0, uni(0, 3)};
  const auto n = static_cast<std::size_t>(uni(2, 7));
  // Directions sorted by angle so that many configurations are plausible.
  std::vector<ICircle> w;
  for (std::size_t i = 0; i < n; ++i) {
    ICircle x{uni(-5, 5), uni(-5, 5), uni(0, 4)};
    if (x.x == 0 && x.y == 0 && uni(0, 3) != 0) x.x = 1;
    w.push_back(x);
  }
  if (uni(0, 4) != 0) {
    std::sort(w.begin(), w.end(), [](const ICircle& a, const ICircle& b) {
      return std::atan2(static_cast<double>(a.y), static_cast<double>(a.x)) <
             std::atan2(static_cast<double>(b.y), static_cast<double>(b.x));
    });
    std::rotate(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(uni(0, static_cast<std::int64_t>(n) - 1)), w.end());
  }
  c.w = w;
  return c;
}

void run_oracle(Config (*make)(std::mt19937_64&), std::uint64_t seed, int count, int min_holds, int min_fails) {
  std::mt19937_64 rng(seed);
  int holds = 0, fails = 0;
  std::map<LocalCondition, int> reasons;
  for (int t = 0; t < count; ++t) {
    const Config c = make(rng);
    std::vector<Circle> w;
    for (const ICircle& x : c.w) w.push_back(to_circle(x, c.disc));
    const LocalCondition got = check_lpd_at(to_circle(c.v, c.disc), w, c.boundary);
    const bool want = oracle_lpd(c.v, c.w, c.boundary, c.disc);
    ++reasons[got];
    (want ? holds : fails) += 1;
    if ((got == LocalCondition::holds) != want) {
      std::string dump = "v = (" + std::to_string(c.v.x) + "," + std::to_string(c.v.y) + "," + std::to_string(c.v.r) + ") w =";
      for (const ICircle& x : c.w) dump += " (" + std::to_string(x.x) + "," + std::to_string(x.y) + "," + std::to_string(x.r) + ")";
      ADD_FAILURE() << "case " << t << (c.boundary ? " boundary" : " interior") << " disc " << c.disc << ": " << dump
                    << "\n  check_lpd_at = " << to_string(got) << ", oracle = " << want;
      return;
    }
  }
  EXPECT_GE(holds, min_holds);
  EXPECT_GE(fails, min_fails);
  for (const auto& [r, k] : reasons) std::cout << "  " << to_string(r) << ": " << k << '\n';
}

}  // namespace

TEST(LpdOracle, FlowerLikeConfigurationsAgree) { run_oracle(&flower_config, 20240611, 40000, 5000, 5000); }

TEST(LpdOracle, TinyDegenerateConfigurationsAgree) { run_oracle(&tiny_config, 77, 60000, 2000, 20000); }
