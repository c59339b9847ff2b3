#pragma once
// A uniform n × n grid of buckets over a box, holding indices (of sites, subsegments, conflict
// zones): each mesher registers an item in the cells its point or bounding box covers and queries
// the cells around a point. Coordinates outside the box (±∞ included) clamp to the border cells.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
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

/// The same in space: n × n × n cells over box {x0, y0, z0, x1, y1, z1} (the 3D star mesher).
template <class Index>
class BucketGrid3 {
public:
  BucketGrid3(std::array<double, 6> box, std::size_t n)
      : box_(box), n_(std::max<std::size_t>(n, 1)), cells_(n_ * n_ * n_), used_((cells_.size() + 63) / 64) {
    for (std::size_t k = 0; k < 3; ++k) w_[k] = std::max(box_[k + 3] - box_[k], 1e-300) / static_cast<double>(n_);
  }
  /// Index along axis k of coordinate v.
  std::size_t index(std::size_t k, double v) const { return clamp((v - box_[k]) / w_[k]); }
  /// The cell containing p.
  const std::vector<Index>& cell_of(const std::array<double, 3>& p) const {
    return cells_[(index(2, p[2]) * n_ + index(1, p[1])) * n_ + index(0, p[0])];
  }
  /// Registers `item` in every cell the box [lo, hi] meets.
  void add_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, Index item) {
    visit(lo, hi, [&](std::vector<Index>& cell) { cell.push_back(item); });
  }
  /// add_box, and first, in each cell whose size is a power of two (≥ 64), erases the entries for which
  /// dead(entry) holds, keeping the others' order (for lazily removed items).
  template <class Dead>
  void add_box_compacting(const std::array<double, 3>& lo, const std::array<double, 3>& hi, const Index& item, Dead&& dead) {
    visit(lo, hi, [&](std::vector<Index>& cell) {
      if (cell.size() >= 64 && (cell.size() & (cell.size() - 1)) == 0) std::erase_if(cell, dead);
      cell.push_back(item);
    });
  }
  /// Removes one registration of `item` from every cell the box [lo, hi] meets.
  void remove_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, Index item) {
    visit(lo, hi, [&](std::vector<Index>& cell) {
      const auto it = std::find(cell.begin(), cell.end(), item);
      if (it != cell.end()) cell.erase(it);
    });
  }
  /// Calls f on every entry of every cell the box [lo, hi] meets (possibly several times per item).
  template <class F>
  void for_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, F&& f) const {
    const std::size_t x0 = index(0, lo[0]), x1 = index(0, hi[0]), y0 = index(1, lo[1]), y1 = index(1, hi[1]);
    const std::size_t z0 = index(2, lo[2]), z1 = index(2, hi[2]);
    for (std::size_t z = z0; z <= z1; ++z)
      for (std::size_t y = y0; y <= y1; ++y) {
        const std::size_t row = (z * n_ + y) * n_;
        for (std::size_t x = x0; x <= x1; ++x)
          if (used_[(row + x) >> 6] >> ((row + x) & 63) & 1)
            for (const Index& item : cells_[row + x]) f(item);
      }
  }

private:
  template <class F>
  void visit(const std::array<double, 3>& lo, const std::array<double, 3>& hi, F&& f) {
    const std::size_t x0 = index(0, lo[0]), x1 = index(0, hi[0]), y0 = index(1, lo[1]), y1 = index(1, hi[1]);
    const std::size_t z0 = index(2, lo[2]), z1 = index(2, hi[2]);
    for (std::size_t z = z0; z <= z1; ++z)
      for (std::size_t y = y0; y <= y1; ++y)
        for (std::size_t x = x0; x <= x1; ++x) {
          const std::size_t c = (z * n_ + y) * n_ + x;
          f(cells_[c]);
          if (!cells_[c].empty()) used_[c >> 6] |= std::uint64_t{1} << (c & 63);
        }
  }
  std::size_t clamp(double t) const {
    if (!(t > 0)) return 0;
    if (!(t < static_cast<double>(n_))) return n_ - 1;
    return static_cast<std::size_t>(t);
  }
  std::array<double, 6> box_;
  std::size_t n_;
  std::array<double, 3> w_{1, 1, 1};
  std::vector<std::vector<Index>> cells_;
  /// One bit per cell: it has held an item (for_box skips the others without touching their vector,
  /// most cells of a fine grid being empty and the vectors' headers not fitting in cache).
  std::vector<std::uint64_t> used_;
};

}  // namespace laguerre::core::detail
