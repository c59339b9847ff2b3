// The heavy variant of StarMesherBoundary.ConvergedImpliesATriangulation (label slow): more seeds,
// fields and domains, with and without rule 6. Every case meets the termination theorem's hypothesis
// (corners of at least 90° in the metric), so every run must converge, to a valid triangulation.
#include "laguerre/core/meshing/StarMesher.hpp"

#include <gtest/gtest.h>

#include <string>

namespace laguerre::core {
namespace {

TEST(StarMesherSweep, ConvergedImpliesATriangulation) {
  const std::string data = std::string(LAGUERRE_TEST_DATA);
  const Domain holes = read_domain(data + "/../../scenarios/domains/square-with-holes.txt");
  const Domain diamond = read_domain(data + "/domains/diamond.txt");
  const Domain hexagon = read_domain(data + "/domains/hexagon.txt");
  const struct {
    const Domain* domain;
    const char* field;
  } cases[] = {{&holes, "uniform:0.12:0.06:0"},   {&holes, "uniform:0.1:0.05:0"},  {&holes, "uniform:0.08:0.04:0"},
               {&holes, "uniform:0.12:0.06:90"},  {&holes, "uniform:0.15:0.1:0"},  {&holes, "uniform:0.1:0.1"},
               {&holes, "shock:0.03:0.15:0.05:0.5"}, {&diamond, "uniform:0.2:0.2"}, {&diamond, "uniform:0.2:0.1:45"},
               {&diamond, "uniform:0.05:0.05"},   {&hexagon, "uniform:0.2:0.2"},   {&hexagon, "uniform:0.15:0.1:10"},
               {&hexagon, "uniform:0.2:0.12:15"}, {&hexagon, "thesis:0.1:1.5:0.2:0.5"}};
  for (const auto& c : cases)
    for (const std::uint64_t seed : {1u, 2u, 3u, 4u, 5u})
      for (const bool corners : {false, true}) {
        SCOPED_TRACE(std::string(c.field) + " seed " + std::to_string(seed) + (corners ? " rule 6" : ""));
        StarMeshOptions o;
        o.seed = seed;
        o.no_lonely_corners = corners;
        const StarMeshResult r = mesh_with_stars(*c.domain, *parse_metric_field(c.field), o);
        ASSERT_TRUE(r.converged) << r.status;
        EXPECT_EQ(check_triangulation(r.mesh, *c.domain), "");
      }
}

}  // namespace
}  // namespace laguerre::core
