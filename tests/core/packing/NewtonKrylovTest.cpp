// core::NewtonKrylovMethod, the centralized reference of Acceleration::newton_krylov: the node-local
// Jacobian rows equal angle_jacobian's, every accepted step lowers ‖θ − 2π‖₂ (the monotone damping),
// the CG solution converges quadratically near the packing, and pack() reaches LPD/GLPD in a few
// Newton steps where plain sweeps need hundreds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/NewtonKrylov.hpp"
#include "laguerre/core/packing/Packer.hpp"

using namespace laguerre::core;

namespace {
PlanarGraph graph(bool polygon, std::size_t n, std::uint64_t seed) {
  return prepare_for_packing(polygon ? random_three_connected(n, seed) : random_delaunay_triangulation(n, seed));
}

double residual_norm2(const PackingComplex& k, const Radii& h) {
  const std::vector<double> theta = angle_sums(k, h);
  double s = 0;
  for (Vertex v = 0; v < theta.size(); ++v)
    if (!k.graph.is_boundary(v)) s += (theta[v] - 2 * std::numbers::pi) * (theta[v] - 2 * std::numbers::pi);
  return s;
}

// A few plain sweeps from the initial radii: a generic point with varied radii.
Radii swept(const PackingComplex& k, int sweeps) {
  Radii h = initial_radii(k), scratch;
  for (int i = 0; i < sweeps; ++i) thurston_sweep(k, h, Sweep::jacobi, UpdateRule::uniform_neighbour, scratch);
  return h;
}
}  // namespace

TEST(NewtonKrylov, StarRowsEqualTheAssembledJacobian) {
  for (bool polygon : {false, true}) {
    const PackingComplex k = PackingComplex::from_graph(graph(polygon, 60, 3));
    const Radii h = swept(k, 4);
    const AngleJacobian jac = angle_jacobian(k, h);
    std::vector<std::int64_t> row(k.graph.num_vertices(), -1);
    for (std::size_t i = 0; i < jac.interior.size(); ++i) row[jac.interior[i]] = static_cast<std::int64_t>(i);
    std::size_t p = 0, checked = 0;
    for (std::size_t i = 0; i < jac.interior.size(); ++i) {
      const Vertex v = jac.interior[i];
      const Dart first = k.graph.first_dart(v);
      std::vector<double> nh, spoke, rim, off;
      for (std::uint32_t e = 0; e < k.graph.degree(v); ++e) {
        nh.push_back(h[k.graph.head(first + e)]);
        if (!k.tangent_only[v]) {
          spoke.push_back(k.cos_angle[first + e]);
          rim.push_back(k.cos_angle[k.graph.next_in_face(first + e)]);
        }
      }
      const double diag = star_jacobian_row(h[v], StarView{nh, spoke, rim}, off);
      for (; p < jac.entries.size() && jac.entries[p].row == i; ++p) {
        const SparseEntry& e = jac.entries[p];
        double mine = diag;
        if (e.col != i)
          for (std::uint32_t j = 0; j < off.size(); ++j)
            if (row[k.graph.head(first + j)] == static_cast<std::int64_t>(e.col)) mine = off[j];
        EXPECT_NEAR(mine, e.value, 1e-12 * std::abs(e.value) + 1e-300) << "row " << i << " col " << e.col;
        ++checked;
      }
      for (std::uint32_t j = 0; j < off.size(); ++j) {
        if (row[k.graph.head(first + j)] < 0) {
          EXPECT_EQ(off[j], 0.0);  // horocycles drop out
        }
      }
    }
    EXPECT_EQ(checked, jac.entries.size());
  }
}

TEST(NewtonKrylov, AcceptedStepsLowerTheResidualAndConvergeQuadratically) {
  for (bool polygon : {false, true}) {
    const PlanarGraph g = graph(polygon, 120, 5);
    const PackingComplex k = PackingComplex::from_graph(g);
    const Layout tree = lay_out(k, initial_radii(k), choose_root(k, RootRule::deepest));
    Radii h = initial_radii(k);
    NewtonKrylovMethod method;
    double before = residual_norm2(k, h);
    int accepted = 0;
    std::vector<double> norms{before};
    for (int step = 0; step < 30 && before > 1e-26; ++step) {
      const KrylovStep s = method.step(k, h, tree, UpdateRule::uniform_neighbour);
      const double after = residual_norm2(k, h);
      if (s.improved) {
        ++accepted;
        // The line search's test, here summed in another order: meaningful above rounding level.
        if (before > 1e-18) {
          EXPECT_LT(after, before) << "step " << step;
        }
        EXPECT_GT(s.cg_iterations, 0);
        EXPECT_EQ(s.exchanges, 1 + (s.cg_iterations + 1) + s.trials);
        EXPECT_EQ(s.sums, (s.cg_iterations + 1) + 1 + s.trials);
      }
      before = after;
      norms.push_back(after);
    }
    EXPECT_GT(accepted, 2);
    EXPECT_LT(before, 1e-20) << (polygon ? "3-connected" : "triangulation");
    // Quadratic convergence at the end: the norm (squared) falls by a factor growing like itself.
    bool fast = false;
    for (std::size_t i = 2; i < norms.size(); ++i)
      fast = fast || (norms[i - 1] < 1e-6 && norms[i] < 1e-3 * norms[i - 1]);
    EXPECT_TRUE(fast);
  }
}

TEST(NewtonKrylov, PackReachesLpdAndGlpdInFewSteps) {
  for (std::uint64_t seed = 1; seed <= 2; ++seed)
    for (bool polygon : {false, true}) {
      const PlanarGraph g = graph(polygon, polygon ? 80 : 150, seed);
      PackOptions opt;
      const PackResult plain = pack(g, opt);
      opt.acceleration = Acceleration::newton_krylov;
      const PackResult r = pack(g, opt);
      SCOPED_TRACE("seed " + std::to_string(seed) + (polygon ? " 3-connected" : ""));
      ASSERT_EQ(r.status, PackStatus::converged);
      EXPECT_EQ(r.local_ok, g.num_vertices());
      EXPECT_LT(r.iterations, plain.iterations);
      EXPECT_GT(r.jumps, 0);
      EXPECT_GT(r.linear_iterations, 0);
      EXPECT_GE(r.exchanges, r.iterations + r.linear_iterations);
      // Deterministic: the same run twice gives the same radii bit for bit.
      const PackResult again = pack(g, opt);
      EXPECT_EQ(again.radii, r.radii);
    }
}
