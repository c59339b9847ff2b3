// The scenario loader: golden validation messages, defaults, sweeps, overrides, path resolution.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/scenarios/ScenarioLoader.hpp"

namespace fs = std::filesystem;
using namespace laguerre;
using namespace laguerre::scenarios;

namespace {
const std::string data_dir = std::string(LAGUERRE_TEST_DATA) + "/scenarios";

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

// Loads data/scenarios/NAME.yaml and returns the messages with the folder prefix removed.
std::vector<std::string> issues_of(const std::string& name, const LoadOptions& options = {}) {
  try {
    (void)load_scenario(data_dir + "/" + name, options);
  } catch (const ScenarioError& e) {
    std::vector<std::string> out;
    for (const auto& i : e.issues())  // the file name as written in the golden files, without its folder
      out.push_back(i.rfind(data_dir + "/", 0) == 0 ? i.substr(data_dir.size() + 1) : i);
    return out;
  }
  return {};
}

Scenario from_text(const std::string& text, const LoadOptions& options = {}) {
  return load_scenario_from_string(text, "test.yaml", data_dir, options);
}
}  // namespace

// Golden files: every problem of each bad file, located by line and column, in file order.
TEST(ScenarioLoader, GoldenMessages) {
  const std::string dir = fs::path(data_dir).lexically_normal().string();
  for (const char* name : {"bad-types", "bad-keys", "bad-files", "duplicate-keys"}) {
    std::vector<std::string> expected;
    for (const auto& l : lines_of(data_dir + "/" + name + ".expected")) expected.push_back(replace_all(l, "{DIR}", dir));
    EXPECT_EQ(issues_of(std::string(name) + ".yaml"), expected) << name;
  }
}

TEST(ScenarioLoader, EveryMessageHasTheDocumentedShape) {
  for (const char* name : {"bad-types.yaml", "bad-keys.yaml", "bad-files.yaml", "duplicate-keys.yaml"})
    for (const auto& m : issues_of(name)) {
      // FILE:LINE:COLUMN: key.path: found X, expected Y
      const std::size_t c1 = m.find(':'), c2 = m.find(':', c1 + 1), c3 = m.find(':', c2 + 1);
      ASSERT_NE(c3, std::string::npos) << m;
      EXPECT_GT(std::stoi(m.substr(c1 + 1, c2 - c1 - 1)), 0) << m;
      EXPECT_GT(std::stoi(m.substr(c2 + 1, c3 - c2 - 1)), 0) << m;
      EXPECT_NE(m.find(": found "), std::string::npos) << m;
      EXPECT_NE(m.find(", expected "), std::string::npos) << m;
    }
}

TEST(ScenarioLoader, SyntaxErrorIsLocated) {
  try {
    (void)from_text("name: x\ntopology: [a, b\n");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].rfind("test.yaml:", 0), 0u) << e.issues()[0];
    EXPECT_NE(e.issues()[0].find("invalid YAML"), std::string::npos);
  }
}

TEST(ScenarioLoader, MissingFileIsReported) {
  try {
    (void)load_scenario(data_dir + "/does-not-exist.yaml");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_NE(e.issues()[0].find("no such scenario file"), std::string::npos) << e.issues()[0];
  }
  try {
    (void)load_scenario(data_dir);
    FAIL() << "a folder was read as a scenario";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0], data_dir + ": is a directory; expected a scenario file (YAML).");
  }
}

// Scenario errors are input errors (the CLI exits 2 on them), with what() the issues, one per line.
TEST(ScenarioLoader, ScenarioErrorIsAnInputError) {
  try {
    (void)from_text("name: x\nseed: -1\nrepetitions: 0\n");
    FAIL() << "no error";
  } catch (const core::InputError& e) {
    const auto* s = dynamic_cast<const ScenarioError*>(&e);
    ASSERT_NE(s, nullptr);
    ASSERT_GE(s->issues().size(), 2u);
    EXPECT_EQ(std::string(e.what()).substr(0, s->issues()[0].size() + 1), s->issues()[0] + "\n");
  }
}

// Latencies and crashes: the scenario keys accept what `laguerre simulate` accepts, with the same rules.
TEST(ScenarioLoader, NetworkForms) {
  const Scenario s = from_text("name: x\ntopology: {generator: delaunay, n: 10}\n"
                               "network: {latency: 'uniform:1ms:1ms', crashes: [3@2ms-5ms, 4@1ms]}\n");
  const auto& net = s.points[0].config.network;
  ASSERT_EQ(net.crashes.size(), 2u);
  EXPECT_EQ(net.crashes[0].recover_at, sim::Time{5000000});
  EXPECT_FALSE(net.crashes[1].recover_at.has_value());
  try {
    (void)from_text("name: x\ntopology: {generator: delaunay, n: 10}\n"
                    "network: {latency: 'uniform:5ms:1ms', crashes: [-1@1ms]}\n");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 2u);
    EXPECT_EQ(e.issues()[0],
              "test.yaml:3:20: network.latency: found 'uniform:5ms:1ms', expected uniform:LO:HI with LO <= HI (5ms is above 1ms)");
    EXPECT_EQ(e.issues()[1], "test.yaml:3:49: network.crashes[0]: found '-1@1ms', expected " + std::string(crash_forms));
  }
}

TEST(ScenarioLoader, Defaults) {
  const Scenario s = from_text("name: d\ntopology: {generator: delaunay, n: 10}\n");
  EXPECT_EQ(s.name, "d");
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.repetitions, 1u);
  ASSERT_EQ(s.points.size(), 1u);
  const ScenarioConfig& c = s.points[0].config;
  EXPECT_EQ(c.topology.generator, "delaunay");
  EXPECT_EQ(c.topology.params.integer("n", 0), 10);
  EXPECT_EQ(c.network.latency_text, "constant:1ms");
  EXPECT_EQ(c.network.latency.base, 1000000);
  EXPECT_FALSE(c.network.lossy());
  EXPECT_FALSE(c.protocol.asynchronous);
  EXPECT_EQ(c.protocol.steps_per_round, 1);
  EXPECT_EQ(c.protocol.stop, StopSpec::lpd);
  EXPECT_EQ(c.routing.schemes.size(), 4u);
  EXPECT_EQ(c.routing.pairs, 0u);
  EXPECT_TRUE(c.outputs.json && c.outputs.csv && c.outputs.pictures);
}

TEST(ScenarioLoader, ParsesEverySection) {
  const Scenario s = from_text(R"(name: all.sections_1
seed: 18446744073709551615
repetitions: 4
topology: {generator: three-connected, n: 30, deletions_per_vertex: 0.5, max_face_size: 5}
network: {latency: "distance:1ms:250:10us", loss: 0.25, duplication: 0.5, crashes: ["3@2ms"], retransmit_after: 7ms}
protocol: {mode: async, steps_per_round: 3, stop: exact, max_iterations: 99, root: smallest-id, exact_reference: true}
routing: {schemes: [gfg, compass], pairs: 12, positions: packing, sample_routes: 0}
outputs: {tables: csv, pictures: false, picture_max_nodes: 7}
)");
  EXPECT_EQ(s.seed, 18446744073709551615ull);
  EXPECT_EQ(s.repetitions, 4u);
  const ScenarioConfig& c = s.points.at(0).config;
  EXPECT_DOUBLE_EQ(c.topology.params.number("deletions_per_vertex", 0), 0.5);
  EXPECT_EQ(c.topology.params.integer("max_face_size", 0), 5);
  EXPECT_EQ(c.network.latency.kind, sim::LatencyKind::distance);
  EXPECT_EQ(c.network.latency.base, 1000000);
  EXPECT_DOUBLE_EQ(c.network.latency.per_unit, 250);
  EXPECT_EQ(c.network.latency.spread, 10000);
  EXPECT_DOUBLE_EQ(c.network.loss, 0.25);
  EXPECT_DOUBLE_EQ(c.network.duplication, 0.5);
  ASSERT_EQ(c.network.crashes.size(), 1u);
  EXPECT_EQ(c.network.crashes[0].node, 3u);
  EXPECT_EQ(c.network.crashes[0].at, 2000000);
  EXPECT_EQ(c.network.retransmit_after, 7000000);
  EXPECT_TRUE(c.protocol.asynchronous);
  EXPECT_EQ(c.protocol.steps_per_round, 3);
  EXPECT_EQ(c.protocol.stop, StopSpec::exact);
  EXPECT_EQ(c.protocol.max_iterations, 99);
  EXPECT_EQ(c.protocol.root, core::RootRule::smallest_id);
  EXPECT_TRUE(c.protocol.exact_reference);
  EXPECT_EQ(c.routing.schemes, (std::vector<core::Scheme>{core::Scheme::gfg, core::Scheme::compass}));
  EXPECT_EQ(c.routing.pairs, 12u);
  EXPECT_EQ(c.routing.positions, GeometricPositions::packing);
  EXPECT_EQ(c.routing.sample_routes, 0u);
  EXPECT_FALSE(c.outputs.json);
  EXPECT_TRUE(c.outputs.csv);
  EXPECT_FALSE(c.outputs.pictures);
  EXPECT_EQ(c.outputs.picture_max_nodes, 7u);
}

// The Cartesian product: the last sweep key varies fastest; a mapping-valued key replaces a whole
// section and a later key sets a value inside it, without leaking into other points.
TEST(ScenarioLoader, SweepExpansion) {
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml");
  EXPECT_EQ(s.sweep_keys, (std::vector<std::string>{"topology", "topology.n", "network.loss"}));
  ASSERT_EQ(s.points.size(), 8u);
  for (std::size_t p = 0; p < 8; ++p) {
    const ScenarioConfig& c = s.points[p].config;
    EXPECT_EQ(s.points[p].index, p);
    const bool three = p / 4 == 1;
    EXPECT_EQ(c.topology.generator, three ? "three-connected" : "delaunay") << p;
    EXPECT_EQ(c.topology.params.has("max_face_size"), three) << p;
    EXPECT_EQ(c.topology.params.integer("n", 0), (p / 2) % 2 == 0 ? 20 : 30) << p;
    EXPECT_DOUBLE_EQ(c.network.loss, p % 2 == 0 ? 0.0 : 0.1) << p;
    EXPECT_EQ(c.network.latency_text, "uniform:1ms:2ms");  // untouched sections carry over
    ASSERT_EQ(s.points[p].values.size(), 3u);
    EXPECT_EQ(s.points[p].values[1].second, (p / 2) % 2 == 0 ? "20" : "30");
  }
}

TEST(ScenarioLoader, OverridesApplyToEveryPointAndFixSweptKeys) {
  LoadOptions o;
  o.overrides = {"topology.n=12", "repetitions=1", "routing.schemes=[gfg]"};
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml", o);
  EXPECT_EQ(s.repetitions, 1u);
  EXPECT_EQ(s.sweep_keys, (std::vector<std::string>{"topology", "network.loss"}));
  ASSERT_EQ(s.points.size(), 4u);
  for (const auto& p : s.points) {
    EXPECT_EQ(p.config.topology.params.integer("n", 0), 12);
    EXPECT_EQ(p.config.routing.schemes, std::vector<core::Scheme>{core::Scheme::gfg});
  }
}

TEST(ScenarioLoader, OverridesCanReplaceOrAddSweepLists) {
  LoadOptions o;
  o.overrides = {"sweep.network.loss=[0.3]", "sweep.protocol.steps_per_round=[1, 2, 3]"};
  const Scenario s = load_scenario(data_dir + "/good-sweep.yaml", o);
  EXPECT_EQ(s.sweep_keys,
            (std::vector<std::string>{"topology", "topology.n", "network.loss", "protocol.steps_per_round"}));
  ASSERT_EQ(s.points.size(), 2u * 2u * 1u * 3u);
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    EXPECT_DOUBLE_EQ(s.points[p].config.network.loss, 0.3);
    EXPECT_EQ(s.points[p].config.protocol.steps_per_round, static_cast<int>(p % 3) + 1);
  }
  o.overrides = {"sweep.network.loss=0.3"};
  try {
    (void)load_scenario(data_dir + "/good-sweep.yaml", o);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0], "--set sweep.network.loss=0.3: sweep.network.loss: found '0.3', expected a non-empty list of values");
  }
}

TEST(ScenarioLoader, BadOverridesAreNamed) {
  LoadOptions o;
  o.overrides = {"topology.n=two", "nonsense", "protocol.bogus=1"};
  const auto issues = issues_of("good-sweep.yaml", o);
  EXPECT_EQ(issues, (std::vector<std::string>{
                        "--set nonsense: found no '=', expected KEY.PATH=VALUE such as topology.n=40",
                        "--set topology.n=two: topology.n: found 'two', expected an integer in [3, 10000000]",
                        "--set protocol.bogus=1: protocol.bogus: found an unknown key, expected one of mode, "
                        "steps_per_round, stop, max_iterations, root, exact_reference, acceleration or termination",
                        // the three-connected points of the sweep need n >= 4
                        "--set topology.n=two: topology.n: found 'two', expected an integer in [4, 10000000]"}));
}

TEST(ScenarioLoader, RelativeFilesResolveAgainstTheScenarioFolder) {
  const Scenario s = load_scenario(data_dir + "/good-file.yaml");
  const std::string path = s.points.at(0).config.topology.params.text("path", "");
  EXPECT_TRUE(fs::path(path).is_absolute() || fs::exists(path));
  EXPECT_TRUE(fs::exists(path)) << path;
  EXPECT_EQ(fs::path(path).filename(), "three-connected-40x5.pc");
}

TEST(ScenarioLoader, CrossFieldRules) {
  try {
    (void)from_text("name: x\ntopology: {generator: uniform-triangulation, n: 10}\nnetwork: {latency: distance:1ms:5}\n"
                    "routing: {positions: physical}\n");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 2u);
    EXPECT_NE(e.issues()[0].find("network.latency"), std::string::npos);
    EXPECT_NE(e.issues()[1].find("routing.positions"), std::string::npos);
  }
  try {
    (void)from_text("name: x\ntopology: {generator: field, n: 10, graph: gabriel}\n");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0], "test.yaml:2:11: topology.radius: found nothing, expected a radius > 0 for graph gabriel");
  }
}

// `attach` and quasi-unit-disk links need link-made plane spanners and a radius; one domain only.
TEST(ScenarioLoader, AttachNeedsAPlanarSpannerOfTheLinks) {
  try {
    (void)from_text("name: x\ntopology: {generator: field, n: 10, attach: true}\n");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 2u);
    EXPECT_NE(e.issues()[0].find("topology.graph: found 'delaunay' with attach or quasi-unit-disk links, expected a "
                                 "planar spanner of the links"),
              std::string::npos)
        << e.issues()[0];
    EXPECT_NE(e.issues()[1].find("topology.radius: found nothing, expected a radius > 0 for the links"), std::string::npos)
        << e.issues()[1];
  }
  try {
    (void)from_text("name: x\ntopology: {generator: field, n: 10, graph: gabriel, radius: 0.2, links: quasi-unit-disk, "
                    "domain: [[[0, 0], [1, 0], [1, 1]]], domain_file: ../../../scenarios/domains/one-large-hole.txt}\n");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_NE(e.issues()[0].find("topology.domain_file: found both domain and domain_file, expected one of them"),
              std::string::npos)
        << e.issues()[0];
  }
  const Scenario ok = from_text(
      "name: x\ntopology: {generator: field, n: 10, graph: rng, radius: 0.2, attach: true, links: quasi-unit-disk, "
      "domain_file: ../../../scenarios/domains/many-small-holes.txt}\n");
  EXPECT_TRUE(ok.points[0].config.topology.params.boolean("attach", false));
}

TEST(ScenarioLoader, PolygonDomains) {
  const Scenario s = from_text("name: x\ntopology:\n  generator: field\n  n: 10\n  domain:\n"
                               "    - [[0, 0], [3, 0], [3, 3], [0, 3]]\n    - [[1, 1], [1, 2], [2, 2]]\n");
  const auto polys = s.points[0].config.topology.params.polygons("domain");
  ASSERT_EQ(polys.size(), 2u);
  EXPECT_EQ(polys[0].size(), 4u);
  EXPECT_DOUBLE_EQ(polys[1][2].x, 2);
  // A self-crossing outer polygon is refused before anything runs.
  EXPECT_THROW((void)from_text("name: x\ntopology:\n  generator: field\n  n: 10\n  domain:\n"
                               "    - [[0, 0], [1, 1], [1, 0], [0, 1]]\n"),
               ScenarioError);
}

// Every bundled example validates (the registry resolves its generators).
TEST(ScenarioLoader, BundledExamplesValidate) {
  std::size_t count = 0;
  for (const auto& e : fs::directory_iterator(std::string(LAGUERRE_TEST_DATA) + "/../../scenarios")) {
    if (e.path().extension() != ".yaml") continue;
    ++count;
    EXPECT_NO_THROW((void)load_scenario(e.path().string())) << e.path();
  }
  EXPECT_GE(count, 8u);
}
