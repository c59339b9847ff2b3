// `laguerre diagram`: the diagrams of thesis Part I from a sites file, as JSON (the combinatorial
// structure) and as SVG/PNG pictures (cells filled, bisectors drawn, sites marked).
//
// Sites files are plain text, one site per line, blank lines and `#` comments ignored:
//   voronoi      x y              (points)
//   power        x y w            (weighted points: pow = |x − p|² − w, w = r²)
//   mobius       x y lambda mu    (δ = λ|x − p|² − μ)
//   mw           x y w            (multiplicatively weighted: |x − p| / w, w > 0)
//   apollonius   x y w            (additively weighted: |x − p| − w; see ApolloniusDiagram.hpp)
//   anisotropic  x y a b c        (M = [[a, b], [b, c]] positive definite; see AnisotropicDiagram.hpp)
// `--recognize CELLS-FILE` solves the inverse problem instead (cells format in Recognition.hpp).
#include <cairo.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "Commands.hpp"
#include "Common.hpp"
#include "Render.hpp"
#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"
#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"
#include "laguerre/core/diagrams/MinimizationDiagram.hpp"
#include "laguerre/core/diagrams/MobiusDiagram.hpp"
#include "laguerre/core/diagrams/PowerDiagram.hpp"
#include "laguerre/core/diagrams/Recognition.hpp"
#include "laguerre/core/diagrams/VoronoiDiagram.hpp"

namespace laguerre::tools {

namespace {
using core::Box;
using core::Point2;
using core::SiteIndex;
using json = nlohmann::json;

struct DiagramArgs {
  std::string kind;
  std::string sites;
  std::string out;
  std::string box;
  int size = 800;
  bool force = false;
  bool recognize = false;
  double tolerance = 1e-9;
};

// ---------------------------------------------------------------------------------------------------
// Input

/// Reads `count` numbers per line; errors name file:line, what was found and what was expected.
std::vector<std::vector<double>> read_rows(const std::string& path, std::size_t count, const std::string& format,
                                           const std::string& kind) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("Cannot open sites file " + path + ".");
  std::vector<std::vector<double>> rows;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::vector<std::string> words;
    for (std::string w; fields >> w;) words.push_back(w);
    if (words.empty()) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (words.size() != count)
      throw std::invalid_argument(where + "expected " + std::to_string(count) + " numbers `" + format + "` for --kind " +
                                  kind + ", found " + std::to_string(words.size()) + " field(s): '" + line + "'.");
    std::vector<double> row;
    for (const std::string& w : words) {
      double v = 0;
      const auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
      if (ec != std::errc() || ptr != w.data() + w.size() || !std::isfinite(v))
        throw std::invalid_argument(where + "expected a finite number in `" + format + "`, found '" + w + "'.");
      row.push_back(v);
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw std::invalid_argument(path + ": no sites (expected lines `" + format + "`).");
  return rows;
}

Box parse_box(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, ',');) {
    double x = 0;
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
    if (ec != std::errc() || ptr != part.data() + part.size())
      throw std::invalid_argument("--box: expected xmin,ymin,xmax,ymax, found '" + text + "'.");
    v.push_back(x);
  }
  if (v.size() != 4) throw std::invalid_argument("--box: expected 4 numbers xmin,ymin,xmax,ymax, found '" + text + "'.");
  const Box b{v[0], v[1], v[2], v[3]};
  if (!b.valid()) throw std::invalid_argument("--box: expected xmin < xmax and ymin < ymax, found '" + text + "'.");
  return b;
}

// ---------------------------------------------------------------------------------------------------
// Pictures

/// What a diagram picture shows, in world coordinates; the view is the box.
struct Scene {
  Box view;
  struct Fill {
    SiteIndex site;
    std::vector<std::vector<Point2>> loops;  // filled with the even-odd rule
  };
  std::vector<Fill> fills;
  const core::MinimizationDiagram* raster = nullptr;  // background for diagrams without cells
  std::vector<std::vector<Point2>> curves;            // edges
  std::vector<Point2> sites;
  std::vector<bool> hidden;
  std::vector<Point2> vertices;
  std::vector<std::pair<Point2, double>> circles;  // site circles (centre, radius), outlined
  std::string title;
};

void draw(cairo_t* cr, const Scene& s, int w, int h) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double sx = w / s.view.width(), sy = h / s.view.height();
  auto X = [&](Point2 p) { return std::pair{(p.x - s.view.xmin) * sx, (s.view.ymax - p.y) * sy}; };
  if (s.raster) {
    const auto& r = *s.raster;
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, r.width(), r.height());
    cairo_surface_flush(img);
    unsigned char* data = cairo_image_surface_get_data(img);
    const int stride = cairo_image_surface_get_stride(img);
    const auto rgb = r.render_rgb(false);
    for (int row = 0; row < r.height(); ++row)
      for (int col = 0; col < r.width(); ++col) {
        const std::size_t k = 3 * (static_cast<std::size_t>(row) * static_cast<std::size_t>(r.width()) + static_cast<std::size_t>(col));
        auto* px = reinterpret_cast<std::uint32_t*>(data + row * stride) + col;
        *px = (std::uint32_t{rgb[k]} << 16) | (std::uint32_t{rgb[k + 1]} << 8) | rgb[k + 2];
      }
    cairo_surface_mark_dirty(img);
    cairo_save(cr);
    cairo_scale(cr, static_cast<double>(w) / r.width(), static_cast<double>(h) / r.height());
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
  }
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
  for (const auto& f : s.fills) {
    cairo_new_path(cr);
    for (const auto& loop : f.loops) {
      if (loop.empty()) continue;
      auto [x0, y0] = X(loop[0]);
      cairo_move_to(cr, x0, y0);
      for (const Point2& p : loop) {
        auto [x, y] = X(p);
        cairo_line_to(cr, x, y);
      }
      cairo_close_path(cr);
    }
    const core::Rgb c = core::site_colour(f.site);
    cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
    cairo_fill(cr);
  }
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1.2);
  for (const auto& c : s.curves) {
    if (c.size() < 2) continue;
    cairo_new_path(cr);
    auto [x0, y0] = X(c[0]);
    cairo_move_to(cr, x0, y0);
    for (const Point2& p : c) {
      auto [x, y] = X(p);
      cairo_line_to(cr, x, y);
    }
    cairo_stroke(cr);
  }
  cairo_set_source_rgba(cr, 0.2, 0.2, 0.6, 0.8);
  cairo_set_line_width(cr, 1.0);
  for (const auto& [c, radius] : s.circles) {
    auto [x, y] = X(c);
    cairo_new_path(cr);
    cairo_arc(cr, x, y, radius * sx, 0, 2 * M_PI);
    cairo_stroke(cr);
  }
  const double r = std::clamp(400.0 / std::sqrt(static_cast<double>(s.sites.size()) + 1), 1.0, 3.5);
  for (const Point2& v : s.vertices) {
    auto [x, y] = X(v);
    cairo_new_path(cr);
    cairo_arc(cr, x, y, r * 0.6, 0, 2 * M_PI);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_fill(cr);
  }
  for (std::size_t i = 0; i < s.sites.size(); ++i) {
    auto [x, y] = X(s.sites[i]);
    cairo_new_path(cr);
    cairo_arc(cr, x, y, r, 0, 2 * M_PI);
    if (i < s.hidden.size() && s.hidden[i]) {
      cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
      cairo_set_line_width(cr, 1);
      cairo_stroke(cr);
    } else {
      cairo_set_source_rgb(cr, 0.8, 0.05, 0.05);
      cairo_fill(cr);
    }
  }
  if (!s.title.empty()) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 13);
    cairo_move_to(cr, 8, 18);
    cairo_show_text(cr, s.title.c_str());
  }
}

/// Writes STEM.svg and STEM.png of the scene, `size` pixels wide (height by the view's aspect).
void render(const Scene& scene, const std::string& stem, int size) {
  const double aspect = scene.view.height() / scene.view.width();
  const int w = size, h = std::clamp(static_cast<int>(std::lround(size * aspect)), 50, 4 * size);
  render_svg_png(stem, w, h, [&](cairo_t* cr) { draw(cr, scene, w, h); });
}

// ---------------------------------------------------------------------------------------------------
// JSON helpers

json pt(Point2 p) { return json::array({p.x, p.y}); }

json piece_json(const core::CurvePiece& c) {
  json j{{"type", c.is_arc ? "arc" : "segment"}, {"from", pt(c.from)}, {"to", pt(c.to)}};
  if (c.is_arc) j["centre"] = pt(c.centre), j["radius"] = c.radius, j["start_angle"] = c.start, j["sweep"] = c.sweep;
  return j;
}

json site_or_null(SiteIndex s) { return s == core::no_site ? json(nullptr) : json(s); }

json index_or_null(std::size_t k) { return k == core::MobiusEdge::npos ? json(nullptr) : json(k); }

json loop_json(const core::BoundaryLoop& l) {
  json pieces = json::array();
  for (const auto& p : l.pieces) {
    json j = piece_json(p.curve);
    j["across"] = site_or_null(p.across);
    j["edge"] = index_or_null(p.edge);
    pieces.push_back(j);
  }
  return pieces;
}

template <class Diagram>
json affine_json(const Diagram& d, json sites) {
  json out{{"sites", std::move(sites)}, {"hidden", d.hidden_sites()}};
  json dual = json::array();
  for (const auto& [a, b] : d.dual_edges()) dual.push_back({a, b});
  out["dual_edges"] = dual;
  json vs = json::array();
  for (const auto& v : d.vertices()) vs.push_back({{"point", pt(v.point)}, {"sites", v.sites}});
  out["vertices"] = vs;
  json es = json::array();
  for (const auto& e : d.edges())
    es.push_back({{"sites", {e.a, e.b}}, {"type", "segment"}, {"from", pt(e.p)}, {"to", pt(e.q)}});
  out["edges"] = es;
  json cells = json::array();
  for (SiteIndex i = 0; i < d.sites().size(); ++i) {
    json comps = json::array();
    if (!d.cell(i).empty()) {
      json outer = json::array();
      for (const Point2& p : d.cell(i)) outer.push_back(pt(p));
      comps.push_back({{"outer", outer}, {"holes", json::array()}});
    }
    cells.push_back({{"site", i}, {"components", comps}});
  }
  out["cells"] = cells;
  const auto report = d.is_valid();
  out["valid"] = report.ok;
  if (!report.ok) out["invalid_reason"] = report.message;
  return out;
}

template <class Diagram>
void affine_scene(const Diagram& d, Scene& scene) {
  for (SiteIndex i = 0; i < d.sites().size(); ++i)
    if (!d.cell(i).empty()) scene.fills.push_back({i, {d.cell(i)}});
  for (const auto& e : d.edges()) scene.curves.push_back({e.p, e.q});
  for (const auto& v : d.vertices())
    if (scene.view.contains(v.point)) scene.vertices.push_back(v.point);
  scene.hidden.assign(d.sites().size(), false);
  for (SiteIndex i : d.hidden_sites()) scene.hidden[i] = true;
}

json sampled_edges_json(const std::vector<core::SampledEdge>& edges, Scene& scene) {
  json es = json::array();
  for (const auto& e : edges) {
    json polys = json::array();
    for (const auto& poly : e.polylines) {
      json p = json::array();
      for (const Point2& q : poly) p.push_back(pt(q));
      polys.push_back(p);
      scene.curves.push_back(poly);
    }
    es.push_back({{"sites", {e.a, e.b}}, {"type", "polylines"}, {"polylines", polys}});
  }
  return es;
}

// ---------------------------------------------------------------------------------------------------

int run_diagram(const DiagramArgs& a) {
  const std::string& k = a.kind;
  Scene scene;
  json out{{"kind", k}, {"sites_file", a.sites}};
  std::vector<Point2> points;
  std::unique_ptr<core::MinimizationDiagram> raster;
  auto choose_box = [&] {
    scene.view = a.box.empty() ? core::bounding_box(points, 0.15) : parse_box(a.box);
    out["box"] = {scene.view.xmin, scene.view.ymin, scene.view.xmax, scene.view.ymax};
  };
  std::string summary;
  int status = 0;

  if (a.recognize) {
    // The inverse problem (thesis Thm 2.2.2): a cells file in, the decision and the recovered sites out.
    core::CellComplex cx;
    try {
      cx = core::read_cell_complex(a.sites);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
    core::RecognitionResult res;
    try {
      res = core::recognize_power_diagram(cx, core::RecognitionOptions{a.tolerance});
    } catch (const core::CellComplexError& e) {
      throw std::invalid_argument(a.sites + ": " + e.what());
    }
    out = json{{"kind", "recognize"}, {"cells_file", a.sites}, {"is_power_diagram", res.is_power_diagram},
               {"message", res.message}, {"tolerance", a.tolerance}};
    json sites = json::array();
    for (const auto& w : res.sites) sites.push_back({{"x", w.x}, {"y", w.y}, {"w", w.w}});
    out["sites"] = sites;
    json broken = json::array();
    for (const auto& b : res.broken)
      broken.push_back({{"kind", b.kind}, {"cell", b.cell}, {"vertex", b.vertex}, {"cycle", b.cycle}, {"defect", b.defect}});
    out["broken"] = broken;
    points = cx.vertices;
    choose_box();
    const double far = 4 * (scene.view.width() + scene.view.height());
    for (std::size_t c = 0; c < cx.cells.size(); ++c) {
      const auto& cell = cx.cells[c];
      std::vector<Point2> loop;
      if (cell.ray_in) {
        const auto& r = cx.rays[*cell.ray_in];
        const Point2 v = cx.vertices[r.vertex];
        const double n = std::hypot(r.direction.x, r.direction.y);
        loop.push_back({v.x + far * r.direction.x / n, v.y + far * r.direction.y / n});
      }
      for (std::size_t v : cell.vertices) loop.push_back(cx.vertices[v]);
      if (cell.ray_out) {
        const auto& r = cx.rays[*cell.ray_out];
        const Point2 v = cx.vertices[r.vertex];
        const double n = std::hypot(r.direction.x, r.direction.y);
        loop.push_back({v.x + far * r.direction.x / n, v.y + far * r.direction.y / n});
      }
      scene.fills.push_back({c, {loop}});
      for (std::size_t i = 0; i + 1 < loop.size(); ++i) scene.curves.push_back({loop[i], loop[i + 1]});
      if (!cell.ray_in && loop.size() > 1) scene.curves.push_back({loop.back(), loop.front()});
    }
    scene.vertices = cx.vertices;
    for (const auto& w : res.sites) {
      scene.sites.push_back({w.x, w.y});
      if (w.w > 0) scene.circles.push_back({{w.x, w.y}, std::sqrt(w.w)});
    }
    scene.title = std::string(res.is_power_diagram ? "recognized as a power diagram: " : "not a power diagram: ") +
                  file_stem(a.sites);
    summary = res.message;
    status = res.is_power_diagram ? 0 : 3;
  } else if (k.empty()) {
    throw std::invalid_argument("diagram: expected --kind voronoi|power|mobius|mw|anisotropic|apollonius, or --recognize.");
  } else if (k == "voronoi" || k == "power") {
    const bool power = k == "power";
    const auto rows = read_rows(a.sites, power ? 3 : 2, power ? "x y w" : "x y", k);
    json sites = json::array();
    std::vector<core::WeightedPoint> wp;
    for (const auto& r : rows) {
      points.push_back({r[0], r[1]});
      wp.push_back({r[0], r[1], power ? r[2] : 0.0});
      sites.push_back(power ? json{{"x", r[0]}, {"y", r[1]}, {"w", r[2]}} : json{{"x", r[0]}, {"y", r[1]}});
      if (power && r[2] > 0) scene.circles.push_back({{r[0], r[1]}, std::sqrt(r[2])});
    }
    choose_box();
    if (power) {
      const core::PowerDiagram d(wp, scene.view);
      out.update(affine_json(d, sites));
      affine_scene(d, scene);
    } else {
      const core::VoronoiDiagram d(points, scene.view);
      out.update(affine_json(d, sites));
      affine_scene(d, scene);
    }
  } else if (k == "mobius" || k == "mw") {
    const bool mw = k == "mw";
    const auto rows = read_rows(a.sites, mw ? 3 : 4, mw ? "x y w" : "x y lambda mu", k);
    std::vector<core::MobiusSite> ms;
    json sites = json::array();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& r = rows[i];
      if (mw && !(r[2] > 0))
        throw std::invalid_argument(a.sites + ": site " + std::to_string(i + 1) + ": expected a weight w > 0 for --kind mw, found " +
                                    std::to_string(r[2]) + ".");
      points.push_back({r[0], r[1]});
      ms.push_back(mw ? core::multiplicative_site(r[0], r[1], r[2]) : core::MobiusSite{r[0], r[1], r[2], r[3]});
      json s{{"x", r[0]}, {"y", r[1]}, {"lambda", ms.back().lambda}, {"mu", ms.back().mu}};
      if (mw) s["w"] = r[2];
      sites.push_back(s);
    }
    choose_box();
    const core::MobiusDiagram d(ms, scene.view);
    out["sites"] = sites;
    out["frame"] = {d.frame().xmin, d.frame().ymin, d.frame().xmax, d.frame().ymax};
    out["hidden"] = d.hidden_sites();
    out["empty_cells"] = d.empty_sites();
    json vs = json::array();
    for (const auto& v : d.vertices()) vs.push_back({{"point", pt(v.point)}, {"sites", v.sites}});
    out["vertices"] = vs;
    json es = json::array();
    const double err = 0.3 * scene.view.width() / a.size;  // under a pixel
    for (const auto& e : d.edges()) {
      json j = piece_json(e.curve);
      j["sites"] = {e.a, e.b};
      j["left"] = e.left;
      j["from_vertex"] = index_or_null(e.from);
      j["to_vertex"] = index_or_null(e.to);
      es.push_back(j);
      scene.curves.push_back(e.curve.sample(0.02, err));
    }
    out["edges"] = es;
    json cells = json::array();
    for (SiteIndex i = 0; i < ms.size(); ++i) {
      json comps = json::array();
      for (const auto& c : d.cell(i)) {
        json holes = json::array();
        Scene::Fill fill{i, {c.outer.polyline(0.02, err)}};
        for (const auto& h : c.holes) holes.push_back(loop_json(h)), fill.loops.push_back(h.polyline(0.02, err));
        comps.push_back({{"outer", loop_json(c.outer)}, {"holes", holes}, {"area", c.area()}});
        scene.fills.push_back(std::move(fill));
      }
      cells.push_back({{"site", i}, {"components", comps}});
    }
    out["cells"] = cells;
    const auto report = d.is_valid();
    out["valid"] = report.ok;
    if (!report.ok) out["invalid_reason"] = report.message;
    for (const auto& v : d.vertices())
      if (scene.view.contains(v.point)) scene.vertices.push_back(v.point);
    scene.hidden.assign(ms.size(), false);
    for (SiteIndex i : d.empty_sites()) scene.hidden[i] = true;
  } else if (k == "apollonius") {
    std::vector<core::ApolloniusSite> as;
    try {
      as = core::read_apollonius_sites(a.sites);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
    json sites = json::array();
    for (const auto& s : as) {
      points.push_back({s.x, s.y}), sites.push_back({{"x", s.x}, {"y", s.y}, {"w", s.w}});
      if (s.w > 0) scene.circles.push_back({{s.x, s.y}, s.w});
    }
    choose_box();
    const core::ApolloniusDiagram d = core::apollonius_diagram_cgal(as);
    out["sites"] = sites;
    out["method"] = d.method;
    out["hidden"] = d.hidden;
    json dual = json::array();
    for (const auto& [p, q] : d.dual_edges) dual.push_back({p, q});
    out["dual_edges"] = dual;
    json vs = json::array();
    for (const auto& v : d.vertices) {
      vs.push_back({{"point", pt(v.position)}, {"sites", v.sites}});
      if (scene.view.contains(v.position)) scene.vertices.push_back(v.position);
    }
    out["vertices"] = vs;
    out["edges"] = sampled_edges_json(core::apollonius_edges(d, scene.view), scene);
    raster = std::make_unique<core::MinimizationDiagram>(scene.view, a.size / 2, std::max(1, static_cast<int>(a.size / 2 * scene.view.height() / scene.view.width())),
                                                         as.size(), [&](SiteIndex i, Point2 x) { return core::apollonius_distance(x, as[i]); });
    scene.hidden.assign(as.size(), false);
    for (SiteIndex i : d.hidden) scene.hidden[i] = true;
  } else if (k == "anisotropic") {
    std::vector<core::AnisotropicSite> an;
    try {
      an = core::read_anisotropic_sites(a.sites);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
    json sites = json::array();
    for (const auto& s : an)
      points.push_back({s.x, s.y}), sites.push_back({{"x", s.x}, {"y", s.y}, {"M", {s.a, s.b, s.c}}});
    choose_box();
    const core::AnisotropicDiagram d = core::anisotropic_diagram(an);
    out["sites"] = sites;
    out["hidden"] = d.hidden;
    json dual = json::array();
    for (const auto& [p, q] : d.dual_edges) dual.push_back({p, q});
    out["dual_edges"] = dual;
    out["dual_triangles"] = d.dual_triangles;
    json vs = json::array();
    for (const auto& v : d.vertices) vs.push_back({{"point", pt(v.position)}, {"sites", v.sites}});
    out["vertices"] = vs;
    const auto restricted = core::restrict_anisotropic(d, scene.view.corners());
    for (const auto& v : restricted.vertices) scene.vertices.push_back(v.position);
    out["edges"] = sampled_edges_json(restricted.edges, scene);
    raster = std::make_unique<core::MinimizationDiagram>(scene.view, a.size / 2, std::max(1, static_cast<int>(a.size / 2 * scene.view.height() / scene.view.width())),
                                                         an.size(), [&](SiteIndex i, Point2 x) { return core::anisotropic_distance(x, an[i]); });
    scene.hidden.assign(an.size(), false);
    for (SiteIndex i : d.hidden) scene.hidden[i] = true;
  } else {
    throw std::invalid_argument("--kind: expected voronoi, power, mobius, mw, anisotropic or apollonius, found '" + k + "'.");
  }
  scene.raster = raster.get();
  if (!a.recognize) {
    scene.sites = points;
    scene.title = k + " diagram of " + std::to_string(points.size()) + " sites (" + file_stem(a.sites) + ")";
    summary = std::to_string(points.size()) + " sites, " + std::to_string(out["vertices"].size()) + " vertices, " +
              std::to_string(out["edges"].size()) + " edges, " + std::to_string(out["hidden"].size()) + " hidden";
  }

  if (a.out.empty() || a.out == "-") {
    std::cout << out.dump(1) << '\n';
    std::cerr << (a.recognize ? "recognize" : k + " diagram") << ": " << summary << '\n';
    return status;
  }
  std::filesystem::path stem(a.out);
  if (stem.extension() == ".json" || stem.extension() == ".svg" || stem.extension() == ".png") stem.replace_extension();
  const std::string js = stem.string() + ".json", svg = stem.string() + ".svg", png = stem.string() + ".png";
  for (const auto& p : {js, svg, png}) check_writable(p, a.force);
  if (stem.has_parent_path()) std::filesystem::create_directories(stem.parent_path());
  {
    std::ofstream f(js);
    f << out.dump(1) << '\n';
    if (!f) throw std::runtime_error("Cannot write " + js + ".");
  }
  render(scene, stem.string(), a.size);
  std::cerr << "wrote " << js << ", " << svg << ", " << png << ": " << summary << '\n';
  return status;
}
}  // namespace

Action add_diagram_command(CLI::App& app) {
  auto args = std::make_shared<DiagramArgs>();
  CLI::App* cmd = app.add_subcommand(
      "diagram",
      "Compute a diagram of thesis Part I from a sites file: JSON of the combinatorial structure and SVG/PNG pictures.\n"
      "Sites files, one site per line (# comments): voronoi `x y`; power `x y w` (|x-p|^2 - w); mobius `x y lambda mu`\n"
      "(lambda|x-p|^2 - mu); mw `x y w` (|x-p|/w, w > 0); apollonius `x y w` (|x-p| - w); anisotropic `x y a b c`.");
  auto* kind = cmd->add_option("--kind", args->kind, "voronoi, power, mobius, mw, anisotropic or apollonius")
                   ->check(CLI::IsMember({"voronoi", "power", "mobius", "mw", "anisotropic", "apollonius"}));
  auto* recognize = cmd->add_flag("--recognize", args->recognize,
                                  "Inverse problem: FILE is a cells file (see Recognition.hpp); decide whether it is a power\n"
                                  "diagram and recover the sites (exit status 0: it is, 3: it is not)");
  kind->excludes(recognize);
  cmd->add_option("--tolerance", args->tolerance, "--recognize: relative tolerance (0: exact decision)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("sites", args->sites, "Sites file (or cells file with --recognize)")->required();
  cmd->add_option("-o,--out", args->out, "Output stem: writes STEM.json, STEM.svg, STEM.png (default: JSON on standard output)");
  cmd->add_option("--box", args->box, "Window xmin,ymin,xmax,ymax (default: the sites' bounding box grown by 15%)");
  cmd->add_option("--size", args->size, "Picture width in pixels")->check(CLI::Range(100, 8000))->capture_default_str();
  cmd->add_flag("--force", args->force, "Overwrite existing output files");
  return [args] { return run_diagram(*args); };
}

}  // namespace laguerre::tools
