// Charts of `laguerre compare`: delivery rate and hop stretch against size, per family and network.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "Render.hpp"
#include "RunPictures.hpp"

namespace laguerre::tools {

namespace {

struct Series {
  std::string scheme;
  std::vector<double> x, y, lo, hi;
};

struct Panel {
  std::string title;
  std::vector<Series> series;
};

const double palette[][3] = {{0.85, 0.1, 0.1}, {0.1, 0.45, 0.1}, {0.9, 0.55, 0.0}, {0.1, 0.3, 0.9},
                             {0.5, 0.1, 0.7},  {0.3, 0.3, 0.3}};

std::size_t colour_of(const std::string& scheme) {
  static const std::vector<std::string> known = core::names_of(scenarios::scheme_names);
  for (std::size_t i = 0; i < known.size(); ++i)
    if (known[i] == scheme) return i;
  return 5;
}

std::vector<Panel> panels_of(const std::vector<scenarios::ComparisonRow>& rows, bool delivery) {
  std::vector<Panel> panels;
  // One panel per family × network condition, across scenario files: `compare a.yaml b.yaml` with
  // the same families at different sizes draws one curve per scheme over all the sizes.
  std::map<std::string, std::size_t> index;
  std::vector<std::vector<std::string>> sources;  // scenario names per panel, first-seen order
  for (const auto& r : rows) {
    const std::string key = r.family + " | " + r.network;
    if (!index.count(key)) {
      index[key] = panels.size();
      panels.push_back({r.family + ", " + r.network, {}});
      sources.emplace_back();
    }
    const std::size_t k = index[key];
    if (std::find(sources[k].begin(), sources[k].end(), r.scenario) == sources[k].end()) sources[k].push_back(r.scenario);
    Panel& p = panels[k];
    auto it = std::find_if(p.series.begin(), p.series.end(), [&](const Series& s) { return s.scheme == r.scheme; });
    if (it == p.series.end()) {
      p.series.push_back({r.scheme, {}, {}, {}, {}});
      it = std::prev(p.series.end());
    }
    double x = std::nan("");
    try {
      x = std::stod(r.size);
    } catch (const std::exception&) {
    }
    if (std::isnan(x)) x = r.nodes_mean;
    const double y = delivery ? r.delivery_mean : r.stretch_mean;
    if (!std::isfinite(x) || !std::isfinite(y)) continue;
    it->x.push_back(x);
    it->y.push_back(y);
    it->lo.push_back(delivery ? r.delivery_ci.low : y);
    it->hi.push_back(delivery ? r.delivery_ci.high : y);
  }
  for (std::size_t k = 0; k < panels.size(); ++k) {
    std::string names;
    for (const std::string& n : sources[k]) names += (names.empty() ? "" : " + ") + n;
    panels[k].title += " (" + names + ")";
    for (Series& ser : panels[k].series) {  // points in increasing size, whatever file they came from
      std::vector<std::size_t> order(ser.x.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ser.x[a] < ser.x[b]; });
      Series sorted{ser.scheme, {}, {}, {}, {}};
      for (std::size_t i : order) {
        sorted.x.push_back(ser.x[i]);
        sorted.y.push_back(ser.y[i]);
        sorted.lo.push_back(ser.lo[i]);
        sorted.hi.push_back(ser.hi[i]);
      }
      ser = std::move(sorted);
    }
  }
  return panels;
}

void draw_chart(cairo_t* cr, const std::vector<Panel>& panels, bool delivery, int pw, int ph, int cols) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const Panel& p = panels[k];
    const double ox = static_cast<double>(static_cast<int>(k) % cols * pw), oy = static_cast<double>(static_cast<int>(k) / cols * ph);
    const double l = ox + 60, r = ox + pw - 20, t = oy + 40, b = oy + ph - 50;
    double x0 = 1e300, x1 = -1e300, y0 = 1.0, y1 = 1.0;
    for (const auto& s : p.series)
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        x0 = std::min(x0, s.x[i]);
        x1 = std::max(x1, s.x[i]);
        if (!delivery) y1 = std::max(y1, s.hi[i]);
        if (delivery) y0 = std::min(y0, std::max(0.0, s.lo[i]));
      }
    if (x0 > x1) {
      x0 = 0;
      x1 = 1;
    }
    // Delivery: from a multiple of 5% below the lowest interval bound (at most 90%) to 100%, so that
    // differences of a few per cent between schemes stay visible.
    if (delivery) y0 = std::clamp(std::floor((y0 - 0.01) * 20) / 20, 0.0, 0.9);
    const bool logx = x0 > 0 && x1 / x0 >= 10;
    auto fx = [&](double x) {
      if (x1 == x0) return (l + r) / 2;
      const double u = logx ? (std::log(x) - std::log(x0)) / (std::log(x1) - std::log(x0)) : (x - x0) / (x1 - x0);
      return l + 0.05 * (r - l) + 0.9 * (r - l) * u;
    };
    if (!delivery) y1 = y1 + 0.05 * (y1 - y0 + 0.1);
    auto fy = [&](double y) { return b - (b - t) * (y - y0) / (y1 - y0); };
    // Axes and grid.
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_set_line_width(cr, 1);
    for (int i = 0; i <= 4; ++i) {
      const double y = y0 + (y1 - y0) * i / 4.0;
      cairo_move_to(cr, l, fy(y));
      cairo_line_to(cr, r, fy(y));
    }
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, l, t, r - l, b - t);
    cairo_stroke(cr);
    cairo_set_font_size(cr, 11);
    char buf[64];
    for (int i = 0; i <= 4; ++i) {
      const double y = y0 + (y1 - y0) * i / 4.0;
      std::snprintf(buf, sizeof buf, delivery ? (y1 - y0 < 0.4 ? "%.1f%%" : "%.0f%%") : "%.2f", delivery ? 100 * y : y);
      cairo_move_to(cr, l - 45, fy(y) + 4);
      cairo_show_text(cr, buf);
    }
    std::vector<double> xs;
    for (const auto& s : p.series) xs.insert(xs.end(), s.x.begin(), s.x.end());
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    for (double x : xs) {
      std::snprintf(buf, sizeof buf, "%g", x);
      cairo_move_to(cr, fx(x) - 10, b + 15);
      cairo_show_text(cr, buf);
    }
    cairo_move_to(cr, (l + r) / 2 - 40, b + 32);
    cairo_show_text(cr, logx ? "nodes (log scale)" : "nodes");
    cairo_set_font_size(cr, 12);
    cairo_move_to(cr, l, t - 22);
    cairo_show_text(cr, p.title.substr(0, 80).c_str());
    cairo_move_to(cr, l, t - 8);
    cairo_show_text(cr, delivery ? "delivery rate (bars: 95% CI)" : "mean hop stretch");
    // Series.
    for (std::size_t si = 0; si < p.series.size(); ++si) {
      const Series& s = p.series[si];
      const auto* c = palette[colour_of(s.scheme)];
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      cairo_set_line_width(cr, 2);
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (i == 0) cairo_move_to(cr, fx(s.x[i]), fy(s.y[i]));
        else cairo_line_to(cr, fx(s.x[i]), fy(s.y[i]));
      }
      cairo_stroke(cr);
      cairo_set_line_width(cr, 1.2);
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        const double dx = 3.0 * (static_cast<double>(si) - 1.5);  // spread the bars of the schemes
        if (delivery && std::isfinite(s.lo[i]) && std::isfinite(s.hi[i])) {
          cairo_move_to(cr, fx(s.x[i]) + dx, fy(s.lo[i]));
          cairo_line_to(cr, fx(s.x[i]) + dx, fy(s.hi[i]));
          cairo_stroke(cr);
        }
        cairo_arc(cr, fx(s.x[i]), fy(s.y[i]), 3, 0, 2 * std::numbers::pi);
        cairo_fill(cr);
      }
      cairo_move_to(cr, r - 110, t + 16 + 15 * static_cast<double>(si));
      cairo_line_to(cr, r - 90, t + 16 + 15 * static_cast<double>(si));
      cairo_stroke(cr);
      cairo_move_to(cr, r - 85, t + 20 + 15 * static_cast<double>(si));
      cairo_show_text(cr, s.scheme.c_str());
    }
  }
}

}  // namespace

std::vector<std::string> render_comparison_charts(const std::vector<scenarios::ComparisonRow>& rows,
                                                  const std::string& stem) {
  std::vector<std::string> out;
  for (const bool delivery : {true, false}) {
    const auto panels = panels_of(rows, delivery);
    if (panels.empty()) continue;
    const int cols = static_cast<int>(std::min<std::size_t>(3, panels.size()));
    const int rows_n = static_cast<int>((panels.size() + 2) / 3);
    const int pw = 460, ph = 320;
    auto paths = render_svg_png(stem + (delivery ? "-delivery" : "-stretch"), cols * pw, rows_n * ph,
                                   [&](cairo_t* cr) { draw_chart(cr, panels, delivery, pw, ph, cols); });
    out.insert(out.end(), paths.begin(), paths.end());
  }
  return out;
}

}  // namespace laguerre::tools
