// The radius-only test against the exact layout-based LPD/GLPD check before convergence
// (docs/radius-only.md, "Measured"): random Delaunay triangulations and random 3-connected graphs,
// 15–64 vertices, after 0 … 233 Jacobi sweeps (2600 configurations), each laid out as core::pack does
// and checked exactly (check_all); the radius-only test (closing gap ≤ τ at every vertex of K) at
// several τ. Prints the four outcome counts per τ, for whole configurations and per vertex.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

using namespace laguerre::core;

namespace {

struct Outcomes {
  int both = 0, neither = 0, radius_only = 0, layout_only = 0;
  void add(bool r, bool l) { (r ? (l ? both : radius_only) : (l ? layout_only : neither)) += 1; }
};

struct Sample {
  double gap;   // largest closing gap over the interior vertices of K
  bool lpd;     // exact check on the layout, every vertex of G
};

}  // namespace

TEST(RadiusOnlyAgreement, ClosingGapAgainstExactLayoutCheck) {
  constexpr std::array<double, 6> taus{1e-1, 3e-2, 1e-2, 1e-3, 1e-4, 1e-6};
  std::array<std::array<Outcomes, 6>, 2> configs{}, vertices{};
  std::array<int, 2> count{};
  for (int kind = 0; kind < 2; ++kind)
    for (std::uint64_t seed = 1; seed <= 100; ++seed) {
      const std::size_t n = 15 + seed % 50;
      const PlanarGraph g = prepare_for_packing(kind == 0 ? random_delaunay_triangulation(n, seed)
                                                          : random_three_connected(n, seed));
      const PackingComplex k = PackingComplex::from_graph(g);
      Radii h = initial_radii(k), scratch;
      const Vertex root = choose_root(k, RootRule::deepest);
      int done = 0;
      for (int it : {0, 1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233}) {
        for (; done < it; ++done) thurston_sweep(k, h, Sweep::jacobi, UpdateRule::uniform_neighbour, scratch);
        const Layout lay = lay_out(k, h, root);
        const CircleEmbedding phi(lay.circles.begin(), lay.circles.begin() + static_cast<long>(g.num_vertices()));
        const std::vector<LocalCondition> exact = check_all(g, phi);
        bool lpd = true;
        for (LocalCondition c : exact) lpd = lpd && c == LocalCondition::holds;
        const double gap = angle_error(k, h);
        ++count[kind];
        for (std::size_t t = 0; t < taus.size(); ++t) {
          const bool r = radius_only_everywhere(k, h, taus[t]);
          EXPECT_EQ(r, gap <= taus[t]);  // the test is the closing gap at every vertex, nothing else
          configs[kind][t].add(r, lpd);
          for (Vertex v = 0; v < g.num_vertices(); ++v) {
            const double theta = angle_sum(k, h, v);
            const bool rv = g.is_boundary(v) || std::abs(theta - 2 * std::numbers::pi) <= taus[t];
            vertices[kind][t].add(rv, exact[v] == LocalCondition::holds);
          }
        }
      }
    }
  for (int kind = 0; kind < 2; ++kind) {
    std::cout << (kind == 0 ? "random Delaunay triangulations" : "random 3-connected graphs") << ", " << count[kind]
              << " configurations\n  tau | configurations: both / neither / radius-only only / layout only"
              << " | vertices: both / neither / radius-only only / layout only\n";
    for (std::size_t t = 0; t < taus.size(); ++t) {
      const Outcomes &c = configs[kind][t], &v = vertices[kind][t];
      std::cout << "  " << taus[t] << " | " << c.both << " / " << c.neither << " / " << c.radius_only << " / "
                << c.layout_only << " | " << v.both << " / " << v.neither << " / " << v.radius_only << " / "
                << v.layout_only << "\n";
    }
    // Both outcomes occur at every tolerance.
    for (std::size_t t = 0; t < taus.size(); ++t) {
      EXPECT_GT(configs[kind][t].both, 0);
      EXPECT_GT(configs[kind][t].neither + configs[kind][t].layout_only, 0);
    }
  }
}
