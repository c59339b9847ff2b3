#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

using namespace laguerre::core;

namespace {
constexpr double pi = std::numbers::pi;

// Wheel: hub 0, rim 1..k counter-clockwise; the outer face is the rim.
PlanarGraph wheel(int k) {
  std::vector<std::vector<Vertex>> rot(k + 1);
  for (int i = 1; i <= k; ++i) rot[0].push_back(i);
  for (int i = 1; i <= k; ++i) {
    const Vertex prev = i == 1 ? k : i - 1, next = i == k ? 1 : i + 1;
    rot[i] = {next, 0, prev};  // ccw around a rim vertex: next rim, hub, previous rim
  }
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  return g.with_outer_dart(g.find_dart(2, 1));  // outer face left of 2→1: the rim, clockwise
}

// Hexagonal patch of the triangular lattice with `rings` rings: a triangulated disc.
PlanarGraph lattice_patch(int rings) {
  std::vector<std::pair<int, int>> pts;  // axial coordinates
  for (int q = -rings; q <= rings; ++q)
    for (int r = -rings; r <= rings; ++r)
      if (std::abs(q + r) <= rings) pts.push_back({q, r});
  std::map<std::pair<int, int>, Vertex> index;
  for (Vertex v = 0; v < pts.size(); ++v) index[pts[v]] = v;
  // Axial neighbour directions in counter-clockwise order.
  const int dq[6] = {1, 0, -1, -1, 0, 1}, dr[6] = {0, 1, 1, 0, -1, -1};
  std::vector<std::vector<Vertex>> rot(pts.size());
  for (Vertex v = 0; v < pts.size(); ++v)
    for (int d = 0; d < 6; ++d) {
      auto it = index.find({pts[v].first + dq[d], pts[v].second + dr[d]});
      if (it != index.end()) rot[v].push_back(it->second);
    }
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  // The outer face is the unique face with more than 3 edges.
  for (Face f = 0; f < g.num_faces(); ++f)
    if (g.face_size(f) > 3) return g.with_outer_dart(g.face_darts(f).front());
  return g;
}

Radii converge(const PackingComplex& k, Sweep sweep, int sweeps) {
  Radii X = initial_radii(k), scratch;
  for (int i = 0; i < sweeps; ++i) thurston_sweep(k, X, sweep, UpdateRule::uniform_neighbour, scratch);
  return X;
}
}  // namespace

TEST(Packing, WheelHubHasTheClosedFormRadius) {
  for (int k = 3; k <= 9; ++k) {
    const PackingComplex pc = PackingComplex::from_graph(wheel(k));
    ASSERT_FALSE(pc.has_face_vertices());
    const Radii X = converge(pc, Sweep::jacobi, 3);
    // k horocycles around the hub: k · 2 asin(√X) = 2π.
    EXPECT_NEAR(x_of_radius(X[0]), std::pow(std::sin(pi / k), 2), 1e-14);
    EXPECT_LT(angle_error(pc, X), 1e-12);
    const Layout lay = lay_out(pc, X, choose_root(pc, RootRule::deepest));
    EXPECT_EQ(lay.root, 0u);
    EXPECT_EQ(lay.precision, Precision::ok);
    EXPECT_NEAR(lay.circles[0].x, 0, 1e-15);
    for (int i = 1; i <= k; ++i) {
      const Circle& c = lay.circles[i];
      EXPECT_NEAR(std::hypot(c.x, c.y) + c.r, 1.0, 1e-12) << "horocycle " << i << " not internally tangent";
      EXPECT_LT(tangency_error(lay.circles, 0, i), 1e-10);
      EXPECT_LT(tangency_error(lay.circles, i, i == k ? 1 : i + 1), 1e-9);
    }
  }
}

TEST(Packing, JacobiAndGaussSeidelConvergeToTheSamePacking) {
  const PackingComplex pc = PackingComplex::from_graph(lattice_patch(4));
  const Radii a = converge(pc, Sweep::jacobi, 3000);
  const Radii b = converge(pc, Sweep::gauss_seidel, 3000);
  EXPECT_LT(angle_error(pc, a), 1e-10);
  EXPECT_LT(angle_error(pc, b), 1e-10);
  for (Vertex v = 0; v < a.size(); ++v)
    if (std::isfinite(a[v])) EXPECT_NEAR(a[v], b[v], 1e-9);
    else EXPECT_EQ(a[v], b[v]);  // both horocycles
}

TEST(Packing, TangencyErrorVanishesAtConvergence) {
  const PlanarGraph g = lattice_patch(4);
  const PackingComplex pc = PackingComplex::from_graph(g);
  double previous = 1e300;
  for (int sweeps : {5, 50, 400, 3000}) {
    const Radii X = converge(pc, Sweep::jacobi, sweeps);
    const Layout lay = lay_out(pc, X, choose_root(pc, RootRule::deepest));
    double err = 0;
    for (Dart d = 0; d < g.num_darts(); ++d) err = std::max(err, tangency_error(lay.circles, g.tail(d), g.head(d)));
    EXPECT_LE(err, previous * 1.0001 + 1e-12) << "after " << sweeps << " sweeps";
    previous = err;
  }
  EXPECT_LT(previous, 1e-8);
}

TEST(Packing, SixfoldSymmetryOfTheLatticePatchIsKept) {
  const PlanarGraph g = lattice_patch(3);
  const PackingComplex pc = PackingComplex::from_graph(g);
  const Radii X = converge(pc, Sweep::jacobi, 2000);
  const Layout lay = lay_out(pc, X, choose_root(pc, RootRule::deepest));
  // The deepest vertex is the centre; the six first-ring circles have equal radii and the packing is
  // centred: their centres sum to ~0.
  const Vertex root = lay.root;
  double sx = 0, sy = 0;
  for (Vertex w : g.neighbours(root)) {
    EXPECT_NEAR(lay.circles[w].r, lay.circles[g.neighbours(root)[0]].r, 1e-10);
    sx += lay.circles[w].x;
    sy += lay.circles[w].y;
  }
  EXPECT_NEAR(sx, 0, 1e-9);
  EXPECT_NEAR(sy, 0, 1e-9);
}

TEST(Packing, FaceVerticesMakeOrthogonalCirclesFor3ConnectedGraphs) {
  // The cube: outer face 0-1-2-3, inner square 4-5-6-7, five inner quadrilaterals.
  std::vector<std::vector<Vertex>> rot = {{3, 4, 1}, {0, 5, 2}, {1, 6, 3}, {2, 7, 0},
                                          {0, 7, 5}, {1, 4, 6}, {2, 5, 7}, {3, 6, 4}};
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  // Pick the outer face 0-1-2-3 whichever orientation the walk has.
  Dart outer = none;
  for (Face f = 0; f < g.num_faces(); ++f) {
    bool all_outer = true;
    for (Dart d : g.face_darts(f)) all_outer &= g.tail(d) < 4;
    if (all_outer) outer = g.face_darts(f).front();
  }
  ASSERT_NE(outer, none);
  g = g.with_outer_dart(outer);
  const PackingComplex pc = PackingComplex::from_graph(g);
  ASSERT_EQ(pc.graph.num_vertices(), 13u);  // 8 + 5 face vertices
  EXPECT_TRUE(pc.graph.inner_faces_are_triangles());
  Radii X = initial_radii(pc), scratch;
  for (int i = 0; i < 400; ++i) thurston_sweep(pc, X, Sweep::jacobi, UpdateRule::uniform_neighbour, scratch);
  EXPECT_LT(angle_error(pc, X), 1e-10);
  const Layout lay = lay_out(pc, X, choose_root(pc, RootRule::deepest));
  for (Dart d = 0; d < pc.graph.num_darts(); ++d) {
    const Vertex u = pc.graph.tail(d), v = pc.graph.head(d);
    const Circle &a = lay.circles[u], &b = lay.circles[v];
    const double d2 = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
    if (pc.cos_angle[d] == 0) {
      EXPECT_NEAR(d2, a.r * a.r + b.r * b.r, 1e-9) << "face circle not orthogonal";
    } else {
      EXPECT_NEAR(std::sqrt(d2), a.r + b.r, 1e-9) << "edge circles not tangent";
    }
  }
}
