// The 3D star mesher on every bundled 3D domain under the bundled 3D fields that converge (label
// slow: tens of seconds each). Each run must converge with a checked tetrahedralization whose
// tetrahedra are empty in the metric of each of their vertices.
#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/StarMesher3.hpp"

#include "../../../core/src/meshing/detail/LocalDelaunay3.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <string>

namespace laguerre::core {
namespace {

class StarMesher3Sweep : public testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(StarMesher3Sweep, ConvergesToACheckedLocallyUniformMesh) {
  const auto [domain_name, spec] = GetParam();
  const PolyhedralDomain domain =
      read_polyhedral_domain(std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/domains/" + domain_name + ".off");
  const auto field = parse_metric_field3(spec);
  StarMesh3Options options;
  options.max_vertices = 20000;
  const StarMesh3Result r = mesh_with_stars(domain, *field, options);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(check_tetrahedralization(r.mesh, domain), "");
  // Locally uniform: each tetrahedron's M_v-circumsphere is empty of the vertices near it, for each of
  // its vertices v (exact predicate; vertices farther than 3 circumradii in the metric are skipped).
  std::size_t violations = 0;
  for (const auto& t : r.mesh.tetrahedra)
    for (std::size_t i = 0; i < 4; ++i) {
      const Metric3& m = r.metrics[t[i]];
      const std::array<double, 6> e{m.xx, m.xy, m.xz, m.yy, m.yz, m.zz};
      for (std::size_t w = 0; w < r.mesh.points.size(); ++w)
        if (w != t[0] && w != t[1] && w != t[2] && w != t[3] &&
            detail::metric_in_sphere(r.mesh.points[t[0]], r.mesh.points[t[1]], r.mesh.points[t[2]],
                                     r.mesh.points[t[3]], r.mesh.points[w], e) > 0)
          ++violations;
    }
  EXPECT_EQ(violations, 0u);
}

INSTANTIATE_TEST_SUITE_P(BundledDomainsAndFields, StarMesher3Sweep,
                         testing::Combine(testing::Values("cube", "box-with-hole"),
                                          testing::Values("uniform:0.15:0.15:0.3", "shock:0.2:0.4:0.5:0.5",
                                                          // the bench's curved sphere layer (docs/star-mesher3.md)
                                                          "sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5",
                                                          // graded along z: cascaded before Pick_valid
                                                          "expr:xx=25;xy=0;xz=0;yy=25;yz=0;zz=25/(1+2*z)^2")),
                         [](const testing::TestParamInfo<StarMesher3Sweep::ParamType>& param_info) {
                           std::string name = std::string(std::get<0>(param_info.param)) + "_" + std::get<1>(param_info.param);
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace laguerre::core
