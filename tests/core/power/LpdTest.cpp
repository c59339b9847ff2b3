// LPD (thesis Def. 5.2.2) on hand-built configurations with known outcomes.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "laguerre/core/power/LocalPowerDiagram.hpp"

using namespace laguerre::core;

namespace {

constexpr double pi = std::numbers::pi;

// Six unit circles around a unit circle at the origin, all tangent: the local cell of the centre is
// the regular hexagon of the six tangent lines.
std::vector<Circle> hexagon_petals(double distance = 2.0, double radius = 1.0) {
  std::vector<Circle> petals;
  for (int k = 0; k < 6; ++k)
    petals.push_back({distance * std::cos(k * pi / 3), distance * std::sin(k * pi / 3), radius});
  return petals;
}

const Circle unit_at_origin{0, 0, 1};

// The hexagon flower as a triangulated disc: centre 0, petals 1..6 counter-clockwise, scaled by 1/3
// so that the petals are internally tangent to the unit circle (an exact maximal packing, up to the
// rounding of the stored doubles).
PlanarGraph flower_graph() {
  std::vector<std::vector<Vertex>> rot(7);
  rot[0] = {1, 2, 3, 4, 5, 6};
  for (Vertex k = 1; k <= 6; ++k) {
    const Vertex next = k == 6 ? 1 : k + 1, prev = k == 1 ? 6 : k - 1;
    rot[k] = {0, prev, next};  // counter-clockwise seen from petal k: centre, previous, next petal
  }
  // Outer face: to the left of petal dart 1→2? The inner triangle (0, 1, 2) is ccw, so the outer face
  // is to the left of 2→1.
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  return g.with_outer_dart(g.find_dart(2, 1));
}

CircleEmbedding flower_embedding() {
  CircleEmbedding phi{{0, 0, 1.0 / 3}};
  for (const Circle& c : hexagon_petals(2.0 / 3, 1.0 / 3)) phi.push_back(c);
  return phi;
}

}  // namespace

TEST(Lpd, ToStringNamesEveryOutcome) {
  EXPECT_EQ(to_string(LocalCondition::holds), "holds");
  EXPECT_EQ(to_string(LocalCondition::missing_edge), "missing_edge");
  EXPECT_EQ(to_string(LocalCondition::cell_crosses_face), "cell_crosses_face");
}

TEST(Lpd, TangentHexagonFlowerHolds) {
  const auto petals = hexagon_petals();
  EXPECT_EQ(check_lpd_at(unit_at_origin, petals, false), LocalCondition::holds);
  // Any cyclic rotation of the list describes the same vertex.
  std::vector<Circle> rotated(petals.begin() + 2, petals.end());
  rotated.insert(rotated.end(), petals.begin(), petals.begin() + 2);
  EXPECT_EQ(check_lpd_at(unit_at_origin, rotated, false), LocalCondition::holds);
}

TEST(Lpd, PullingOnePetalAwayLosesItsEdge) {
  // Petal 0 at distance d (radius 1): its bisector is the line x = d/2; the neighbouring tangent lines
  // meet on the x axis at x = 2, so the edge shrinks to nothing at d = 4.
  for (double d : {2.5, 3.0, 3.9}) {
    auto petals = hexagon_petals();
    petals[0] = {d, 0, 1};
    EXPECT_EQ(check_lpd_at(unit_at_origin, petals, false), LocalCondition::holds) << "d = " << d;
  }
  for (double d : {4.1, 5.0, 10.0}) {
    auto petals = hexagon_petals();
    petals[0] = {d, 0, 1};
    EXPECT_EQ(check_lpd_at(unit_at_origin, petals, false), LocalCondition::missing_edge) << "d = " << d;
  }
}

TEST(Lpd, SwappedNeighboursAreOutOfOrder) {
  auto petals = hexagon_petals();
  std::swap(petals[1], petals[2]);
  EXPECT_EQ(check_lpd_at(unit_at_origin, petals, false), LocalCondition::neighbour_order);
  // Clockwise listing.
  auto cw = hexagon_petals();
  std::reverse(cw.begin(), cw.end());
  EXPECT_EQ(check_lpd_at(unit_at_origin, cw, false), LocalCondition::neighbour_order);
}

TEST(Lpd, NeighboursWindingTwiceAreOutOfOrder) {
  // Six directions 120° apart visit every direction twice: all left turns, winding number 2.
  std::vector<Circle> twice;
  for (int k = 0; k < 6; ++k) twice.push_back({2 * std::cos(k * 2 * pi / 3), 2 * std::sin(k * 2 * pi / 3), 1});
  EXPECT_EQ(check_lpd_at(unit_at_origin, twice, false), LocalCondition::neighbour_order);
}

TEST(Lpd, SwollenNeighbourSwallowsTheSite) {
  // pow(0, v) = −1 and pow(0, w) = 4 − r²: p(v) leaves its cell when r² > 5.
  auto petals = hexagon_petals();
  petals[3].r = 2.5;
  EXPECT_EQ(check_lpd_at(unit_at_origin, petals, false), LocalCondition::site_outside_cell);
  petals[3].r = 2.0;  // pow(0, w) = 0 > −1: still inside, but the big petal eats its neighbours' edges
  EXPECT_NE(check_lpd_at(unit_at_origin, petals, false), LocalCondition::site_outside_cell);
}

TEST(Lpd, UnboundedInteriorCellFails) {
  // Three neighbours within a half-plane: the cell is unbounded, the cyclic order cannot close.
  const std::vector<Circle> w{{2, 0, 1}, {0, 2, 1}, {-2, 0, 1}};
  EXPECT_EQ(check_lpd_at(unit_at_origin, w, false), LocalCondition::neighbour_order);
  // The same chain is fine for a boundary vertex whose outer face is below.
  EXPECT_EQ(check_lpd_at(unit_at_origin, w, true), LocalCondition::holds);
}

TEST(Lpd, ExactlyDegenerateZeroLengthEdgeIsNoAdjacency) {
  // Unit circles at (0,0), (2,0), (2,2), (0,2) are all orthogonal to the unit circle centred at
  // (1,1): the bisectors x = 1, x + y = 2 and y = 1 meet at (1,1), so the edge of (2,2) has length 0.
  const std::vector<Circle> w{{2, 0, 1}, {2, 2, 1}, {0, 2, 1}, {-2, 0, 1}, {0, -2, 1}};
  EXPECT_EQ(check_lpd_at(unit_at_origin, w, false), LocalCondition::missing_edge);
  // Shrinking the diagonal circle a little makes the edge vanish for good; growing it gives it length.
  auto grown = w;
  grown[1].r = 1.0625;
  EXPECT_EQ(check_lpd_at(unit_at_origin, grown, false), LocalCondition::holds);
  // The perturbed test decides by ids: the edge of (2,2) exists iff (2,2) is raised less than the
  // others, i.e. has the largest id among v, (2,0), (2,2), (0,2).
  const std::vector<std::uint64_t> big_diag{1, 9, 2, 3, 4};
  const std::vector<std::uint64_t> small_diag{1, 0, 2, 3, 4};
  EXPECT_EQ(check_lpd_at_perturbed(unit_at_origin, 5, w, big_diag, false), LocalCondition::holds);
  EXPECT_EQ(check_lpd_at_perturbed(unit_at_origin, 5, w, small_diag, false), LocalCondition::missing_edge);
}

TEST(Lpd, SiteOnTheCellBoundaryCounts) {
  // A point site v (radius 0) at the origin and w at (0, −3) with radius 3: pow(0, v) = 0 = pow(0, w),
  // so p(v) lies on the bisector, in the closed cell.
  const Circle point_site{0, 0, 0};
  std::vector<Circle> w{{4, 0, 1}, {0, 4, 1}, {-4, 0, 1}, {0, -3, 3}};
  EXPECT_NE(check_lpd_at(point_site, w, false), LocalCondition::site_outside_cell);
  w[3].r = 3.0000001;
  EXPECT_EQ(check_lpd_at(point_site, w, false), LocalCondition::site_outside_cell);
}

TEST(Lpd, BoundaryRuleDependsOnTheUnitDisc) {
  // Boundary vertex v = unit circle at the origin with the chain w1 = (2,−1), w2 = (0,2), w3 = (−2,−1)
  // (unit circles): the normals turn by 116.6° twice and the closing turn is 126.8° < 180°, so the
  // local cell is the bounded triangle of the bisectors 2x − y = 2.5, y = 1, −2x − y = 2.5 and its
  // outer corner Cell(v) ∩ Cell(w3) ∩ Cell(w1) is (0, −2.5). Scaling the picture by s moves the corner
  // to (0, −2.5 s): outside the unit disc for s = 1, 0.5, inside for s = 0.25.
  const std::vector<Circle> base{{2, -1, 1}, {0, 2, 1}, {-2, -1, 1}};
  auto scaled = [](const Circle& c, double s) { return Circle{c.x * s, c.y * s, c.r * s}; };
  for (double s : {1.0, 0.5, 0.25}) {
    std::vector<Circle> w;
    for (const Circle& c : base) w.push_back(scaled(c, s));
    const auto expected = 2.5 * s > 1 ? LocalCondition::holds : LocalCondition::boundary_vertex_inside_disc;
    EXPECT_EQ(check_lpd_at(scaled(unit_at_origin, s), w, true), expected) << "scale " << s;
  }
  // Scale 0.5 and shift up by 0.25: the corner is (0, −1) exactly, on the unit circle, not outside.
  std::vector<Circle> shifted;
  for (const Circle& c : base) shifted.push_back({c.x * 0.5, c.y * 0.5 + 0.25, 0.5});
  EXPECT_EQ(check_lpd_at({0, 0.25, 0.5}, shifted, true), LocalCondition::boundary_vertex_inside_disc);
  for (Circle& c : shifted) c.y -= 0x1p-40;  // shift down by 2^-40 (exactly): corner just outside
  EXPECT_EQ(check_lpd_at({0, 0.25 - 0x1p-40, 0.5}, shifted, true), LocalCondition::holds);
  // Interior vertices have no boundary rule.
  EXPECT_EQ(check_lpd_at(scaled(unit_at_origin, 0.25), std::vector<Circle>{scaled(base[0], 0.25), scaled(base[1], 0.25), scaled(base[2], 0.25)}, false),
            LocalCondition::holds);
}

TEST(Lpd, BoundaryChainMustTurnLessThanAFullCircle) {
  // Directions at angles 0.9 k: every step is a left turn of 0.9 rad.
  std::vector<Circle> spiral;
  for (int k = 0; k < 8; ++k) spiral.push_back({4 * std::cos(k * 0.9), 4 * std::sin(k * 0.9), 1});
  EXPECT_EQ(check_lpd_at(unit_at_origin, spiral, true), LocalCondition::neighbour_order);  // 6.3 rad > 2π
  spiral.pop_back();  // 5.4 rad, closing turn 0.88 rad: a bounded heptagon, outer corner at distance ≈ 2.2
  EXPECT_EQ(check_lpd_at(unit_at_origin, spiral, true), LocalCondition::holds);
  spiral.resize(4);   // 2.7 rad: unbounded cell, no outer corner
  EXPECT_EQ(check_lpd_at(unit_at_origin, spiral, true), LocalCondition::holds);
}

TEST(Lpd, DegreeTwoBoundaryVertexIgnoresItsInnerCorner) {
  // Three mutually tangent horocycle-like circles: the corner of the inner triangle is inside the
  // disc, which the boundary rule must not reject (it concerns the outer-face side only).
  const double r = 1.0 / (1.0 + 2.0 / std::sqrt(3.0));  // three equal circles tangent to each other and to the unit circle
  std::vector<Circle> c;
  for (int k = 0; k < 3; ++k) c.push_back({(1 - r) * std::cos(pi / 2 + k * 2 * pi / 3), (1 - r) * std::sin(pi / 2 + k * 2 * pi / 3), r});
  std::vector<std::vector<Vertex>> rot{{1, 2}, {2, 0}, {0, 1}};
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  g = g.with_outer_dart(g.find_dart(1, 0));  // the clockwise triangle is the outer face
  for (Vertex v = 0; v < 3; ++v) EXPECT_EQ(check_lpd(g, c, v), LocalCondition::holds) << v;
  EXPECT_EQ(check_lpd_at(c[0], std::vector<Circle>{c[1], c[2]}, true), LocalCondition::holds);
  EXPECT_EQ(check_lpd_at(c[0], std::vector<Circle>{c[2], c[1]}, true), LocalCondition::neighbour_order);
}

TEST(Lpd, FlowerGraphHoldsEverywhere) {
  const PlanarGraph g = flower_graph();
  ASSERT_TRUE(g.is_valid(true));
  ASSERT_TRUE(g.inner_faces_are_triangles());
  const CircleEmbedding phi = flower_embedding();
  for (Vertex v = 0; v < 7; ++v) EXPECT_EQ(check_lpd(g, phi, v), LocalCondition::holds) << v;
  for (LocalCondition c : check_all(g, phi)) EXPECT_EQ(c, LocalCondition::holds);
  EXPECT_EQ(check_local(g, phi, 3), LocalCondition::holds);
}

TEST(Lpd, FirstDartPutsTheOuterFaceBetweenLastAndFirst) {
  const PlanarGraph g = flower_graph();
  EXPECT_EQ(lpd_first_dart(g, 0), g.first_dart(0));
  // At petal 1 (direction 0°) the neighbours are seen at 120° (petal 2), 180° (centre) and 240°
  // (petal 6); the outer face is around 0°, so the chain is w1 = 2, w2 = 0, w3 = 6.
  Dart d = lpd_first_dart(g, 1);
  EXPECT_EQ(g.head(d), 2u);
  d = g.next_ccw(d);
  EXPECT_EQ(g.head(d), 0u);
  d = g.next_ccw(d);
  EXPECT_EQ(g.head(d), 6u);
  EXPECT_EQ(g.face_of(d), g.outer_face());  // the dart v→wn bounds the outer face
}

TEST(Lpd, FlowerGraphShrunkStillHolds) {
  // The petals' chains turn by 120° only, so their cells are unbounded on the outer side and the
  // boundary rule holds at any scale.
  const PlanarGraph g = flower_graph();
  CircleEmbedding phi = flower_embedding();
  for (Circle& c : phi) c = {c.x * 0.1, c.y * 0.1, c.r * 0.1};
  for (LocalCondition c : check_all(g, phi)) EXPECT_EQ(c, LocalCondition::holds);
  // A centre grown past its petals swallows their sites: each petal fails.
  phi[0].r = 0.1;
  const auto all = check_all(g, phi);
  for (Vertex v = 1; v <= 6; ++v) EXPECT_EQ(all[v], LocalCondition::site_outside_cell) << v;
}

TEST(Lpd, LocalCellPolygonOfTheHexagonIsAHexagon) {
  PlanarGraph g = PlanarGraph::from_rotation({{1, 2, 3, 4, 5, 6}, {0, 6, 2}, {0, 1, 3}, {0, 2, 4}, {0, 3, 5}, {0, 4, 6}, {0, 5, 1}});
  CircleEmbedding phi{unit_at_origin};
  for (const Circle& c : hexagon_petals()) phi.push_back(c);
  const auto poly = local_cell_polygon(g, phi, 0, 3.0);
  ASSERT_EQ(poly.size(), 6u);
  for (const Point2& p : poly) EXPECT_NEAR(std::hypot(p.x, p.y), 2 / std::sqrt(3.0), 1e-12);
  double area2 = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    area2 += a.x * b.y - a.y * b.x;
  }
  EXPECT_GT(area2, 0);  // counter-clockwise
}
