#pragma once
/// @file
/// Thurston's iteration for the maximal packing of a triangulated disc in the hyperbolic plane.

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
/// exactly (bracketed secant on √X), which is Thurston's original update.
enum class UpdateRule {
  uniform_neighbour,  ///< closed form where possible, exact solve elsewhere (default)
  exact               ///< exact angle-sum solve everywhere
};

/// Radii state: X(v) = e^{-2 h(v)} per vertex of the complex, 0 on the boundary (horocycles).
using Radii = std::vector<double>;

/// The thesis's initial state: horocycles on the boundary, hyperbolic radius 1 inside.
Radii initial_radii(const PackingComplex& k);

/// Angle sum θ(v) at an interior vertex v for radii X.
double angle_sum(const PackingComplex& k, const Radii& X, Vertex v);

/// Largest |θ(v) − 2π| over interior vertices.
double angle_error(const PackingComplex& k, const Radii& X);

/// New X for interior vertex v with its neighbours held at `X` (the single-vertex update).
double updated_radius(const PackingComplex& k, const Radii& X, Vertex v, UpdateRule rule);

/// One full sweep over the interior vertices. `scratch` is reused across calls (Jacobi needs a copy).
void thurston_sweep(const PackingComplex& k, Radii& X, Sweep sweep, UpdateRule rule, Radii& scratch);

}  // namespace laguerre::core
