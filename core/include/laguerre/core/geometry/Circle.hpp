#pragma once
/// @file
/// Euclidean circles and the circle embedding φ = (p, σ) of a graph.

#include <cmath>
#include <concepts>
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

/// IEEE binary128 (GCC's and Clang's __float128 on x86-64): 113-bit significand, exponents down to
/// 2^-16382. The coordinates of a layout computed in LayoutArithmetic::binary128 (docs/precision.md).
__extension__ typedef __float128 Float128;

/// A circle with binary128 coordinates: 16 bytes per coordinate. The exact predicates of
/// Predicates.hpp take it as they take Circle, as the exact rationals its numbers are.
struct Circle128 {
  Float128 x = 0;  ///< centre abscissa
  Float128 y = 0;  ///< centre ordinate
  Float128 r = 0;  ///< radius
};

/// The binary128 circle type, for overloads written as constrained templates: a braced list such as
/// {0, 0, 1} deduces no template argument, so calls written with braces keep meaning the Circle ones.
template <class C>
concept Binary128Circle = std::same_as<C, Circle128>;

/// A binary128 circle per vertex, indexed by core::Vertex.
using CircleEmbedding128 = std::vector<Circle128>;

/// The circle rounded to doubles (each coordinate to nearest).
inline Circle to_double(const Circle128& c) {
  return {static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.r)};
}

}  // namespace laguerre::core
