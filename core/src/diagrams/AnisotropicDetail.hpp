#pragma once
/// @file
/// Internal: the regular complex of the lifted anisotropic sites in R⁵ (AnisotropicLifting.cpp).

#include <array>
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

}  // namespace laguerre::core::detail
