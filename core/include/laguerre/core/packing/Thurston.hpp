#pragma once
/// @file
/// Thurston's iteration for the maximal packing of a triangulated disc in the hyperbolic plane.

#include <span>
#include <vector>

#include "laguerre/core/packing/PackingComplex.hpp"

namespace laguerre::core {

/// Order of the vertex updates within one sweep.
enum class Sweep {
  jacobi,       ///< every update reads the previous iterate (what a synchronous network computes)
  gauss_seidel  ///< updates in vertex order, each reading the newest values
};

/// How an interior vertex's new radius is computed from its neighbours.
///
/// Vertices whose triangles are all tangencies use the closed-form uniform-neighbour model; vertices
/// touching an orthogonal edge (3-connected graphs) have no closed form and solve their angle sum
/// exactly (bracketed secant on log h), which is Thurston's original update.
enum class UpdateRule {
  uniform_neighbour,  ///< closed form where possible, exact solve elsewhere (default)
  exact               ///< exact angle-sum solve everywhere
};

/// Radii state: the hyperbolic radius h(v) ∈ (0, ∞) per interior vertex of the complex, ∞ on the
/// boundary (horocycles). Stored as h, not X = e^{-2h}: X cannot represent small circles (see
/// HyperbolicTriangle.hpp), and e^{-2h}, 1 − e^{-2h} are computed from h with full precision.
using Radii = std::vector<double>;

/// The thesis's initial state: horocycles on the boundary, hyperbolic radius 1 inside.
Radii initial_radii(const PackingComplex& k);

/// Angle sum θ(v) at an interior vertex v for radii `h`.
double angle_sum(const PackingComplex& k, const Radii& h, Vertex v);

/// Angle sums θ(v) of every vertex (0 on the boundary), lifting each radius once.
std::vector<double> angle_sums(const PackingComplex& k, const Radii& h);

/// Largest |θ(v) − 2π| over interior vertices.
double angle_error(const PackingComplex& k, const Radii& h);

/// New radius of interior vertex v with its neighbours held at `h` (the single-vertex update).
double updated_radius(const PackingComplex& k, const Radii& h, Vertex v, UpdateRule rule);

/// What one interior vertex v knows for its update, in node-local form: its neighbours' values in
/// counter-clockwise order and, where v touches an orthogonal edge, the intersection cosines.
///
/// This is the form in which the distributed protocol computes, and the centralized functions above
/// evaluate exactly the same arithmetic in the same order (the sums run around v starting from
/// `neighbour_h[0]`, which must be the neighbour towards `PlanarGraph::first_dart(v)` for the two to
/// agree bit for bit).
struct StarView {
  std::span<const double> neighbour_h;  ///< hyperbolic radii of the neighbours of v, counter-clockwise (∞: horocycle)
  /// Empty if every triangle around v is a tangency triangle (`PackingComplex::tangent_only`); else
  /// `cos_spoke[i]` is the cosine on edge v–neighbour i and `cos_rim[i]` the cosine on edge
  /// neighbour i – neighbour i+1 (indices mod degree).
  std::span<const double> cos_spoke;
  std::span<const double> cos_rim;      ///< see `cos_spoke` (same length)
};

/// Angle sum at an interior vertex of radius `hv` with the star `s`: tangent angles summed from
/// neighbour 0 counter-clockwise when `s.cos_spoke` is empty, overlap angles otherwise.
double star_angle_sum(double hv, const StarView& s);

/// New radius of an interior vertex of radius `hv` with the star `s` (the node-local `updated_radius`): the
/// uniform-neighbour closed form when `rule` asks for it and the star is tangent-only, otherwise the
/// exact angle-sum solve.
double star_updated_radius(double hv, const StarView& s, UpdateRule rule);

/// One full sweep over the interior vertices. `scratch` is reused across calls (Jacobi needs a copy).
void thurston_sweep(const PackingComplex& k, Radii& h, Sweep sweep, UpdateRule rule, Radii& scratch);

}  // namespace laguerre::core
