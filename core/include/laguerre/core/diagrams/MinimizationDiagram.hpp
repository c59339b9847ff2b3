#pragma once
/// @file
/// Raster minimization diagrams: label every pixel of a W×H grid over a box by the site whose distance
/// function is smallest there. The brute-force oracle of every diagram test and the renderer of last
/// resort for any distance (power, Möbius, Apollonius, anisotropic, …).
///
/// Pixel (col, row) has its centre at (xmin + (col + ½)·w/W, ymax − (row + ½)·h/H): row 0 is the top
/// line, as in an image. Ties: the label is the smallest index whose value is within `tie_tolerance`
/// of the minimum, and the pixel is reported tied when a second site is within that tolerance.
/// `margin(col, row)` is (second smallest − smallest) so tests can restrict comparisons to pixels
/// clearly inside one cell ("away from edges").

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "laguerre/core/diagrams/Sites.hpp"

namespace laguerre::core {

/// An RGB colour with 8-bit channels.
using Rgb = std::array<std::uint8_t, 3>;

/// A well-spread colour for site i (golden-angle hue walk; pale enough to draw sites on top).
Rgb site_colour(SiteIndex i);

/// A labelled raster: the minimization diagram of n distance functions sampled at pixel centres.
class MinimizationDiagram {
 public:
  /// Distance of site `i` at point `x` (any real-valued function; NaN counts as +∞).
  using DistanceFunction = std::function<double(SiteIndex i, Point2 x)>;

  /// Samples `f` for sites 0..site_count−1 at the centres of a width × height grid over `box`.
  /// Throws InputError for a non-positive size or an invalid box.
  MinimizationDiagram(const Box& box, int width, int height, std::size_t site_count, const DistanceFunction& f,
                      double tie_tolerance = 0.0);

  /// The sampled box.
  const Box& box() const { return box_; }
  /// Number of columns.
  int width() const { return width_; }
  /// Number of rows.
  int height() const { return height_; }
  /// Number of sites.
  std::size_t site_count() const { return site_count_; }
  /// Centre of pixel (col, row).
  Point2 pixel_centre(int col, int row) const;
  /// The minimizing site at pixel (col, row) (no_site if every value is +∞ or NaN, or there are no sites).
  SiteIndex label(int col, int row) const { return labels_[index(col, row)]; }
  /// Whether a second site attains the minimum within the tie tolerance at pixel (col, row).
  bool tied(int col, int row) const { return tied_[index(col, row)] != 0; }
  /// Second smallest value minus smallest value at pixel (col, row) (+∞ with fewer than two sites).
  double margin(int col, int row) const { return margins_[index(col, row)]; }
  /// Number of pixels labelled by each site.
  std::vector<std::size_t> pixel_counts() const;
  /// Number of tied pixels.
  std::size_t tie_count() const;
  /// Sites that label no pixel (hidden, or with a cell smaller than the sampling step or outside the box).
  std::vector<SiteIndex> unlabelled_sites() const;

  /// Row-major RGB image (3 bytes per pixel) filled with `site_colour(label)`; ties in black when
  /// `mark_ties`, unlabelled pixels in white.
  std::vector<std::uint8_t> render_rgb(bool mark_ties = true) const;
  /// Writes the rendered image as a binary PPM (P6) file; throws std::runtime_error on I/O failure.
  void write_ppm(const std::string& path, bool mark_ties = true) const;

 private:
  std::size_t index(int col, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(col);
  }
  Box box_;
  int width_;
  int height_;
  std::size_t site_count_;
  std::vector<SiteIndex> labels_;
  std::vector<std::uint8_t> tied_;
  std::vector<double> margins_;
};

}  // namespace laguerre::core
