#pragma once
/// @file
/// Möbius diagrams on the unit sphere S² (thesis §2.1.1, "Möbius diagrams on spheres") through the
/// stereographic projection.
///
/// A site is (P, λ, μ) with P ∈ R³ and distance δ(X) = λ|X − P|² − μ for X on S². The stereographic
/// projection from the north pole N = (0, 0, 1) onto the plane z = 0, x = (X₁, X₂)/(1 − X₃), has inverse
/// X = (2x, |x|² − 1)/(|x|² + 1). Since |X|² = 1, δ(X)·(|x|² + 1) = A|x|² − 2 b·x + C with
///   A = λ|P − N|² − μ,  b = 2λ(P₁, P₂),  C = λ|P + N|² − μ,
/// and the common positive factor |x|² + 1 does not change which site is smallest. So the projected
/// diagram is the planar Möbius diagram of the sites (b/A, λ' = A, μ' = |b|²/A − C) (A may be negative:
/// the linearization does not need λ' > 0; A = 0, i.e. N on the site's bisecting sphere with every
/// other site, is refused). We compute that planar diagram (MobiusDiagram) and map vertices and edges
/// back with the inverse projection; circles and lines of the plane map to circles of S².
/// The planar window [−R, R]² covers the sphere except the cap around N of angular radius 2·atan(1/R);
/// `locate` works on the whole sphere (except N itself, which it maps to a far point).

#include <array>
#include <vector>

#include "laguerre/core/diagrams/MobiusDiagram.hpp"

namespace laguerre::core {

/// A point of R³.
using Point3 = std::array<double, 3>;

/// A Möbius site for the sphere: δ(X) = λ|X − P|² − μ.
struct SphereMobiusSite {
  Point3 p{};         ///< the point P (anywhere in R³; on S² for the usual "spherical Voronoi" sites)
  double lambda = 1;  ///< multiplicative weight
  double mu = 0;      ///< additive weight
};

/// δ(X) = λ|X − P|² − μ in doubles.
double sphere_mobius_distance(const Point3& x, const SphereMobiusSite& s);

/// Stereographic projection from N = (0, 0, 1) onto z = 0 (X on S², X ≠ N).
Point2 stereographic(const Point3& x);

/// Inverse stereographic projection: the point of S² above x.
Point3 inverse_stereographic(Point2 x);

/// The planar Möbius site of the projected distance (see the file comment); throws
/// InputError when A = 0.
MobiusSite stereographic_site(const SphereMobiusSite& s);

/// Möbius diagram on S², computed in the plane through the stereographic projection.
class SphericalMobiusDiagram {
 public:
  /// Builds the diagram; the planar window is [−R, R]² with R = `window` (> 0).
  explicit SphericalMobiusDiagram(std::vector<SphereMobiusSite> sites, double window = 10);
  /// The sites.
  const std::vector<SphereMobiusSite>& sites() const { return sites_; }
  /// The planar diagram of the projected sites.
  const MobiusDiagram& planar() const { return planar_; }
  /// A site minimizing δ at X ∈ S² (through the planar point location).
  SiteIndex locate(const Point3& x) const;
  /// The vertices mapped back to the sphere (same order as planar().vertices()).
  std::vector<Point3> vertices() const;
  /// Each edge of the planar diagram mapped back to the sphere as a polyline (arcs sampled every
  /// `step` radians of the planar circle, segments subdivided into `segment_points` points).
  std::vector<std::vector<Point3>> edge_polylines(double step = 0.02, int segment_points = 200) const;

 private:
  std::vector<SphereMobiusSite> sites_;
  MobiusDiagram planar_;
};

}  // namespace laguerre::core
