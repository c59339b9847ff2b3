#pragma once
/// @file
/// Angles of triangles of hyperbolic circles, accurate for horocycles and for vanishing circles.
///
/// A hyperbolic circle is stored by its radius h ∈ (0, ∞] (h = ∞ is a horocycle). The angle formulas
/// are rational in X = e^{-2h}, but X alone cannot carry a small circle: at h = 10^-6, X = 1 − 2·10^-6
/// keeps only ten significant digits of h, and every (1 − X) in a formula loses the rest. Uniform
/// random 3-connected maps and punctured triangulations have hyperbolic radii down to 10^-6 and below
/// behind their small cuts, and with X alone Thurston's iteration stalls there at angle errors of
/// radians. So the formulas read the pair `Lift` = (X, X̄ = 1 − X), both computed from h with full
/// relative precision (exp and expm1), and are written so that nothing cancels: 1 − XY = X̄ + X·Ȳ,
/// and the triangles of G′ have closed forms with no subtraction at all (below).
///
/// Three circles x, y, z whose pairs meet at angles θ_xy, θ_xz, θ_yz (θ = 0: externally tangent,
/// θ = π/2: orthogonal) have centres at distances
///     cosh l_xy = cosh h_x cosh h_y + cos θ_xy · sinh h_x sinh h_y,
/// and the angle α at x of the triangle of centres follows the hyperbolic law of cosines
///     cos α = (cosh l_xy cosh l_xz − cosh l_yz) / (sinh l_xy sinh l_xz).
///
/// Three tangencies: sin²(α/2) = sinh h_y sinh h_z / (sinh(h_x+h_y) sinh(h_x+h_z))
///                             = X Ȳ Z̄ / ((X̄ + X Ȳ)(X̄ + X Z̄)).
/// The triangles of G′ (x, y tangent, a face circle f orthogonal to both): inverting at the tangency
/// point T of x and y maps them to parallel lines, and a circle orthogonal to two parallel lines is a
/// line through the image of T, so f passes through T. The triangle of centres (x, y, f) is therefore
/// the union of the right triangles (x, T, f) and (y, T, f), with legs h_x, h_f and h_y, h_f, and the
/// hyperbolic right-triangle rule tan A = tanh(opposite leg) / sinh(adjacent leg) gives
///     angle at x = atan(tanh h_f / sinh h_x)                       (independent of h_y),
///     angle at f = atan(tanh h_x / sinh h_f) + atan(tanh h_y / sinh h_f),
/// with tanh h = X̄ / (1 + X) and sinh h = X̄ / (2√X).

namespace laguerre::core {

/// A hyperbolic radius h ∈ (0, ∞] as the two numbers the angle formulas read: X = e^{-2h} and
/// X̄ = 1 − X, each with full relative precision (X = 0, X̄ = 1 for a horocycle).
struct Lift {
  double x = 0;     ///< X = e^{-2h}
  double xbar = 1;  ///< X̄ = 1 − X = −expm1(−2h)
};

/// The lift of hyperbolic radius h (h = ∞: a horocycle).
Lift lift(double h);

/// Angle at x of the triangle of three mutually tangent circles (x at the vertex, y and z its
/// neighbours). Requires h_x < ∞; y and z may be horocycles.
double tangent_angle(Lift x, Lift y, Lift z);

/// Angle at x for circles meeting pairwise at angles with cosines `cxy`, `cxz`, `cyz` (1 = tangent,
/// 0 = orthogonal). The patterns of G′ — three tangencies, or one tangency and two right angles —
/// use the closed forms above and keep full relative precision; any other pattern uses the general
/// law of cosines in X, which loses digits for vanishing circles (h ≲ 10^-4). Requires h_x < ∞.
double overlap_angle(Lift x, Lift y, Lift z, double cxy, double cxz, double cyz);

/// The uniform-neighbour update (Collins & Stephenson 2003, hyperbolic form) for a vertex whose k
/// neighbours are all tangent to it: given its current radius h and angle sum θ, find the common
/// neighbour value U that would produce θ, then the radius h' that makes the angle sum 2π with k
/// neighbours U. Closed form, written without cancellation for small and large circles; h' ∈ (0, ∞).
double uniform_neighbour_update(double h, double theta, int k);

/// Hyperbolic radius h from X = e^{-2h} (∞ for X = 0).
double radius_of(double X);
/// X = e^{-2h} from a hyperbolic radius (0 for h = ∞).
double x_of_radius(double h);

}  // namespace laguerre::core
