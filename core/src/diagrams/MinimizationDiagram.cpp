#include "laguerre/core/diagrams/MinimizationDiagram.hpp"
#include "laguerre/core/Error.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace laguerre::core {

Rgb site_colour(SiteIndex i) {
  // Hue walk by the golden angle; saturation and value cycle slowly so neighbours differ even for
  // many sites. HSV → RGB.
  const double h = std::fmod(static_cast<double>(i) * 137.50776405, 360.0) / 60.0;
  const double s = 0.35 + 0.2 * static_cast<double>(i % 3) / 2.0;
  const double v = 0.97 - 0.12 * static_cast<double>((i / 3) % 3) / 2.0;
  const double c = v * s, x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h) % 6) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  auto byte = [](double t) { return static_cast<std::uint8_t>(std::lround(std::clamp(t, 0.0, 1.0) * 255)); };
  return {byte(r + m), byte(g + m), byte(b + m)};
}

MinimizationDiagram::MinimizationDiagram(const Box& box, int width, int height, std::size_t site_count,
                                         const DistanceFunction& f, double tie_tolerance)
    : box_(box), width_(width), height_(height), site_count_(site_count) {
  if (width <= 0 || height <= 0) throw InputError("minimization diagram: raster size must be positive");
  if (!box.valid()) throw InputError("minimization diagram: the box must satisfy xmin < xmax, ymin < ymax");
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  labels_.assign(n, no_site);
  tied_.assign(n, 0);
  margins_.assign(n, std::numeric_limits<double>::infinity());
  const double inf = std::numeric_limits<double>::infinity();
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      const Point2 x = pixel_centre(col, row);
      double best = inf, second = inf;
      SiteIndex arg = no_site;
      for (SiteIndex i = 0; i < site_count; ++i) {
        double v = f(i, x);
        if (std::isnan(v)) v = inf;
        if (v < best) {
          second = best, best = v, arg = i;
        } else if (v < second) {
          second = v;
        }
      }
      const std::size_t k = index(col, row);
      if (best == inf) continue;
      // The label is the smallest index within the tolerance of the minimum.
      for (SiteIndex i = 0; i < arg; ++i) {
        const double v = f(i, x);
        if (!std::isnan(v) && v - best <= tie_tolerance) {
          arg = i;
          break;
        }
      }
      labels_[k] = arg;
      margins_[k] = second - best;
      tied_[k] = (second - best <= tie_tolerance) ? 1 : 0;
    }
}

Point2 MinimizationDiagram::pixel_centre(int col, int row) const {
  return {box_.xmin + (col + 0.5) * box_.width() / width_, box_.ymax - (row + 0.5) * box_.height() / height_};
}

std::vector<std::size_t> MinimizationDiagram::pixel_counts() const {
  std::vector<std::size_t> counts(site_count_, 0);
  for (SiteIndex s : labels_)
    if (s != no_site) ++counts[s];
  return counts;
}

std::size_t MinimizationDiagram::tie_count() const {
  std::size_t t = 0;
  for (auto v : tied_) t += v;
  return t;
}

std::vector<SiteIndex> MinimizationDiagram::unlabelled_sites() const {
  std::vector<SiteIndex> out;
  const auto counts = pixel_counts();
  for (SiteIndex i = 0; i < site_count_; ++i)
    if (counts[i] == 0) out.push_back(i);
  return out;
}

std::vector<std::uint8_t> MinimizationDiagram::render_rgb(bool mark_ties) const {
  std::vector<std::uint8_t> rgb(labels_.size() * 3, 255);
  for (std::size_t k = 0; k < labels_.size(); ++k) {
    if (labels_[k] == no_site) continue;
    const Rgb c = (mark_ties && tied_[k]) ? Rgb{0, 0, 0} : site_colour(labels_[k]);
    rgb[3 * k] = c[0], rgb[3 * k + 1] = c[1], rgb[3 * k + 2] = c[2];
  }
  return rgb;
}

void MinimizationDiagram::write_ppm(const std::string& path, bool mark_ties) const {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot open '" + path + "' for writing");
  out << "P6\n" << width_ << ' ' << height_ << "\n255\n";
  const auto rgb = render_rgb(mark_ties);
  out.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
  if (!out) throw std::runtime_error("write to '" + path + "' failed");
}

}  // namespace laguerre::core
