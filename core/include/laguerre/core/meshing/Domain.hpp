#pragma once
/// @file
/// Planar domains to mesh: an outer polygon, polygonal holes and constraint segments inside
/// (thesis §2.7's Ω and C).
///
/// Domain file format (text, one item per line, `#` starts a comment, blank lines ignored):
///
///     outer            # starts the outer boundary: the following `x y` lines are its vertices
///     0 0
///     1 0
///     1 1
///     0 1
///     hole             # starts a hole (as many as needed), vertices follow the same way
///     0.4 0.4
///     0.6 0.4
///     0.5 0.6
///     segment 0.1 0.9 0.3 0.9   # a constraint segment x1 y1 x2 y2, anywhere inside
///
/// Polygons are closed implicitly (the last vertex connects to the first), may be given in either
/// orientation (they are stored with the outer boundary counter-clockwise and holes clockwise, so the
/// domain is on the left of every boundary edge), must be simple, with holes strictly inside the outer
/// boundary and pairwise disjoint, and constraint segments inside the domain, not crossing boundaries or
/// each other except at shared endpoints. All these tests use exact predicates.

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace laguerre::core {

/// A domain that violates the rules of the file comment; `what()` names the file, line and rule.
class DomainError : public InputError {
public:
  using InputError::InputError;
};

/// Where a point lies with respect to a domain.
enum class DomainSide { outside, boundary, inside };

/// A polygonal domain with holes and constraint segments: what the mesher refines (core/meshing) and
/// where sensor fields are deployed (scenarios/fields).
class Domain {
public:
  /// Builds and validates a domain; throws DomainError naming the offending polygon and edge.
  Domain(std::vector<Point2> outer, std::vector<std::vector<Point2>> holes = {},
         std::vector<std::array<Point2, 2>> segments = {});

  /// The unit square [0, 1]².
  static Domain unit_square();

  /// The rectangle [xmin, xmax] × [ymin, ymax], no holes; DomainError unless xmin < xmax and ymin < ymax.
  static Domain rectangle(double xmin, double ymin, double xmax, double ymax);

  /// The outer boundary, counter-clockwise.
  const std::vector<Point2>& outer() const { return outer_; }
  /// The holes, each clockwise.
  const std::vector<std::vector<Point2>>& holes() const { return holes_; }
  /// The constraint segments.
  const std::vector<std::array<Point2, 2>>& segments() const { return segments_; }

  /// Every boundary edge (outer, then holes) and every constraint segment: the input constraints C.
  std::vector<std::array<Point2, 2>> constraints() const;

  /// A piece of a constraint between two consecutive constraint endpoints on it.
  struct ConstraintPiece {
    Point2 a;                    ///< first endpoint (the constraint's first endpoint, or one inside it)
    Point2 b;                    ///< second endpoint
    std::size_t constraint = 0;  ///< index of the constraint in `constraints()`
  };
  /// The constraints split at every other constraint endpoint that lies on them (a wall ending on the
  /// boundary splits that boundary edge; exact collinearity), in constraint order, each constraint's
  /// pieces from its first endpoint on: the initial subsegments of both meshers.
  std::vector<ConstraintPiece> constraint_pieces() const;

  /// Exact classification of `p` (boundary = on the outer boundary or a hole's boundary).
  DomainSide locate(Point2 p) const;

  /// Area of the domain (outer area minus hole areas), in doubles.
  double area() const;

  /// Bounding box {xmin, ymin, xmax, ymax} of the outer boundary.
  std::array<double, 4> bounding_box() const;

  /// Whether the open triangle abc lies inside the domain and meets no constraint: no point of the
  /// boundary (outer or holes) and no point of a constraint segment is in its interior (a segment is a
  /// wall for this test, e.g. no sensor link across it). Precondition: a, b, c counter-clockwise and at
  /// least one of them strictly inside (precondition: InternalError otherwise). Exact: a boundary edge or
  /// segment meets the open triangle unless a triangle edge line or the segment's own line weakly
  /// separates them (separating axes). Cost O(edges + segments).
  bool triangle_inside(Point2 a, Point2 b, Point2 c) const;

private:
  std::vector<Point2> outer_;
  std::vector<std::vector<Point2>> holes_;
  std::vector<std::array<Point2, 2>> segments_;
};

/// Reads a domain file (format in the file comment). Throws DomainError "<file>:<line>: <message>".
Domain read_domain(const std::string& path);

}  // namespace laguerre::core
