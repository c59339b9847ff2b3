// The raster oracle itself: known answers (two sites split at their bisector), tie reporting, margins,
// pixel geometry and the rendered image.

#include <gtest/gtest.h>

#include <cmath>

#include "laguerre/core/diagrams/MinimizationDiagram.hpp"

using namespace laguerre::core;

TEST(MinimizationDiagram, TwoPointsSplitAtTheBisector) {
  const Point2 a{-1, 0}, b{1, 0};
  const MinimizationDiagram d({-2, -1, 2, 1}, 40, 20, 2, [&](SiteIndex i, Point2 x) {
    return squared_distance(x, i == 0 ? a : b);
  });
  for (int row = 0; row < d.height(); ++row)
    for (int col = 0; col < d.width(); ++col) {
      const Point2 x = d.pixel_centre(col, row);
      EXPECT_EQ(d.label(col, row), x.x < 0 ? 0u : 1u);
      EXPECT_NEAR(d.margin(col, row), 4 * std::fabs(x.x), 1e-12);  // |x−a|² − |x−b|² = 4x
      EXPECT_FALSE(d.tied(col, row));
    }
  const auto counts = d.pixel_counts();
  EXPECT_EQ(counts[0], 400u);
  EXPECT_EQ(counts[1], 400u);
  EXPECT_TRUE(d.unlabelled_sites().empty());
}

TEST(MinimizationDiagram, PixelCentresAndOrientation) {
  const MinimizationDiagram d({0, 0, 4, 2}, 4, 2, 1, [](SiteIndex, Point2) { return 0.0; });
  EXPECT_DOUBLE_EQ(d.pixel_centre(0, 0).x, 0.5);
  EXPECT_DOUBLE_EQ(d.pixel_centre(0, 0).y, 1.5);  // row 0 is the top line
  EXPECT_DOUBLE_EQ(d.pixel_centre(3, 1).x, 3.5);
  EXPECT_DOUBLE_EQ(d.pixel_centre(3, 1).y, 0.5);
}

TEST(MinimizationDiagram, TiesAreReportedAndResolvedToTheSmallestIndex) {
  // Sites 1 and 2 are the same function; site 0 is worse everywhere.
  const MinimizationDiagram d({0, 0, 1, 1}, 8, 8, 3, [](SiteIndex i, Point2 x) { return i == 0 ? 5.0 : x.x; });
  EXPECT_EQ(d.tie_count(), 64u);
  EXPECT_EQ(d.label(3, 3), 1u);
  EXPECT_EQ(d.unlabelled_sites(), (std::vector<SiteIndex>{0, 2}));
  // A tolerance turns near-ties into ties.
  const MinimizationDiagram e({0, 0, 1, 1}, 8, 8, 2, [](SiteIndex i, Point2) { return i == 0 ? 1.0 : 1.0 + 1e-12; }, 1e-9);
  EXPECT_EQ(e.tie_count(), 64u);
  EXPECT_EQ(e.label(0, 0), 0u);
}

TEST(MinimizationDiagram, NanAndInfinityNeverWin) {
  const MinimizationDiagram d({0, 0, 1, 1}, 4, 4, 2, [](SiteIndex i, Point2) { return i == 0 ? std::nan("") : 3.0; });
  EXPECT_EQ(d.label(1, 1), 1u);
  const MinimizationDiagram e({0, 0, 1, 1}, 4, 4, 1, [](SiteIndex, Point2) { return INFINITY; });
  EXPECT_EQ(e.label(1, 1), no_site);
}

TEST(MinimizationDiagram, RenderUsesSiteColours) {
  const MinimizationDiagram d({0, 0, 2, 1}, 2, 1, 2, [](SiteIndex i, Point2 x) { return i == 0 ? x.x : 2 - x.x; });
  const auto rgb = d.render_rgb();
  ASSERT_EQ(rgb.size(), 6u);
  EXPECT_EQ((Rgb{rgb[0], rgb[1], rgb[2]}), site_colour(0));
  EXPECT_EQ((Rgb{rgb[3], rgb[4], rgb[5]}), site_colour(1));
  EXPECT_NE(site_colour(0), site_colour(1));
}

TEST(MinimizationDiagram, RejectsBadRasters) {
  auto f = [](SiteIndex, Point2) { return 0.0; };
  EXPECT_THROW(MinimizationDiagram({0, 0, 1, 1}, 0, 4, 1, f), InputError);
  EXPECT_THROW(MinimizationDiagram({0, 0, 0, 1}, 4, 4, 1, f), InputError);
}
