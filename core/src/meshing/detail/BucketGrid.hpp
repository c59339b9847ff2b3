#pragma once
// A uniform n × n grid of buckets over a box, holding indices (of sites, subsegments, conflict
// zones): each mesher registers an item in the cells its point or bounding box covers and queries
// the cells around a point. Coordinates outside the box (±∞ included) clamp to the border cells.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace laguerre::core::detail {

template <class Index>
class BucketGrid {
public:
  /// n × n cells over box {x0, y0, x1, y1} (n ≥ 1; an empty box gets cells of size 1e-300).
  BucketGrid(std::array<double, 4> box, std::size_t n) : box_(box), n_(std::max<std::size_t>(n, 1)), cells_(n_ * n_) {
    w_ = std::max(box_[2] - box_[0], 1e-300) / static_cast<double>(n_);
    h_ = std::max(box_[3] - box_[1], 1e-300) / static_cast<double>(n_);
  }
  /// Column of abscissa x.
  std::size_t ix(double x) const { return clamp((x - box_[0]) / w_); }
  /// Row of ordinate y.
  std::size_t iy(double y) const { return clamp((y - box_[1]) / h_); }
  /// Cell (column i, row j).
  std::vector<Index>& at(std::size_t i, std::size_t j) { return cells_[j * n_ + i]; }
  /// Cell (column i, row j).
  const std::vector<Index>& at(std::size_t i, std::size_t j) const { return cells_[j * n_ + i]; }
  /// The cell containing (x, y).
  const std::vector<Index>& cell_of(double x, double y) const { return at(ix(x), iy(y)); }
  /// Registers `item` in the cell of (x, y).
  void add_point(double x, double y, Index item) { at(ix(x), iy(y)).push_back(item); }
  /// Registers `item` in every cell the box [x0, x1] × [y0, y1] meets.
  void add_box(double x0, double y0, double x1, double y1, Index item) {
    for (std::size_t j = iy(y0); j <= iy(y1); ++j)
      for (std::size_t i = ix(x0); i <= ix(x1); ++i) at(i, j).push_back(item);
  }
  /// Calls f on every entry of every cell the box [x0, x1] × [y0, y1] meets (an item registered in
  /// several of those cells is seen several times).
  template <class F>
  void for_box(double x0, double y0, double x1, double y1, F&& f) const {
    for (std::size_t j = iy(y0); j <= iy(y1); ++j)
      for (std::size_t i = ix(x0); i <= ix(x1); ++i)
        for (Index item : at(i, j)) f(item);
  }

private:
  std::size_t clamp(double t) const {
    if (!(t > 0)) return 0;
    if (!(t < static_cast<double>(n_))) return n_ - 1;  // also +∞
    return static_cast<std::size_t>(t);
  }
  std::array<double, 4> box_;
  std::size_t n_;
  double w_ = 1, h_ = 1;
  std::vector<std::vector<Index>> cells_;
};

}  // namespace laguerre::core::detail
