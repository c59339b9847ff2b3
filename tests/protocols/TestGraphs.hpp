#pragma once
// Random graphs prepared for packing, and the number of property cases, for the protocol tests.

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"

namespace laguerre::protocols::testing {

// A random Delaunay triangulation of n points, prepared for packing.
inline core::PlanarGraph delaunay(std::size_t n, std::uint64_t seed) {
  return core::prepare_for_packing(core::random_delaunay_triangulation(n, seed));
}

// A random 3-connected plane graph with n vertices, prepared for packing.
inline core::PlanarGraph three_connected(std::size_t n, std::uint64_t seed) {
  return core::prepare_for_packing(core::random_three_connected(n, seed));
}

// LAGUERRE_PROPERTY_CASES (at least 1) if set, else `fallback`.
inline std::uint64_t property_cases(std::uint64_t fallback) {
  const char* s = std::getenv("LAGUERRE_PROPERTY_CASES");
  return s ? std::max<std::uint64_t>(1, std::strtoull(s, nullptr, 10)) : fallback;
}

}  // namespace laguerre::protocols::testing
