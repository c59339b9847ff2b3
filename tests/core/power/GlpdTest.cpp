// GLPD (thesis Def. 5.2.4) and the φ-triangulation G(φ) (Def. 5.2.3).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

using namespace laguerre::core;

namespace {

// k × k grid graph, vertex i + k j at (2i, 2j)·scale with radius `scale`: adjacent circles are
// tangent and the four circles of each square face are orthogonal to the circle of radius `scale`
// at the square's centre — the exact (and exactly degenerate) G-circle packing pattern with face
// circles. Outer face: the outer 4(k−1)-cycle.
struct Grid {
  PlanarGraph g;
  CircleEmbedding phi;
};

Grid grid(int k, double scale = 0.125, std::vector<std::uint64_t> ids = {}) {
  auto idx = [k](int i, int j) { return static_cast<Vertex>(i + k * j); };
  std::vector<std::vector<Vertex>> rot(static_cast<std::size_t>(k * k));
  CircleEmbedding phi(rot.size());
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      auto& r = rot[idx(i, j)];
      if (i + 1 < k) r.push_back(idx(i + 1, j));  // 0°
      if (j + 1 < k) r.push_back(idx(i, j + 1));  // 90°
      if (i > 0) r.push_back(idx(i - 1, j));      // 180°
      if (j > 0) r.push_back(idx(i, j - 1));      // 270°
      phi[idx(i, j)] = {2 * i * scale, 2 * j * scale, scale};
    }
  PlanarGraph g = PlanarGraph::from_rotation(rot, std::move(ids));
  g = g.with_outer_dart(g.find_dart(idx(1, 0), idx(0, 0)));  // left of (1,0)→(0,0) is outside
  return {std::move(g), std::move(phi)};
}

// The convex pentagon of thesis Fig. 5.5 as a 5-cycle: v = 0 at the origin, then (2,−2), (4,−1),
// (4,1), (2,2), all of radius 1 except v.
Grid pentagon(double v_radius) {
  std::vector<std::vector<Vertex>> rot{{1, 4}, {2, 0}, {3, 1}, {4, 2}, {0, 3}};
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  g = g.with_outer_dart(g.find_dart(1, 0));
  CircleEmbedding phi{{0, 0, v_radius}, {2, -2, 1}, {4, -1, 1}, {4, 1, 1}, {2, 2, 1}};
  return {std::move(g), std::move(phi)};
}

// LPD on G(φ), perturbed by the ids, from the graph G(φ) itself.
LocalCondition perturbed_lpd_in(const PlanarGraph& h, const CircleEmbedding& phi, Vertex v) {
  std::vector<Circle> nb;
  std::vector<std::uint64_t> ids;
  Dart d = lpd_first_dart(h, v);
  for (std::uint32_t i = 0; i < h.degree(v); ++i, d = h.next_ccw(d)) {
    nb.push_back(phi[h.head(d)]);
    ids.push_back(h.id(h.head(d)));
  }
  return check_lpd_at_perturbed(phi[v], h.id(v), nb, ids, h.is_boundary(v));
}

bool is_lpd_reason(LocalCondition c) {
  return c == LocalCondition::site_outside_cell || c == LocalCondition::neighbour_order ||
         c == LocalCondition::missing_edge || c == LocalCondition::boundary_vertex_inside_disc;
}

// Diagonals of a triangulation of a convex polygon never cross and there are m − 3 of them.
void expect_triangulation(std::size_t m, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& d) {
  ASSERT_EQ(d.size(), m - 3);
  for (const auto& [a, b] : d) {
    EXPECT_LT(a, b);
    EXPECT_GE(b - a, 2u);
    EXPECT_FALSE(a == 0 && b == m - 1);
    for (const auto& [c, e] : d) {
      const bool cross = (a < c && c < b && b < e) || (c < a && a < e && e < b);
      EXPECT_FALSE(cross) << a << "-" << b << " crosses " << c << "-" << e;
    }
  }
}

}  // namespace

TEST(Glpd, OrthogonalGridPatternHoldsEverywhere) {
  for (int k : {3, 4, 5}) {
    const Grid gr = grid(k);
    ASSERT_TRUE(gr.g.is_valid(true));
    ASSERT_FALSE(gr.g.inner_faces_are_triangles());
    const auto all = check_all(gr.g, gr.phi);
    for (Vertex v = 0; v < all.size(); ++v) {
      EXPECT_EQ(all[v], LocalCondition::holds) << "k = " << k << ", v = " << v;
      EXPECT_EQ(check_local(gr.g, gr.phi, v), all[v]);
    }
  }
}

TEST(Glpd, OrthogonalGridHoldsWhateverTheIds) {
  // The perturbation, hence G(φ), depends on the ids; GLPD must hold for each choice.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint64_t> ids(16);
    std::iota(ids.begin(), ids.end(), std::uint64_t{100});
    std::shuffle(ids.begin(), ids.end(), rng);
    const Grid gr = grid(4, 0.125, ids);
    for (LocalCondition c : check_all(gr.g, gr.phi)) EXPECT_EQ(c, LocalCondition::holds) << "trial " << trial;
  }
}

TEST(Glpd, WithoutThePerturbationTheDegenerateGridWouldFail) {
  // Plain LPD on G(φ) sees the zero-length diagonal edges: this is why GLPD perturbs.
  const Grid gr = grid(3);
  const PlanarGraph h = phi_triangulation(gr.g, gr.phi);
  int failures = 0;
  for (Vertex v = 0; v < h.num_vertices(); ++v) failures += check_lpd(h, gr.phi, v) != LocalCondition::holds;
  EXPECT_GT(failures, 0);
}

TEST(Glpd, NonConvexFaceIsReported) {
  Grid gr = grid(3, 1.0);
  gr.phi[4] = {0.8, 0.8, 1};  // the centre moves into the square (0,0),(2,0),(2,2),(0,2): reflex corner
  EXPECT_EQ(check_glpd(gr.g, gr.phi, 0), LocalCondition::face_not_convex);
  EXPECT_EQ(check_glpd(gr.g, gr.phi, 4), LocalCondition::face_not_convex);
  EXPECT_EQ(check_glpd(gr.g, gr.phi, 8), LocalCondition::holds);  // the far corner's faces are fine
  gr.phi[4] = {1, 1, 1};  // collinear corners: not strictly convex
  EXPECT_EQ(check_glpd(gr.g, gr.phi, 0), LocalCondition::face_not_convex);
  EXPECT_THROW(phi_triangulation(gr.g, gr.phi), laguerre::core::InternalError);
}

TEST(Glpd, LocalCellCrossingAFarFaceEdgeFails) {
  // Thesis Fig. 5.5. With σ(v) = 3.5 the bisectors of v with (2,−2) and (2,2) are 4x ∓ 4y = 19.25,
  // meeting at (4.8125, 0): the local cell in G reaches past the edge [(4,−1), (4,1)]. In G(φ) v is
  // joined to every corner (its lifted point is far below), and LPD holds there.
  const Grid big = pentagon(3.5);
  const auto diagonals = phi_triangulation_diagonals(big.g, big.phi);
  EXPECT_EQ(diagonals, (std::vector<std::pair<Vertex, Vertex>>{{0, 2}, {0, 3}}));
  EXPECT_EQ(perturbed_lpd_in(phi_triangulation(big.g, big.phi), big.phi, 0), LocalCondition::holds);
  EXPECT_EQ(check_glpd(big.g, big.phi, 0), LocalCondition::cell_crosses_face);
  // With σ(v) = 1 the cell's apex is (2, 0), well inside the face.
  const Grid small = pentagon(1.0);
  EXPECT_EQ(check_glpd(small.g, small.phi, 0), LocalCondition::holds);
}

TEST(Glpd, AgreesWithPerturbedLpdOnThePhiTriangulation) {
  // Jittered grids: faces stay convex, G(φ) is generic; the LPD part of GLPD must be exactly the
  // perturbed LPD of v in the graph phi_triangulation builds.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-1, 1);
  int holds = 0, lpd_fails = 0, crossings = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Grid gr = grid(5, 1.0);
    const double amount = trial % 3 == 0 ? 0.1 : trial % 3 == 1 ? 0.3 : 0.55;
    for (Circle& c : gr.phi)
      c = {c.x + amount * jitter(rng), c.y + amount * jitter(rng), c.r * std::exp(2 * amount * jitter(rng))};
    if (trial % 4 == 0) gr.phi[12].r *= 2;  // a swollen centre
    const PlanarGraph h = phi_triangulation(gr.g, gr.phi);
    ASSERT_TRUE(h.is_valid(true));
    ASSERT_TRUE(h.inner_faces_are_triangles());
    ASSERT_EQ(h.num_edges(), gr.g.num_edges() + 16u);  // one diagonal per square
    ASSERT_EQ(h.boundary_cycle(), gr.g.boundary_cycle());
    for (Vertex v = 0; v < gr.g.num_vertices(); ++v) {
      const LocalCondition glpd = check_glpd(gr.g, gr.phi, v);
      const LocalCondition lpd = perturbed_lpd_in(h, gr.phi, v);
      ASSERT_NE(glpd, LocalCondition::face_not_convex);
      if (lpd != LocalCondition::holds) {
        EXPECT_EQ(glpd, lpd) << "trial " << trial << " v " << v;
        ++lpd_fails;
      } else {
        EXPECT_FALSE(is_lpd_reason(glpd)) << "trial " << trial << " v " << v;
        (glpd == LocalCondition::holds ? holds : crossings) += 1;
      }
    }
  }
  std::cout << "  holds " << holds << ", LPD failures " << lpd_fails << ", crossings " << crossings << '\n';
  EXPECT_GT(holds, 1000);
  EXPECT_GT(lpd_fails, 100);
}

TEST(PhiTriangulation, SquareTieIsBrokenByIds) {
  // Four unit circles at the corners of a 2 × 2 square: all orthogonal to the unit circle at its
  // centre, so both diagonals are regular. The perturbation raises the smallest id most, making it an
  // ear: the diagonal avoids it.
  const std::vector<Circle> sq{{0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
  using D = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  EXPECT_EQ(regular_triangulation_diagonals(sq, std::vector<std::uint64_t>{0, 1, 2, 3}), (D{{1, 3}}));
  EXPECT_EQ(regular_triangulation_diagonals(sq, std::vector<std::uint64_t>{5, 0, 7, 9}), (D{{0, 2}}));
  EXPECT_EQ(regular_triangulation_diagonals(sq, std::vector<std::uint64_t>{5, 8, 7, 1}), (D{{0, 2}}));
  // Without the tie, the smaller circle's corner is cut off.
  const std::vector<Circle> uneven{{0, 0, 0.5}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
  EXPECT_EQ(regular_triangulation_diagonals(uneven, std::vector<std::uint64_t>{9, 1, 2, 3}), (D{{1, 3}}));
}

TEST(PhiTriangulation, DoesNotDependOnTheStartingCorner) {
  // Twelve equal circles centred on the integer points of the circle of radius 5: exactly degenerate
  // (one common orthogonal circle), so the triangulation is decided by the ids alone; every rotation
  // of the input must give the same edges.
  const std::vector<Circle> poly{{5, 0, 1},  {4, 3, 1},   {3, 4, 1},   {0, 5, 1},  {-3, 4, 1}, {-4, 3, 1},
                                 {-5, 0, 1}, {-4, -3, 1}, {-3, -4, 1}, {0, -5, 1}, {3, -4, 1}, {4, -3, 1}};
  const std::size_t m = poly.size();
  const std::vector<std::uint64_t> ids{40, 3, 17, 8, 99, 21, 5, 60, 12, 33, 2, 71};
  auto as_id_pairs = [&](std::size_t shift) {
    std::vector<Circle> p(m);
    std::vector<std::uint64_t> q(m);
    for (std::size_t i = 0; i < m; ++i) {
      p[i] = poly[(i + shift) % m];
      q[i] = ids[(i + shift) % m];
    }
    const auto d = regular_triangulation_diagonals(p, q);
    expect_triangulation(m, d);
    std::set<std::pair<std::uint64_t, std::uint64_t>> out;
    for (auto [a, b] : d) out.emplace(std::min(q[a], q[b]), std::max(q[a], q[b]));
    return out;
  };
  const auto reference = as_id_pairs(0);
  for (std::size_t s = 1; s < m; ++s) EXPECT_EQ(as_id_pairs(s), reference) << "shift " << s;
  // The smallest id (2) is raised most: it is an ear, no diagonal touches it.
  for (const auto& [a, b] : reference) EXPECT_TRUE(a != 2 && b != 2);
}

TEST(PhiTriangulation, MatchesBruteForceLowerHull) {
  // Random convex polygons with random radii: generic, so the regular triangulation is the set of
  // triangles with every other lifted point strictly above their plane (O(m^4) search).
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t m = 4 + static_cast<std::size_t>(trial % 9);
    std::vector<double> angles(m);
    for (double& a : angles) a = 2 * std::numbers::pi * u01(rng);
    std::sort(angles.begin(), angles.end());
    std::vector<Circle> poly;
    for (double a : angles) poly.push_back({std::cos(a), std::sin(a), 0.05 + 0.5 * u01(rng)});
    if (!is_strictly_convex(poly)) continue;
    std::vector<std::uint64_t> ids(m);
    std::iota(ids.begin(), ids.end(), std::uint64_t{0});
    std::set<std::pair<std::uint32_t, std::uint32_t>> brute;
    for (std::uint32_t a = 0; a < m; ++a)
      for (std::uint32_t b = a + 1; b < m; ++b)
        for (std::uint32_t c = b + 1; c < m; ++c) {
          bool lower = true;
          for (std::uint32_t t = 0; t < m && lower; ++t)
            if (t != a && t != b && t != c)
              lower = radical_centre_power_side(poly[a], poly[b], poly[c], poly[t]) == Sign::positive;
          if (!lower) continue;
          for (auto [x, y] : {std::pair{a, b}, std::pair{b, c}, std::pair{a, c}})
            if (y - x >= 2 && !(x == 0 && y == m - 1)) brute.emplace(x, y);
        }
    const auto d = regular_triangulation_diagonals(poly, ids);
    expect_triangulation(m, d);
    EXPECT_EQ(std::set(d.begin(), d.end()), brute) << "trial " << trial;
  }
}

TEST(PhiTriangulation, BuildsAValidTriangulatedGraph) {
  const Grid gr = grid(4, 0.125, {});
  const PlanarGraph h = phi_triangulation(gr.g, gr.phi);
  ASSERT_TRUE(h.is_valid(true));
  EXPECT_TRUE(h.inner_faces_are_triangles());
  EXPECT_EQ(h.num_vertices(), gr.g.num_vertices());
  EXPECT_EQ(h.num_edges(), gr.g.num_edges() + 9u);
  EXPECT_EQ(h.ids(), gr.g.ids());
  EXPECT_EQ(h.boundary_cycle(), gr.g.boundary_cycle());
  // Every G edge survives, and the diagonals are those listed.
  for (Dart d = 0; d < gr.g.num_darts(); ++d) EXPECT_NE(h.find_dart(gr.g.tail(d), gr.g.head(d)), none);
  for (const auto& [a, b] : phi_triangulation_diagonals(gr.g, gr.phi)) EXPECT_NE(h.find_dart(a, b), none);
  // Rotations stay counter-clockwise in the embedding: every inner face of G(φ) is a ccw triangle.
  for (Face f = 0; f < h.num_faces(); ++f) {
    if (f == h.outer_face()) continue;
    const auto darts = h.face_darts(f);
    EXPECT_EQ(orientation(centre(gr.phi[h.tail(darts[0])]), centre(gr.phi[h.tail(darts[1])]),
                          centre(gr.phi[h.tail(darts[2])])),
              Sign::positive);
  }
  // Triangulated input is returned unchanged.
  const PlanarGraph again = phi_triangulation(h, gr.phi);
  EXPECT_EQ(again.num_edges(), h.num_edges());
}
