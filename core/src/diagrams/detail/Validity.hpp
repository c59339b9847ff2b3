#pragma once
/// @file
/// Internal: the common tail of every `bool is_valid(bool verbose = false) const` of core/diagrams and
/// core/meshing (CGAL's shape): the checks produce the first violated invariant as a sentence (empty
/// when all hold), and this reports it.

#include <iostream>
#include <string>

namespace laguerre::core::detail {

/// True when `violation` is empty; otherwise false, and with `verbose` writes the violation on a line of
/// std::cerr.
inline bool report_validity(const std::string& violation, bool verbose) {
  if (violation.empty()) return true;
  if (verbose) std::cerr << violation << '\n';
  return false;
}

}  // namespace laguerre::core::detail
