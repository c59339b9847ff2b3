// The layout's methods and arithmetics (docs/precision.md): frames and binary128 agree with the
// network's wave wherever doubles suffice, known answers on the wheel, and a packing whose circles
// shrink below what doubles resolve is reported collapsed and never claimed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/Embedding.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/Newton.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

using namespace laguerre::core;

namespace {
constexpr LayoutMethod methods[] = {LayoutMethod::wave, LayoutMethod::frames};
constexpr LayoutArithmetic arithmetics[] = {LayoutArithmetic::binary64, LayoutArithmetic::binary128};

// Radii of g packed by Newton to rounding level.
Radii newton_radii(const PlanarGraph& g) {
  PackOptions opt;
  opt.acceleration = Acceleration::newton;
  opt.stop = StopRule::angle;
  opt.angle_epsilon = 1e-13;
  opt.max_iterations = 40;
  return pack(g, opt).radii;
}

// Wheel: hub 0, rim 1..k counter-clockwise; the outer face is the rim.
PlanarGraph wheel(int k) {
  std::vector<std::vector<Vertex>> rot(k + 1);
  for (int i = 1; i <= k; ++i) rot[0].push_back(i);
  for (int i = 1; i <= k; ++i) {
    const Vertex prev = i == 1 ? k : i - 1, next = i == k ? 1 : i + 1;
    rot[i] = {next, 0, prev};
  }
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  return g.with_outer_dart(g.find_dart(2, 1));
}

// Outer triangle 0, 1, 2, vertex 3 inside it, then vertex k inside the face (k−3, k−2, k−1): a chain
// of circles each tangent to the three before it (Coxeter's loxodromic sequence), whose radii shrink
// by ~2.89 per vertex.
PlanarGraph nested_chain(int length) {
  std::vector<std::uint64_t> ids;
  std::vector<Point2> p = {{0, 0}, {1, 0}, {0.5, 0.9}};
  std::vector<std::pair<Vertex, Vertex>> edges = {{0, 1}, {1, 2}, {2, 0}};
  for (int k = 3; k < 3 + length; ++k) {
    const Vertex a = k == 3 ? 0 : k - 3, b = k == 3 ? 1 : k - 2, c = k == 3 ? 2 : k - 1;
    p.push_back({(p[a].x + p[b].x + p[c].x) / 3, (p[a].y + p[b].y + p[c].y) / 3});
    for (Vertex w : {a, b, c}) edges.push_back({w, static_cast<Vertex>(k)});
  }
  for (std::size_t i = 0; i < p.size(); ++i) ids.push_back(i);
  return graph_from_drawing(ids, p, edges, "nested chain").graph;
}
}  // namespace

TEST(LayoutPrecision, ResolutionCountsUnitsInTheLastPlace) {
  EXPECT_EQ(circle_resolution({0, 0, 0.25}), std::ldexp(1.0, 52));          // ulp(0.25) = 2^-54
  // In binary128 the last unit is 2^60 times smaller: ulp(0.25) = 2^-114, ulp(0.5) = 2^-113.
  EXPECT_EQ(circle_resolution(Circle128{0, 0, 0.25}), std::ldexp(1.0, 112));
  EXPECT_EQ(circle_resolution(Circle128{0.5, 0, std::ldexp(1.0, -60)}), std::ldexp(1.0, 53));
  EXPECT_EQ(circle_resolution(Circle128{-0.75, 0.5, 0}), 0.0);
  EXPECT_EQ(circle_resolution({0.5, 0, std::ldexp(1.0, -60)}), std::ldexp(1.0, -7));  // ulp(0.5) = 2^-53
  EXPECT_EQ(circle_resolution({-0.75, 0.5, 0}), 0.0);
  EXPECT_EQ(circle_resolution({NAN, 0, 0.1}), 0.0);
}

TEST(LayoutPrecision, WheelRimSitsAtTheRootsOfUnityInEveryMethod) {
  for (int k : {3, 5, 8}) {
    const PlanarGraph g = wheel(k);
    const PackingComplex pc = PackingComplex::from_graph(g);
    const Radii h = newton_radii(g);
    for (LayoutMethod m : methods)
      for (LayoutArithmetic a : arithmetics) {
        const Layout lay = lay_out(pc, h, 0, m, a);
        EXPECT_EQ(lay.method, m);
        EXPECT_EQ(lay.arithmetic, a);
        EXPECT_EQ(lay.precision, Precision::ok);
        const double s = lay.circles[0].r;
        for (int i = 1; i <= k; ++i) {
          // Rim vertex i: ideal point at angle 2π(i−1)/k, horocycle of Euclidean radius (1 − s)/2.
          const double t = 2 * std::numbers::pi * (i - 1) / k;
          EXPECT_NEAR(lay.centre[i].real(), std::cos(t), 1e-14) << k << " " << i;
          EXPECT_NEAR(lay.centre[i].imag(), std::sin(t), 1e-14) << k << " " << i;
          EXPECT_NEAR(lay.circles[i].r, (1 - s) / 2, 1e-14) << k << " " << i;
        }
      }
  }
}

TEST(LayoutPrecision, FramesAndQuadrupleAgreeWithTheWaveWhereDoublesSuffice) {
  // A 400-vertex random Delaunay triangulation (depth ~15 rounds): every method and arithmetic gives
  // the same circles to ~1e-10 of their radii, on the same spanning tree.
  const PlanarGraph g = random_delaunay_triangulation(400, 11).graph;
  const PackingComplex pc = PackingComplex::from_graph(g);
  const Radii h = newton_radii(g);
  const Vertex root = choose_root(pc, RootRule::deepest);
  const Layout ref = lay_out(pc, h, root);
  EXPECT_EQ(ref.precision, Precision::ok);
  EXPECT_LT(max_tangency_error(g, ref.circles), 1e-10);
  for (LayoutMethod m : methods)
    for (LayoutArithmetic a : arithmetics) {
      const Layout lay = lay_out(pc, h, root, m, a);
      EXPECT_EQ(lay.parent, ref.parent);
      EXPECT_EQ(lay.wave, ref.wave);
      EXPECT_LT(max_tangency_error(g, lay.circles), 1e-10);
      for (Vertex v = 0; v < g.num_vertices(); ++v) {
        const Circle &c = lay.circles[v], &r = ref.circles[v];
        EXPECT_LT(std::hypot(c.x - r.x, c.y - r.y) / r.r, 1e-10) << v;
        EXPECT_LT(std::abs(c.r - r.r) / r.r, 1e-10) << v;
      }
    }
}

TEST(LayoutPrecision, CirclesBelowTheDoublesResolutionAreNeverClaimed) {
  // 45 nested circles: the last ones are < 1e-18 of the disc, far below the ulp of their centres.
  const PlanarGraph g = nested_chain(45);
  for (LayoutMethod m : methods) {
    PackOptions opt;
    opt.acceleration = Acceleration::newton;
    opt.stop = StopRule::angle;  // the packing itself, not the first LPD on the way
    opt.angle_epsilon = 1e-12;
    opt.max_iterations = 80;
    opt.layout_method = m;
    // The deepest root would be the chain's last vertex, and the smallest circles would sit at the
    // origin, where doubles resolve them; rooted at the chain's first vertex they sit near 0.3.
    opt.root = RootRule::smallest_id;
    const PackResult r = pack(g, opt);
    EXPECT_LT(r.angle_error, 1e-12);
    EXPECT_LT(r.layout.smallest_radius, 1e-18);
    EXPECT_LT(r.layout.resolution, Layout::collapsed_resolution);
    EXPECT_EQ(r.layout.precision, Precision::collapsed);
    EXPECT_EQ(r.status, PackStatus::precision_loss);
  }
  // The first 12 of them are well inside what doubles resolve: claimed as usual.
  PackOptions opt;
  opt.acceleration = Acceleration::newton;
  opt.stop = StopRule::angle;
  opt.angle_epsilon = 1e-12;
  opt.layout_method = LayoutMethod::frames;
  const PackResult r = pack(nested_chain(12), opt);
  EXPECT_EQ(r.status, PackStatus::converged);
  EXPECT_NE(r.layout.precision, Precision::collapsed);
}

namespace {
// The 45 nested circles packed by Newton to an angle error of 1e-12, rooted at the chain's first
// vertex (its smallest circles then sit near 0.3, where doubles cannot resolve them), in the frames
// layout of arithmetic `a`.
PackOptions nested_chain_options(LayoutArithmetic a) {
  PackOptions opt;
  opt.acceleration = Acceleration::newton;
  opt.stop = StopRule::angle;
  opt.angle_epsilon = 1e-12;
  opt.max_iterations = 80;
  opt.layout_method = LayoutMethod::frames;
  opt.layout_arithmetic = a;
  opt.root = RootRule::smallest_id;
  return opt;
}
}  // namespace

TEST(LayoutPrecision, Binary128KeepsTheCirclesThatDoublesCollapseAndDecidesOnThem) {
  // The same 45 nested circles laid out in binary128: the circles are kept in binary128, where the
  // smallest (< 1e-18 near 0.3) still span ~10^16 ulps; precision, LPD and the tangency error are
  // decided on them, and the run converges where binary64 ends precision_loss (above).
  const PlanarGraph g = nested_chain(45);
  const PackResult r = pack(g, nested_chain_options(LayoutArithmetic::binary128));
  ASSERT_EQ(r.circles128.size(), g.num_vertices());
  EXPECT_EQ(bytes_per_coordinate(r.layout), 16);
  EXPECT_LT(r.layout.smallest_radius, 1e-18);
  EXPECT_GE(r.layout.resolution, Layout::degraded_resolution);
  EXPECT_EQ(r.layout.precision, Precision::ok);
  EXPECT_EQ(significand_bits_needed(r.layout), 113);
  EXPECT_EQ(r.status, PackStatus::converged);
  EXPECT_EQ(r.local_ok, g.num_vertices());  // LPD on the binary128 circles
  EXPECT_LT(r.max_tangency_error, 1e-6);    // measured in binary128
  // The kept circles round to the stored doubles, on which LPD does not hold everywhere (collapsed).
  std::size_t double_ok = 0;
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    const Circle d = to_double(r.circles128[v]);
    EXPECT_EQ(d.x, r.circles[v].x);
    EXPECT_EQ(d.r, r.circles[v].r);
    double_ok += check_lpd(g, r.circles, v) == LocalCondition::holds;
  }
  EXPECT_LT(double_ok, g.num_vertices());
  // LPD on the binary128 circles: greedy power routing decided on them delivers every ordered pair
  // (thesis Theorem 5.3.1).
  const RoutingStats routed = evaluate_routing(g, r.circles, Scheme::greedy_power, {}, &r.circles128);
  EXPECT_EQ(routed.coordinate_bytes, 16);
  EXPECT_EQ(routed.pairs, g.num_vertices() * (g.num_vertices() - 1));
  EXPECT_EQ(routed.delivered, routed.pairs);
}

namespace {
// Records, per check, the layout's precision and whether the coordinates were checked.
struct CheckLog : PackVisitor {
  std::vector<Precision> precision;
  std::vector<bool> checked;
  std::vector<std::size_t> lpd;
  void on_layout(int, const Layout& layout) override { precision.push_back(layout.precision); }
  void on_check(int, double, std::size_t ok) override {
    checked.push_back(true);
    lpd.push_back(ok);
  }
  void on_unchecked(int, double, Precision p) override {
    EXPECT_TRUE(p == Precision::collapsed || p == Precision::unrepresentable);
    checked.push_back(false);
    lpd.push_back(0);
  }
};
}  // namespace

TEST(LayoutPrecision, CollapsedLayoutsMidRunAreNotCheckedAndTheFinalOneIs) {
  // The nested chain rooted at its first vertex: Newton's layouts collapse once the chain's radii
  // shrink below the doubles' resolution, and stay collapsed. Stopped by LPD with a cap, the run
  // checks only the representable layouts, goes on to the cap instead of ending on a collapsed one,
  // checks the final layout anyway, and ends precision_loss.
  const PlanarGraph g = nested_chain(45);
  for (const StopRule stop : {StopRule::lpd, StopRule::exact, StopRule::cap}) {
    PackOptions opt;
    opt.acceleration = Acceleration::newton;
    opt.stop = stop;
    opt.max_iterations = 30;
    opt.root = RootRule::smallest_id;
    opt.layout_method = LayoutMethod::frames;
    CheckLog log;
    const PackResult r = pack(g, opt, &log);
    ASSERT_EQ(log.precision.size(), log.checked.size());
    ASSERT_EQ(static_cast<int>(log.checked.size()), r.layouts);
    int skipped = 0;
    for (std::size_t i = 0; i < log.checked.size(); ++i) {
      const bool collapsed = log.precision[i] == Precision::collapsed || log.precision[i] == Precision::unrepresentable;
      const bool last = i + 1 == log.checked.size();
      EXPECT_EQ(log.checked[i], !collapsed || last) << to_string(stop) << " check " << i;
      skipped += !log.checked[i];
    }
    EXPECT_EQ(skipped, r.skipped_checks);
    EXPECT_GT(r.skipped_checks, 0) << to_string(stop);
    EXPECT_EQ(r.iterations, opt.max_iterations) << to_string(stop);  // the collapsed layouts did not end it
    EXPECT_EQ(r.layout.precision, Precision::collapsed);
    EXPECT_EQ(r.status, PackStatus::precision_loss);
    EXPECT_EQ(r.local.size(), g.num_vertices());  // the final layout was checked
    if (stop != StopRule::exact) {  // (exact: LPD is counted after the run)
      EXPECT_EQ(r.local_ok, log.lpd.back());
    }
    if (r.first_lpd >= 0) {  // only ever recorded on a checked, representable layout (one check per step)
      EXPECT_TRUE(log.checked[static_cast<std::size_t>(r.first_lpd)]);
      EXPECT_NE(log.precision[static_cast<std::size_t>(r.first_lpd)], Precision::collapsed);
    }
  }
}

TEST(LayoutPrecision, StopWhenCollapsedStopsOnlyCollapsedLayoutsAndKeepsThePlacedBits) {
  // The packer's mid-run layouts stop at the first collapsed circle (lay_out's stop_when_collapsed).
  // On the nested chain's collapsed radii (Newton to the cap) the stopped wave must say collapsed as
  // the whole one does, be incomplete, and agree bit for bit on every circle it placed; on
  // representable radii (the initial ones) it must be the whole layout.
  const PlanarGraph g = nested_chain(45);
  PackOptions opt;
  opt.acceleration = Acceleration::newton;
  opt.stop = StopRule::cap;
  opt.max_iterations = 30;
  opt.root = RootRule::smallest_id;
  opt.layout_method = LayoutMethod::frames;
  const PackResult r = pack(g, opt);
  ASSERT_EQ(r.layout.precision, Precision::collapsed);
  const PackingComplex k = PackingComplex::from_graph(g);
  const Vertex root = choose_root(k, RootRule::smallest_id);
  for (const LayoutMethod method : {LayoutMethod::frames, LayoutMethod::wave}) {
    const Layout whole = lay_out(k, r.radii, root, method, LayoutArithmetic::binary64, false);
    const Layout stopped = lay_out(k, r.radii, root, method, LayoutArithmetic::binary64, true);
    ASSERT_TRUE(whole.complete);
    ASSERT_TRUE(whole.precision == Precision::collapsed || whole.precision == Precision::unrepresentable);
    EXPECT_TRUE(stopped.precision == Precision::collapsed || stopped.precision == Precision::unrepresentable);
    EXPECT_FALSE(stopped.complete);
    std::size_t placed = 0;
    for (Vertex v = 0; v < k.graph.num_vertices(); ++v) {
      if (stopped.wave[v] == none) {
        EXPECT_TRUE(std::isnan(stopped.circles[v].r)) << v;
        continue;
      }
      ++placed;
      EXPECT_EQ(stopped.wave[v], whole.wave[v]) << v;
      EXPECT_EQ(stopped.circles[v].x, whole.circles[v].x) << v;
      EXPECT_EQ(stopped.circles[v].y, whole.circles[v].y) << v;
      EXPECT_EQ(stopped.circles[v].r, whole.circles[v].r) << v;
    }
    EXPECT_LT(placed, k.graph.num_vertices());
    EXPECT_GE(stopped.smallest_radius, whole.smallest_radius);
    const Layout first = lay_out(k, initial_radii(k), root, method, LayoutArithmetic::binary64, true);
    EXPECT_TRUE(first.complete);
    EXPECT_NE(first.precision, Precision::collapsed);
  }
}

TEST(LayoutPrecision, MixedArithmeticKeepsBinary128sCirclesWithLocalStepsInDoubles) {
  // LayoutArithmetic::mixed: frames and circles in binary128, the steps from the radii in doubles.
  // Where doubles suffice it is the frames layout to ~1e-10 of the radii, on the same tree ...
  {
    const PlanarGraph g = random_delaunay_triangulation(400, 11).graph;
    const PackingComplex pc = PackingComplex::from_graph(g);
    const Radii h = newton_radii(g);
    const Vertex root = choose_root(pc, RootRule::deepest);
    const Layout ref = lay_out(pc, h, root, LayoutMethod::frames, LayoutArithmetic::binary128);
    const Layout mix = lay_out(pc, h, root, LayoutMethod::frames, LayoutArithmetic::mixed);
    EXPECT_EQ(mix.arithmetic, LayoutArithmetic::mixed);
    EXPECT_EQ(mix.parent, ref.parent);
    EXPECT_EQ(bytes_per_coordinate(mix), 16);
    EXPECT_LT(max_tangency_error(g, mix.circles128), 1e-10);
    for (Vertex v = 0; v < g.num_vertices(); ++v) {
      const Circle &c = mix.circles[v], &r = ref.circles[v];
      EXPECT_LT(std::hypot(c.x - r.x, c.y - r.y) / r.r, 1e-10) << v;
      EXPECT_LT(std::abs(c.r - r.r) / r.r, 1e-10) << v;
    }
  }
  // ... and where they do not (the 45 nested circles below 1e-18 near 0.3), its circles are tangent
  // as well as binary128's to a factor of 10 (the angle error bounds both), and decided on in binary128: LPD everywhere,
  // every pair delivered. (They are not binary128's circles to 1e-12: a rounding in a step moves the
  // whole subtree below it by a near-identity disc automorphism, which deep in the chain displaces
  // the tiny circles by many radii while keeping their tangencies; binary128's own layout is such a
  // displaced copy too, 2^60 times less.)
  const PlanarGraph g = nested_chain(45);
  const PackResult r = pack(g, nested_chain_options(LayoutArithmetic::mixed));
  EXPECT_EQ(r.status, PackStatus::converged);
  EXPECT_EQ(r.layout.precision, Precision::ok);
  EXPECT_EQ(r.local_ok, g.num_vertices());
  EXPECT_LT(r.layout.smallest_radius, 1e-18);
  ASSERT_EQ(r.circles128.size(), g.num_vertices());
  const PackingComplex pc = PackingComplex::from_graph(g);
  const Layout quad = lay_out(pc, r.radii, r.layout.root, LayoutMethod::frames, LayoutArithmetic::binary128);
  const double mixed_error = max_tangency_error(g, r.circles128), quad_error = max_tangency_error(g, quad.circles128);
  EXPECT_LT(mixed_error, 1e-5);
  EXPECT_LT(mixed_error, 10 * quad_error);  // measured 5.2e-7 against 1.3e-7 (angle error 1e-12)
  const RoutingStats routed = evaluate_routing(g, r.circles, Scheme::greedy_power, {}, &r.circles128);
  EXPECT_EQ(routed.delivered, routed.pairs);
  EXPECT_THROW(lay_out(pc, r.radii, r.layout.root, LayoutMethod::wave, LayoutArithmetic::mixed),
               laguerre::core::InternalError);
}

TEST(LayoutPrecision, Binary128RefinementClosesTheFlowersBeyondTheDoubles) {
  // Newton's double radii close each flower to ~1e-15 rad at best; refined in binary128 (residuals in
  // binary128, the solve in doubles) they close to 1e-30, and the binary128 layout of the refined
  // radii is tangent orders of magnitude better than that of the doubles.
  struct Case {
    PlanarGraph g;
    RootRule root;
  };
  const Case cases[] = {{random_delaunay_triangulation(300, 5).graph, RootRule::deepest},
                        {nested_chain(45), RootRule::smallest_id}};
  for (const Case& c : cases) {
    const PackingComplex pc = PackingComplex::from_graph(c.g);
    const Radii h = newton_radii(c.g);
    NewtonMethod newton;
    const Radii128 q = newton.refine128(pc, h);
    Radii128 widened(h.begin(), h.end());
    double before = 0, after = 0;
    for (const double e : angle_residuals128(pc, widened)) before = std::max(before, std::abs(e));
    for (const double e : angle_residuals128(pc, q)) after = std::max(after, std::abs(e));
    EXPECT_GT(before, 1e-20);
    EXPECT_LT(after, 1e-28);
    for (Vertex v = 0; v < h.size(); ++v)
      if (std::isfinite(h[v])) EXPECT_LT(std::abs(static_cast<double>(q[v] / h[v]) - 1), 1e-9) << v;
      else EXPECT_FALSE(q[v] - q[v] == 0) << v;  // ∞ stays ∞
    const Vertex root = choose_root(pc, c.root);
    const Layout from_doubles = lay_out(pc, h, root, LayoutMethod::frames, LayoutArithmetic::binary128);
    const Layout refined = lay_out(pc, q, root, LayoutMethod::frames);
    EXPECT_EQ(refined.arithmetic, LayoutArithmetic::binary128);
    EXPECT_EQ(refined.parent, from_doubles.parent);
    const double e_doubles = max_tangency_error(c.g, from_doubles.circles128);
    const double e_refined = max_tangency_error(c.g, refined.circles128);
    EXPECT_LT(e_refined, 1e-12) << e_doubles;
    std::printf("tangency error: doubles %.3g, refined %.3g\n", e_doubles, e_refined);
    EXPECT_LT(e_refined, e_doubles / 1000);
  }
}
