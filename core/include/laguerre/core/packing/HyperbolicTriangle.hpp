#pragma once
/// @file
/// Angles of triangles of hyperbolic circles, in the horocycle-safe parametrization X = e^{-2h}.
///
/// A hyperbolic circle of radius h ∈ (0, ∞] is stored as X = e^{-2h} ∈ [0, 1): X = 0 is a horocycle
/// (h = ∞), X → 1 a vanishing circle. Three circles x, y, z whose pairs meet at angles θ_xy, θ_xz, θ_yz
/// (θ = 0: externally tangent, θ = π/2: orthogonal) have centres at distances
///     cosh l_xy = cosh h_x cosh h_y + cos θ_xy · sinh h_x sinh h_y,
/// and the angle α at x of the triangle of centres follows the hyperbolic law of cosines
///     cos α = (cosh l_xy cosh l_xz − cosh l_yz) / (sinh l_xy sinh l_xz).
/// With cosh h = (1+X)/(2√X) and sinh h = (1−X)/(2√X) every term is a polynomial in X, Y, Z divided by
/// powers of √(XYZ) that cancel, which gives formulas valid for horocycles at y and z (never at x).

namespace laguerre::core {

/// Angle at x of the triangle of three mutually tangent circles (X at the vertex, Y and Z its
/// neighbours), from sin²(α/2) = X(1−Y)(1−Z) / ((1−XY)(1−XZ)). Requires X ∈ (0,1), Y, Z ∈ [0,1).
double tangent_angle(double X, double Y, double Z);

/// Angle at x for circles meeting pairwise at angles with cosines `cxy`, `cxz`, `cyz` (1 = tangent,
/// 0 = orthogonal). Equals tangent_angle when all cosines are 1 (up to rounding). Requires X ∈ (0,1),
/// Y, Z ∈ [0,1), cosines in [0, 1] and a non-degenerate triangle.
double overlap_angle(double X, double Y, double Z, double cxy, double cxz, double cyz);

/// The uniform-neighbour update (Collins & Stephenson 2003, hyperbolic form) for a vertex whose k
/// neighbours are all tangent to it: given its current X and angle sum θ, find the common neighbour
/// value U that would produce θ, then the X' that makes the angle sum 2π with k neighbours U.
/// Closed form; returns X' ∈ (0, 1).
double uniform_neighbour_update(double X, double theta, int k);

/// Hyperbolic radius h from X (∞ for X = 0).
double radius_of(double X);
/// X = e^{-2h} from a hyperbolic radius (0 for h = ∞).
double x_of_radius(double h);

}  // namespace laguerre::core
