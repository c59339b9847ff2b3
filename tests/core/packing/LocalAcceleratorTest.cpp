// core::LocalAccelerator, the per-vertex state of the local accelerations: known answers on a scalar
// linear map (the spectral radius it estimates, the faster convergence), the safeguard, and pack()
// with it reaching LPD/GLPD.
#include <gtest/gtest.h>

#include <cmath>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Accelerator.hpp"
#include "laguerre/core/packing/Packer.hpp"

using namespace laguerre::core;

namespace {
// Iterates h ← next(h, F(h)) for F(h) = 1 + λ (h − 1) and returns |h − 1| after `steps`; every output
// must stay in [f/2, 2f].
double run_linear(LocalAccelerator& a, double lambda, double h, int steps) {
  for (int k = 0; k < steps; ++k) {
    const double f = 1 + lambda * (h - 1);
    h = a.next(h, f);
    EXPECT_GE(h, 0.5 * f);
    EXPECT_LE(h, 2 * f);
  }
  return std::abs(h - 1);
}
}  // namespace

TEST(LocalAccelerator, PlainReturnsTheUpdate) {
  for (Acceleration kind : {Acceleration::plain, Acceleration::anderson, Acceleration::newton}) {
    LocalAccelerator a(kind);
    for (double f : {0.5, 1.5, 1e-12}) {
      EXPECT_EQ(a.next(1.0, f), f);
      EXPECT_FALSE(a.accelerated());
    }
  }
}

TEST(LocalAccelerator, ChebyshevFindsTheContractionOfALinearMap) {
  // The residuals of a scalar linear map shrink by exactly λ: ρ = λ once two window ratios agree
  // (then the ratios of the second-order iteration's double root, ~ k μ^k, lift it somewhat: by up
  // to a third of 1 − λ here, which only slows the rate to √(ω − 1) of the larger ω).
  for (double lambda : {0.5, 0.9, 0.99}) {
    LocalAccelerator a(Acceleration::chebyshev);
    const double plain = std::pow(lambda, 200);
    const double err = run_linear(a, lambda, 1.8, 200);
    EXPECT_GE(a.rho(), lambda - 1e-12) << lambda;
    EXPECT_LT(a.rho(), lambda + 0.5 * (1 - lambda)) << lambda;
    EXPECT_LT(err, std::max(1e-14, 1e-3 * plain)) << lambda;  // ≥ 1000× ahead of plain sweeps
    EXPECT_EQ(a.restarts(), 0);
  }
}

TEST(LocalAccelerator, LocalSuperstepSumsTheGeometricSeries) {
  LocalAccelerator a(Acceleration::local_superstep);
  const double err = run_linear(a, 0.95, 1.5, 12);
  EXPECT_LT(err, 1e-9);  // one jump lands on the fixed point of a linear map (plain: 0.95^12 ≈ 0.54)
}

TEST(LocalAccelerator, OutOfBracketValuesFallBackToThePlainUpdate) {
  LocalAccelerator a(Acceleration::chebyshev);
  run_linear(a, 0.9, 1.8, 30);
  ASSERT_GT(a.rho(), 0.0);
  // A sudden fall of the plain update: the extrapolation h_{k−1} + ω (f − h_{k−1}) would be negative.
  for (int i = 0; i < 25; ++i) {
    const double h = a.next(1.0, 1.0);  // history at 1
    (void)h;
    const double f = 1e-3;
    EXPECT_EQ(a.next(1.0, f), f);
    EXPECT_FALSE(a.accelerated());
    run_linear(a, 0.9, 1.8, 12);  // rebuild a history
  }
  EXPECT_EQ(a.restarts(), 20);  // then plain for good
  run_linear(a, 0.9, 1.8, 30);
  EXPECT_FALSE(a.accelerated());
}

TEST(LocalAccelerator, PackReachesLpdAndGlpdWithFewerSweeps) {
  for (std::uint64_t seed = 1; seed <= 2; ++seed)
    for (bool polygon : {false, true}) {
      const PlanarGraph g =
          prepare_for_packing(polygon ? random_three_connected(80, seed) : random_delaunay_triangulation(150, seed));
      PackOptions opt;
      const PackResult plain = pack(g, opt);
      for (Acceleration kind : {Acceleration::chebyshev, Acceleration::local_superstep}) {
        opt.acceleration = kind;
        const PackResult r = pack(g, opt);
        SCOPED_TRACE(std::string(to_string(kind)) + " seed " + std::to_string(seed) + (polygon ? " 3-connected" : ""));
        ASSERT_EQ(r.status, PackStatus::converged);
        EXPECT_EQ(r.local_ok, g.num_vertices());
        if (kind == Acceleration::chebyshev) {
          EXPECT_LT(r.iterations, plain.iterations);
          EXPECT_GT(r.jumps, 0);
        }
      }
    }
}
