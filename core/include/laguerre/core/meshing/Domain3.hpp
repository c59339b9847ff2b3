#pragma once
/// @file
/// Polyhedral domains of space: the region bounded by a closed, oriented triangle surface (one or
/// more components: a box with a cavity is an outer box surface and an inner one), the 3D Ω of the
/// star mesher (StarMesher3.hpp).
///
/// Files: OFF (`OFF`, then `nv nf ne`, nv lines `x y z`, nf lines `3 i j k` with indices from 0; `#`
/// comments) or a Medit `.mesh` of dimension 3 whose `Triangles` are the surface (Medit.hpp). The
/// surface must be
///   - made of non-degenerate triangles (three distinct, non-collinear vertices: exact predicate),
///   - closed and manifold along edges (every edge in exactly two triangles),
///   - consistently oriented (the two triangles at an edge traverse it in opposite directions),
///   - free of self-intersections (CGAL Polygon_mesh_processing, exact predicates).
/// The orientation of each component does not matter: components are re-oriented so that the normals
/// point out of the domain (a component nested in an odd number of others bounds a cavity).
/// Violations throw DomainError "<file>:<line>: <message>" naming the triangles' lines.

#include "laguerre/core/meshing/Domain.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace laguerre::core {

/// A point of space.
using Point3 = std::array<double, 3>;

/// The region bounded by a closed oriented triangle surface (see the file comment).
class PolyhedralDomain {
public:
  /// Validates and orients the surface; `lines` (optional, one per triangle) and `source` locate the
  /// triangles in messages. Throws DomainError.
  PolyhedralDomain(std::vector<Point3> vertices, std::vector<std::array<std::size_t, 3>> triangles,
                   std::vector<std::size_t> lines = {}, const std::string& source = "");
  ~PolyhedralDomain();
  PolyhedralDomain(PolyhedralDomain&&) noexcept;
  PolyhedralDomain& operator=(PolyhedralDomain&&) noexcept;

  /// The box [x0, x1] × [y0, y1] × [z0, z1] (12 triangles).
  static PolyhedralDomain box(double x0, double y0, double z0, double x1, double y1, double z1);

  /// The surface's vertices.
  const std::vector<Point3>& vertices() const { return vertices_; }
  /// The surface's triangles, oriented with their normal (b − a) × (c − a) pointing out of Ω.
  const std::vector<std::array<std::size_t, 3>>& triangles() const { return triangles_; }
  /// Number of connected components of the surface.
  std::size_t components() const { return components_; }

  /// Exact classification of p (Side_of_triangle_mesh).
  DomainSide locate(const Point3& p) const;
  /// The enclosed volume (outer volumes minus cavities), in doubles.
  double volume() const { return volume_; }
  /// {xmin, ymin, zmin, xmax, ymax, zmax}.
  std::array<double, 6> bounding_box() const;

private:
  std::vector<Point3> vertices_;
  std::vector<std::array<std::size_t, 3>> triangles_;
  std::size_t components_ = 0;
  double volume_ = 0;
  struct Locator;
  std::unique_ptr<Locator> locator_;
};

/// Reads a polyhedral domain from an OFF file or a 3D Medit `.mesh` surface (by extension: `.off`,
/// `.mesh`). Throws DomainError or MeshInputError "<file>:<line>: <message>".
PolyhedralDomain read_polyhedral_domain(const std::string& path);

/// Whether `path` names a 3D domain: an `.off` file, or a `.mesh` file of dimension 3.
bool is_3d_domain_file(const std::string& path);

}  // namespace laguerre::core
