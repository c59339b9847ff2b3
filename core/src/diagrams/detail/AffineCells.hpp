#pragma once
/// @file
/// Internal: the CGAL-free half of the affine diagrams. Given the sites (as weighted points) and the
/// adjacency of the dual triangulation, clips every cell to the box (half-plane by half-plane,
/// remembering which neighbour made each side), extracts the edges and checks the invariants.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/diagrams/AffineDiagram.hpp"

namespace laguerre::core::detail {

/// Cells, edges and dual edges of an affine diagram computed from its dual triangulation.
struct AffineCells {
  std::vector<Polygon> cells;                            ///< per site, clipped to the box
  std::vector<StraightEdge> edges;                       ///< primal edges in the box, sorted
  std::vector<std::pair<SiteIndex, SiteIndex>> dual;     ///< dual edges (a < b), sorted
};

/// Computes the cells of the non-hidden sites from `neighbours` (the dual triangulation's adjacency:
/// the cell of i is the box cut by the half-planes of its neighbours) and the edges between them.
AffineCells build_affine_cells(const std::vector<WeightedPoint>& sites, const std::vector<bool>& hidden,
                               const std::vector<std::vector<SiteIndex>>& neighbours, const Box& box);

/// Invariants shared by the affine diagrams: cells convex and counter-clockwise, hidden cells empty,
/// symmetric dual, centroids located in their own cell (or on a tie, judged by `power`), areas adding
/// up to the box area, vertices finite. Returns the first violation, or empty.
std::string check_affine_cells(const std::vector<WeightedPoint>& sites, const std::vector<bool>& hidden,
                               const AffineCells& cells, const std::vector<DiagramVertex>& vertices, const Box& box,
                               const std::function<SiteIndex(Point2)>& locate);

}  // namespace laguerre::core::detail
