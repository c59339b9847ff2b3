#pragma once
/// @file
/// The radius-only local test (docs/radius-only.md): what a vertex can decide about LPD from its own
/// hyperbolic radius and its neighbours' alone, with no layout.
///
/// For a triangulated disc the test at v is: (a) interior v: the closing gap |θ(v) − 2π| ≤
/// `angle_gap`; (b) for every inner corner (w_{i−1}, w_i, w_{i+1}) of v's star (cyclic for an interior
/// vertex, i = 2 … n−1 from w1 for a boundary vertex), the inversive distance between the circle of
/// w_{i+1} and the orthocircle of (v, w_{i−1}, w_i), computed in a local frame of the two triangles
/// (v, w_{i−1}, w_i), (v, w_i, w_{i+1}) laid out from the radii, is at least `margin` (and the exact
/// power-side predicate on the frame's circles is positive). docs/radius-only.md proves that on any
/// layout in which v's star is consistent (its tangencies hold), (b) is exactly LPD(v), whatever the
/// Möbius normalization; the closing gap (a) bounds how far the star is from closing. For a complex
/// with face vertices (3-connected graphs) only (a) is tested, at every interior vertex of K: a
/// trigger, not a proven condition (see the note).

#include <span>

#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

namespace laguerre::core {

/// Tolerances of the radius-only test.
struct RadiusOnlyTolerance {
  double angle_gap = 1e-2;  ///< radians: largest accepted |θ(v) − 2π| at an interior vertex
  double margin = 1e-9;     ///< smallest accepted inversive distance of a corner test (frame rounding)
};

/// The radius-only test at one vertex of K. `star` lists the neighbours' radii counter-clockwise (∞:
/// horocycle), from w1 just after the outer wedge for a boundary vertex (`lpd_first_dart`), from any
/// neighbour for an interior one; `star.cos_spoke` empty iff the star is tangent-only, as for
/// `star_angle_sum`. Returns `holds`, `neighbour_order` (closing gap above `angle_gap`),
/// `missing_edge` (a corner test below the margin) or `unrepresentable` (a frame could not be laid
/// out in doubles, or four horocycles meet at a corner). O(deg) layouts of 4 circles.
LocalCondition check_radius_only(double h_v, const StarView& star, bool boundary, const RadiusOnlyTolerance& tol);

/// The radius-only test at vertex v of K with radii h (builds the star as PackingComplex stores it).
LocalCondition check_radius_only(const PackingComplex& k, const Radii& h, Vertex v, const RadiusOnlyTolerance& tol);

/// Whether the radius-only test holds at every vertex of K.
bool radius_only_everywhere(const PackingComplex& k, const Radii& h, const RadiusOnlyTolerance& tol);

/// Sign-exact corner test used by `check_radius_only` (exposed for tests): the inversive distance
/// between w_{i+1} and the orthocircle of (v, w_{i−1}, w_i) for mutually tangent circles with radii
/// h_v, h_a = h(w_{i−1}), h_b = h(w_i), h_c = h(w_{i+1}) (∞: horocycle), the triangles (v, a, b) and
/// (v, b, c) counter-clockwise; NaN if no frame can be laid out.
double corner_inversive_distance(double h_v, double h_a, double h_b, double h_c);

}  // namespace laguerre::core
