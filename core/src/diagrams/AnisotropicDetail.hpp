#pragma once
/// @file
/// Internal: the regular complex of the lifted anisotropic sites in R⁵ (AnisotropicLifting.cpp), built
/// at once or kept and grown one batch of sites at a time.

#include <array>
#include <memory>
#include <vector>

#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"

namespace laguerre::core::detail {

/// The regular triangulation of the spheres σ_i of R⁵ (see AnisotropicDiagram.hpp).
struct RegularComplex {
  int dimension = -1;                             ///< its dimension
  std::vector<std::array<SiteIndex, 3>> triangles;  ///< its triangles (all finite), sorted, unique
  std::vector<std::vector<SiteIndex>> neighbours;   ///< per site, its neighbours (empty when hidden)
  std::vector<char> visible;                        ///< per site, whether it is a vertex
};

/// Builds the regular complex of `sites` (only those with keep[i] set).
RegularComplex regular_complex(const std::vector<AnisotropicSite>& sites, const std::vector<char>& keep);

/// The same regular triangulation kept alive while sites are added. CGAL perturbs degenerate
/// configurations symbolically (by a lexicographic order of the lifted points), so the triangulation of
/// a set of points does not depend on the order in which they were inserted: after any sequence of
/// insert() calls, neighbours() and triangles_of() describe regular_complex() of all the sites so far.
class LiftedTriangulation {
public:
  LiftedTriangulation();
  ~LiftedTriangulation();
  LiftedTriangulation(const LiftedTriangulation&) = delete;
  LiftedTriangulation& operator=(const LiftedTriangulation&) = delete;

  /// Inserts sites[i] for every i of `added` (indices not inserted before; `sites` holds at least every
  /// site inserted so far, unchanged). Returns the sites whose neighbours or triangles may have changed
  /// (every vertex of a full cell created by an insertion), sorted and unique; or, with `all` set, when
  /// the dimension changed or a vertex was hidden, every site inserted so far.
  std::vector<SiteIndex> insert(const std::vector<AnisotropicSite>& sites, const std::vector<SiteIndex>& added, bool& all);

  /// The dimension of the triangulation (−1 when empty).
  int dimension() const;
  /// The regular-complex neighbours of site s, increasing (empty when s is hidden or not inserted).
  std::vector<SiteIndex> neighbours(SiteIndex s) const;
  /// Appends the regular-complex triangles that have s as a vertex (increasing labels; may repeat).
  void triangles_of(SiteIndex s, std::vector<std::array<SiteIndex, 3>>& out) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace laguerre::core::detail
