// `laguerre mesh` as a user runs it: bundled domains, outputs and their guarantees, refusals and errors.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "CliRunner.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using MeshRun = laguerre::cli_test::Outcome;

MeshRun mesh(const std::string& args) { return laguerre::cli_test::run("mesh " + args); }

class MeshCli : public laguerre::cli_test::ScratchDir {};

const std::string domains = std::string(LAGUERRE_SOURCE_DIR) + "/scenarios/domains/";

}  // namespace

TEST_F(MeshCli, BundledDomainsMeshWithTheirGuarantees) {
  for (const char* name : {"square-with-holes", "l-shape-with-wall"}) {
    const std::string stem = path(name);
    const MeshRun r = mesh(domains + name + ".txt --metric thesis:0.15:4:0.2:0.5 --json -o " + stem);
    ASSERT_EQ(r.status, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["converged"].get<bool>());
    EXPECT_TRUE(j["valid_triangulation"].get<bool>()) << j["validation"];
    // ρ₀ = 1 promises smallest angles of at least 30° in the metrics of the vertices, up to γ₀.
    EXPECT_LE(j["quality"]["radius_edge"]["max"].get<double>(), 1.5);
    EXPECT_GE(j["quality"]["smallest_angle_degrees"]["min"].get<double>(), 19.4);
    for (const char* ext : {".mesh", ".sol", ".vtk", ".json", ".svg", ".png"})
      EXPECT_TRUE(fs::exists(stem + ext)) << stem << ext;
    std::ifstream medit(stem + ".mesh");
    std::string first;
    medit >> first;
    EXPECT_EQ(first, "MeshVersionFormatted");
  }
}

TEST_F(MeshCli, RefusesToOverwriteAndExplainsBadInput) {
  const std::string stem = path("square");
  ASSERT_EQ(mesh("square --metric uniform:0.3:0.3 --no-picture -o " + stem).status, 0);
  const MeshRun again = mesh("square --metric uniform:0.3:0.3 --no-picture -o " + stem);
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.out.find("Refusing to overwrite " + stem + ".mesh"), std::string::npos) << again.out;
  EXPECT_EQ(mesh("square --metric uniform:0.3:0.3 --no-picture --force -o " + stem).status, 0);

  const MeshRun metric = mesh("square --metric uniform:0.3 -o " + path("m"));
  EXPECT_EQ(metric.status, 2);
  EXPECT_NE(metric.out.find("usage uniform:H1:H2"), std::string::npos) << metric.out;

  std::ofstream(path("bad.txt")) << "outer\n0 0\n1 0\n1 1\n0 1\nhole\n0.5 0.5\n2 0.5\n0.5 0.7\n";
  const MeshRun domain = mesh(path("bad.txt") + " -o " + path("m"));
  EXPECT_EQ(domain.status, 2);
  EXPECT_NE(domain.out.find("bad.txt: hole 1 is not strictly inside the outer boundary"), std::string::npos)
      << domain.out;

  const MeshRun shape = mesh("square --algorithm voronoi --shape-bound 0.1 -o " + path("m"));
  EXPECT_EQ(shape.status, 2);
  EXPECT_NE(shape.out.find("--shape-bound"), std::string::npos) << shape.out;
}

TEST_F(MeshCli, StoppedEarlyExitsThree) {
  const MeshRun r = mesh("square --metric uniform:0.05:0.05 --max-vertices 50 --no-picture -o " + path("cap"));
  EXPECT_EQ(r.status, 3) << r.out;
  EXPECT_NE(r.out.find("max_vertices"), std::string::npos) << r.out;
}

TEST_F(MeshCli, VoronoiAlgorithmOnABundledDomain) {
  // Thesis Part II on the L-shaped domain with a wall: converged, valid, every Voronoi vertex within
  // the shape bound, the same outputs and report as the star mesher.
  const std::string stem = path("lv");
  const MeshRun r = mesh(domains + "l-shape-with-wall.txt --algorithm voronoi --metric thesis:0.2:4:0.2:1.5 "
                         "--shape-bound 1 --size-bound 2 --json -o " + stem);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["algorithm"], "voronoi");
  EXPECT_TRUE(j["converged"].get<bool>()) << j["status"];
  EXPECT_TRUE(j["valid_triangulation"].get<bool>()) << j["validation"];
  EXPECT_LE(j["rules"]["worst_vertex_radius_edge"].get<double>(), 1.0);
  for (const char* rule : {"encroached", "ellipse", "bad_shape", "duplicate", "overlap", "size", "redirected", "rounds"})
    EXPECT_TRUE(j["rules"].contains(rule)) << rule;
  EXPECT_GT(j["rules"]["rounds"].get<int>(), 0);
  for (const char* ext : {".mesh", ".sol", ".vtk", ".json", ".svg", ".png"}) EXPECT_TRUE(fs::exists(stem + ext)) << stem << ext;

  const MeshRun table = mesh("square --algorithm voronoi --metric uniform:0.2:0.2 --no-picture -o " + path("sv"));
  ASSERT_EQ(table.status, 0) << table.out;
  EXPECT_NE(table.out.find("algorithm voronoi"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("1 encroached"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("smallest angle"), std::string::npos) << table.out;

  const MeshRun cap = mesh("square --algorithm voronoi --metric uniform:0.05:0.05 --max-vertices 40 --no-picture -o " +
                           path("vc"));
  EXPECT_EQ(cap.status, 3) << cap.out;
  EXPECT_NE(cap.out.find("max_vertices"), std::string::npos) << cap.out;
}

TEST_F(MeshCli, MeshQualityOfAMeshFileIsTheReportOfMesh) {
  // The report of `mesh-quality` on the .mesh that `mesh` wrote is the one `mesh` printed (the field is
  // evaluated at the same vertices); --domain checks the triangulation; bad input exits 2.
  const std::string stem = path("q");
  const std::string metric = "thesis:0.15:4:0.2:0.5";
  const MeshRun made = mesh(domains + "square-with-holes.txt --metric " + metric + " --no-picture --json -o " + stem);
  ASSERT_EQ(made.status, 0) << made.out;
  const auto mj = nlohmann::json::parse(made.out);
  const auto measured = laguerre::cli_test::run("mesh-quality " + stem + ".mesh --metric " + metric + " --json --domain " +
                                                domains + "square-with-holes.txt");
  ASSERT_EQ(measured.status, 0) << measured.out;
  const auto qj = nlohmann::json::parse(measured.out);
  EXPECT_EQ(qj["vertices"], mj["vertices"]);
  EXPECT_EQ(qj["triangles"], mj["triangles"]);
  EXPECT_EQ(qj["quality"], mj["quality"]);
  EXPECT_TRUE(qj["valid_triangulation"].get<bool>()) << qj["validation"];
  // The same mesh is not a triangulation of the plain square (the holes are not covered).
  const auto other = laguerre::cli_test::run("mesh-quality " + stem + ".mesh --metric " + metric + " --domain square");
  EXPECT_EQ(other.status, 3) << other.out;
  EXPECT_NE(other.out.find("domain       square: "), std::string::npos) << other.out;
  EXPECT_NE(other.out.find("smallest angle"), std::string::npos) << other.out;
  const auto missing = laguerre::cli_test::run("mesh-quality " + path("none.mesh") + " --metric " + metric);
  EXPECT_EQ(missing.status, 2) << missing.out;
  const auto field = laguerre::cli_test::run("mesh-quality " + stem + ".mesh --metric uniform:0.3");
  EXPECT_EQ(field.status, 2) << field.out;
  EXPECT_NE(field.out.find("usage uniform:H1:H2"), std::string::npos) << field.out;
}

TEST_F(MeshCli, SlantedEdgesAndHoleCornersMeshValidly) {
  // Regression (StarMesher.hpp): the diamond threw "exact predicate orientation: … NaN" (exit 1), and
  // square-with-holes at uniform:0.12:0.06:0 reported "converged" with a hole in the mesh (exit 3).
  const std::string diamond = std::string(LAGUERRE_SOURCE_DIR) + "/tests/data/domains/diamond.txt";
  for (const std::string& args : {diamond + " --metric uniform:0.2:0.2",
                                  domains + "square-with-holes.txt --metric uniform:0.12:0.06:0"}) {
    const MeshRun r = mesh(args + " --no-picture --json -o " + path("m") + " --force");
    ASSERT_EQ(r.status, 0) << args << "\n" << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["converged"].get<bool>()) << args;
    EXPECT_TRUE(j["valid_triangulation"].get<bool>()) << args << ": " << j["validation"];
  }
}

TEST_F(MeshCli, ThreeDimensionalDomainsMeshWithACheckedTetrahedralization) {
  // The bundled cube and box with a hole: 3D is detected from the .off file, the report is in the
  // metric, the outputs exist and the Medit file holds the tetrahedra the JSON counts.
  for (const char* name : {"cube", "box-with-hole"}) {
    const std::string stem = path(std::string(name) + "3d");
    const MeshRun r = mesh(domains + name + ".off --metric uniform:0.3:0.3:0.4 --json -o " + stem);
    ASSERT_EQ(r.status, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["converged"].get<bool>());
    EXPECT_TRUE(j["valid_tetrahedralization"].get<bool>()) << j["validation"];
    EXPECT_EQ(j["dimension"], 3);
    EXPECT_GT(j["quality"]["smallest_dihedral_degrees"]["min"].get<double>(), 0);
    EXPECT_LE(j["quality"]["radius_edge"]["max"].get<double>(), 2 + 1e-9);
    for (const char* ext : {".mesh", ".sol", ".vtk", ".json", ".svg", ".png"}) EXPECT_TRUE(fs::exists(stem + ext)) << stem << ext;
    std::ifstream medit(stem + ".mesh");
    std::string word;
    std::size_t tets = 0;
    while (medit >> word)
      if (word == "Tetrahedra") medit >> tets;
    EXPECT_EQ(tets, j["tetrahedra"].get<std::size_t>());
    // `mesh-quality` of the tetrahedral .mesh gives the report `mesh` printed and checks it against
    // the domain; against the other domain the check fails (exit 3).
    const auto measured = laguerre::cli_test::run("mesh-quality " + stem + ".mesh --metric uniform:0.3:0.3:0.4 --json --domain " +
                                                  domains + name + ".off");
    ASSERT_EQ(measured.status, 0) << measured.out;
    const auto m = nlohmann::json::parse(measured.out);
    EXPECT_TRUE(m["valid_tetrahedralization"].get<bool>()) << m["validation"];
    EXPECT_EQ(m["tetrahedra"], j["tetrahedra"]);
    EXPECT_EQ(m["quality"], j["quality"]);
    const char* other = std::string(name) == "cube" ? "box-with-hole" : "cube";
    EXPECT_EQ(laguerre::cli_test::run("mesh-quality " + stem + ".mesh --metric uniform:0.3:0.3:0.4 --domain " + domains + other +
                                      ".off").status, 3);
  }
  // The table names the 3D quantities.
  const MeshRun table = mesh(domains + "cube.off --metric uniform:0.4:0.4:0.4 --no-picture -o " + path("t3"));
  EXPECT_EQ(table.status, 0) << table.out;
  EXPECT_NE(table.out.find("valid tetrahedralization of the domain"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("smallest dihedral"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("slivers"), std::string::npos) << table.out;
}

TEST_F(MeshCli, ThreeDimensionalBadInputAndEarlyStops) {
  // A surface with a missing face: exit 2, file and line named.
  std::ofstream(path("open.off")) << "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n";
  const MeshRun open = mesh(path("open.off") + " --metric uniform:0.3:0.3:0.3 -o " + path("o"));
  EXPECT_EQ(open.status, 2);
  EXPECT_NE(open.out.find("open.off:"), std::string::npos) << open.out;
  EXPECT_NE(open.out.find("not closed"), std::string::npos) << open.out;
  // A 2D field specification on a 3D domain.
  const MeshRun field = mesh(domains + "cube.off --metric uniform:0.3:0.3 -o " + path("f"));
  EXPECT_EQ(field.status, 2);
  EXPECT_NE(field.out.find("uniform:H1:H2:H3"), std::string::npos) << field.out;
  // The Voronoi algorithm is 2D only.
  EXPECT_EQ(mesh(domains + "cube.off --metric uniform:0.3:0.3:0.3 --algorithm voronoi -o " + path("v")).status, 2);
  // Capped: exit 3, no checked status.
  const MeshRun cap = mesh(domains + "cube.off --metric uniform:0.1:0.1:0.1 --max-vertices 30 --no-picture -o " + path("c"));
  EXPECT_EQ(cap.status, 3) << cap.out;
  EXPECT_NE(cap.out.find("max_vertices"), std::string::npos) << cap.out;
}
