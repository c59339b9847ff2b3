// `laguerre mesh` on bad input: numbers the meshers cannot represent, and directories or missing files
// where a domain or a background mesh is expected, all refused with exit status 2 and a message naming
// the file (and line).
#include <gtest/gtest.h>

#include "CliRunner.hpp"

#include <initializer_list>
#include <string>

namespace {

class MeshInputCli : public laguerre::cli_test::ScratchDir {
 protected:
  void expect_input_error(const std::string& args, std::initializer_list<std::string> parts) const {
    const laguerre::cli_test::Outcome r = laguerre::cli_test::run("mesh " + args + " --force -o " + path("out"));
    EXPECT_EQ(r.status, 2) << args << ": " << r.out;
    for (const std::string& part : parts) EXPECT_NE(r.out.find(part), std::string::npos) << args << ": " << r.out;
  }
};

}  // namespace

TEST_F(MeshInputCli, DomainCoordinatesBeyondTheAdmissibleRangeNameTheLine) {
  // Formerly a vertex at 1e300 gave "valid triangulation" with 0 triangles.
  const std::string huge = write("huge.txt", "outer\n0 0\n1e300 0\n1 1\n0 1\n");
  expect_input_error(huge, {huge + ":3: found '1e300' in a vertex 'x y'", "between 1e-150 and 1e150"});
  const std::string tiny = write("tiny.txt", "outer\n0 0\n1 0\n1 1e-200\n0 1\n");
  expect_input_error(tiny, {tiny + ":4:", "between 1e-150 and 1e150"});
}

TEST_F(MeshInputCli, DirectoriesAndMissingFiles) {
  expect_input_error(path(""), {"is a directory; expected a domain file."});
  expect_input_error(path("missing.txt"), {"missing.txt: no such domain file"});
  expect_input_error("square --metric mesh:" + path(""), {"is a directory; expected a Medit mesh file."});
  const std::string mesh = write("bg.mesh", "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\n"
                                            "Triangles\n1\n1 2 3 0\nEnd\n");
  expect_input_error("square --metric mesh:" + mesh + ":" + path(""), {"is a directory; expected a Medit solution file."});
  expect_input_error("square --metric mesh:" + mesh, {"bg.sol: no such Medit solution file"});
}
