// Pictures of scenario runs (laguerre run): network, packing, power diagram, routes.
#include "RunPictures.hpp"

#include "Render.hpp"


#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "laguerre/core/power/LocalPowerDiagram.hpp"

namespace laguerre::tools {

namespace {

struct Frame {
  double cx = 0, cy = 0, half = 1.05;  // the square [cx ± half] × [cy ± half], y up
};

Frame frame_of(const core::CircleEmbedding& pts) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& c : pts) {
    x0 = std::min(x0, c.x - c.r);
    x1 = std::max(x1, c.x + c.r);
    y0 = std::min(y0, c.y - c.r);
    y1 = std::max(y1, c.y + c.r);
  }
  if (pts.empty() || !(x1 > x0) || !(y1 >= y0)) return {};
  Frame f;
  f.cx = (x0 + x1) / 2;
  f.cy = (y0 + y1) / 2;
  f.half = 0.53 * std::max({x1 - x0, y1 - y0, 1e-9});
  return f;
}

// Sets up panel (col, row) of `size` pixels showing `f`; returns one pixel in frame units.
double enter_panel(cairo_t* cr, int col, int row, int size, int top, const Frame& f) {
  cairo_save(cr);
  cairo_translate(cr, col * size, top + row * size);
  cairo_rectangle(cr, 0, 0, size, size);
  cairo_clip(cr);
  cairo_translate(cr, size / 2.0, size / 2.0);
  cairo_scale(cr, size / (2 * f.half), -size / (2 * f.half));
  cairo_translate(cr, -f.cx, -f.cy);
  return 2 * f.half / size;
}

void caption(cairo_t* cr, int col, int row, int size, int top, const std::string& text) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);  // keep the caption readable over the drawing
  cairo_rectangle(cr, col * size + 4, top + row * size + 4, ext.x_advance + 8, 19);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_move_to(cr, col * size + 8, top + row * size + 18);
  cairo_show_text(cr, text.c_str());
}

void draw_edges(cairo_t* cr, const core::PlanarGraph& g, const core::CircleEmbedding& at, double px, double width) {
  cairo_set_line_width(cr, width * px);
  for (core::Dart d = 0; d < g.num_darts(); ++d) {
    const auto u = g.tail(d), w = g.head(d);
    if (u > w) continue;
    cairo_move_to(cr, at[u].x, at[u].y);
    cairo_line_to(cr, at[w].x, at[w].y);
  }
  cairo_stroke(cr);
}

void unit_circle(cairo_t* cr, double px) {
  cairo_new_path(cr);
  cairo_arc(cr, 0, 0, 1, 0, 2 * std::numbers::pi);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.2 * px);
  cairo_stroke(cr);
}

void draw_path(cairo_t* cr, const std::vector<core::Vertex>& path, const core::CircleEmbedding& at, double px,
               double width) {
  if (path.size() < 2) return;
  cairo_set_line_width(cr, width * px);
  cairo_move_to(cr, at[path[0]].x, at[path[0]].y);
  for (std::size_t j = 1; j < path.size(); ++j) cairo_line_to(cr, at[path[j]].x, at[path[j]].y);
  cairo_stroke(cr);
}

}  // namespace

std::vector<std::string> render_run_picture(const scenarios::RunArtifacts& run, const std::string& title,
                                            const std::string& stem, int panel) {
  const core::PlanarGraph& g = run.topology.graph;
  const core::CircleEmbedding& phi = run.circles;
  const std::size_t n = g.num_vertices();
  core::CircleEmbedding net;  // where the network is drawn
  if (!run.topology.positions.empty())
    for (const auto& p : run.topology.positions) net.push_back({p.x, p.y, 0.0});
  else
    for (const auto& c : phi) net.push_back({c.x, c.y, 0.0});
  const Frame nf = frame_of(net), disc{};
  const double dot = std::clamp(3.0 - std::log10(static_cast<double>(std::max<std::size_t>(n, 1))), 0.6, 3.0);
  const int top = 30;
  std::vector<std::vector<core::Point2>> cells(n);
  for (core::Vertex v = 0; v < n; ++v) cells[v] = core::local_cell_polygon(g, phi, v, 2.0);
  std::size_t holds = 0;
  for (auto c : run.local) holds += c == core::LocalCondition::holds;

  auto paint = [&](cairo_t* cr) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    // 1. The network.
    double px = enter_panel(cr, 0, 0, panel, top, nf);
    cairo_set_source_rgba(cr, 0.25, 0.25, 0.25, 0.8);
    draw_edges(cr, g, net, px, 0.7);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.4);
    for (const auto& p : net) {
      cairo_new_path(cr);
      cairo_arc(cr, p.x, p.y, dot * px, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
    cairo_restore(cr);
    // 2. The packing, coloured by LPD/GLPD status.
    px = enter_panel(cr, 1, 0, panel, top, disc);
    for (core::Vertex v = 0; v < n; ++v)
      draw_status_circle(cr, phi[v].x, phi[v].y, std::max(phi[v].r, 0.0),
                         v < run.local.size() && run.local[v] == core::LocalCondition::holds, 0.6, 0.7, 0.5 * px);
    unit_circle(cr, px);
    cairo_restore(cr);
    // 3. The power diagram: local power cells, clipped to the unit disc.
    px = enter_panel(cr, 0, 1, panel, top, disc);
    cairo_new_path(cr);
    cairo_arc(cr, 0, 0, 1, 0, 2 * std::numbers::pi);
    cairo_clip(cr);
    for (core::Vertex v = 0; v < n; ++v) {
      const auto& cell = cells[v];
      if (cell.size() < 3) continue;
      cairo_new_path(cr);
      cairo_move_to(cr, cell[0].x, cell[0].y);
      for (std::size_t i = 1; i < cell.size(); ++i) cairo_line_to(cr, cell[i].x, cell[i].y);
      cairo_close_path(cr);
      const double hue = static_cast<double>((g.id(v) * 2654435761u) % 1000) / 1000.0;
      cairo_set_source_rgba(cr, 0.6 + 0.3 * hue, 0.75, 0.95 - 0.3 * hue, 0.5);
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, 0.1, 0.2, 0.6);
      cairo_set_line_width(cr, 0.6 * px);
      cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
    for (const auto& c : phi) {
      cairo_new_path(cr);
      cairo_arc(cr, c.x, c.y, std::min(dot * px, std::max(c.r, 0.3 * px)), 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
    cairo_reset_clip(cr);
    unit_circle(cr, px);
    cairo_restore(cr);
    // 4. Sample routes on the network: greedy power (red) vs GFG (blue, dashed).
    px = enter_panel(cr, 1, 1, panel, top, nf);
    cairo_set_source_rgba(cr, 0.6, 0.6, 0.6, 0.6);
    draw_edges(cr, g, net, px, 0.5);
    for (std::size_t i = 0; i < run.greedy_routes.size(); ++i) {
      cairo_set_source_rgba(cr, 0.85, 0.1, 0.1, 0.85);
      draw_path(cr, run.greedy_routes[i], net, px, 3.0);
      if (i < run.gfg_routes.size()) {
        const double dash[] = {6 * px, 4 * px};
        cairo_set_dash(cr, dash, 2, 0);
        cairo_set_source_rgba(cr, 0.1, 0.3, 0.9, 0.85);
        draw_path(cr, run.gfg_routes[i], net, px, 1.8);
        cairo_set_dash(cr, nullptr, 0, 0);
      }
      const auto& path = run.greedy_routes[i];
      if (!path.empty()) {
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_new_path(cr);
        cairo_arc(cr, net[path.front()].x, net[path.front()].y, 4 * px, 0, 2 * std::numbers::pi);
        cairo_fill(cr);
      }
    }
    cairo_restore(cr);
    // Captions and title.
    caption(cr, 0, 0, panel, top, run.topology.positions.empty() ? "network (drawn at the packing's centres)"
                                                                 : "network (physical positions)");
    caption(cr, 1, 0, panel, top,
            "packing: LPD/GLPD holds at " + std::to_string(holds) + "/" + std::to_string(n) + " (green), fails (red)");
    caption(cr, 0, 1, panel, top, "power diagram: local power cells, clipped to the unit disc");
    caption(cr, 1, 1, panel, top, "sample routes: greedy power (red) vs GFG (blue, dashed)");
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, 16);
    cairo_move_to(cr, 8, 21);
    cairo_show_text(cr, title.c_str());
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 1);
    cairo_move_to(cr, panel, top);
    cairo_line_to(cr, panel, top + 2 * panel);
    cairo_move_to(cr, 0, top + panel);
    cairo_line_to(cr, 2 * panel, top + panel);
    cairo_stroke(cr);
  };
  return render_svg_png(stem, 2 * panel, top + 2 * panel, paint);
}

}  // namespace laguerre::tools
