// How uniform maps become discs: puncturing at the largest-degree vertex, or the largest face outside.
#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/scenarios/generators/UniformThreeConnected.hpp"
#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/scenarios/ScenarioLoader.hpp"
#include "laguerre/scenarios/Topology.hpp"
#include "../../support/Scratch.hpp"

namespace laguerre::scenarios {
namespace {

TEST(OuterRule, PunctureLeavesATriangulatedDiscBoundedByTheHubsLink) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const core::PlanarGraph sphere = uniform_triangulation(51, seed);
    std::uint32_t hub_degree = 0;
    for (core::Vertex v = 0; v < sphere.num_vertices(); ++v) hub_degree = std::max(hub_degree, sphere.degree(v));
    const core::PlanarGraph disc = puncture_at_max_degree(sphere);
    ASSERT_TRUE(disc.is_valid());
    EXPECT_EQ(disc.num_vertices(), 50u);
    EXPECT_EQ(disc.num_edges(), sphere.num_edges() - hub_degree);
    EXPECT_EQ(disc.face_size(disc.outer_face()), hub_degree);
    for (core::Face f = 0; f < disc.num_faces(); ++f)
      if (f != disc.outer_face()) {
        EXPECT_EQ(disc.face_size(f), 3u);
      }
    core::GraphInput in{disc, {}, "punctured", true};
    core::GraphKind kind{};
    core::prepare_for_packing(in, &kind);
    EXPECT_EQ(kind, core::GraphKind::triangulated_disc);
  }
  EXPECT_THROW(puncture_at_max_degree(uniform_triangulation(3, 1)), laguerre::core::InternalError);
}

TEST(OuterRule, LargestFaceGoesOutside) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const core::PlanarGraph map = with_largest_outer_face(uniform_three_connected(50, seed));
    ASSERT_TRUE(map.is_valid());
    std::uint32_t largest = 0;
    for (core::Face f = 0; f < map.num_faces(); ++f) largest = std::max(largest, map.face_size(f));
    EXPECT_EQ(map.face_size(map.outer_face()), largest);
  }
}

TEST(OuterRule, FileTopologyPuncturesASphereOnlyWhenAsked) {
  const core::PlanarGraph sphere = uniform_triangulation(30, 7);
  const std::string path = (laguerre::testing::scratch_folder() / "laguerre-outer-rule-sphere.edges").string();
  std::ofstream(path) << core::write_edge_list(sphere);
  TopologyParams params;
  params.set("path", path);
  const Topology face = build_topology("file", params, 1);
  EXPECT_EQ(face.graph.num_vertices(), 30u);
  EXPECT_TRUE(face.removed.empty());
  EXPECT_EQ(face.note, "");
  params.set("outer", std::string("puncture"));
  const Topology punctured = build_topology("file", params, 1);
  EXPECT_EQ(punctured.graph.num_vertices(), 29u);
  EXPECT_EQ(punctured.kind, core::GraphKind::triangulated_disc);
  ASSERT_EQ(punctured.removed.size(), 1u);
  EXPECT_EQ(punctured.removed[0], sphere.id(core::puncture_vertex(sphere)));
  EXPECT_EQ(punctured.graph.boundary_cycle().size(), sphere.degree(core::puncture_vertex(sphere)));
  EXPECT_NE(punctured.note.find("vertex " + std::to_string(punctured.removed[0]) + " removed"), std::string::npos)
      << punctured.note;
  // The loader refuses another value, naming the key and the choices.
  const std::string yaml = "name: t\nseed: 1\ntopology:\n  generator: file\n  path: " + path + "\n  outer: hole\n";
  try {
    (void)load_scenario_from_string(yaml, "t.yaml", std::filesystem::temp_directory_path().string());
    ADD_FAILURE() << "no error";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("outer"), std::string::npos) << what;
    EXPECT_NE(what.find("hole"), std::string::npos) << what;
    EXPECT_NE(what.find("puncture"), std::string::npos) << what;
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace laguerre::scenarios
