// The inverse problem for affine diagrams: round trips through random power diagrams, perturbed
// complexes rejected with the broken cycle named, exact decisions on decimal input, reader errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include "laguerre/core/diagrams/Recognition.hpp"
#include "../../support/Scratch.hpp"

namespace laguerre::core {
namespace {

std::vector<WeightedPoint> random_sites(unsigned seed, std::size_t n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), w(0, 0.01);
  std::vector<WeightedPoint> s;
  for (std::size_t i = 0; i < n; ++i) s.push_back({u(rng), u(rng), w(rng)});
  return s;
}

/// Pairs of cells sharing an edge or a ray, translated through `label`.
std::set<std::pair<SiteIndex, SiteIndex>> adjacency(const CellComplex& cx, const std::vector<SiteIndex>& label) {
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> by_edge;
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    const auto& cell = cx.cells[c];
    const std::size_t k = cell.vertices.size();
    for (std::size_t m = 0; m + (cell.ray_in ? 1 : 0) < k; ++m)
      by_edge[std::minmax(cell.vertices[m], cell.vertices[(m + 1) % k])].push_back(c);
    if (cell.ray_in) by_edge[{*cell.ray_in, SIZE_MAX}].push_back(c), by_edge[{*cell.ray_out, SIZE_MAX}].push_back(c);
  }
  std::set<std::pair<SiteIndex, SiteIndex>> out;
  for (const auto& [edge, cells] : by_edge) {
    EXPECT_EQ(cells.size(), 2u);
    if (cells.size() == 2) out.insert(std::minmax(label[cells[0]], label[cells[1]]));
  }
  return out;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = laguerre::testing::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

TEST(Recognition, RoundTripThroughRandomPowerDiagrams) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const auto sites = random_sites(seed, 30 + 20 * seed);
    std::vector<SiteIndex> cell_site;
    const CellComplex original = power_diagram_complex(sites, &cell_site);
    // Through the file format (17 significant digits, read back as exact decimals).
    const CellComplex cx = read_cell_complex(write_temp("roundtrip.txt", format_cell_complex(original)));
    const RecognitionResult r = recognize_power_diagram(cx);
    ASSERT_TRUE(r.is_power_diagram) << "seed " << seed << ": " << r.message;
    ASSERT_EQ(r.sites.size(), cx.cells.size());
    // Sites are recovered up to p ↦ κp + t (κ > 0): fit on cells 0 and 1, check all.
    const WeightedPoint &p0 = sites[cell_site[0]], &p1 = sites[cell_site[1]];
    const double kappa = std::hypot(r.sites[1].x - r.sites[0].x, r.sites[1].y - r.sites[0].y) / std::hypot(p1.x - p0.x, p1.y - p0.y);
    ASSERT_GT(kappa, 0);
    for (std::size_t c = 0; c < cx.cells.size(); ++c) {
      const WeightedPoint& p = sites[cell_site[c]];
      EXPECT_NEAR(r.sites[c].x - r.sites[0].x, kappa * (p.x - p0.x), 1e-6 * kappa) << "seed " << seed << " cell " << c;
      EXPECT_NEAR(r.sites[c].y - r.sites[0].y, kappa * (p.y - p0.y), 1e-6 * kappa) << "seed " << seed << " cell " << c;
    }
    // The recovered sites give the same diagram: same adjacency, same vertices.
    std::vector<SiteIndex> again_site;
    const CellComplex again = power_diagram_complex(r.sites, &again_site);
    std::vector<SiteIndex> identity(cx.cells.size());
    for (std::size_t c = 0; c < identity.size(); ++c) identity[c] = c;
    std::vector<SiteIndex> original_label(cx.cells.size());
    for (std::size_t c = 0; c < cx.cells.size(); ++c) original_label[c] = c;  // cell c of cx is site c of r.sites
    EXPECT_EQ(adjacency(again, again_site), adjacency(cx, original_label)) << "seed " << seed;
    auto sorted_vertices = [](std::vector<Point2> v) {
      std::sort(v.begin(), v.end(), [](Point2 a, Point2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
      return v;
    };
    const auto va = sorted_vertices(again.vertices), vb = sorted_vertices(cx.vertices);
    ASSERT_EQ(va.size(), vb.size());
    for (std::size_t i = 0; i < va.size(); ++i) {
      EXPECT_NEAR(va[i].x, vb[i].x, 1e-7);
      EXPECT_NEAR(va[i].y, vb[i].y, 1e-7);
    }
  }
}

TEST(Recognition, PerturbedVertexBreaksTheCyclesAroundIt) {
  const auto sites = random_sites(11, 80);
  const CellComplex cx = power_diagram_complex(sites);
  // Vertex → cells around it; vertex → neighbouring vertices.
  std::vector<std::set<std::size_t>> cells_at(cx.vertices.size());
  std::vector<std::set<std::size_t>> next_to(cx.vertices.size());
  std::vector<char> touches_unbounded(cx.vertices.size(), 0);
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    const auto& cell = cx.cells[c];
    for (std::size_t m = 0; m < cell.vertices.size(); ++m) {
      const std::size_t v = cell.vertices[m], w = cell.vertices[(m + 1) % cell.vertices.size()];
      cells_at[v].insert(c);
      if (cell.ray_in) touches_unbounded[v] = 1;
      if (v != w) next_to[v].insert(w), next_to[w].insert(v);
    }
  }
  int tried = 0;
  for (std::size_t v = 0; v < cx.vertices.size() && tried < 5; ++v) {
    if (touches_unbounded[v] || cells_at[v].size() != 3) continue;
    ++tried;
    CellComplex bad = cx;
    bad.vertices[v].x += 2e-5, bad.vertices[v].y += 1e-5;
    const RecognitionResult r = recognize_power_diagram(bad);
    EXPECT_FALSE(r.is_power_diagram) << "vertex " << v;
    ASSERT_FALSE(r.broken.empty());
    std::set<std::size_t> near(cells_at[v]);
    for (std::size_t w : next_to[v]) near.insert(cells_at[w].begin(), cells_at[w].end());
    bool names_a_cell_at_v = false;
    for (const BrokenCycle& b : r.broken) {
      EXPECT_EQ(b.kind, "cell") << r.message;
      EXPECT_EQ(near.count(b.cell), 1u) << "vertex " << v << " reported cell " << b.cell;
      names_a_cell_at_v = names_a_cell_at_v || cells_at[v].count(b.cell) == 1;
      EXPECT_GT(b.defect, 1e-9);
      EXPECT_GE(b.cycle.size(), 3u);
    }
    EXPECT_TRUE(names_a_cell_at_v) << r.message;
    // The unperturbed complex stays accepted.
    EXPECT_TRUE(recognize_power_diagram(cx).is_power_diagram);
  }
  EXPECT_EQ(tried, 5);
}

TEST(Recognition, ExactDecisionOnDecimals) {
  // The Voronoi diagram of a grid written in decimals: exact (τ = 0) acceptance, degree-4 vertices.
  const CellComplex cx = read_cell_complex(std::string(LAGUERRE_TEST_DATA) + "/../../tools/examples/diagrams/cells-grid.txt");
  const RecognitionResult r = recognize_power_diagram(cx, {0.0});
  ASSERT_TRUE(r.is_power_diagram) << r.message;
  // The recovered sites form a square grid: equal spacing in both directions (up to the gauge).
  const double dx = r.sites[8].x - r.sites[2].x;  // cells 2 (bottom-left) and 8 (bottom-right)
  EXPECT_GT(std::abs(dx), 0);
  // Decimals rounded from a true power diagram (17 digits) are exactly inconsistent: τ = 0 rejects
  // them, the default τ = 1e-9 accepts them.
  const CellComplex rounded = read_cell_complex(write_temp("rounded.txt", format_cell_complex(power_diagram_complex(random_sites(5, 40)))));
  EXPECT_FALSE(recognize_power_diagram(rounded, {0.0}).is_power_diagram);
  EXPECT_TRUE(recognize_power_diagram(rounded, {1e-9}).is_power_diagram);
}

TEST(Recognition, NonConvexCellIsReported) {
  const CellComplex cx = power_diagram_complex(random_sites(3, 40));
  // Push a bounded cell's vertex far inward: its corner turns right.
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    if (cx.cells[c].ray_in) continue;
    CellComplex bad = cx;
    const std::size_t v = bad.cells[c].vertices[0];
    double cx_ = 0, cy_ = 0;
    for (std::size_t w : bad.cells[c].vertices) cx_ += bad.vertices[w].x, cy_ += bad.vertices[w].y;
    cx_ /= static_cast<double>(bad.cells[c].vertices.size()), cy_ /= static_cast<double>(bad.cells[c].vertices.size());
    bad.vertices[v] = {cx_ + 0.05 * (bad.vertices[v].x - cx_), cy_ + 0.05 * (bad.vertices[v].y - cy_)};
    const RecognitionResult r = recognize_power_diagram(bad);
    EXPECT_FALSE(r.is_power_diagram);
    bool convexity = false;
    for (const BrokenCycle& b : r.broken) convexity = convexity || (b.kind == "convexity");
    EXPECT_TRUE(convexity) << r.message;
    return;
  }
  FAIL() << "no bounded cell";
}

TEST(Recognition, ReaderReportsFileAndLine) {
  auto error_of = [](const std::string& text) {
    try {
      read_cell_complex(write_temp("bad-cells.txt", text));
    } catch (const CellComplexError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("v 0 0\nv 1 zz\n").find(":2:"), std::string::npos);
  EXPECT_NE(error_of("v 0 0\nq 1\n").find("expected a record"), std::string::npos);
  EXPECT_NE(error_of("v 0 0\nr 3 1 0\n").find(":2:"), std::string::npos);
  // A triangle used by one cell only: its edges border one cell.
  const std::string lone = error_of("v 0 0\nv 1 0\nv 0 1\nc 0 1 2\n");
  EXPECT_NE(lone.find(":4:"), std::string::npos) << lone;
  EXPECT_NE(lone.find("only one cell"), std::string::npos) << lone;
}

TEST(Recognition, BundledExamples) {
  const RecognitionResult ok = recognize_power_diagram(read_cell_complex(std::string(LAGUERRE_TEST_DATA) + "/../../tools/examples/diagrams/cells-power-12.txt"));
  EXPECT_TRUE(ok.is_power_diagram) << ok.message;
  EXPECT_EQ(ok.sites.size(), 11u);  // one of the 12 weighted points is hidden
  const CellComplex bad_cx = read_cell_complex(std::string(LAGUERRE_TEST_DATA) + "/../../tools/examples/diagrams/cells-not-power.txt");
  const RecognitionResult bad = recognize_power_diagram(bad_cx);
  EXPECT_FALSE(bad.is_power_diagram);
  ASSERT_FALSE(bad.broken.empty());
  // Vertex 1 was moved: every broken cycle is a cell through vertex 1 or through one of its neighbours.
  std::set<std::size_t> near_cells;
  std::set<std::size_t> near_vertices{1};
  for (const auto& c : bad_cx.cells)
    for (std::size_t m = 0; m < c.vertices.size(); ++m)
      if (c.vertices[m] == 1) {
        near_vertices.insert(c.vertices[(m + 1) % c.vertices.size()]);
        near_vertices.insert(c.vertices[(m + c.vertices.size() - 1) % c.vertices.size()]);
      }
  for (std::size_t i = 0; i < bad_cx.cells.size(); ++i)
    for (std::size_t v : bad_cx.cells[i].vertices)
      if (near_vertices.count(v)) near_cells.insert(i);
  for (const BrokenCycle& b : bad.broken) EXPECT_EQ(near_cells.count(b.cell), 1u) << b.kind << " " << b.cell;
}

}  // namespace
}  // namespace laguerre::core
