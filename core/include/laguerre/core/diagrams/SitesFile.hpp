#pragma once
/// @file
/// Reading the text files of the diagrams (sites files, cells files): one record per line, blank lines
/// and `#` comments ignored, every error an InputError naming file:line, what was found and what was
/// expected. Files are opened with open_input_file.
///
/// Admissible numbers in a sites file: finite, and either 0 or of magnitude in
/// [min_site_magnitude, max_site_magnitude] = [1e-150, 1e150]. Then every square and every product of
/// two input numbers is a finite, normal double (between 1e-300 and 1e300), which the filtered exact
/// predicates and the double constructions of the diagrams need; outside this range the CGAL filters
/// overflow or the constructed vertices underflow to 0/0, so such numbers are rejected at their line.

#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "laguerre/core/Error.hpp"

namespace laguerre::core {

/// Smallest magnitude of a non-zero number in a sites file.
inline constexpr double min_site_magnitude = 1e-150;
/// Largest magnitude of a number in a sites file.
inline constexpr double max_site_magnitude = 1e150;

/// Whether `v` is an admissible input number: 0, or finite of magnitude in [min_site_magnitude,
/// max_site_magnitude] (domain files follow the same rule).
inline bool admissible_magnitude(double v) {
  const double a = std::abs(v);
  return v == 0 || (a >= min_site_magnitude && a <= max_site_magnitude);
}

/// A non-blank line of a text input file: its one-based number and its white-space separated words
/// (the `#` comment removed).
struct InputLine {
  std::size_t number = 0;          ///< one-based line number
  std::vector<std::string> words;  ///< the fields, at least one
};

/// The non-blank lines of `path`, opened as a `what` ("sites file", "cells file") by open_input_file.
std::vector<InputLine> read_input_lines(const std::string& path, std::string_view what);

/// A record of a sites file: its line and its numbers (as many as the columns).
struct SiteRow {
  std::size_t line = 0;        ///< one-based line number
  std::vector<double> values;  ///< the numbers, one per column
};

/// Reads a sites file of `columns` (space-separated column names, e.g. "x y w") per line: every value
/// finite and in the admissible range (file comment). `kind` names the diagram in the messages
/// ("power diagram"). Throws InputError at file:line for a wrong field count or a bad number, and
/// InputError naming the file when it holds no site.
std::vector<SiteRow> read_site_rows(const std::string& path, std::string_view columns, std::string_view kind);

}  // namespace laguerre::core
