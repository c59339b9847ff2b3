// `laguerre diagram`: the diagrams of thesis Part I from a sites file, as JSON (the combinatorial
// structure) and as SVG/PNG pictures (cells filled, bisectors drawn, sites marked).
//
// Sites files are plain text, one site per line, blank lines and `#` comments ignored, numbers in the
// admissible range of core/diagrams/SitesFile.hpp; the columns of every kind are in the table `kinds`
// below, which also drives the dispatch, the help text and the error messages.
// `--recognize CELLS-FILE` solves the inverse problem instead (cells format in Recognition.hpp).
#include <cairo.h>

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>
#include <tuple>

#include "Commands.hpp"
#include "Common.hpp"
#include "Render.hpp"
#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"
#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"
#include "laguerre/core/diagrams/MinimizationDiagram.hpp"
#include "laguerre/core/diagrams/MobiusDiagram.hpp"
#include "laguerre/core/diagrams/PowerDiagram.hpp"
#include "laguerre/core/diagrams/Recognition.hpp"
#include "laguerre/core/diagrams/SitesFile.hpp"
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

Box parse_box(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, ',');) {
    double x = 0;
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
    if (ec != std::errc() || ptr != part.data() + part.size())
      throw core::InputError("--box", 0, "expected xmin,ymin,xmax,ymax, found '" + text + "'.");
    v.push_back(x);
  }
  if (v.size() != 4) throw core::InputError("--box", 0, "expected 4 numbers xmin,ymin,xmax,ymax, found '" + text + "'.");
  const Box b{v[0], v[1], v[2], v[3]};
  if (!b.valid()) throw core::InputError("--box", 0, "expected xmin < xmax and ymin < ymax, found '" + text + "'.");
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
  auto trace = [&](const std::vector<Point2>& line) {  // the polyline as a new sub-path
    auto [x0, y0] = X(line[0]);
    cairo_move_to(cr, x0, y0);
    for (const Point2& p : line) {
      auto [x, y] = X(p);
      cairo_line_to(cr, x, y);
    }
  };
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
      trace(loop);
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
    trace(c);
    cairo_stroke(cr);
  }
  cairo_set_source_rgba(cr, 0.2, 0.2, 0.6, 0.8);
  cairo_set_line_width(cr, 1.0);
  for (const auto& [c, radius] : s.circles) {
    // Cairo flattens an arc into segments by its pixel size: a circle far larger than the picture would
    // take forever, and its visible part is (under a pixel from) straight or outside anyway.
    if (!(radius * sx <= 1e5)) continue;
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

/// What a kind's build function reads and fills: the JSON, the picture, the sites' centres.
struct Build {
  const DiagramArgs& args;
  Scene& scene;
  json& out;
  std::vector<Point2>& points;
  std::unique_ptr<core::MinimizationDiagram>& raster;

  /// The window: --box, or the bounding box of `points` grown by 15%.
  void choose_box() {
    scene.view = args.box.empty() ? core::bounding_box(points, 0.15) : parse_box(args.box);
    out["box"] = {scene.view.xmin, scene.view.ymin, scene.view.xmax, scene.view.ymax};
  }
  /// The background raster of a diagram without cell polygons, half the picture's resolution.
  template <class Distance>
  void rasterize(std::size_t sites, Distance distance) {
    raster = std::make_unique<core::MinimizationDiagram>(
        scene.view, args.size / 2, std::max(1, static_cast<int>(args.size / 2 * scene.view.height() / scene.view.width())),
        sites, distance);
  }
};

/// A diagram kind: its --kind name, the columns of its sites file, what the columns mean (help text),
/// its name in messages, and the function that reads the file and builds the diagram.
struct DiagramKind {
  std::string_view name;
  std::string_view columns;
  std::string_view meaning;
  std::string_view title;
  void (*build)(const DiagramKind& kind, Build& b);

  std::vector<core::SiteRow> rows(const Build& b) const {
    return core::read_site_rows(b.args.sites, columns, title);
  }
};

/// `"valid"` (and `"invalid_reason"`: the first broken invariant, which is_valid(true) writes to
/// std::cerr) of a diagram.
template <class Diagram>
void validity_json(const Diagram& d, json& out) {
  std::ostringstream reason;
  std::streambuf* const saved = std::cerr.rdbuf(reason.rdbuf());
  bool ok = false;
  try {
    ok = d.is_valid(true);
  } catch (...) {
    std::cerr.rdbuf(saved);
    throw;
  }
  std::cerr.rdbuf(saved);
  out["valid"] = ok;
  if (!ok) {
    std::string text = reason.str();
    while (!text.empty() && text.back() == '\n') text.pop_back();
    out["invalid_reason"] = text;
  }
}

void build_affine(const DiagramKind& kind, Build& b) {
  const bool power = kind.name == "power";
  json sites = json::array();
  std::vector<core::WeightedPoint> wp;
  for (const core::SiteRow& row : kind.rows(b)) {
    const auto& r = row.values;
    b.points.push_back({r[0], r[1]});
    wp.push_back({r[0], r[1], power ? r[2] : 0.0});
    sites.push_back(power ? json{{"x", r[0]}, {"y", r[1]}, {"w", r[2]}} : json{{"x", r[0]}, {"y", r[1]}});
    if (power && r[2] > 0) b.scene.circles.push_back({{r[0], r[1]}, std::sqrt(r[2])});
  }
  b.choose_box();
  auto finish = [&](const auto& d) {
    b.out.update(affine_json(d, sites));
    validity_json(d, b.out);
    affine_scene(d, b.scene);
  };
  if (power)
    finish(core::PowerDiagram(wp, b.scene.view));
  else
    finish(core::VoronoiDiagram(b.points, b.scene.view));
}

void build_mobius(const DiagramKind& kind, Build& b) {
  const bool mw = kind.name == "mw";
  std::vector<core::MobiusSite> ms;
  json sites = json::array();
  for (const core::SiteRow& row : kind.rows(b)) {
    const auto& r = row.values;
    if (mw && !(r[2] > 0))
      throw core::InputError(b.args.sites, row.line,
                             "found the weight w = " + json(r[2]).dump() + "; expected w > 0 (" + std::string(kind.title) + " sites).");
    b.points.push_back({r[0], r[1]});
    ms.push_back(mw ? core::multiplicative_site(r[0], r[1], r[2]) : core::MobiusSite{r[0], r[1], r[2], r[3]});
    core::require_liftable(ms.back(), b.args.sites, row.line, "the site");
    json site{{"x", r[0]}, {"y", r[1]}, {"lambda", ms.back().lambda}, {"mu", ms.back().mu}};
    if (mw) site["w"] = r[2];
    sites.push_back(site);
  }
  b.choose_box();
  Scene& scene = b.scene;
  json& out = b.out;
  const core::MobiusDiagram d(ms, scene.view);
  out["sites"] = sites;
  out["frame"] = {d.frame().xmin, d.frame().ymin, d.frame().xmax, d.frame().ymax};
  out["hidden"] = d.hidden_sites();
  out["empty_cells"] = d.empty_sites();
  json vs = json::array();
  for (const auto& v : d.vertices()) vs.push_back({{"point", pt(v.point)}, {"sites", v.sites}});
  out["vertices"] = vs;
  json es = json::array();
  const double err = 0.3 * scene.view.width() / b.args.size;  // under a pixel
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
  validity_json(d, out);
  for (const auto& v : d.vertices())
    if (scene.view.contains(v.point)) scene.vertices.push_back(v.point);
  scene.hidden.assign(ms.size(), false);
  for (SiteIndex i : d.empty_sites()) scene.hidden[i] = true;
}

/// The JSON and picture parts the Apollonius and anisotropic diagrams share.
template <class Diagram>
void curved_json(const Diagram& d, Build& b) {
  json dual = json::array();
  for (const auto& [p, q] : d.dual_edges) dual.push_back({p, q});
  b.out["hidden"] = d.hidden;
  b.out["dual_edges"] = dual;
  json vs = json::array();
  for (const auto& v : d.vertices) vs.push_back({{"point", pt(v.position)}, {"sites", v.sites}});
  b.out["vertices"] = vs;
  b.scene.hidden.assign(d.sites.size(), false);
  for (SiteIndex i : d.hidden) b.scene.hidden[i] = true;
}

void build_apollonius(const DiagramKind&, Build& b) {
  const std::vector<core::ApolloniusSite> as = core::read_apollonius_sites(b.args.sites);
  json sites = json::array();
  for (const auto& s : as) {
    b.points.push_back({s.x, s.y}), sites.push_back({{"x", s.x}, {"y", s.y}, {"w", s.w}});
    if (s.w > 0) b.scene.circles.push_back({{s.x, s.y}, s.w});
  }
  b.choose_box();
  const core::ApolloniusDiagram d = core::apollonius_diagram_cgal(as);
  b.out["sites"] = sites;
  b.out["method"] = d.method;
  curved_json(d, b);
  for (const auto& v : d.vertices)
    if (b.scene.view.contains(v.position)) b.scene.vertices.push_back(v.position);
  b.out["edges"] = sampled_edges_json(core::apollonius_edges(d, b.scene.view), b.scene);
  b.rasterize(as.size(), [&](SiteIndex i, Point2 x) { return core::apollonius_distance(x, as[i]); });
}

void build_anisotropic(const DiagramKind&, Build& b) {
  const std::vector<core::AnisotropicSite> an = core::read_anisotropic_sites(b.args.sites);
  json sites = json::array();
  for (const auto& s : an)
    b.points.push_back({s.x, s.y}), sites.push_back({{"x", s.x}, {"y", s.y}, {"M", {s.a, s.b, s.c}}});
  b.choose_box();
  const core::AnisotropicDiagram d = core::anisotropic_diagram(an);
  b.out["sites"] = sites;
  b.out["dual_triangles"] = d.dual_triangles;
  curved_json(d, b);
  const auto restricted = core::restrict_anisotropic(d, b.scene.view.corners());
  for (const auto& v : restricted.vertices) b.scene.vertices.push_back(v.position);
  b.out["edges"] = sampled_edges_json(restricted.edges, b.scene);
  b.rasterize(an.size(), [&](SiteIndex i, Point2 x) { return core::anisotropic_distance(x, an[i]); });
}

/// The diagram kinds, in the order of the help text and the messages.
constexpr std::array<DiagramKind, 6> kinds{{
    {"voronoi", "x y", "points", "Voronoi diagram", build_affine},
    {"power", "x y w", "weighted points, |x-p|^2 - w", "power diagram", build_affine},
    {"mobius", "x y lambda mu", "lambda|x-p|^2 - mu", "Möbius diagram", build_mobius},
    {"mw", "x y w", "multiplicatively weighted, |x-p|/w, w > 0", "multiplicatively weighted Voronoi diagram",
     build_mobius},
    {"anisotropic", core::anisotropic_columns, "(x-p)^T M (x-p), M = [[a, b], [b, c]] positive definite",
     "anisotropic diagram", build_anisotropic},
    {"apollonius", core::apollonius_columns, "additively weighted, |x-p| - w", "Apollonius diagram", build_apollonius},
}};

/// "voronoi, power, …, anisotropic or apollonius" with `separator` between the names (", " or "|").
std::string kind_names(std::string_view separator, std::string_view last) {
  std::string text;
  for (std::size_t i = 0; i < kinds.size(); ++i)
    text += std::string(i == 0 ? "" : i + 1 == kinds.size() ? last : separator) + std::string(kinds[i].name);
  return text;
}

const DiagramKind& find_kind(const std::string& name) {
  for (const DiagramKind& k : kinds)
    if (k.name == name) return k;
  throw core::InputError("--kind", 0, "expected " + kind_names(", ", " or ") + ", found '" + name + "'.");
}

/// The inverse problem (thesis Thm 2.2.2): a cells file in, the decision and the recovered sites out.
/// Returns the exit status (0: a power diagram, 3: not) and the summary line.
std::pair<int, std::string> run_recognize(const DiagramArgs& a, Build& b) {
  const core::CellComplex cx = core::read_cell_complex(a.sites);
  core::RecognitionResult res;
  try {
    res = core::recognize_power_diagram(cx, core::RecognitionOptions{a.tolerance});
  } catch (const core::CellComplexError& e) {
    throw core::InputError(a.sites, 0, e.what());
  }
  Scene& scene = b.scene;
  json& out = b.out;
  out = json{{"kind", "recognize"}, {"cells_file", a.sites}, {"is_power_diagram", res.is_power_diagram},
             {"message", res.message}, {"tolerance", a.tolerance}};
  json sites = json::array();
  for (const auto& w : res.sites) sites.push_back({{"x", w.x}, {"y", w.y}, {"w", w.w}});
  out["sites"] = sites;
  json broken = json::array();
  for (const auto& br : res.broken)
    broken.push_back({{"kind", br.kind}, {"cell", br.cell}, {"vertex", br.vertex}, {"cycle", br.cycle}, {"defect", br.defect}});
  out["broken"] = broken;
  b.points = cx.vertices;
  b.choose_box();
  const double far = 4 * (scene.view.width() + scene.view.height());
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    const auto& cell = cx.cells[c];
    std::vector<Point2> loop;
    auto ray_end = [&](std::size_t ray) {
      const auto& r = cx.rays[ray];
      const Point2 v = cx.vertices[r.vertex];
      const double n = std::hypot(r.direction.x, r.direction.y);
      loop.push_back({v.x + far * r.direction.x / n, v.y + far * r.direction.y / n});
    };
    if (cell.ray_in) ray_end(*cell.ray_in);
    for (std::size_t v : cell.vertices) loop.push_back(cx.vertices[v]);
    if (cell.ray_out) ray_end(*cell.ray_out);
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
  return {res.is_power_diagram ? 0 : 3, res.message};
}

int run_diagram(const DiagramArgs& a) {
  const std::string& k = a.kind;
  Scene scene;
  json out{{"kind", k}, {"sites_file", a.sites}};
  std::vector<Point2> points;
  std::unique_ptr<core::MinimizationDiagram> raster;
  Build b{a, scene, out, points, raster};
  std::string summary;
  int status = 0;

  if (a.recognize) {
    std::tie(status, summary) = run_recognize(a, b);
  } else {
    if (k.empty()) throw core::InputError("diagram: expected --kind " + kind_names("|", "|") + ", or --recognize.");
    const DiagramKind& kind = find_kind(k);
    try {
      kind.build(kind, b);
    } catch (const core::InputError& e) {
      if (!e.source().empty()) throw;
      throw core::InputError(a.sites, 0, std::string(kind.title) + ": " + e.message());
    }
    scene.raster = raster.get();
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
  std::string help =
      "Compute a diagram of thesis Part I from a sites file: JSON of the combinatorial structure and SVG/PNG pictures.\n"
      "Sites files, one site per line (# comments):";
  std::vector<std::string> names;
  for (const DiagramKind& k : kinds) {
    help += std::string(&k == &kinds.front() ? " " : "; ") + std::string(k.name) + " `" + std::string(k.columns) + "` (" +
            std::string(k.meaning) + ")";
    names.emplace_back(k.name);
  }
  CLI::App* cmd = app.add_subcommand("diagram", help + ".");
  auto* kind = cmd->add_option("--kind", args->kind, kind_names(", ", " or "))->check(CLI::IsMember(names));
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
