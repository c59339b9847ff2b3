// The topology registry: one table per generator (parameters with their defaults, check, build), the
// documentation generated from it, and builds that read the table's defaults.
#include <gtest/gtest.h>

#include <string>

#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/scenarios/Topology.hpp"

using namespace laguerre;
using scenarios::TopologyParams;

TEST(TopologyRegistry, EveryAvailableGeneratorBuildsAndDocumentsItsDefaults) {
  for (const scenarios::GeneratorInfo& g : scenarios::topology_generators()) {
    EXPECT_EQ(static_cast<bool>(g.build), g.available) << g.name;
    for (const scenarios::ParamSpec& p : g.params) {
      if (p.default_value) {
        EXPECT_EQ(p.default_text, scenarios::describe(*p.default_value)) << g.name << "." << p.name;
      }
      EXPECT_FALSE(p.required && p.default_value) << g.name << "." << p.name;
    }
  }
}

TEST(TopologyRegistry, HelpIsGeneratedFromTheTable) {
  const std::string help = scenarios::generators_help();
  EXPECT_NE(help.find("three-connected: random 3-connected plane graph"), std::string::npos) << help;
  EXPECT_NE(help.find("  max_face_size (integer in [4, 1000]; default 8): largest face a deletion may create\n"),
            std::string::npos)
      << help;
  EXPECT_NE(help.find("  n (integer in [3, 1e+07]; required): number of vertices\n"), std::string::npos) << help;
  EXPECT_NE(help.find("  outer (choice puncture|root-face; default puncture): "), std::string::npos) << help;
  EXPECT_NE(help.find("  domain (file; default the unit square): "), std::string::npos) << help;
  for (const scenarios::GeneratorInfo& g : scenarios::topology_generators())
    EXPECT_NE(help.find(g.name + ": " + g.summary), std::string::npos) << g.name;
}

TEST(TopologyRegistry, AbsentParametersTakeTheTableDefaults) {
  TopologyParams given, spelled;
  given.set("n", std::int64_t{40});
  spelled.set("n", std::int64_t{40});
  spelled.set("deletions_per_vertex", 0.75);
  spelled.set("max_face_size", std::int64_t{8});
  const auto a = scenarios::build_topology("three-connected", given, 5);
  const auto b = scenarios::build_topology("three-connected", spelled, 5);
  EXPECT_EQ(core::write_edge_list(a.graph), core::write_edge_list(b.graph));
  EXPECT_EQ(a.name, "three-connected(n=40)");
  spelled.set("max_face_size", std::int64_t{4});
  EXPECT_NE(core::write_edge_list(scenarios::build_topology("three-connected", spelled, 5).graph),
            core::write_edge_list(a.graph));
}

TEST(TopologyRegistry, TopologyErrorIsAnInputErrorWithTheSameText) {
  try {
    (void)scenarios::build_topology("no-such-generator", TopologyParams{}, 1);
    FAIL() << "no TopologyError";
  } catch (const core::InputError& e) {
    EXPECT_STREQ(e.what(), "unknown topology generator 'no-such-generator'");
    EXPECT_EQ(e.message(), "unknown topology generator 'no-such-generator'");
    EXPECT_EQ(e.source(), "");
    EXPECT_NE(dynamic_cast<const scenarios::TopologyError*>(&e), nullptr);
  }
}
