// The one reader of sites files (and the line reader of cells files): comments and blank lines, the
// column count, the admissible range of numbers, and errors naming file:line, the value and the column.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "laguerre/core/diagrams/SitesFile.hpp"
#include "laguerre/core/diagrams/VoronoiDiagram.hpp"
#include "../../support/Scratch.hpp"

namespace laguerre::core {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = laguerre::testing::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

/// The error of reading `text` as `x y w` sites, or "" when it reads.
std::string error_of(const std::string& text) {
  try {
    read_site_rows(write_temp("sites-error.txt", text), "x y w", "power diagram");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SitesFile, CommentsBlankLinesAndLineNumbers) {
  const std::string path = write_temp("sites.txt", "# header\n\n0 0 1   # first\n  +1.5 -2 0\n\n3e2 4 -1e-3\n");
  const auto rows = read_site_rows(path, "x y w", "power diagram");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].line, 3u);
  EXPECT_EQ(rows[1].line, 4u);
  EXPECT_EQ(rows[2].line, 6u);
  EXPECT_EQ(rows[1].values, (std::vector<double>{1.5, -2, 0}));
  EXPECT_EQ(rows[2].values, (std::vector<double>{300, 4, -1e-3}));
  const auto lines = read_input_lines(path, "sites file");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].words, (std::vector<std::string>{"0", "0", "1"}));
}

TEST(SitesFile, ErrorsNameFileLineValueAndColumn) {
  std::string e = error_of("0 0 1\n1 2\n");
  EXPECT_NE(e.find("sites-error.txt:2: found 2 field(s) '1 2'; expected 3 numbers `x y w` (power diagram sites)."),
            std::string::npos) << e;
  e = error_of("0 0 1\n\n1 zz 0\n");
  EXPECT_NE(e.find(":3: found 'zz' in column 2 `y`; expected a finite number (power diagram sites)."), std::string::npos) << e;
  for (const char* bad : {"inf", "nan", "-inf", "1x", "0x10", "1,5"}) {
    e = error_of(std::string("0 0 ") + bad + " 1\n");
    EXPECT_FALSE(e.empty()) << bad;
  }
  e = error_of("0 0 1\n");
  EXPECT_EQ(e, "");
  e = error_of("# nothing\n\n");
  EXPECT_NE(e.find("no sites; expected lines `x y w`"), std::string::npos) << e;
}

TEST(SitesFile, AdmissibleRange) {
  // 0 and magnitudes in [1e-150, 1e150] pass; beyond, and below (but not 0), the line is refused.
  EXPECT_EQ(error_of("1e150 -1e150 1e-150\n0 -0 -1e-150\n"), "");
  for (const char* bad : {"1e160", "-1.000001e150", "1e300", "1e-300", "-1e-151", "1e-400", "1e400"}) {
    const std::string e = error_of(std::string("0 0 1\n1 ") + bad + " 1\n");
    EXPECT_NE(e.find(":2: found '" + std::string(bad) + "' in column 2 `y`; expected 0 or a magnitude between 1e-150 and 1e150"),
              std::string::npos)
        << bad << ": " << e;
  }
  EXPECT_TRUE(admissible_magnitude(0));
  EXPECT_TRUE(admissible_magnitude(-1e150));
  EXPECT_FALSE(admissible_magnitude(1e151));
  EXPECT_FALSE(admissible_magnitude(5e-324));
}

TEST(SitesFile, MissingFileAndDirectory) {
  try {
    read_site_rows(laguerre::testing::scratch_folder().string(), "x y", "Voronoi diagram");
    FAIL() << "read a directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory; expected a sites file."), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_site_rows(laguerre::testing::scratch_path("no-such-sites.txt"), "x y", "Voronoi diagram"), InputError);
}

TEST(SitesFile, UnrepresentableVerticesAreNeverValid) {
  // Built directly (no reader): the circumcentre of these sites is about (0, -5e599), beyond the
  // doubles; the diagram must not call itself valid.
  const VoronoiDiagram huge({{-1e300, 0}, {1e300, 0}, {0, 1}}, {-1, -1, 1, 1});
  ASSERT_EQ(huge.vertices().size(), 1u);
  const Point2 v = huge.vertices()[0].point;
  EXPECT_FALSE(std::isfinite(v.x) && std::isfinite(v.y)) << v.x << ", " << v.y;
  EXPECT_FALSE(huge.is_valid());
  // Three sites 1e-300 apart: the doubles' construction underflows (0/0), the exact fallback does not.
  const VoronoiDiagram tiny({{0, 0}, {1e-300, 0}, {0, 1e-300}}, {-1, -1, 1, 1});
  ASSERT_EQ(tiny.vertices().size(), 1u);
  EXPECT_EQ(tiny.vertices()[0].point.x, 5e-301);
  EXPECT_EQ(tiny.vertices()[0].point.y, 5e-301);
  EXPECT_TRUE(tiny.is_valid(true));
  // The same triangle at a representable scale is valid.
  const VoronoiDiagram fine({{0, 0}, {1e-100, 0}, {0, 1e-100}}, {-1, -1, 1, 1});
  EXPECT_TRUE(fine.is_valid(true));
}

}  // namespace
}  // namespace laguerre::core
