// `laguerre diagram`: every kind on the bundled example sites, the JSON structure, known answers on
// small inputs, and the errors for bad input (file:line, what was found and expected).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "CliRunner.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
using laguerre::cli_test::Outcome;
using laguerre::cli_test::run;

class DiagramCli : public laguerre::cli_test::ScratchDir {};

std::string example(const std::string& name) {
  return std::string(LAGUERRE_SOURCE_DIR) + "/tools/examples/diagrams/" + name;
}

json load(const std::string& p) { return json::parse(std::ifstream(p)); }
}  // namespace

TEST_F(DiagramCli, EveryKindOnTheBundledExamples) {
  const std::array<std::pair<const char*, const char*>, 6> cases{{{"voronoi", "voronoi-points-9.txt"},
                                                                  {"power", "power-circles-10.txt"},
                                                                  {"mobius", "mobius-random-40.txt"},
                                                                  {"mw", "mw-sites-9.txt"},
                                                                  {"apollonius", "apollonius-circles.txt"},
                                                                  {"anisotropic", "anisotropic-flowers.txt"}}};
  for (const auto& [kind, file] : cases) {
    const std::string stem = path(kind);
    const Outcome r = run(std::string("diagram --kind ") + kind + " " + example(file) + " -o " + stem);
    ASSERT_EQ(r.status, 0) << kind << ": " << r.out;
    for (const char* ext : {".json", ".svg", ".png"}) EXPECT_GT(fs::file_size(stem + ext), 100u) << kind << ext;
    const json j = load(stem + ".json");
    EXPECT_EQ(j["kind"], kind);
    EXPECT_FALSE(j["sites"].empty());
    EXPECT_FALSE(j["edges"].empty());
    for (const auto& e : j["edges"]) {
      ASSERT_EQ(e["sites"].size(), 2u);
      EXPECT_LT(e["sites"][0].get<int>(), e["sites"][1].get<int>());
    }
    if (j.contains("valid")) {
      EXPECT_TRUE(j["valid"].get<bool>()) << kind << ": " << j.value("invalid_reason", "");
    }
  }
}

TEST_F(DiagramCli, VoronoiJsonOnStandardOutput) {
  // Three points of a right triangle: one Voronoi vertex at the hypotenuse midpoint, three edges.
  const std::string f = write("tri.txt", "# a right triangle\n0 0\n2 0\n\n0 2  # legs of length 2\n");
  const Outcome r = run("diagram --kind voronoi " + f + " --box -3,-3,5,5", false);
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["vertices"].size(), 1u);
  EXPECT_NEAR(j["vertices"][0]["point"][0].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(j["vertices"][0]["point"][1].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(j["edges"].size(), 3u);
  EXPECT_EQ(j["dual_edges"].size(), 3u);
  EXPECT_EQ(j["cells"].size(), 3u);
  // The three clipped cells tile the 8 × 8 box.
  double area = 0;
  for (const auto& c : j["cells"]) {
    const auto& poly = c["components"][0]["outer"];
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const auto& p = poly[k];
      const auto& q = poly[(k + 1) % poly.size()];
      area += 0.5 * (p[0].get<double>() * q[1].get<double>() - p[1].get<double>() * q[0].get<double>());
    }
  }
  EXPECT_NEAR(area, 64.0, 1e-9);
}

TEST_F(DiagramCli, PowerReportsTheHiddenSite) {
  const Outcome r = run("diagram --kind power " + example("power-circles-10.txt"), false);
  ASSERT_EQ(r.status, 0);
  const json j = json::parse(r.out);
  EXPECT_EQ(j["hidden"], json::array({9}));
  EXPECT_TRUE(j["cells"][9]["components"].empty());
}

TEST_F(DiagramCli, MobiusRingHasADisconnectedCellWithAHole) {
  const Outcome r = run("diagram --kind mobius " + example("mobius-ring-9.txt") + " --box -0.4,-0.4,1.4,1.4", false);
  ASSERT_EQ(r.status, 0);
  const json j = json::parse(r.out);
  const auto& comps = j["cells"][0]["components"];
  ASSERT_EQ(comps.size(), 2u);
  EXPECT_EQ(comps[0]["holes"].size() + comps[1]["holes"].size(), 1u);
  // Every ring site's cell is one component without holes; all edges are circle arcs or segments
  // between labelled vertices.
  for (int k = 1; k <= 8; ++k) {
    ASSERT_EQ(j["cells"][k]["components"].size(), 1u);
    EXPECT_TRUE(j["cells"][k]["components"][0]["holes"].empty());
  }
  for (const auto& e : j["edges"]) EXPECT_TRUE(e["type"] == "arc" || e["type"] == "segment");
}

TEST_F(DiagramCli, MultiplicativelyWeightedTwoSites) {
  // |x| / 2 = |x − (3, 0)| / 1: the Apollonius circle of centre (4, 0), radius 2.
  const std::string f = write("mw.txt", "0 0 2\n3 0 1\n");
  const Outcome r = run("diagram --kind mw " + f + " --box -5,-5,8,5", false);
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["edges"].size(), 1u);
  EXPECT_EQ(j["edges"][0]["type"], "arc");
  EXPECT_NEAR(j["edges"][0]["centre"][0].get<double>(), 4.0, 1e-12);
  EXPECT_NEAR(j["edges"][0]["radius"].get<double>(), 2.0, 1e-12);
  EXPECT_EQ(j["edges"][0]["left"], 1);  // the smaller weight (larger λ) is inside
}

TEST_F(DiagramCli, BadInputNamesFileAndLine) {
  const std::string f = write("bad.txt", "0 0 1\n1 2\n");
  Outcome r = run("diagram --kind power " + f);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find(f + ":2:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("expected 3 numbers `x y w`"), std::string::npos) << r.out;
  const std::string g = write("nan.txt", "0 0 1 2\n1 zz 1 0\n");
  r = run("diagram --kind mobius " + g);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find(g + ":2:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("'zz'"), std::string::npos) << r.out;
  const std::string h = write("neg.txt", "0 0 1\n1 1 -2\n");
  r = run("diagram --kind mw " + h);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("w > 0"), std::string::npos) << r.out;
  r = run("diagram --kind voronoi " + example("voronoi-points-9.txt") + " --box 1,0,0,1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--box"), std::string::npos) << r.out;
  r = run("diagram --kind voronoi " + path("missing.txt"));
  EXPECT_EQ(r.status, 2);
  r = run("diagram --kind hexagonal " + example("voronoi-points-9.txt"));
  EXPECT_NE(r.status, 0);
}

TEST_F(DiagramCli, RefusesToOverwriteWithoutForce) {
  const std::string stem = path("v");
  ASSERT_EQ(run("diagram --kind voronoi " + example("voronoi-points-9.txt") + " -o " + stem).status, 0);
  const Outcome r = run("diagram --kind voronoi " + example("voronoi-points-9.txt") + " -o " + stem);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--force"), std::string::npos);
  EXPECT_EQ(run("diagram --kind voronoi " + example("voronoi-points-9.txt") + " -o " + stem + " --force").status, 0);
}

TEST_F(DiagramCli, RecognizeRoundTrip) {
  // A power diagram's cells file is recognized; the recovered sites (up to p ↦ κp + t) give a power
  // diagram with as many visible cells and as many vertices as the file has.
  Outcome r = run("diagram --recognize " + example("cells-power-12.txt"), false);
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["is_power_diagram"].get<bool>());
  EXPECT_TRUE(j["broken"].empty());
  std::ifstream in(example("cells-power-12.txt"));
  std::size_t cells = 0, vertices = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("c ", 0) == 0) ++cells;
    if (line.rfind("v ", 0) == 0) ++vertices;
  }
  ASSERT_EQ(j["sites"].size(), cells);
  std::ostringstream sites;
  sites.precision(17);
  for (const auto& s : j["sites"]) sites << s["x"].get<double>() << ' ' << s["y"].get<double>() << ' ' << s["w"].get<double>() << '\n';
  const std::string f = write("recovered.txt", sites.str());
  r = run("diagram --kind power " + f, false);
  ASSERT_EQ(r.status, 0) << r.out;
  const json p = json::parse(r.out);
  EXPECT_TRUE(p["hidden"].empty());
  EXPECT_EQ(p["vertices"].size(), vertices);
  // Not a power diagram: exit status 3 and the broken cycles.
  r = run("diagram --recognize " + example("cells-not-power.txt"), false);
  EXPECT_EQ(r.status, 3);
  const json q = json::parse(r.out);
  EXPECT_FALSE(q["is_power_diagram"].get<bool>());
  EXPECT_FALSE(q["broken"].empty());
  // --kind and --recognize exclude each other; neither is an error.
  EXPECT_NE(run("diagram --kind power --recognize " + example("cells-power-12.txt")).status, 0);
  EXPECT_EQ(run("diagram " + example("cells-power-12.txt")).status, 2);
}
