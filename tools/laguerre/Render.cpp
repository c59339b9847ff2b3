#include "Render.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace laguerre::tools {

namespace {
// Draws in the unit-disc frame [-1.05, 1.05]² with y up.
void draw(cairo_t* cr, const PackingPicture& p, int size) {
  const double margin = 1.05;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_save(cr);
  cairo_translate(cr, size / 2.0, size / 2.0);
  cairo_scale(cr, size / (2 * margin), -size / (2 * margin));
  const double px = 2 * margin / size;  // one pixel in disc units
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);

  const auto& c = *p.circles;
  // Circles, filled by status.
  for (std::size_t v = 0; v < c.size(); ++v)
    draw_status_circle(cr, c[v].x, c[v].y, c[v].r, v < p.ok.size() && p.ok[v], 0.55, 0.6, 0.8 * px);
  if (p.face_circles) {
    const double dash[] = {4 * px, 3 * px};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_source_rgb(cr, 0.45, 0.45, 0.8);
    cairo_set_line_width(cr, 0.8 * px);
    for (const auto& f : *p.face_circles) {
      cairo_new_path(cr);
      cairo_arc(cr, f.x, f.y, f.r, 0, 2 * std::numbers::pi);
      cairo_stroke(cr);
    }
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  // Local power cells.
  cairo_set_source_rgb(cr, 0.1, 0.2, 0.6);
  cairo_set_line_width(cr, 1.0 * px);
  for (const auto& cell : p.cells) {
    if (cell.size() < 2) continue;
    cairo_new_path(cr);
    cairo_move_to(cr, cell[0].x, cell[0].y);
    for (std::size_t i = 1; i < cell.size(); ++i) cairo_line_to(cr, cell[i].x, cell[i].y);
    cairo_close_path(cr);
    cairo_stroke(cr);
  }
  // Edges between centres.
  const auto& g = *p.graph;
  cairo_set_source_rgba(cr, 0.3, 0.3, 0.3, 0.7);
  cairo_set_line_width(cr, 0.6 * px);
  for (core::Dart d = 0; d < g.num_darts(); ++d) {
    const auto u = g.tail(d), w = g.head(d);
    if (u > w) continue;
    cairo_move_to(cr, c[u].x, c[u].y);
    cairo_line_to(cr, c[w].x, c[w].y);
  }
  cairo_stroke(cr);
  // Routes.
  const double palette[][3] = {{0.85, 0.1, 0.1}, {0.1, 0.3, 0.9}, {0.9, 0.55, 0.0}, {0.5, 0.1, 0.7}};
  for (std::size_t i = 0; i < p.routes.size(); ++i) {
    const auto& path = p.routes[i];
    if (path.size() < 2) continue;
    const auto* col = palette[i % 4];
    cairo_set_source_rgb(cr, col[0], col[1], col[2]);
    cairo_set_line_width(cr, 2.5 * px);
    cairo_move_to(cr, c[path[0]].x, c[path[0]].y);
    for (std::size_t j = 1; j < path.size(); ++j) cairo_line_to(cr, c[path[j]].x, c[path[j]].y);
    cairo_stroke(cr);
  }
  // Unit circle.
  cairo_new_path(cr);
  cairo_arc(cr, 0, 0, 1, 0, 2 * std::numbers::pi);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.5 * px);
  cairo_stroke(cr);
  cairo_restore(cr);
  if (!p.title.empty()) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size / 55.0);
    cairo_move_to(cr, 10, size / 40.0);
    cairo_show_text(cr, p.title.c_str());
  }
}

void check(cairo_status_t status, const std::string& path) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("Cannot write picture " + path + ": " + cairo_status_to_string(status) + ".");
}
}  // namespace

void draw_status_circle(cairo_t* cr, double x, double y, double r, bool ok, double alpha_ok, double alpha_bad,
                        double line_width) {
  cairo_new_path(cr);
  cairo_arc(cr, x, y, r, 0, 2 * std::numbers::pi);
  if (ok)
    cairo_set_source_rgba(cr, 0.55, 0.85, 0.55, alpha_ok);
  else
    cairo_set_source_rgba(cr, 0.95, 0.45, 0.4, alpha_bad);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_line_width(cr, line_width);
  cairo_stroke(cr);
}

std::vector<std::string> render_svg_png(const std::string& stem, int width, int height,
                                        const std::function<void(cairo_t*)>& draw_on) {
  const std::string svg = stem + ".svg", png = stem + ".png";
  {
    cairo_surface_t* s = cairo_svg_surface_create(svg.c_str(), width, height);
    cairo_t* cr = cairo_create(s);
    draw_on(cr);
    cairo_destroy(cr);
    cairo_surface_finish(s);
    const cairo_status_t st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    check(st, svg);
  }
  {
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
    cairo_t* cr = cairo_create(s);
    draw_on(cr);
    cairo_destroy(cr);
    const cairo_status_t st = cairo_surface_write_to_png(s, png.c_str());
    cairo_surface_destroy(s);
    check(st, png);
  }
  return {svg, png};
}

std::vector<std::string> render_packing(const PackingPicture& picture, const std::string& stem, int size) {
  return render_svg_png(stem, size, size, [&](cairo_t* cr) { draw(cr, picture, size); });
}

}  // namespace laguerre::tools
