#pragma once
/// @file
/// Euclidean circles and the circle embedding φ = (p, σ) of a graph.

#include <cmath>
#include <vector>

namespace laguerre::core {

/// A Euclidean circle: centre (x, y) and radius r ≥ 0. As a power-diagram site its weight is r².
struct Circle {
  double x = 0;  ///< centre abscissa
  double y = 0;  ///< centre ordinate
  double r = 0;  ///< radius
};

/// Power distance pow(q, c) = |q − p(c)|² − r(c)², evaluated in doubles (for display and metrics
/// only: every geometric *decision* goes through the exact predicates of Predicates.hpp).
inline double power(double qx, double qy, const Circle& c) {
  const double dx = qx - c.x, dy = qy - c.y;
  return dx * dx + dy * dy - c.r * c.r;
}

/// A circle per vertex, indexed by core::Vertex: the map φ = (p, σ) of thesis §5.2.
using CircleEmbedding = std::vector<Circle>;

}  // namespace laguerre::core
