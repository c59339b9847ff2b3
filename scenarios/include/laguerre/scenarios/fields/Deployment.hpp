#pragma once
/// @file
/// Random deployments of sensors in a polygonal domain (core::Domain, core/meshing/Domain.hpp): uniform
/// and clustered.
///
/// Both are deterministic for given arguments on every platform: they draw from std::mt19937_64 (whose
/// output the C++ standard fixes) through our own mapping to doubles (the top 53 bits times 2^-53) and
/// to integers (rejection, no modulo bias), never through the standard distributions. The Gaussian
/// cluster shape also uses std::log and std::sqrt (Marsaglia's polar method): sqrt is correctly
/// rounded by IEEE 754, log is within one ulp in glibc; the disc shape uses only + and ×.
/// Every returned point is strictly inside the domain (core::Domain::locate, exact) and the points are
/// pairwise distinct (a repeated point is redrawn).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "laguerre/core/meshing/Domain.hpp"

namespace laguerre::scenarios {

/// n points uniformly distributed in the domain, by rejection from its bounding box: a draw is kept
/// iff it lies strictly inside. Precondition: n > 0. Throws core::InputError if the acceptance rate is
/// hopeless (fewer than n accepted after 1000 n + 10^6 draws: the domain is a sliver of its box).
std::vector<core::Point2> deploy_uniform(const core::Domain& domain, std::size_t n, std::uint64_t seed);

/// Shape of a cluster around its parent.
enum class ClusterShape {
  gaussian,  ///< isotropic normal offset with standard deviation `spread` (Thomas process)
  disc       ///< uniform offset in the disc of radius `spread` (Matérn cluster process)
};

/// Parameters of a clustered deployment.
struct ClusterOptions {
  std::size_t clusters = 10;              ///< number of parent points (≥ 1)
  double spread = 0.05;                   ///< σ (gaussian) or radius (disc) of a cluster, > 0
  ClusterShape shape = ClusterShape::gaussian;  ///< cluster shape
};

/// n points of a Thomas / Matérn cluster process conditioned on n points inside the domain:
/// `clusters` parents are drawn uniformly in the domain (as deploy_uniform), then each point picks a
/// parent uniformly at random and an offset of the given shape; a point outside the domain (or on
/// its boundary) is redrawn, parent included. Parents are not part of the result. Preconditions: n > 0,
/// clusters > 0, spread > 0 and finite. Throws core::InputError if fewer than n points are accepted
/// after 1000 n + 10^6 draws.
std::vector<core::Point2> deploy_clustered(const core::Domain& domain, std::size_t n, const ClusterOptions& options,
                                           std::uint64_t seed);

}  // namespace laguerre::scenarios
