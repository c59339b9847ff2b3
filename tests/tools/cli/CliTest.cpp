// Runs the `laguerre` program as a user would and checks exit codes, messages and outputs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "CliRunner.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {
using laguerre::cli_test::Outcome;
using laguerre::cli_test::run;

class Cli : public laguerre::cli_test::ScratchDir {};

const std::string example = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/delaunay-60.txt";
const std::string example3 = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/three-connected-60.txt";
}  // namespace

TEST_F(Cli, HelpForEveryCommand) {
  for (const char* c : {"", "pack", "route", "thesis-table", "generate", "simulate"}) {
    const Outcome r = run(std::string(c) + " --help");
    EXPECT_EQ(r.status, 0) << c;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << c;
  }
}

TEST_F(Cli, PackWritesAGreedyEmbeddingAndPicture) {
  for (const auto& g : {example, example3}) {
    const std::string stem = path(fs::path(g).stem().string());
    const Outcome r = run("pack " + g + " -o " + stem);
    ASSERT_EQ(r.status, 0) << r.out;
    std::ifstream in(stem + ".json");
    const auto doc = nlohmann::json::parse(in);
    EXPECT_EQ(doc["format"], "laguerre-embedding");
    EXPECT_EQ(doc["packing"]["status"], "converged");
    ASSERT_EQ(doc["vertices"].size(), 60u);
    for (const auto& v : doc["vertices"]) EXPECT_EQ(v["local"], "holds");
    std::ifstream png(stem + ".png", std::ios::binary);
    char sig[8] = {};
    png.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
    EXPECT_TRUE(fs::file_size(stem + ".svg") > 1000);
  }
}

// The embedding file is streamed vertex by vertex (write_embedding_json): it must be, byte for byte,
// nlohmann's dump(1) of the document it holds (what `pack` wrote when it built the whole document),
// on a triangulation and on a 3-connected graph (face circles), in the file and on --json.
TEST_F(Cli, PackEmbeddingFileIsTheCanonicalDumpOfItsDocument) {
  for (const auto& g : {example, example3}) {
    const std::string stem = path(fs::path(g).stem().string());
    ASSERT_EQ(run("pack " + g + " --no-picture -o " + stem).status, 0);
    std::ifstream in(stem + ".json");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto doc = nlohmann::json::parse(text);
    EXPECT_EQ(doc.dump(1) + "\n", text) << g;
    EXPECT_EQ(doc["vertices"].size(), 60u);
    EXPECT_EQ(doc["vertices"][7]["local"], "holds");
    EXPECT_FALSE(doc["outer_face"].empty());
    if (g == example3) {
      EXPECT_FALSE(doc["face_circles"].empty());
    }
    const Outcome r = run("pack " + g + " --no-picture --json", false);  // standard output only
    ASSERT_EQ(r.status, 0);
    auto streamed = nlohmann::json::parse(r.out);
    EXPECT_EQ(streamed.dump(1) + "\n", r.out) << g;
    streamed["packing"].erase("seconds");  // the run's timings differ; everything else is the file's
    streamed["packing"].erase("cpu_seconds");
    streamed["packing"].erase("phase_seconds");
    auto stored = doc;
    stored["packing"].erase("seconds");
    stored["packing"].erase("cpu_seconds");
    stored["packing"].erase("phase_seconds");
    EXPECT_EQ(streamed, stored) << g;
  }
}

TEST_F(Cli, PackRefusesToOverwriteWithoutForce) {
  const std::string stem = path("e");
  ASSERT_EQ(run("pack " + example + " -o " + stem).status, 0);
  const Outcome again = run("pack " + example + " -o " + stem);
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.out.find("Refusing to overwrite"), std::string::npos) << again.out;
  EXPECT_EQ(run("pack " + example + " -o " + stem + " --force").status, 0);
}

TEST_F(Cli, RouteOnAnEmbeddingDeliversEverything) {
  const std::string stem = path("e");
  ASSERT_EQ(run("pack " + example + " -o " + stem).status, 0);
  const Outcome r = run("route " + stem + ".json --scheme greedy-power --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["schemes"][0]["pairs"], 60 * 59);
  EXPECT_EQ(doc["schemes"][0]["delivered"], 60 * 59);
}

TEST_F(Cli, BadInputGetsAClearErrorAndExitCode2) {
  const Outcome missing = run("pack " + path("nope.txt"));
  EXPECT_NE(missing.status, 0);
  const std::string bad = write("bad.txt", "1 2\n2 3\nthree 1\n");
  Outcome r = run("pack " + bad);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("bad.txt:3"), std::string::npos) << r.out;
  // K5 is not planar.
  const std::string k5 = write("k5.txt", "1 2\n1 3\n1 4\n1 5\n2 3\n2 4\n2 5\n3 4\n3 5\n4 5\n");
  r = run("pack " + k5);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("planar"), std::string::npos) << r.out;
  // A path is neither a triangulated disc nor 3-connected.
  const std::string path3 = write("path.txt", "1 2\n2 3\n3 4\n");
  r = run("pack " + path3);
  EXPECT_EQ(r.status, 2) << r.out;
  r = run("route " + example + " --pairs many");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--pairs"), std::string::npos) << r.out;
  r = run("pack " + example + " --stop sometimes");
  EXPECT_NE(r.status, 0);
}

TEST_F(Cli, PackNamesTheGraphFileProblemAndExits2) {
  const std::string text = write("tri.txt", "1 2\n2 3\n3 1\n");
  Outcome r = run("pack " + text + " --format planar_code");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("tri.txt: expected a planar_code file (header '>>planar_code<<'), found '1 2'"), std::string::npos)
      << r.out;
  // 50,000 nested elements: an error naming the file and line, not a stack overflow.
  std::string deep = "<?xml version=\"1.0\"?>\n<graphml>\n<graph>\n";
  for (int i = 0; i < 50000; ++i) deep += "<a>\n";
  r = run("pack " + write("deep.graphml", deep));
  EXPECT_EQ(r.status, 2) << r.out.substr(0, 300);
  EXPECT_NE(r.out.find("deep.graphml:258: the <a> element here is nested 257 deep"), std::string::npos)
      << r.out.substr(0, 300);
}

TEST_F(Cli, ThesisTableRunsOnASmallSample) {
  const Outcome r = run("thesis-table --count 2 --size 30 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto pos = r.out.find('{');
  const auto doc = nlohmann::json::parse(r.out.substr(pos));
  ASSERT_EQ(doc["families"].size(), 4u);  // triangulations, 3-connected, spheres under face and under puncture
  for (const auto& f : doc["families"]) {
    EXPECT_EQ(f["graphs"], 2);
    EXPECT_EQ(f["greedy_delivery_min"], 1.0);
    EXPECT_GE(f["ratio_mean"].template get<double>(), 1.0);
  }
}

TEST_F(Cli, GenerateIsDeterministic) {
  const Outcome a = run("generate three-connected -n 40 --seed 9");
  const Outcome b = run("generate three-connected -n 40 --seed 9");
  const Outcome c = run("generate three-connected -n 40 --seed 10");
  EXPECT_EQ(a.status, 0);
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out, c.out);
}

TEST_F(Cli, GenerateUniformFamiliesThatPack) {
  // The scenario samplers through `generate`, written as edge lists with their outer face, then
  // packed to LPD/GLPD: the way to reproduce one graph of a scenario run outside it.
  for (const char* family : {"uniform-triangulation", "uniform-three-connected"}) {
    const std::string file = path(std::string(family) + ".txt");
    const Outcome g = run(std::string("generate ") + family + " -n 40 --seed 3 --format edges -o " + file);
    ASSERT_EQ(g.status, 0) << g.out;
    EXPECT_EQ(run(std::string("generate ") + family + " -n 40 --seed 3 --format edges").out,
              run(std::string("generate ") + family + " -n 40 --seed 3 --format edges").out);
    const Outcome p = run("pack " + file + " --no-picture -o " + path(family));
    EXPECT_EQ(p.status, 0) << p.out;
    EXPECT_NE(p.out.find("40 / 40"), std::string::npos) << p.out;
  }
  const Outcome coords = run("generate uniform-triangulation -n 40 --format coords");
  EXPECT_EQ(coords.status, 2);
  EXPECT_NE(coords.out.find("no vertex positions"), std::string::npos) << coords.out;
}

TEST_F(Cli, PlanarCodeFilesWithSeveralGraphs) {
  const std::string pc = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/graphs/three-connected-40x5.pc";
  for (int i = 1; i <= 5; ++i) {
    const Outcome r = run("pack " + pc + " --index " + std::to_string(i) + " --no-picture -o " + path("g" + std::to_string(i)));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("#" + std::to_string(i)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("GLPD         40 / 40"), std::string::npos) << r.out;
  }
  const Outcome bad = run("pack " + pc + " --index 6 --no-picture -o " + path("g6"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("holds 5 graph(s)"), std::string::npos) << bad.out;
  const Outcome routed = run("route " + pc + " --index 2 --scheme greedy-power --json");
  ASSERT_EQ(routed.status, 0) << routed.out;
  const auto doc = nlohmann::json::parse(routed.out);
  EXPECT_EQ(doc["schemes"][0]["delivered"], doc["schemes"][0]["pairs"]);
}

TEST_F(Cli, SimulateRunsTheProtocolAndMatchesTheCore) {
  for (const auto& g : {example, example3}) {
    const Outcome r = run("simulate " + g + " --verify --latency uniform:1ms:4ms -N 2 --pairs 300 --json");
    ASSERT_EQ(r.status, 0) << r.out;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["converged_nodes"], 60);
    EXPECT_EQ(doc["local_condition_holds"], 60);
    EXPECT_EQ(doc["verify"], "identical to core::pack, bit for bit");
    EXPECT_EQ(doc["packets"], 300);
    EXPECT_EQ(doc["delivered"], 300);
    EXPECT_GT(doc["events_per_second"].get<double>(), 0.0);
  }
  // Same seed, same run; the simulated time depends on the seed through the random latencies.
  const Outcome a = run("simulate " + example + " --latency uniform:1ms:4ms --seed 3 --json --pairs 10");
  const Outcome b = run("simulate " + example + " --latency uniform:1ms:4ms --seed 3 --json --pairs 10");
  const Outcome c = run("simulate " + example + " --latency uniform:1ms:4ms --seed 4 --json --pairs 10");
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out), jc = nlohmann::json::parse(c.out);
  EXPECT_EQ(ja["simulated_seconds"], jb["simulated_seconds"]);
  EXPECT_EQ(ja["messages"], jb["messages"]);
  EXPECT_NE(ja["simulated_seconds"], jc["simulated_seconds"]);
}

TEST_F(Cli, SimulateRejectsWhatItCannotDoYet) {
  Outcome r = run("simulate " + example + " --mode sometimes");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--mode"), std::string::npos) << r.out;
  laguerre::cli_test::expect_bad_input("simulate " + example + " --latency sometimes", {"--latency"});
  laguerre::cli_test::expect_bad_input("simulate " + example + " --crash 17x", {"--crash"});
  laguerre::cli_test::expect_bad_input("simulate " + example + " --crash 999@1ms", {"no node with id 999"});
}

TEST_F(Cli, SimulateSurvivesLossAndDuplicationBitForBit) {
  const auto doc =
      laguerre::cli_test::run_json("simulate " + example + " --loss 0.2 --dup 0.05 --latency uniform:1ms:5ms --verify --pairs 50 --json");
  EXPECT_EQ(doc["converged_nodes"], 60);
  EXPECT_EQ(doc["verify"], "identical to core::pack, bit for bit");
  EXPECT_GT(doc["reliability"]["retransmissions"].get<int>(), 0);
  EXPECT_GT(doc["reliability"]["duplicates"].get<int>(), 0);
  EXPECT_EQ(doc["reliability"]["links_given_up"], 0);
  const Outcome text = run("simulate " + example + " --loss 0.1 --dup 0.05 --verify --pairs 10");
  ASSERT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("retransmissions"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("duplicates detected"), std::string::npos) << text.out;
}

TEST_F(Cli, SimulateRunsTheAsynchronousMode) {
  for (const auto& g : {example, example3}) {
    const Outcome r = run("simulate " + g + " --mode async --loss 0.1 --latency uniform:1ms:4ms --verify --pairs 50 --json");
    ASSERT_EQ(r.status, 0) << r.out;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["mode"], "async");
    EXPECT_EQ(doc["converged_nodes"], 60);
    EXPECT_NE(doc["verify"].get<std::string>().find("holds at 60/60 nodes"), std::string::npos) << r.out;
    EXPECT_EQ(doc["delivered"], doc["packets"]);
  }
}

TEST_F(Cli, SimulateReportsACrashedNodeAtEverySurvivor) {
  const Outcome r = run("simulate " + example + " --crash 17@100ms --verify --json --pairs 5");
  EXPECT_EQ(r.status, 3) << r.out;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["survivors"], 59);
  EXPECT_EQ(doc["failed_nodes"], 59);
  EXPECT_EQ(doc["suspects"]["17"], 59);
  EXPECT_EQ(doc["verify"], "not applicable: the run was abandoned after a node failure");
}

namespace {
/// The icosahedron with ids 3..14: a triangulated sphere, every vertex of degree 5.
std::string icosahedron_edges() {
  std::string text = "# the icosahedron: every face a triangle, no '# outer:' line\n";
  auto edge = [&](int a, int b) { text += std::to_string(a + 3) + " " + std::to_string(b + 3) + "\n"; };
  for (int i = 1; i <= 5; ++i) {
    const int next = i % 5 + 1;
    edge(0, i);             // top to the upper ring
    edge(i, next);          // upper ring
    edge(i + 5, next + 5);  // lower ring
    edge(i, i + 5);
    edge(i, next + 5);
    edge(11, i + 5);  // bottom to the lower ring
  }
  return text;
}
}  // namespace

TEST_F(Cli, OuterPunctureRemovesTheLargestDegreeVertexAndReportsIt) {
  using laguerre::cli_test::run_json;
  const std::string sphere = write("ico.edges", icosahedron_edges());
  nlohmann::json doc = run_json("pack " + sphere + " --json --no-picture");
  EXPECT_EQ(doc["outer_rule"], "face");
  EXPECT_TRUE(doc["removed_vertices"].empty());
  EXPECT_EQ(doc["vertices"].size(), 12u);
  EXPECT_EQ(doc["outer_face"].size(), 3u);

  doc = run_json("pack " + sphere + " --outer puncture --json --no-picture");
  EXPECT_EQ(doc["outer_rule"], "puncture");
  EXPECT_EQ(doc["removed_vertices"], nlohmann::json::array({3}));  // all of degree 5: the smallest id
  EXPECT_EQ(doc["vertices"].size(), 11u);
  EXPECT_EQ(doc["packing"]["status"], "converged");
  std::vector<std::uint64_t> outer = doc["outer_face"].get<std::vector<std::uint64_t>>();
  std::sort(outer.begin(), outer.end());
  EXPECT_EQ(outer, (std::vector<std::uint64_t>{4, 5, 6, 7, 8}));  // the link of vertex 3
  for (const auto& v : doc["vertices"]) EXPECT_NE(v["id"], 3);
  const Outcome text = run("pack " + sphere + " --outer puncture --no-picture -o " + path("ico"));
  EXPECT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("removed      1 vertex 3 (--outer puncture"), std::string::npos) << text.out;

  doc = run_json("simulate " + sphere + " --outer puncture --json");
  EXPECT_EQ(doc["removed_vertices"], nlohmann::json::array({3}));
  EXPECT_EQ(doc["nodes"], 11);
  EXPECT_EQ(doc["packets"], 11 * 10);
  EXPECT_EQ(doc["delivered"], doc["packets"]);
}

TEST_F(Cli, ThesisTablePacksTheSameSpheresUnderBothOuterRules) {
  const nlohmann::json doc = laguerre::cli_test::run_json("thesis-table --family spheres --count 2 --size 30 --json");
  ASSERT_EQ(doc["families"].size(), 2u);
  EXPECT_EQ(doc["families"][0]["family"], "spheres/face");
  EXPECT_EQ(doc["families"][1]["family"], "spheres/puncture");
  EXPECT_EQ(doc["families"][0]["removed_vertices"], 0);
  EXPECT_EQ(doc["families"][1]["removed_vertices"], 2);
  EXPECT_EQ(doc["families"][0]["n_mean"], 30.0);
  EXPECT_EQ(doc["families"][1]["n_mean"], 29.0);
  for (const auto& f : doc["families"]) {
    EXPECT_EQ(f["graphs"], 2);
    EXPECT_EQ(f["not_converged"], 0);
    EXPECT_EQ(f["greedy_delivery_min"], 1.0);
  }
  ASSERT_EQ(doc["graphs"].size(), 4u);  // sphere#1 face, sphere#1 puncture, sphere#2 face, sphere#2 puncture
  EXPECT_EQ(doc["graphs"][0]["name"], doc["graphs"][1]["name"]);
  EXPECT_EQ(doc["graphs"][0]["outer"], "face");
  EXPECT_EQ(doc["graphs"][1]["outer"], "puncture");
}
