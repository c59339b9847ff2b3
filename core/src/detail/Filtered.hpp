#pragma once
/// @file
/// Internal: the filter that turns a generic expression into an exact predicate.
/// Only .cpp files of core include this header (it pulls in CGAL's number types).

#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Uncertain.h>

#include "laguerre/core/geometry/Predicates.hpp"

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace laguerre::core::detail {

/// Throws std::domain_error naming `predicate` if any value is NaN or infinite. Called before the
/// exact stage: GMP aborts the process (SIGFPE) when asked to convert a non-finite double, and a
/// non-finite input has no exact answer anyway. An embedding with such values is reported, not routed.
inline void require_finite(const char* predicate, std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v))
      throw std::domain_error(std::string("exact predicate ") + predicate +
                              ": an input coordinate or radius is NaN or infinite; the geometry cannot be decided");
}

/// Evaluates `f.template operator()<NT>()` first with NT = interval arithmetic; if any comparison
/// inside is uncertain (CGAL throws Uncertain_conversion_exception), evaluates again with NT = `Exact`.
/// The doubles fed to NT(...) convert exactly in both, so the result is the exact answer provided
/// `Exact` is exact for the operations f uses: CGAL::Exact_rational for anything (division
/// included); CGAL::Mpzf (a binary floating-point number with an unbounded integer significand: no
/// gcd, no allocation below a few hundred bits) for polynomial expressions — + − × and comparisons
/// only — which it evaluates exactly and several times faster than rationals.
template <class Exact, class F>
auto filtered_with(F&& f) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    try {
      return f.template operator()<CGAL::Interval_nt<false>>();
    } catch (CGAL::Uncertain_conversion_exception&) {
    }
  }
  return f.template operator()<Exact>();
}

/// filtered_with with exact rationals: for any expression of + − × / and comparisons.
template <class F>
auto filtered(F&& f) {
  return filtered_with<CGAL::Exact_rational>(std::forward<F>(f));
}

/// Sign of an NT value as a laguerre Sign; throws Uncertain_conversion_exception for an interval
/// containing zero but not reduced to it.
template <class NT>
Sign sign_of(const NT& v) {
  if (v > 0) return Sign::positive;
  if (v < 0) return Sign::negative;
  return Sign::zero;
}

}  // namespace laguerre::core::detail
