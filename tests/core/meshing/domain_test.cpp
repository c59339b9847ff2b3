// Domains to mesh: validation rules, exact point location, area, and the domain file format.
#include "laguerre/core/meshing/Domain.hpp"
#include "../../support/Scratch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

namespace laguerre::core {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const DomainError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Domain, NormalizesOrientationAndMeasuresArea) {
  // Outer given clockwise, hole counter-clockwise: both are flipped.
  const Domain d({{0, 0}, {0, 2}, {2, 2}, {2, 0}}, {{{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}}});
  EXPECT_EQ(orientation(d.outer()[0], d.outer()[1], d.outer()[2]), Sign::positive);
  EXPECT_EQ(orientation(d.holes()[0][0], d.holes()[0][1], d.holes()[0][2]), Sign::negative);
  EXPECT_DOUBLE_EQ(d.area(), 4 - 1);
  EXPECT_EQ(d.constraints().size(), 8u);
}

TEST(Domain, ConstraintPiecesSplitEdgesWhereAWallEnds) {
  // The L shape with a wall from (0, 1.5) on the left side to (0.6, 1.5): the left side (0, 2)–(0, 0)
  // is split at the wall's end; every other constraint is one piece; pieces follow constraint order
  // and cover each constraint exactly.
  const Domain d({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {}, {{Point2{0, 1.5}, Point2{0.6, 1.5}}});
  const auto constraints = d.constraints();
  const auto pieces = d.constraint_pieces();
  ASSERT_EQ(pieces.size(), constraints.size() + 1);
  std::size_t split = 0;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    std::vector<Domain::ConstraintPiece> of;
    for (const auto& p : pieces)
      if (p.constraint == i) of.push_back(p);
    ASSERT_FALSE(of.empty());
    EXPECT_EQ(of.front().a.x, constraints[i][0].x);
    EXPECT_EQ(of.front().a.y, constraints[i][0].y);
    EXPECT_EQ(of.back().b.x, constraints[i][1].x);
    EXPECT_EQ(of.back().b.y, constraints[i][1].y);
    for (std::size_t k = 1; k < of.size(); ++k) EXPECT_TRUE(of[k].a.x == of[k - 1].b.x && of[k].a.y == of[k - 1].b.y);
    if (of.size() == 2) {
      ++split;
      EXPECT_EQ(of[0].b.x, 0.0);
      EXPECT_EQ(of[0].b.y, 1.5);
    }
  }
  EXPECT_EQ(split, 1u);
  for (std::size_t k = 1; k < pieces.size(); ++k) EXPECT_LE(pieces[k - 1].constraint, pieces[k].constraint);
}

TEST(Domain, LocatesPointsExactly) {
  const Domain d({{0, 0}, {3, 0}, {3, 3}, {0, 3}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  EXPECT_EQ(d.locate({0.5, 0.5}), DomainSide::inside);
  EXPECT_EQ(d.locate({1.5, 1.5}), DomainSide::outside);  // in the hole
  EXPECT_EQ(d.locate({1.5, 1}), DomainSide::boundary);   // on the hole
  EXPECT_EQ(d.locate({3, 1.5}), DomainSide::boundary);
  EXPECT_EQ(d.locate({0, 0}), DomainSide::boundary);
  EXPECT_EQ(d.locate({-1e-300, 1}), DomainSide::outside);
  EXPECT_EQ(d.locate({1e-300, 1}), DomainSide::inside);
  EXPECT_EQ(d.locate({1.5, 3}), DomainSide::boundary);
  // Rays through vertices are counted once: points level with the hole's corners.
  EXPECT_EQ(d.locate({0.5, 1}), DomainSide::inside);
  EXPECT_EQ(d.locate({2.5, 2}), DomainSide::inside);
}

TEST(Domain, LocationAgreesWithAClosedFormShape) {
  // An L-shaped outer boundary with a triangular hole, classified against its closed-form description
  // on random points and on a grid that hits vertices' heights exactly.
  const Domain d({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {{{0.2, 0.2}, {0.8, 0.2}, {0.5, 0.7}}});
  EXPECT_NEAR(d.area(), 3 - 0.15, 1e-12);
  auto truth = [](double x, double y) {
    const bool in_l = x > 0 && y > 0 && x < 2 && y < 2 && (y < 1 || x < 1);
    const bool in_hole = y > 0.2 && y < 0.7 && std::abs(x - 0.5) < 0.3 * (0.7 - y) / 0.5;
    return in_l && !in_hole;
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 2.1);
  for (int i = 0; i < 100000; ++i) {
    const double x = u(rng), y = u(rng);
    const DomainSide side = d.locate({x, y});
    if (side != DomainSide::boundary) {
      ASSERT_EQ(side == DomainSide::inside, truth(x, y)) << x << ' ' << y;
    }
  }
  for (int i = 1; i < 40; ++i)
    for (int j = 1; j < 40; ++j) {
      const double x = i / 20.0 + 0.0125, y = j / 20.0;  // rows through the vertices' heights 1 and 2
      if (std::abs(y - 1) > 1e-12 && std::abs(y - 0.2) > 1e-12) {
        EXPECT_EQ(d.locate({x, y}) == DomainSide::inside, truth(x, y)) << x << ' ' << y;
      }
    }
}

TEST(Domain, RejectsInvalidDomainsWithReasons) {
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 0}}); }).find("the outer boundary has 2 vertices"), std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 1}, {1, 0}, {0, 1}}); }).find("is not simple"), std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 0}, {2, 0}}); }).find("folds back"), std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {2, 0}, {1, 0}, {1, 1}}); }).find("folds back"), std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.5, 0.5}, {1.5, 0.5}, {0.5, 0.8}}}); })
                .find("hole 1 is not strictly inside"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              Domain({{0, 0}, {4, 0}, {4, 4}, {0, 4}},
                     {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}, {{1.5, 1.5}, {3, 1.5}, {3, 3}}});
            }).find("hole 2 meets hole 1"),
            std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, {{Point2{0.5, 0.5}, Point2{1.5, 0.5}}}); })
                .find("endpoint outside"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {},
                     {{Point2{0.2, 0.5}, Point2{0.8, 0.5}}, {Point2{0.5, 0.2}, Point2{0.5, 0.8}}});
            }).find("crosses constraint segment 1"),
            std::string::npos);
  // A constraint ending on the boundary is fine; one running along it is not.
  EXPECT_EQ(error_of([] { Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, {{Point2{0, 0.5}, Point2{0.5, 0.5}}}); }),
            "no error");
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, {{Point2{0.2, 0}, Point2{0.5, 0}}}); })
                .find("crosses the boundary edge"),
            std::string::npos);
}

TEST(Domain, ReadsTheFileFormatAndReportsLines) {
  const auto dir = laguerre::testing::scratch_folder() / "laguerre-domain-test";
  std::filesystem::create_directories(dir);
  const std::string good = (dir / "good.txt").string(), bad = (dir / "bad.txt").string();
  {
    std::ofstream out(good);
    out << "# a square with a hole\nouter\n0 0\n1 0\n1 1\n0 1\n\nhole\n0.4 0.4\n0.6 0.4\n0.5 0.6  # tip\n"
           "segment 0.1 0.9 0.3 0.9\n";
  }
  const Domain d = read_domain(good);
  EXPECT_EQ(d.outer().size(), 4u);
  ASSERT_EQ(d.holes().size(), 1u);
  EXPECT_EQ(d.segments().size(), 1u);
  EXPECT_NEAR(d.area(), 1 - 0.02, 1e-12);
  {
    std::ofstream out(bad);
    out << "outer\n0 0\n1 0\n1 x\n";
  }
  EXPECT_EQ(error_of([&] { read_domain(bad); }), bad + ":4: expected a finite number in a vertex 'x y', found 'x'");
  {
    std::ofstream out(bad);
    out << "0 0\n";
  }
  EXPECT_EQ(error_of([&] { read_domain(bad); }), bad + ":1: expected 'outer', 'hole' or 'segment', found '0'");
  {
    std::ofstream out(bad);
    out << "outer\n0 0\n1 0\n";
  }
  EXPECT_EQ(error_of([&] { read_domain(bad); }), bad + ": the outer boundary has 2 vertices, expected at least 3");
  std::filesystem::remove_all(dir);
}

// The cases below come from the sensor-field copy of Domain (scenarios/fields), merged into this one.

TEST(Domain, RejectsBadHolesAndRectangles) {
  const std::vector<Point2> square4{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, square9{{0, 0}, {9, 0}, {9, 9}, {0, 9}};
  const auto sq = [](double x0, double y0, double x1, double y1) {
    return std::vector<Point2>{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  };
  EXPECT_NE(error_of([&] { Domain(square4, {sq(5, 5, 6, 6)}); }).find("hole 1 is not strictly inside the outer boundary"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Domain(square4, {sq(1, 1, 2, 2), sq(3, 3, 5, 5)}); }).find("hole 2 is not strictly inside"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Domain(square4, {sq(0, 1, 1, 2)}); }).find("hole 1 is not strictly inside"),  // on the edge
            std::string::npos);
  EXPECT_NE(error_of([&] { Domain(square9, {sq(1, 1, 5, 5), sq(2, 2, 3, 3)}); }).find("hole 2 and hole 1 are nested"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Domain(square9, {sq(1, 1, 3, 3), sq(3, 1, 5, 3)}); }).find("hole 2 meets hole 1"),
            std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {1, 0}, {1, std::nan("")}}); }).find("non-finite"), std::string::npos);
  EXPECT_NE(error_of([] { Domain({{0, 0}, {3, 0}, {2, 0}, {2, 2}}); }).find("folds back"), std::string::npos);  // a spike
  EXPECT_EQ(error_of([&] { Domain(square4, {sq(1, 1, 2, 2), sq(2.5, 2.5, 3, 3)}); }), "no error");
  EXPECT_NE(error_of([] { Domain::rectangle(1, 0, 1, 2); }).find("xmin < xmax"), std::string::npos);
  const Domain r = Domain::rectangle(-1, 0, 2, 0.5);
  EXPECT_DOUBLE_EQ(r.area(), 1.5);
  EXPECT_EQ(r.bounding_box(), (std::array<double, 4>{-1, 0, 2, 0.5}));
}

TEST(Domain, LocatesAHairAroundAHoleEdge) {
  const Domain d({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  EXPECT_EQ(d.locate({1.5, 2}), DomainSide::boundary);
  EXPECT_EQ(d.locate({1, 1}), DomainSide::boundary);  // hole corner
  EXPECT_EQ(d.locate({1.5, std::nextafter(2.0, 0.0)}), DomainSide::outside);
  EXPECT_EQ(d.locate({1.5, std::nextafter(2.0, 3.0)}), DomainSide::inside);
  // Rays towards +x through the hole's corners (1, 1) and (2, 1), and along its edge y = 2.
  EXPECT_EQ(d.locate({0.5, 1}), DomainSide::inside);
  EXPECT_EQ(d.locate({0.5, 2}), DomainSide::inside);
  EXPECT_EQ(d.locate({5, 1}), DomainSide::outside);
}

TEST(Domain, TriangleInside) {
  const Domain d({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  EXPECT_TRUE(d.triangle_inside({0.5, 0.5}, {3.5, 0.5}, {3.5, 0.9}));
  EXPECT_FALSE(d.triangle_inside({0.5, 0.5}, {3.5, 0.5}, {3.5, 3.5}));  // cuts through the hole
  EXPECT_FALSE(d.triangle_inside({0.5, 0.5}, {3.5, 0.5}, {1.5, 1.5}));  // a vertex in the hole
  EXPECT_FALSE(d.triangle_inside({0.5, 1.5}, {1.5, 0.5}, {2.5, 1.5}));  // pokes into the hole
  EXPECT_TRUE(d.triangle_inside({0.5, 0.5}, {1, 0.5}, {1, 1}));         // touches the hole's corner only
  EXPECT_THROW((void)d.triangle_inside({0.5, 0.5}, {1, 1}, {1, 0.5}), InternalError);  // clockwise
  const Domain l({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});  // an L: a reflex corner at (1, 1)
  EXPECT_THROW((void)l.triangle_inside({0, 0}, {2, 0}, {2, 1}), InternalError);  // all on the boundary
  EXPECT_FALSE(l.triangle_inside({1.6, 0.6}, {0.6, 1.6}, {0.5, 0.5}));  // the reflex corner is inside it
  EXPECT_FALSE(l.triangle_inside({1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}));  // a vertex outside
  EXPECT_FALSE(l.triangle_inside({1.5, 0.5}, {1.9, 0.9}, {1.2, 1.3}));  // a vertex outside
  EXPECT_TRUE(l.triangle_inside({1.5, 0.5}, {0.5, 1.5}, {0.5, 0.5}));
  // A constraint segment is a wall: a triangle across it is refused, one beside it kept.
  const Domain w({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, {}, {{Point2{1, 0.5}, Point2{1, 1.5}}});
  EXPECT_FALSE(w.triangle_inside({0.5, 1}, {1.5, 0.9}, {1.5, 1.1}));
  EXPECT_TRUE(w.triangle_inside({0.2, 0.2}, {0.8, 0.2}, {0.8, 1.8}));
  EXPECT_TRUE(w.triangle_inside({0.5, 0.2}, {1, 0.5}, {0.5, 1}));  // touches the wall's end only
}

}  // namespace
}  // namespace laguerre::core
