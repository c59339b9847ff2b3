#pragma once
/// @file
/// The radius-only termination test (docs/radius-only.md): what a vertex decides from its own
/// hyperbolic radius and its neighbours' alone, with no layout.
///
/// The note proves that on a layout in which a vertex's star is consistent (its tangencies hold), LPD
/// holds at that vertex in every Möbius normalization: the power tests of the check are Möbius
/// invariant there, and each corner test has inversive distance ≥ 2. So before convergence LPD fails
/// only through the layout's inconsistency, which the radii measure locally by the closing gap
/// |θ(v) − 2π| of each star, and globally by the holonomy of the layout (not a local quantity). The
/// radius-only test is therefore the closing gap at every interior vertex of K; it gates the layout
/// and the exact LPD/GLPD check, which still decides (Termination::radius_only in Packer.hpp,
/// `PackingParams::termination` in the protocol).

#include <cstdint>

#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// What each check of StopRule::lpd costs (names: PackingNames.hpp).
enum class Termination {
  layout,      ///< lay out and check LPD/GLPD exactly at every check (thesis §5.3)
  radius_only,  ///< the radius-only test first; lay out and check exactly only when it holds everywhere
                ///< (and at the cap); each failed exact check halves its tolerance
  radius_flood  ///< radius_only with the test's AND flooded on the radius exchange: the tested iterate
                ///< is laid out D steps later (radius_flood_depth), no convergecast per round
};

/// Whether the closing gap of a star is within `angle_gap` radians: |θ(v) − 2π| ≤ angle_gap for an
/// interior vertex (θ by `star_angle_sum`, so bit for bit what the iteration computes), always for a
/// boundary vertex (a horocycle's star has no closing condition). False if θ is not finite.
bool radius_only_holds(double h_v, const StarView& star, bool boundary, double angle_gap);

/// `radius_only_holds` at every vertex of K with radii h.
bool radius_only_everywhere(const PackingComplex& k, const Radii& h, double angle_gap);

/// The flooded gate (Termination::radius_flood, docs/radius-only.md §8). D = 2·(largest wave of
/// the layout tree) + 2 bounds the diameter of K (every vertex is within wave + 1 hops of the root), so
/// an AND flooded over K for D exchanges has reached every vertex.
std::uint32_t radius_flood_depth(const Layout& layout);
/// The same from the largest wave (what the protocol learns at set-up).
std::uint32_t radius_flood_depth(std::uint32_t height);

/// The tested rounds are every `period`-th round (round r tests step r·N): period = ⌈D / (63·N)⌉ at least 1,
/// so that at most 64 tests are pending at once (one bit each in the radius message).
int radius_flood_period(int depth, int steps_per_check);

/// Whether step t is tested: t = r·N with r a multiple of `period`.
bool radius_flood_tested(long long t, int steps_per_check, int period);

}  // namespace laguerre::core
