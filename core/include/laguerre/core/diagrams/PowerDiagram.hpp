#pragma once
/// @file
/// Power (Laguerre) diagram and its dual regular triangulation, through CGAL's Regular_triangulation_2
/// with exact predicates (Epick).
///
/// Sites are weighted points (p_i, w_i); the power cell of i is {x : |x − p_i|² − w_i ≤ |x − p_j|² − w_j
/// for all j}, a convex polygon, possibly empty: then site i is *hidden* (it is not a vertex of the
/// regular triangulation). Equal sites (same point and weight) keep one representative, the others are
/// reported hidden. Cells are clipped to the box given at construction (unbounded cells included).
/// Combinatorial decisions (triangulation, hidden sites, point location) are exact for the double
/// inputs; cell polygons and vertices are double constructions.
///
/// Degenerate inputs: collinear sites give a 1-dimensional triangulation (no triangles, no vertices;
/// cells are parallel strips); four or more sites with a common orthogonal circle are triangulated in
/// one of the valid ways (CGAL's symbolic perturbation), so some dual edges have a primal edge of length
/// zero, which `edges()` omits.

#include "laguerre/core/diagrams/AffineDiagram.hpp"

namespace laguerre::core {

/// Power diagram of weighted points, clipped to a box, with its dual regular triangulation (the API
/// is AffineDiagram's).
using PowerDiagram = AffineDiagram<WeightedPoint>;

}  // namespace laguerre::core
