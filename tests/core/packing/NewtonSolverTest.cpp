// The symmetric variable of Newton's method (u = log tanh(h/2)) and the solvers made for it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Newton.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/core/random/Random.hpp"

using namespace laguerre::core;

namespace {
PlanarGraph delaunay(std::size_t n, std::uint64_t seed) { return prepare_for_packing(random_delaunay_triangulation(n, seed)); }
PlanarGraph three_connected(std::size_t n, std::uint64_t seed) { return prepare_for_packing(random_three_connected(n, seed)); }

// Interior radii drawn log-uniformly in [10^-lo_decades, 10^hi_decades]; horocycles stay.
Radii random_radii(const PackingComplex& k, std::uint64_t seed, double lo_decades, double hi_decades) {
  SplitMix64 rng(seed);
  Radii h = initial_radii(k);
  for (double& x : h)
    if (std::isfinite(x)) x = std::pow(10.0, -lo_decades + (lo_decades + hi_decades) * rng.uniform01());
  return h;
}

using Dense = std::vector<std::vector<double>>;

Dense dense_of(const AngleJacobian& j) {
  const std::size_t n = j.interior.size();
  Dense a(n, std::vector<double>(n, 0.0));
  for (const SparseEntry& e : j.entries) a[e.row][e.col] = e.value;
  return a;
}

// Dense Cholesky of a: whether every pivot is positive (a is then positive definite).
bool cholesky_succeeds(Dense a) {
  const std::size_t n = a.size();
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t p = 0; p < c; ++p) a[c][c] -= a[c][p] * a[c][p];
    if (!(a[c][c] > 0)) return false;
    a[c][c] = std::sqrt(a[c][c]);
    for (std::size_t r = c + 1; r < n; ++r) {
      for (std::size_t p = 0; p < c; ++p) a[r][c] -= a[r][p] * a[c][p];
      a[r][c] /= a[c][c];
    }
  }
  return true;
}

struct Case {
  std::string name;
  PlanarGraph graph;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (std::uint64_t seed : {1, 2, 3}) {
    out.push_back({"delaunay-" + std::to_string(seed), delaunay(50, seed)});
    out.push_back({"three-connected-" + std::to_string(seed), three_connected(50, seed)});  // G′ with face circles
  }
  return out;
}
}  // namespace

TEST(NewtonSolver, NamesParseAndPrint) {
  for (NewtonSolver s : {NewtonSolver::lu, NewtonSolver::cholesky, NewtonSolver::pcg})
    EXPECT_EQ(parse_name(newton_solver_names, name_of(newton_solver_names, s), "--newton-solver"), s);
  EXPECT_THROW(parse_name(newton_solver_names, "qr", "--newton-solver"), InputError);
  EXPECT_TRUE(cholesky_backend() == "cholmod" || cholesky_backend() == "eigen-ldlt");
}

TEST(NewtonSolver, SymmetricVariableRoundTrips) {
  for (double h : {1e-300, 1e-20, 1e-8, 0.3, 1.0, 2.5, 20.0, 300.0}) {
    const double u = u_of_radius(h);
    EXPECT_LT(u, 0) << h;
    EXPECT_NEAR(radius_of_u(u) / h, 1.0, 1e-13) << h;
  }
  EXPECT_EQ(u_of_radius(INFINITY), 0.0);  // horocycles at u = 0
  EXPECT_TRUE(std::isinf(radius_of_u(0.0)));
  EXPECT_NEAR(u_of_radius(1.0), std::log(std::tanh(0.5)), 1e-15);
}

TEST(NewtonSolver, ClosedFormJacobianEqualsFiniteDifferencesInU) {
  // Column w of J = ∂θ/∂u against central differences of the exactly evaluated angle sums, at random
  // radii spanning five decades (10^-4 to 10), on triangulations and on G′.
  for (const Case& c : cases()) {
    const PackingComplex k = PackingComplex::from_graph(c.graph);
    const Radii h = random_radii(k, 11, 4, 1);
    const AngleJacobian j = angle_jacobian(k, h);
    const Dense a = dense_of(j);
    ASSERT_GT(j.interior.size(), 10u) << c.name;
    for (std::size_t col = 0; col < j.interior.size(); ++col) {
      const Vertex w = j.interior[col];
      const double u = u_of_radius(h[w]), eps = 1e-6 * std::min(1.0, -u);  // u ± eps < 0
      Radii up = h, down = h;
      up[w] = radius_of_u(u + eps);
      down[w] = radius_of_u(u - eps);
      const std::vector<double> tu = angle_sums(k, up), td = angle_sums(k, down);
      for (std::size_t row = 0; row < j.interior.size(); ++row) {
        const Vertex v = j.interior[row];
        const double fd = (tu[v] - td[v]) / (2 * eps);
        // Truncation O(eps²) plus the rounding of the angle sums, ~10^-15 / eps.
        EXPECT_NEAR(a[row][col], fd, 1e-6 * (1 + std::abs(fd)) + 1e-14 / eps) << c.name << " row " << row << " col " << col;
      }
    }
  }
}

TEST(NewtonSolver, JacobianInUIsSymmetricNegativeDefiniteAndInLogHIsNot) {
  for (const Case& c : cases())
    for (std::uint64_t seed : {5, 6}) {
      const PackingComplex k = PackingComplex::from_graph(c.graph);
      const Radii h = random_radii(k, seed, 8, 1);
      const AngleJacobian j = angle_jacobian(k, h);
      const Dense a = dense_of(j);
      const std::size_t n = a.size();
      double asym_u = 0, asym_s = 0;
      Dense minus(n, std::vector<double>(n));
      for (std::size_t r = 0; r < n; ++r) {
        double row_sum = 0;
        for (std::size_t q = 0; q < n; ++q) {
          const double scale = std::max(std::abs(a[r][q]), std::abs(a[q][r]));
          if (scale > 0) asym_u = std::max(asym_u, std::abs(a[r][q] - a[q][r]) / scale);
          // ∂θ/∂(log h) = J diag(du/ds), du/ds = h / sinh h: the variable of the LU path.
          const double sr = a[r][q] * h[j.interior[q]] / std::sinh(h[j.interior[q]]);
          const double sq = a[q][r] * h[j.interior[r]] / std::sinh(h[j.interior[r]]);
          if (std::max(std::abs(sr), std::abs(sq)) > 0)
            asym_s = std::max(asym_s, std::abs(sr - sq) / std::max(std::abs(sr), std::abs(sq)));
          if (r != q) {
            EXPECT_GE(a[r][q], 0) << c.name;
          }
          row_sum += a[r][q];
          minus[r][q] = -a[r][q];
        }
        EXPECT_LT(a[r][r], 0) << c.name;
        EXPECT_LT(row_sum, 0) << c.name << " row " << r;  // strict diagonal dominance
      }
      EXPECT_LT(asym_u, 1e-13) << c.name;
      EXPECT_GT(asym_s, 1e-2) << c.name;  // the symmetry is the variable's, not the graph's
      EXPECT_TRUE(cholesky_succeeds(minus)) << c.name;
      EXPECT_FALSE(cholesky_succeeds(a)) << c.name;  // J itself is negative definite
    }
}

TEST(NewtonSolver, EverySolverReachesTheSamePackingAndLpd) {
  // Documented tolerance: radii agree to 10^-8 relative once every angle sum is within 10^-11 of 2π
  // (the packing is unique; the solvers differ only in rounding and in the path there).
  for (const PlanarGraph& g : {delaunay(300, 5), three_connected(300, 6)}) {
    std::map<NewtonSolver, PackResult> results;
    for (NewtonSolver s : {NewtonSolver::lu, NewtonSolver::cholesky, NewtonSolver::pcg}) {
      PackOptions opt;
      opt.acceleration = Acceleration::newton;
      opt.newton_solver = s;
      opt.stop = StopRule::angle;
      opt.angle_epsilon = 1e-11;
      const PackResult r = pack(g, opt);
      ASSERT_EQ(r.status, PackStatus::converged) << name_of(newton_solver_names, s);
      EXPECT_LE(r.iterations, 30) << name_of(newton_solver_names, s);
      EXPECT_GE(r.jumps, r.iterations - 2) << name_of(newton_solver_names, s);
      opt.stop = StopRule::lpd;
      const PackResult lpd = pack(g, opt);
      ASSERT_EQ(lpd.status, PackStatus::converged) << name_of(newton_solver_names, s);
      EXPECT_EQ(lpd.local_ok, g.num_vertices());
      results.emplace(s, r);
    }
    const Radii& ref = results.at(NewtonSolver::lu).radii;
    for (NewtonSolver s : {NewtonSolver::cholesky, NewtonSolver::pcg})
      for (std::size_t i = 0; i < ref.size(); ++i)
        if (std::isfinite(ref[i])) EXPECT_NEAR(results.at(s).radii[i] / ref[i], 1.0, 1e-8) << name_of(newton_solver_names, s);
        else EXPECT_EQ(results.at(s).radii[i], ref[i]);
  }
}

TEST(NewtonSolver, StepsNeverIncreaseTheResidualAndAreDeterministic) {
  const PlanarGraph g = three_connected(200, 9);
  const PackingComplex k = PackingComplex::from_graph(g);
  for (NewtonSolver s : {NewtonSolver::cholesky, NewtonSolver::pcg}) {
    NewtonMethod method(s), again(s);
    Radii h = initial_radii(k), h2 = h;
    double previous = angle_error(k, h);
    int steps = 0;
    for (; steps < 40; ++steps) {
      const Radii before = h;
      const NewtonStep step = method.step(k, h);
      const NewtonStep step2 = again.step(k, h2);
      EXPECT_EQ(h, h2) << name_of(newton_solver_names, s);  // same input, same bits
      EXPECT_EQ(step.linear_iterations, step2.linear_iterations);
      EXPECT_EQ(step.error_before, previous);
      if (!step.improved) {
        EXPECT_EQ(h, before);  // a failed step changes nothing
        break;
      }
      if (s == NewtonSolver::pcg) {
        EXPECT_GT(step.linear_iterations, 0);
      }
      previous = step.error_after;
    }
    EXPECT_LT(previous, 1e-10) << name_of(newton_solver_names, s);
    EXPECT_LT(steps, 30);
  }
}
