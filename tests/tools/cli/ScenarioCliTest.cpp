// `laguerre run` and `laguerre compare` as a user runs them: exit codes, outputs, the overwrite
// refusal, golden validation messages, and every bundled example scenario at a small size.
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

namespace {
using Result = laguerre::cli_test::Outcome;

Result run_laguerre(const std::string& args) { return laguerre::cli_test::run(args); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string source = LAGUERRE_SOURCE_DIR;
const std::string scenarios = source + "/scenarios/";
const std::string data = source + "/tests/data/scenarios/";

class ScenarioCli : public laguerre::cli_test::ScratchDir {
protected:
  std::string out(const std::string& name) const { return path(name); }
};
}  // namespace

TEST_F(ScenarioCli, QuickstartWritesResultsAndPictures) {
  const Result r = run_laguerre("run " + scenarios + "quickstart.yaml -o " + out("q"));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("greedy-power"), std::string::npos) << r.out;
  const auto doc = nlohmann::json::parse(slurp(dir_ / "q" / "results.json"));
  EXPECT_EQ(doc["scenario"], "quickstart");
  ASSERT_EQ(doc["runs"].size(), 1u);
  const auto& run = doc["runs"][0];
  EXPECT_EQ(run["status"], "ok");
  EXPECT_EQ(run["nodes"], 60);
  EXPECT_EQ(run["local_condition_holds"], 60);
  EXPECT_EQ(run["routing"]["greedy-power"]["pairs"], 60 * 59);
  EXPECT_EQ(run["routing"]["greedy-power"]["delivered"], 60 * 59);  // LPD ⇒ greedy power delivers
  for (const char* f : {"results.csv", "pictures/point-000.svg", "pictures/point-000.png"})
    EXPECT_GT(fs::file_size(dir_ / "q" / f), 100u) << f;
  // CSV: a header and one line per scheme.
  std::istringstream csv(slurp(dir_ / "q" / "results.csv"));
  std::size_t lines = 0;
  for (std::string l; std::getline(csv, l);) ++lines;
  EXPECT_EQ(lines, 1u + 4u);
}

TEST_F(ScenarioCli, RefusesToOverwriteWithoutForce) {
  ASSERT_EQ(run_laguerre("run " + scenarios + "quickstart.yaml -o " + out("q") + " --set topology.n=20").status, 0);
  const Result again = run_laguerre("run " + scenarios + "quickstart.yaml -o " + out("q") + " --set topology.n=20");
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.out.find("Refusing to overwrite the result folder"), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("--force"), std::string::npos);
  std::ofstream(dir_ / "q" / "notes.txt") << "mine";
  EXPECT_EQ(run_laguerre("run " + scenarios + "quickstart.yaml -o " + out("q") + " --set topology.n=20 --force").status, 0);
  EXPECT_TRUE(fs::exists(dir_ / "q" / "notes.txt"));  // --force replaces only what run writes
  EXPECT_EQ(run_laguerre("compare " + scenarios + "quickstart.yaml -o " + out("q") + " --set topology.n=20").status, 2);
}

TEST_F(ScenarioCli, JobsDoNotChangeResults) {
  const std::string common = "run " + data + "good-sweep.yaml --set repetitions=1 ";
  ASSERT_EQ(run_laguerre(common + "--jobs 1 -o " + out("a")).status, 0);
  ASSERT_EQ(run_laguerre(common + "--jobs 2 -o " + out("b")).status, 0);
  auto strip = [](nlohmann::json d) {
    for (auto& run : d["runs"]) run.erase("wall_seconds");
    return d;
  };
  EXPECT_EQ(strip(nlohmann::json::parse(slurp(dir_ / "a" / "results.json"))),
            strip(nlohmann::json::parse(slurp(dir_ / "b" / "results.json"))));
  EXPECT_EQ(slurp(dir_ / "a" / "results.csv"), slurp(dir_ / "b" / "results.csv"));
}

// The golden messages, through the program: stderr lists them all, exit status 2, nothing written.
TEST_F(ScenarioCli, ValidationMessagesAndExitStatus) {
  for (const char* name : {"bad-types", "bad-keys", "duplicate-keys"}) {
    const Result r = run_laguerre("run " + data + name + ".yaml -o " + out(name));
    EXPECT_EQ(r.status, 2) << name;
    std::istringstream expected(slurp(data + name + ".expected"));
    std::size_t count = 0;
    for (std::string line; std::getline(expected, line);) {
      if (line.empty()) continue;
      ++count;
      EXPECT_NE(r.out.find(data + line), std::string::npos) << "missing: " << line << "\nin:\n" << r.out;
    }
    EXPECT_NE(r.out.find(std::to_string(count) + " problem(s)"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out(name)));
  }
  const Result set = run_laguerre("run " + scenarios + "quickstart.yaml -o " + out("x") + " --set topology.n=2");
  EXPECT_EQ(set.status, 2);
  EXPECT_NE(set.out.find("--set topology.n=2: topology.n: found '2', expected an integer in [3, 10000000]"),
            std::string::npos)
      << set.out;
}

TEST_F(ScenarioCli, UnsupportedTopologyExitsThree) {
  const Result r = run_laguerre("run " + data + "unpackable.yaml -o " + out("u"));
  EXPECT_EQ(r.status, 3) << r.out;
  EXPECT_NE(r.out.find("unsupported"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "u" / "results.json"));
}

TEST_F(ScenarioCli, CompareWritesTablesAndCharts) {
  const Result r = run_laguerre("compare " + data + "good-sweep.yaml --set repetitions=2 --set network.loss=0 -o " + out("c"));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("95% CI"), std::string::npos) << r.out;
  const auto doc = nlohmann::json::parse(slurp(dir_ / "c" / "comparison.json"));
  ASSERT_EQ(doc["rows"].size(), 8u);  // (2 families × 2 sizes) × 2 schemes
  for (const auto& row : doc["rows"]) {
    EXPECT_EQ(row["runs"], 2);
    EXPECT_EQ(row["ci_method"], "t");
    if (row["scheme"] == "greedy-power") {
      EXPECT_EQ(row["delivery_mean"], 1.0);
    }
  }
  for (const char* f : {"comparison.csv", "charts/comparison-delivery.svg", "charts/comparison-delivery.png",
                        "charts/comparison-stretch.svg", "charts/comparison-stretch.png"})
    EXPECT_GT(fs::file_size(dir_ / "c" / f), 100u) << f;
}

// Every bundled example at a small size (the sizes keep each under a few seconds).
TEST_F(ScenarioCli, EveryExampleRunsSmall) {
  struct Example {
    const char* file;
    const char* overrides;
    bool all_ok;
  };
  const Example examples[] = {
      {"quickstart.yaml", "--set topology.n=30", true},
      {"thesis-triangulations.yaml", "--set repetitions=2 --set topology.n=20", true},
      {"thesis-3connected.yaml", "--set repetitions=2 --set topology.n=20", true},
      {"sensor-field.yaml", "--set repetitions=1 --set topology.n=300", true},
      {"field-with-holes.yaml", "--set repetitions=1 --set topology.n=150", false},
      {"lossy.yaml", "--set repetitions=1 --set topology.n=30", true},
      {"large.yaml", "--set topology.n=300", true},
      {"comparison.yaml",
       "--set repetitions=1 --set 'sweep.topology=[{generator: uniform-triangulation, n: 30}, {generator: "
       "uniform-three-connected, n: 30}, {generator: field, n: 60, graph: local-delaunay, radius: 0.3, repair: "
       "three-connected-core}]'",
       false},
      {"comparison-5000.yaml",
       "--set repetitions=1 --set 'sweep.topology=[{generator: uniform-triangulation, n: 300}, {generator: "
       "uniform-three-connected, n: 300}, {generator: field, n: 300, graph: local-delaunay, radius: 0.13, repair: "
       "three-connected-core}]'",
       true},
      {"comparison-50000.yaml",
       "--set protocol.steps_per_round=2 --set 'sweep.topology=[{generator: delaunay, n: 300}, {generator: field, "
       "n: 300, graph: local-delaunay, radius: 0.13, repair: three-connected-core, attach: true}]'",
       true},
      {"mesh-field.yaml", "--set repetitions=1 --set topology.metric=uniform:0.25:0.25", true},
      {"mesh-holes.yaml", "--set repetitions=1 --set topology.metric=uniform:0.25:0.25", true},
      {"baseline-hyperbolic.yaml",
       "--set repetitions=1 --set routing.pairs=200 --set 'sweep.topology=[{generator: field, n: 80, radius: 0.25, "
       "domain: [[[0, 0], [1, 0], [1, 1], [0, 1]], [[0.2, 0.2], [0.4, 0.2], [0.4, 0.35], [0.2, 0.35]]], "
       "graph: local-delaunay, repair: three-connected-core}]'",
       true},
      {"field-holes-comparison.yaml",
       "--set repetitions=1 --set routing.pairs=500 --set 'sweep.topology=[{generator: field, n: 200, radius: 0.14, "
       "graph: local-delaunay, repair: three-connected-core, attach: true}]'",
       true},
      {"field-holes-50000.yaml", "--set topology.n=200 --set topology.radius=0.14 --set routing.pairs=500", true},
  };
  std::size_t bundled = 0;
  for (const auto& e : fs::directory_iterator(scenarios)) bundled += e.path().extension() == ".yaml";
  EXPECT_EQ(bundled, std::size(examples)) << "a bundled scenario has no test here";
  for (const auto& e : examples) {
    const std::string dir = out(fs::path(e.file).stem().string());
    const Result r = run_laguerre("run " + scenarios + e.file + " " + e.overrides + " -o " + dir);
    // 0: every run ok; 3: some run ended otherwise (e.g. a sparse random field that cannot be packed).
    EXPECT_TRUE(r.status == 0 || (!e.all_ok && r.status == 3)) << e.file << " exit " << r.status << "\n" << r.out;
    const auto doc = nlohmann::json::parse(slurp(fs::path(dir) / "results.json"));
    std::size_t ok = 0;
    for (const auto& run : doc["runs"]) ok += run["status"] == "ok";
    EXPECT_GT(ok, 0u) << e.file;
    if (std::string(e.file).rfind("thesis", 0) == 0) {
      EXPECT_NE(r.out.find("to an exact packing"), std::string::npos) << r.out;
    }
  }
}

// `run --help` lists the topology generators with their keys, from the registry's own table
// (scenarios::generators_help), so the help cannot drift from what the loader accepts.
TEST_F(ScenarioCli, RunHelpListsTheGeneratorsAndTheirKeys) {
  const Result r = run_laguerre("run --help");
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* needle : {"Topology generators", "\ndelaunay: ", "\nuniform-three-connected: ", "\nfield: ",
                             "  repair (choice fail|"})
    EXPECT_NE(r.out.find(needle), std::string::npos) << needle << "\n" << r.out;
}
