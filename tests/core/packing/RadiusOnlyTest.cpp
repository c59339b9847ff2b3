// The radius-only test (docs/radius-only.md) against the exact layout-based LPD check.
//
// 1. The theorem: on a consistent star (its tangencies hold) the corner tests decide LPD(v) exactly,
//    in every Möbius normalization. Random stars are laid out from random radii (boundary stars are
//    always consistent; interior stars are closed by solving θ(v) = 2π for h_v), moved by random
//    disc automorphisms, and `check_lpd_at` on the moved circles is compared with
//    the radius-only test. Every consistent star satisfies LPD (docs/radius-only.md, Theorem 1): "holds" in
//    every frame, and every corner test in the local frame of two triangles passes (Lemma 1).
// 2. core::pack with Termination::radius_only never claims LPD on a failed check and ends with the
//    same embedding guarantee as the layout termination.
// The agreement before convergence is tests/core/property/RadiusOnlyAgreementProperty.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <numbers>
#include <bit>
#include <vector>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/Placement.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/core/random/Random.hpp"

using namespace laguerre::core;
using Complex = std::complex<double>;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// A random hyperbolic radius over several orders of magnitude, or a horocycle.
double random_h(SplitMix64& rng) { return std::exp(-6 + 8 * rng.uniform01()); }

// Image of a Euclidean circle inside the unit disc under z ↦ (z − a)/(1 − ā z) (through 3 points).
Circle moved(const Circle& c, Complex a) {
  auto m = [&](Complex z) { return (z - a) / (1.0 - std::conj(a) * z); };
  const Complex p = m(Complex(c.x + c.r, c.y)), q = m(Complex(c.x, c.y + c.r)), r = m(Complex(c.x - c.r, c.y));
  const Complex b = q - p, d = r - p;
  const double den = 2 * (b.real() * d.imag() - b.imag() * d.real());
  const double bb = std::norm(b), dd = std::norm(d);
  const Complex o = p + Complex((d.imag() * bb - b.imag() * dd) / den, (b.real() * dd - d.real() * bb) / den);
  return {o.real(), o.imag(), std::abs(p - o)};
}

// Lays out the chain of tangent triangles (v, w_i, w_{i+1}), i = 0 … n−2, from the radii: v at the
// origin if interior, else w_j (an interior neighbour) at the origin. Returns v's circle then the w's.
std::vector<Circle> chain(double hv, const std::vector<double>& hw) {
  auto lv = [](double h) { return LayoutVertex{h, std::isfinite(h)}; };
  const std::size_t n = hw.size();
  std::vector<PlacedCircle> p(n);
  PlacedCircle pv;
  if (std::isfinite(hv)) {
    pv = place_root(hv);
    p[0] = place_first_neighbour(hv, lv(hw[0]), 1.0);
  } else {
    pv = place_root(hw[1]);  // boundary star: w_1 (index 1) is interior in these tests
    std::swap(pv, p[1]);
    pv = place_first_neighbour(hw[1], lv(hv), 1.0);
    p[0] = place_in_face(lv(hw[0]), lv(hw[1]), p[1], lv(hv), pv, {});
  }
  const std::size_t from = std::isfinite(hv) ? 1 : 2;
  for (std::size_t i = from; i < n; ++i) p[i] = place_in_face(lv(hw[i]), lv(hv), pv, lv(hw[i - 1]), p[i - 1], {});
  std::vector<Circle> out{pv.circle};
  for (const PlacedCircle& c : p) out.push_back(c.circle);
  return out;
}

// The corner test of the brief's local frame: the inversive distance between w_{i+1} = c and the orthocircle of (v, a = w_{i−1},
// b = w_i), for circles laid out consistently from the radii (two tangent triangles (v, a, b),
// (v, b, c), counter-clockwise), rooted at an interior one of them. NaN if all four are horocycles.
double corner_inversive_distance(double hv, double ha, double hb, double hc) {
  auto lv = [](double h) { return LayoutVertex{h, std::isfinite(h)}; };
  const LayoutVertex V = lv(hv), A = lv(ha), B = lv(hb), C = lv(hc);
  PlacedCircle pv, pa, pb, pc;
  if (V.interior || B.interior) {
    pv = V.interior ? place_root(hv) : place_first_neighbour(hb, V, 1.0);
    pb = V.interior ? place_first_neighbour(hv, B, 1.0) : place_root(hb);
    pa = place_in_face(A, B, pb, V, pv, {});  // (a, b, v) counter-clockwise
    pc = place_in_face(C, V, pv, B, pb, {});  // (c, v, b)
  } else if (A.interior) {
    pa = place_root(ha);
    pv = place_first_neighbour(ha, V, 1.0);
    pb = place_in_face(B, V, pv, A, pa, {});
    pc = place_in_face(C, V, pv, B, pb, {});
  } else if (C.interior) {
    pc = place_root(hc);
    pv = place_first_neighbour(hc, V, 1.0);
    pb = place_in_face(B, C, pc, V, pv, {});
    pa = place_in_face(A, B, pb, V, pv, {});
  } else {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const Circle &v = pv.circle, &a = pa.circle, &b = pb.circle, &c = pc.circle;
  // Radical centre q of (v, a, b) and ρ² = pow(q, v); I = (pow(q, c) − ρ²) / (2 r_c ρ).
  auto z = [](const Circle& x) { return x.x * x.x + x.y * x.y - x.r * x.r; };
  const double ax = 2 * (a.x - v.x), ay = 2 * (a.y - v.y), bx = 2 * (b.x - v.x), by = 2 * (b.y - v.y);
  const double ra = z(a) - z(v), rb = z(b) - z(v), det = ax * by - ay * bx;
  const double qx = (ra * by - ay * rb) / det, qy = (ax * rb - ra * bx) / det;
  const double rho2 = power(qx, qy, v);
  return (power(qx, qy, c) - rho2) / (2 * c.r * std::sqrt(rho2));
}

double solve_closed(const std::vector<double>& hw) {
  // θ(h) decreases from deg·π to 0: bisect θ(h) = 2π in log h.
  double lo = -40, hi = 10;
  const StarView s{hw, {}, {}};
  for (int k = 0; k < 200; ++k) {
    const double mid = (lo + hi) / 2;
    (star_angle_sum(std::exp(mid), s) > 2 * std::numbers::pi ? lo : hi) = mid;
  }
  return std::exp((lo + hi) / 2);
}

struct Outcomes {
  int both = 0, neither = 0, radius_only = 0, layout_only = 0;
  void add(bool r, bool l) { (r ? (l ? both : radius_only) : (l ? layout_only : neither)) += 1; }
  int total() const { return both + neither + radius_only + layout_only; }
};
std::ostream& operator<<(std::ostream& o, const Outcomes& c) {
  return o << "both hold " << c.both << ", neither " << c.neither << ", radius-only only " << c.radius_only
           << ", layout only " << c.layout_only;
}

// At the cap a gated termination still lays out the current radii and checks them, whatever its
// tests said: one layout, three iterations, the reported conditions those of the exact check.
void expect_cap_ends_with_a_checked_layout(Termination t) {
  PackOptions capped;
  capped.termination = t;
  capped.max_iterations = 3;
  const PlanarGraph g = prepare_for_packing(random_delaunay_triangulation(200, 3));
  const PackResult c = pack(g, capped);
  EXPECT_EQ(c.status, PackStatus::iteration_cap) << to_string(t);
  EXPECT_EQ(c.layouts, 1) << to_string(t);
  EXPECT_EQ(c.iterations, 3) << to_string(t);
  EXPECT_EQ(check_all(g, c.circles), c.local) << to_string(t);
}

}  // namespace

TEST(RadiusOnly, ConsistentStarsDecideLpdInEveryMoebiusFrame) {
  SplitMix64 rng(17);
  Outcomes interior, boundary;
  double min_corner = inf;
  for (int trial = 0; trial < 4000; ++trial) {
    const bool is_boundary = trial % 2 == 1;
    const std::size_t n = (is_boundary ? 2 : 3) + rng.next() % 7;
    std::vector<double> hw(n);
    for (double& h : hw) h = random_h(rng);
    double hv;
    if (is_boundary) {
      if (n < 3) hw.push_back(random_h(rng));
      hw.front() = hw.back() = inf;  // w1, wn on the boundary
      hv = inf;
    } else {
      hv = solve_closed(hw);
    }
    // Lemma 1 (b): every corner test of two consistent triangles passes, in a frame laid out from the
    // radii (the brief's local normalized layout): its inversive distance is positive.
    for (std::size_t i = is_boundary ? 1 : 0; i < (is_boundary ? n - 1 : n); ++i) {
      const double d = corner_inversive_distance(hv, hw[(i + n - 1) % n], hw[i], hw[(i + 1) % n]);
      ASSERT_GT(d, 0) << "trial " << trial << " corner " << i;
      min_corner = std::min(min_corner, d);
    }
    const bool r = radius_only_holds(hv, StarView{hw, {}, {}}, is_boundary, 1e-9);
    ASSERT_TRUE(r) << "a closed star has no closing gap";
    const std::vector<Circle> c = chain(hv, hw);
    for (int m = 0; m < 4; ++m) {
      const double rad = 0.9 * std::sqrt(rng.uniform01()), ang = 2 * std::numbers::pi * rng.uniform01();
      const Complex a = m == 0 ? 0.0 : std::polar(rad, ang);
      std::vector<Circle> moved_star;
      for (std::size_t i = 1; i < c.size(); ++i) moved_star.push_back(moved(c[i], a));
      const LocalCondition l = check_lpd_at(moved(c[0], a), moved_star, is_boundary);
      (is_boundary ? boundary : interior).add(r, l == LocalCondition::holds);
      EXPECT_EQ(l, LocalCondition::holds) << "trial " << trial << " frame " << m;
    }
  }
  std::cout << "consistent interior stars: " << interior << "\nconsistent boundary stars: " << boundary
            << "\nsmallest corner inversive distance: " << min_corner << "\n";
  // docs/radius-only.md, Theorem 1: a consistent star satisfies LPD in every frame.
  EXPECT_EQ(interior.both, interior.total());
  EXPECT_EQ(boundary.both, boundary.total());
  EXPECT_GT(interior.total(), 7000);
}

TEST(RadiusOnly, PackWithRadiusOnlyTerminationClaimsOnlyCheckedLpd) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const PlanarGraph g = prepare_for_packing(seed % 2 ? random_delaunay_triangulation(60, seed)
                                                       : random_three_connected(60, seed));
    PackOptions layout, radius;
    radius.termination = Termination::radius_only;
    const PackResult a = pack(g, layout), b = pack(g, radius);
    ASSERT_EQ(b.status, PackStatus::converged) << seed;
    EXPECT_EQ(b.local_ok, g.num_vertices());
    EXPECT_EQ(check_all(g, b.circles), b.local);  // the claim is the exact check on the final layout
    // The radius-only run stops no earlier than the layout run (it checks a subset of the
    // iterations), and computes fewer layouts.
    EXPECT_GE(b.iterations, a.iterations);
    EXPECT_LT(b.layouts, a.layouts);
    EXPECT_EQ(a.layouts, a.iterations + 1);
  }
  expect_cap_ends_with_a_checked_layout(Termination::radius_only);
  EXPECT_EQ(parse_termination("radius-only"), Termination::radius_only);
  EXPECT_EQ(parse_termination("radius-flood"), Termination::radius_flood);
  EXPECT_EQ(to_string(Termination::layout), "layout");
}

// The flooded gate (Termination::radius_flood, docs/radius-only.md §8): the AND of the gap test
// travels on the radius exchange and is known D steps after the tested step, D = 2·(layout-tree
// height) + 2 ≥ the diameter of K. The run tests the same iterates as the convergecast gate, lays out
// the tested iterate D steps later, claims LPD only on a passed exact check, and, when the first
// gated check passes, ends with the convergecast gate's radii bit for bit.
TEST(RadiusOnly, FloodedGateLaysOutTheTestedIterateDStepsLater) {
  int same = 0, failed_checks = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed)
    for (double gap : {1e-2, 0.3}) {
      const PlanarGraph g = prepare_for_packing(seed % 2 ? random_delaunay_triangulation(60, seed)
                                                         : random_three_connected(60, seed));
      PackOptions gate;
      gate.termination = Termination::radius_only;
      gate.steps_per_check = 1 + static_cast<int>(seed % 3);
      gate.radius_only_gap = gap;
      PackOptions flood = gate;
      flood.termination = Termination::radius_flood;
      const PackResult a = pack(g, gate), b = pack(g, flood);
      SCOPED_TRACE("seed " + std::to_string(seed) + " gap " + std::to_string(gap));
      ASSERT_EQ(b.status, PackStatus::converged);
      EXPECT_EQ(b.local_ok, g.num_vertices());
      EXPECT_EQ(check_all(g, b.circles), b.local);
      // D from the combinatorial layout tree, and D ≥ the diameter of K (BFS from every vertex).
      const PackingComplex k = PackingComplex::from_graph(g);
      const auto depth = static_cast<int>(radius_flood_depth(lay_out(k, initial_radii(k), choose_root(k, RootRule::deepest))));
      EXPECT_EQ(b.flood_depth, depth);
      const PlanarGraph& kg = k.graph;
      for (Vertex s = 0; s < kg.num_vertices(); ++s) {
        std::vector<int> d(kg.num_vertices(), -1);
        std::vector<Vertex> queue{s};
        d[s] = 0;
        for (std::size_t q = 0; q < queue.size(); ++q)
          for (Dart e = kg.first_dart(queue[q]); e < kg.first_dart(queue[q]) + kg.degree(queue[q]); ++e)
            if (d[kg.head(e)] < 0) {
              d[kg.head(e)] = d[queue[q]] + 1;
              queue.push_back(kg.head(e));
            }
        for (int x : d) EXPECT_LE(x, depth);
      }
      EXPECT_EQ(b.decision_step, b.iterations + depth);
      EXPECT_EQ(b.iterations % gate.steps_per_check, 0);
      if (a.layouts == 1) {  // the first gated check passed: the same iterate, D steps later
        ++same;
        EXPECT_EQ(b.layouts, 1);
        EXPECT_EQ(b.iterations, a.iterations);
        ASSERT_EQ(b.radii.size(), a.radii.size());
        for (std::size_t v = 0; v < a.radii.size(); ++v) EXPECT_EQ(std::bit_cast<std::uint64_t>(b.radii[v]), std::bit_cast<std::uint64_t>(a.radii[v])) << v;
      } else {
        failed_checks += b.layouts - 1;
      }
    }
  EXPECT_GT(same, 0);
  EXPECT_GT(failed_checks, 0);  // both outcomes of the exact check occur
  expect_cap_ends_with_a_checked_layout(Termination::radius_flood);
  EXPECT_EQ(radius_flood_period(126, 2), 1);
  EXPECT_EQ(radius_flood_period(127, 2), 2);
  EXPECT_TRUE(radius_flood_tested(12, 3, 2));
  EXPECT_FALSE(radius_flood_tested(9, 3, 2));
}
