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

/// The JSON a successful `laguerre ARGS` writes on standard output.
json run_json(const std::string& args) {
  const Outcome r = run(args, false);
  EXPECT_EQ(r.status, 0) << args << ": " << r.out;
  return r.status == 0 ? json::parse(r.out) : json();
}

/// `laguerre ARGS` must fail with exit status 2 and a message containing every one of `parts`.
void expect_input_error(const std::string& args, std::initializer_list<std::string> parts) {
  const Outcome r = run(args);
  EXPECT_EQ(r.status, 2) << args << ": " << r.out;
  for (const std::string& part : parts) EXPECT_NE(r.out.find(part), std::string::npos) << args << ": " << r.out;
}
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
  const json j = run_json("diagram --kind voronoi " + f + " --box -3,-3,5,5");
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
  const json j = run_json("diagram --kind power " + example("power-circles-10.txt"));
  EXPECT_EQ(j["hidden"], json::array({9}));
  EXPECT_TRUE(j["cells"][9]["components"].empty());
}

TEST_F(DiagramCli, MobiusRingHasADisconnectedCellWithAHole) {
  const json j = run_json("diagram --kind mobius " + example("mobius-ring-9.txt") + " --box -0.4,-0.4,1.4,1.4");
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
  const json j = run_json("diagram --kind mw " + f + " --box -5,-5,8,5");
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

TEST_F(DiagramCli, NumbersBeyondTheAdmissibleRangeNameTheLine) {
  // Formerly: 1e160 crashed with SIGFPE, 1e-300 gave "valid": true with a vertex [null, null], weights
  // of 1e300 ran for minutes. Now each is refused at its line (exit status 2).
  const std::string range = "expected 0 or a magnitude between 1e-150 and 1e150";
  const std::string big = write("big.txt", "0 0\n1e160 0\n0 1e160\n");
  expect_input_error("diagram --kind voronoi " + big, {big + ":2: found '1e160' in column 1 `x`", range});
  const std::string tiny = write("tiny.txt", "0 0\n1e-300 0\n0 1e-300\n");
  expect_input_error("diagram --kind voronoi " + tiny, {tiny + ":2: found '1e-300' in column 1 `x`", range});
  const std::string heavy = write("heavy.txt", "0 0 1\n1 0 1\n0 1 1e300\n");
  expect_input_error("diagram --kind power " + heavy, {heavy + ":3: found '1e300' in column 3 `w`", range, "power diagram"});
  expect_input_error("diagram --kind apollonius " + heavy, {heavy + ":3:", range, "Apollonius diagram"});
  expect_input_error("diagram --kind anisotropic " + write("m.txt", "0 0 1 0 1\n1 1 1e200 0 1\n"), {":2:", range});
  // Möbius and mw sites: the lifted sphere (λx, λy, (1 − λ)/2, weight) must stay within 1e75.
  const std::string lifted = write("lifted.txt", "0 0 1 0\n1 1 1 0\n1e40 0 1e40 0\n");
  expect_input_error("diagram --kind mobius " + lifted, {lifted + ":3:", "lifts to a sphere of magnitude", "at most 1e75"});
  const std::string light = write("light.txt", "0 0 1\n1 1 1e-38\n");
  expect_input_error("diagram --kind mw " + light, {light + ":2:", "at most 1e75"});
  // At the edge of the range the diagram is computed; a picture with a circle of radius 1e75 in a
  // window of size 3 does not stall (Cairo used to flatten it into countless segments).
  const json scaled = run_json("diagram --kind power " + write("edge.txt", "0 0 2.5e149\n1e75 0 0\n0 1e75 0\n-1e75 -1e75 1\n"));
  EXPECT_TRUE(scaled["valid"].get<bool>()) << scaled.value("invalid_reason", "");
  EXPECT_TRUE(scaled["hidden"].empty());
  EXPECT_EQ(scaled["vertices"].size(), 3u);  // the origin inside the triangle of the other three
  const Outcome r = run("diagram --kind power " + write("huge.txt", "0 0 1e150\n1 0 0\n0 1 0\n-1 -1 1\n") + " -o " + path("huge"));
  ASSERT_EQ(r.status, 0) << r.out;
  const json huge = load(path("huge.json"));
  EXPECT_TRUE(huge["valid"].get<bool>()) << huge.value("invalid_reason", "");
  // The three light sites' cells are non-empty but lie beyond x or y = 5e149: one cell fills the box.
  EXPECT_TRUE(huge["hidden"].empty());
  EXPECT_TRUE(huge["edges"].empty());
  EXPECT_EQ(huge["cells"][0]["components"].size(), 1u);
  for (int k = 1; k <= 3; ++k) EXPECT_TRUE(huge["cells"][k]["components"].empty());
}

TEST_F(DiagramCli, EveryKindNamesItselfInItsErrors) {
  expect_input_error("diagram --kind mw " + write("mw0.txt", "0 0 1\n1 1 0\n"),
                     {"mw0.txt:2: found the weight w = 0", "w > 0", "multiplicatively weighted Voronoi diagram"});
  expect_input_error("diagram --kind mw " + write("mw2.txt", "0 0 1\n1 1\n"),
                     {"mw2.txt:2:", "`x y w` (multiplicatively weighted Voronoi diagram sites)"});
  const Outcome r = run("diagram --kind mw " + write("mw3.txt", "0 0 1\n1 1 1e-200\n"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out.find("Möbius"), std::string::npos) << r.out;
  expect_input_error("diagram --kind mobius " + write("mo.txt", "0 0 1\n"), {"`x y lambda mu` (Möbius diagram sites)"});
  expect_input_error("diagram --kind anisotropic " + write("an.txt", "0 0 1 0\n"), {"`x y a b c` (anisotropic diagram sites)"});
  expect_input_error("diagram --kind voronoi " + write("empty.txt", "# nothing\n"), {"no sites", "Voronoi diagram"});
}

TEST_F(DiagramCli, DirectoriesAndMissingFilesAreReportedAsEverywhere) {
  for (const char* kind : {"voronoi", "power", "mobius", "mw", "apollonius", "anisotropic"})
    expect_input_error(std::string("diagram --kind ") + kind + " " + path(""), {"is a directory; expected a sites file."});
  expect_input_error("diagram --recognize " + path(""), {"is a directory; expected a cells file."});
  expect_input_error("diagram --kind power " + path("missing.txt"), {"missing.txt: no such sites file"});
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
