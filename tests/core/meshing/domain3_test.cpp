// Polyhedral domains: the bundled surfaces are accepted with their known volumes, every kind of bad
// surface is refused with the file, line and rule, point location is exact on the boundary.
#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/Medit.hpp"
#include "../../support/Scratch.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace laguerre::core {
namespace {

const std::string domains = std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/domains/";

std::string write(const std::string& name, const std::string& text) {
  const auto dir = laguerre::testing::scratch_folder() / "laguerre_domain3_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

/// The message of the DomainError `f` throws ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The unit cube's 8 vertices and 12 outward triangles, as OFF text with `faces` replacing the faces.
const char* cube_vertices = "OFF\n8 12 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
const char* cube_faces =
    "3 0 2 1\n3 1 2 3\n3 4 5 6\n3 5 7 6\n3 0 1 4\n3 1 5 4\n3 2 6 3\n3 3 6 7\n3 0 4 2\n3 2 4 6\n3 1 3 5\n3 3 7 5\n";

TEST(PolyhedralDomain, BundledDomainsHaveTheirVolumes) {
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  EXPECT_NEAR(cube.volume(), 1, 1e-15);
  EXPECT_EQ(cube.components(), 1u);
  const PolyhedralDomain holed = read_polyhedral_domain(domains + "box-with-hole.off");
  EXPECT_NEAR(holed.volume(), 1 - 0.25 * 0.25, 1e-15);
  EXPECT_EQ(holed.locate({0.5, 0.5, 0.5}), DomainSide::outside);  // in the hole
  EXPECT_EQ(holed.locate({0.2, 0.5, 0.5}), DomainSide::inside);
  EXPECT_EQ(holed.locate({0.375, 0.5, 0.5}), DomainSide::boundary);  // on the hole's wall, exactly
  EXPECT_EQ(cube.locate({1, 0.3, 0.7}), DomainSide::boundary);
  EXPECT_EQ(cube.locate({1 + 1e-16 * 4, 0.3, 0.7}), DomainSide::outside);
  EXPECT_NEAR(PolyhedralDomain::box(0, 0, 0, 2, 1, 0.5).volume(), 1, 1e-15);
}

TEST(PolyhedralDomain, OrientationOfComponentsIsFixedAndCavitiesCount) {
  // The cube given inward (every face reversed) is the same domain.
  std::string reversed = cube_vertices;
  for (const char* f : {"3 0 1 2\n", "3 1 3 2\n", "3 4 6 5\n", "3 5 6 7\n", "3 0 4 1\n", "3 1 4 5\n", "3 2 3 6\n",
                        "3 3 7 6\n", "3 0 2 4\n", "3 2 6 4\n", "3 1 5 3\n", "3 3 5 7\n"})
    reversed += f;
  EXPECT_NEAR(read_polyhedral_domain(write("inward.off", reversed)).volume(), 1, 1e-15);
  // A box with a cavity: two components, the inner one oriented whichever way, volume 1 − 1/8.
  const PolyhedralDomain outer = PolyhedralDomain::box(0, 0, 0, 1, 1, 1);
  const PolyhedralDomain inner = PolyhedralDomain::box(0.25, 0.25, 0.25, 0.75, 0.75, 0.75);
  std::vector<Point3> v = outer.vertices();
  auto t = outer.triangles();
  for (const Point3& p : inner.vertices()) v.push_back(p);
  for (auto f : inner.triangles()) t.push_back({f[0] + 8, f[1] + 8, f[2] + 8});
  const PolyhedralDomain cavity(v, t);
  EXPECT_EQ(cavity.components(), 2u);
  EXPECT_NEAR(cavity.volume(), 0.875, 1e-15);
  EXPECT_EQ(cavity.locate({0.5, 0.5, 0.5}), DomainSide::outside);
  EXPECT_EQ(cavity.locate({0.1, 0.5, 0.5}), DomainSide::inside);
}

TEST(PolyhedralDomain, BadSurfacesAreRefusedWithFileLineAndRule) {
  // Not closed: the last face missing.
  std::string faces = cube_faces;
  std::string open = std::string(cube_vertices).replace(std::string(cube_vertices).find("8 12"), 4, "8 11") +
                     faces.substr(0, faces.rfind("3 3 7 5"));
  std::string m = error_of([&] { read_polyhedral_domain(write("open.off", open)); });
  EXPECT_NE(m.find("open.off:"), std::string::npos) << m;
  EXPECT_NE(m.find("not closed"), std::string::npos) << m;
  // Inconsistently oriented: one face reversed (line 21 is the 11th face).
  std::string flipped = std::string(cube_vertices) + faces;
  flipped.replace(flipped.find("3 1 3 5"), 7, "3 1 5 3");
  m = error_of([&] { read_polyhedral_domain(write("flipped.off", flipped)); });
  EXPECT_NE(m.find("flipped.off:"), std::string::npos) << m;
  EXPECT_NE(m.find("consistently oriented"), std::string::npos) << m;
  EXPECT_NE(m.find("line 21"), std::string::npos) << m;
  // Self-intersecting: two cubes overlapping, each closed and oriented.
  std::string two = "OFF\n16 24 0\n";
  for (double s : {0.0, 0.5})
    for (int k = 0; k < 8; ++k)
      two += std::to_string((k & 1) + s) + " " + std::to_string((k >> 1 & 1) + s) + " " + std::to_string((k >> 2 & 1) + s) + "\n";
  two += faces;
  for (std::size_t pos = 0; pos < faces.size();) {
    const std::size_t end = faces.find('\n', pos);
    std::istringstream f(faces.substr(pos, end - pos));
    int n, a, b, c;
    f >> n >> a >> b >> c;
    two += "3 " + std::to_string(a + 8) + " " + std::to_string(b + 8) + " " + std::to_string(c + 8) + "\n";
    pos = end + 1;
  }
  m = error_of([&] { read_polyhedral_domain(write("two.off", two)); });
  EXPECT_NE(m.find("intersects itself"), std::string::npos) << m;
  EXPECT_NE(m.find("two.off:"), std::string::npos) << m;
  // Syntax: a quad, an index out of range, a degenerate triangle, a missing header.
  std::string quad = std::string(cube_vertices) + "4 0 1 2 3\n";
  m = error_of([&] { read_polyhedral_domain(write("quad.off", quad)); });
  EXPECT_NE(m.find("quad.off:11:"), std::string::npos) << m;
  EXPECT_NE(m.find("found a face with 4 vertices"), std::string::npos) << m;
  std::string range = std::string(cube_vertices) + "3 0 1 9\n";
  EXPECT_NE(error_of([&] { read_polyhedral_domain(write("range.off", range)); }).find("out of range"), std::string::npos);
  std::string degenerate = std::string(cube_vertices) + faces;
  degenerate.replace(degenerate.find("3 0 2 1"), 7, "3 0 0 1");
  EXPECT_NE(error_of([&] { read_polyhedral_domain(write("degenerate.off", degenerate)); }).find("degenerate"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_polyhedral_domain(write("header.off", "PLY\n")); }).find("expected 'OFF'"),
            std::string::npos);
}

TEST(PolyhedralDomain, MeditSurfacesAreReadAndCheckedToo) {
  const PolyhedralDomain cube = read_polyhedral_domain(domains + "cube.off");
  TetMesh surface;
  for (const Point3& p : cube.vertices()) surface.points.push_back(p);
  surface.point_refs.assign(8, 0);
  surface.triangles = cube.triangles();
  surface.triangle_refs.assign(12, 1);
  const auto dir = laguerre::testing::scratch_folder() / "laguerre_domain3_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "cube.mesh").string();
  write_medit_mesh(path, surface);
  EXPECT_TRUE(is_3d_domain_file(path));
  EXPECT_NEAR(read_polyhedral_domain(path).volume(), 1, 1e-15);
  surface.triangles.pop_back();
  surface.triangle_refs.pop_back();
  write_medit_mesh(path, surface);
  const std::string m = error_of([&] { read_polyhedral_domain(path); });
  EXPECT_NE(m.find("cube.mesh:"), std::string::npos) << m;
  EXPECT_NE(m.find("not closed"), std::string::npos) << m;
}

}  // namespace
}  // namespace laguerre::core
