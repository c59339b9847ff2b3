// `laguerre mesh`: anisotropic meshing of a polygonal domain under a metric field, with a quality
// report, Medit/VTK/JSON outputs and a picture.
#include <cairo.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "Common.hpp"
#include "Render.hpp"
#include "laguerre/core/meshing/Domain.hpp"
#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/MeshQuality.hpp"
#include "laguerre/core/meshing/StarMesher.hpp"
#include "laguerre/core/meshing/StarMesher3.hpp"
#include "laguerre/core/meshing/VoronoiMesher.hpp"
#include "laguerre/core/meshing/Vtk.hpp"

namespace laguerre::tools {

namespace {

struct MeshArgs {
  std::string domain;
  std::string metric = "shock";
  std::string algorithm = "stars";
  std::string out;
  core::StarMeshOptions options;
  double shape_bound = 1.0;  ///< B of the voronoi algorithm
  bool corner_shells = true;  ///< voronoi: concentric shells at acute input corners
  bool rebuild_diagram = false;  ///< voronoi: the whole diagram every round (the former path)
  CLI::Option* max_vertices_option = nullptr;
  CLI::Option* radius_edge_option = nullptr;
  double sliver_bound = core::StarMesh3Options{}.sliver_bound;  ///< 3D: σ₀
  bool force = false;
  bool json = false;
  bool picture = true;
};

nlohmann::json summary_json(const core::QualitySummary& s) {
  return {{"count", s.count}, {"min", s.min},           {"mean", s.mean},           {"max", s.max},
          {"p5", s.p5},       {"p95", s.p95},           {"bin_start", s.bin_start}, {"bin_width", s.bin_width},
          {"histogram", s.histogram}};
}

/// The domain file `name`, or the unit square for "square".
core::Domain domain_named(const std::string& name) {
  return name == "square" ? core::Domain::unit_square() : core::read_domain(name);
}

/// The quality report in JSON (the "quality" object of `mesh` and `mesh-quality`).
nlohmann::json quality_json(const core::MeshQuality& q) {
  return {{"radius_edge", summary_json(q.radius_edge)},
          {"smallest_angle_degrees", summary_json(q.smallest_angle)},
          {"distortion", summary_json(q.distortion)},
          {"edge_length", summary_json(q.edge_length)}};
}

/// The 3D quality report in JSON (dihedral angles, sliverity and slivers counted with their bound).
nlohmann::json quality3_json(const core::MeshQuality& q) {
  return {{"radius_edge", summary_json(q.radius_edge)},
          {"smallest_dihedral_degrees", summary_json(q.smallest_angle)},
          {"sliverity", summary_json(q.sliverity)},
          {"slivers", q.slivers},
          {"sliver_bound", q.sliver_bound},
          {"distortion", summary_json(q.distortion)},
          {"edge_length", summary_json(q.edge_length)}};
}

/// The quality table of `mesh` and `mesh-quality`: triangles, or tetrahedra (`solid`: dihedral angles
/// and sliverity).
void print_quality(const core::MeshQuality& q, bool solid = false) {
  const int w = solid ? 18 : 16;
  std::printf("quality      %-*s %8s %8s %8s %8s %8s\n", w, "(in the metric)", "min", "p5", "mean", "p95", "max");
  auto row = [w](const char* name, const core::QualitySummary& x) {
    std::printf("             %-*s %8.3f %8.3f %8.3f %8.3f %8.3f\n", w, name, x.min, x.p5, x.mean, x.p95, x.max);
  };
  row(solid ? "smallest dihedral" : "smallest angle", q.smallest_angle);
  row("radius-edge", q.radius_edge);
  if (solid) row("sliverity", q.sliverity);
  row("edge length", q.edge_length);
  row("distortion", q.distortion);
  if (solid) std::printf("slivers      %zu (sliverity below %g in the metric of a vertex)\n", q.slivers, q.sliver_bound);
}

/// The mesh, triangles coloured by their smallest angle in the metric (red < 20°, green ≥ 40°).
void draw_mesh(cairo_t* cr, const core::TriangleMesh& mesh, const core::MeshQuality& q, const core::Domain& domain,
               int size, const std::string& title) {
  const auto box = domain.bounding_box();
  const double span = std::max(box[2] - box[0], box[3] - box[1]);
  const double margin = 0.03 * span;
  const double scale = size / (span + 2 * margin);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_save(cr);
  cairo_translate(cr, 0, size);
  cairo_scale(cr, scale, -scale);
  cairo_translate(cr, margin - box[0], margin - box[1]);
  const double px = 1 / scale;
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    cairo_move_to(cr, mesh.points[tri[0]][0], mesh.points[tri[0]][1]);
    cairo_line_to(cr, mesh.points[tri[1]][0], mesh.points[tri[1]][1]);
    cairo_line_to(cr, mesh.points[tri[2]][0], mesh.points[tri[2]][1]);
    cairo_close_path(cr);
    const double a = std::clamp((q.elements[t].smallest_angle - 20) / 20, 0.0, 1.0);
    cairo_set_source_rgb(cr, 0.95 - 0.4 * a, 0.55 + 0.35 * a, 0.5);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, std::min(0.6, 0.25 + 2e3 / static_cast<double>(mesh.triangles.size() + 1)) * px);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0.6);
  cairo_set_line_width(cr, 1.5 * px);
  for (const auto& c : domain.constraints()) {
    cairo_move_to(cr, c[0].x, c[0].y);
    cairo_line_to(cr, c[1].x, c[1].y);
  }
  cairo_stroke(cr);
  cairo_restore(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size / 60.0);
  cairo_move_to(cr, 10, size / 45.0);
  cairo_show_text(cr, title.c_str());
}

/// What either mesher returns, for the common report.
struct MeshOutcome {
  core::TriangleMesh mesh;
  std::vector<core::Metric> metrics;
  bool converged = false;
  std::string status;
  nlohmann::json rules;      ///< per-rule counts
  std::string rules_line;    ///< the same, one line for the table
  nlohmann::json options;    ///< the algorithm's parameters
};

MeshOutcome run_stars(const core::Domain& domain, const core::MetricField& field, const MeshArgs& a) {
  const core::StarMeshResult r = core::mesh_with_stars(domain, field, a.options);
  MeshOutcome o{r.mesh, r.metrics, r.converged, r.status, {}, {}, {}};
  o.rules = {{"encroachment", r.stats.encroachment}, {"distortion", r.stats.distortion},
             {"size", r.stats.size},                 {"shape", r.stats.shape},
             {"inconsistency", r.stats.inconsistency}, {"snapped", r.stats.snapped},
             {"corners", r.stats.corners},
             {"star_updates", r.stats.star_updates}, {"consistency_sweeps", r.stats.consistency_sweeps}};
  char line[256];
  std::snprintf(line, sizeof line, "encroachment %zu, distortion %zu, size %zu, shape %zu, inconsistency %zu (snapped %zu)",
                r.stats.encroachment, r.stats.distortion, r.stats.size, r.stats.shape, r.stats.inconsistency,
                r.stats.snapped);
  o.rules_line = line;
  if (a.options.no_lonely_corners) o.rules_line += ", lonely corners " + std::to_string(r.stats.corners);
  o.options = {{"size_bound", a.options.size_bound},
               {"radius_edge_bound", a.options.radius_edge_bound},
               {"distortion_bound", a.options.distortion_bound},
               {"picking_ratio", a.options.picking_ratio},
               {"max_vertices", a.options.max_vertices},
               {"seed", a.options.seed},
               {"no_lonely_corners", a.options.no_lonely_corners}};
  return o;
}

MeshOutcome run_voronoi(const core::Domain& domain, const core::MetricField& field, const MeshArgs& a, bool tty) {
  if (!(a.shape_bound >= 0.58 && a.shape_bound <= 100))
    throw core::InputError("--shape-bound must be between 0.58 and 100 (an equilateral triangle has a radius-edge "
                                "ratio of 1/sqrt(3) = 0.577, so a smaller bound cannot be met); got " +
                                std::to_string(a.shape_bound) + ".");
  core::VoronoiMeshOptions v;
  v.shape_bound = a.shape_bound;
  v.size_bound = a.options.size_bound;
  v.corner_shells = a.corner_shells;
  v.rebuild_diagram = a.rebuild_diagram;
  // The star mesher's default cap (10⁶) is far beyond what whole-diagram rounds reach in minutes.
  v.max_vertices = a.max_vertices_option && a.max_vertices_option->count() ? a.options.max_vertices : 20000;
  if (tty)
    v.on_round = [](const core::VoronoiRound& r) {
      std::cerr << "\rmeshing: round " << r.round << ", " << r.sites << " vertices" << std::flush;
    };
  const core::VoronoiMeshResult r = core::mesh_with_voronoi(domain, field, v);
  MeshOutcome o{r.mesh, r.metrics, r.converged(), r.message, {}, {}, {}};
  o.rules = {{"encroached", r.stats.encroached}, {"ellipse", r.stats.ellipse},     {"bad_shape", r.stats.bad_shape},
             {"duplicate", r.stats.duplicate},   {"overlap", r.stats.overlap},     {"size", r.stats.size},
             {"redirected", r.stats.redirected}, {"rounds", r.stats.rounds},
             {"diagram_seconds", r.stats.diagram_seconds}};
  char line[256];
  std::snprintf(line, sizeof line,
                "1 encroached %zu, 2 ellipse %zu, 3 bad shape %zu, 4 duplicate %zu, 5 overlap %zu, 6 size %zu "
                "(redirected to breakpoints %zu; %zu rounds)",
                r.stats.encroached, r.stats.ellipse, r.stats.bad_shape, r.stats.duplicate, r.stats.overlap,
                r.stats.size, r.stats.redirected, r.stats.rounds);
  o.rules_line = line;
  o.options = {{"shape_bound", v.shape_bound},     {"size_bound", v.size_bound},
               {"corner_shells", v.corner_shells}, {"max_vertices", v.max_vertices},
               {"rebuild_diagram", v.rebuild_diagram},
               {"status", core::to_string(r.status)}};
  double worst = 0;
  for (double b : r.shape) worst = std::max(worst, b);
  o.rules["worst_vertex_radius_edge"] = worst;
  std::snprintf(line, sizeof line, "; worst Voronoi vertex radius-edge %.3f (B = %g)", worst, v.shape_bound);
  o.rules_line += line;
  return o;
}

/// The intersection of a tetrahedron with the plane x_axis = c, as a polygon in the other two
/// coordinates (empty if it misses the plane).
std::vector<std::array<double, 2>> slice(const core::TetMesh& mesh, const std::array<std::size_t, 4>& t, int axis, double c) {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  std::vector<std::array<double, 2>> poly;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      const auto& p = mesh.points[t[i]];
      const auto& q = mesh.points[t[j]];
      const double a = p[axis] - c, b = q[axis] - c;
      if ((a < 0 && b > 0) || (a > 0 && b < 0)) {
        const double s = a / (a - b);
        poly.push_back({p[u] + s * (q[u] - p[u]), p[w] + s * (q[w] - p[w])});
      }
    }
  if (poly.size() < 3) return {};
  double cx = 0, cy = 0;
  for (const auto& p : poly) cx += p[0] / static_cast<double>(poly.size()), cy += p[1] / static_cast<double>(poly.size());
  std::sort(poly.begin(), poly.end(), [&](const auto& l, const auto& r) {
    return std::atan2(l[1] - cy, l[0] - cx) < std::atan2(r[1] - cy, r[0] - cx);
  });
  return poly;
}

/// Three axis-aligned slices (x, y, z through the box centre, nudged off the vertices' planes) of a
/// tetrahedral mesh side by side, the cut tetrahedra coloured by their smallest dihedral angle in the
/// metric (red < 10°, green ≥ 30°).
void draw_slices(cairo_t* cr, const core::TetMesh& mesh, const core::MeshQuality& q, const std::array<double, 6>& box,
                 int panel, const std::string& title) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const char* names[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const double span = std::max(box[u + 3] - box[u], box[w + 3] - box[w]);
    const double c = 0.5 * (box[axis] + box[axis + 3]) + 0.0137 * (box[axis + 3] - box[axis]);
    const double margin = 0.05 * span, scale = panel / (span + 2 * margin);
    cairo_save(cr);
    cairo_translate(cr, axis * panel, panel + 30);
    cairo_scale(cr, scale, -scale);
    cairo_translate(cr, margin - box[u], margin - box[w]);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
      const auto poly = slice(mesh, mesh.tetrahedra[t], axis, c);
      if (poly.empty()) continue;
      cairo_move_to(cr, poly[0][0], poly[0][1]);
      for (std::size_t k = 1; k < poly.size(); ++k) cairo_line_to(cr, poly[k][0], poly[k][1]);
      cairo_close_path(cr);
      const double g = std::clamp((q.elements[t].smallest_angle - 10) / 20, 0.0, 1.0);
      cairo_set_source_rgb(cr, 0.95 - 0.4 * g, 0.55 + 0.35 * g, 0.5);
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
      cairo_set_line_width(cr, 0.5 / scale);
      cairo_stroke(cr);
    }
    cairo_restore(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, 14);
    cairo_move_to(cr, axis * panel + 10, 48);
    const std::string label = std::string(names[axis]) + " = " + std::to_string(c).substr(0, 6) + " (" + names[u] + " right, " +
                              names[w] + " up)";
    cairo_show_text(cr, label.c_str());
  }
  cairo_set_font_size(cr, 15);
  cairo_move_to(cr, 10, 20);
  cairo_show_text(cr, title.c_str());
}

/// `laguerre mesh` on a 3D domain (an .off file or a 3D Medit surface): the star mesher of
/// core/meshing/StarMesher3.hpp, with the same outputs, report and exit statuses as in 2D.
int run_mesh3(MeshArgs& a) {
  if (a.algorithm != "stars")
    throw core::InputError("--algorithm", 0, "3D domains are meshed with 'stars' only; got '" + a.algorithm + "'");
  const core::PolyhedralDomain domain = core::read_polyhedral_domain(a.domain);
  const auto field = core::parse_metric_field3(a.metric);
  const std::string stem = a.out.empty() ? "out/mesh/" + file_stem(a.domain) : a.out;
  std::vector<std::string> outputs = {stem + ".mesh", stem + ".sol", stem + ".vtk", stem + ".json"};
  if (a.picture) outputs.insert(outputs.end(), {stem + ".svg", stem + ".png"});
  for (const auto& o : outputs) check_writable(o, a.force);
  if (const auto dir = std::filesystem::path(stem).parent_path(); !dir.empty()) std::filesystem::create_directories(dir);
  core::StarMesh3Options o;
  o.size_bound = a.options.size_bound;
  o.distortion_bound = a.options.distortion_bound;
  o.picking_ratio = a.options.picking_ratio;
  o.seed = a.options.seed;
  o.sliver_bound = a.sliver_bound;
  if (a.radius_edge_option && a.radius_edge_option->count()) o.radius_edge_bound = a.options.radius_edge_bound;
  if (a.max_vertices_option && a.max_vertices_option->count()) o.max_vertices = a.options.max_vertices;
  const bool tty = isatty(STDERR_FILENO);
  if (tty) o.progress = [](std::size_t n) { std::cerr << "\rmeshing: " << n << " vertices" << std::flush; };
  const auto start = std::chrono::steady_clock::now();
  const core::StarMesh3Result r = core::mesh_with_stars(domain, *field, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (tty) std::cerr << "\r\033[K";
  const std::string valid = core::check_tetrahedralization(r.mesh, domain);
  const core::MeshQuality q = core::measure_quality(r.mesh, r.metrics, o.sliver_bound);
  core::write_medit_mesh(stem + ".mesh", r.mesh);
  core::write_medit_sol(stem + ".sol", r.metrics);
  core::write_vtk(stem + ".vtk", r.mesh, r.metrics, &q);
  const auto& s = r.stats;
  nlohmann::json j = {
      {"domain", a.domain},
      {"dimension", 3},
      {"metric", field->describe()},
      {"algorithm", "stars"},
      {"status", r.status},
      {"converged", r.converged},
      {"valid_tetrahedralization", valid.empty()},
      {"validation", valid},
      {"vertices", r.mesh.points.size()},
      {"tetrahedra", r.mesh.tetrahedra.size()},
      {"boundary_triangles", r.mesh.triangles.size()},
      {"domain_volume", domain.volume()},
      {"seconds", seconds},
      {"options",
       {{"size_bound", o.size_bound}, {"radius_edge_bound", o.radius_edge_bound}, {"distortion_bound", o.distortion_bound},
        {"sliver_bound", o.sliver_bound}, {"picking_ratio", o.picking_ratio}, {"picking_tries", o.picking_tries},
        {"max_vertices", o.max_vertices}, {"seed", o.seed}}},
      {"rules",
       {{"edge_splits", s.edge_splits}, {"facet_splits", s.facet_splits}, {"distortion", s.distortion}, {"size", s.size},
        {"shape", s.shape}, {"sliver", s.sliver}, {"inconsistency", s.inconsistency}, {"snapped", s.snapped},
        {"rejected_picks", s.rejected_picks}, {"star_updates", s.star_updates}, {"consistency_sweeps", s.consistency_sweeps},
        {"last_sweep_inconsistent", s.last_sweep_inconsistent}}},
      {"quality", quality3_json(q)},
  };
  std::ofstream(stem + ".json") << j.dump(2) << '\n';
  if (a.picture)
    render_svg_png(stem, 1500, 540, [&](cairo_t* cr) {
      draw_slices(cr, r.mesh, q, domain.bounding_box(), 500,
                  field->describe() + ": " + std::to_string(r.mesh.points.size()) + " vertices, " +
                      std::to_string(r.mesh.tetrahedra.size()) + " tetrahedra, min dihedral " +
                      std::to_string(static_cast<int>(q.smallest_angle.min)) + " deg in the metric");
    });
  if (a.json) {
    std::cout << j.dump(2) << '\n';
  } else {
    std::printf("mesh         %s (3D), metric %s, algorithm stars\n", a.domain.c_str(), field->describe().c_str());
    std::printf("status       %s; %s\n", r.status.c_str(), valid.empty() ? "valid tetrahedralization of the domain" : valid.c_str());
    std::printf("size         %zu vertices, %zu tetrahedra, %zu boundary triangles in %.2f s\n", r.mesh.points.size(),
                r.mesh.tetrahedra.size(), r.mesh.triangles.size(), seconds);
    std::printf("rules        edges %zu, facets %zu, distortion %zu, size %zu, shape %zu, sliver %zu, inconsistency %zu "
                "(snapped %zu, picks rejected %zu; %zu sweeps, the last found %zu inconsistent)\n",
                s.edge_splits, s.facet_splits, s.distortion, s.size, s.shape, s.sliver, s.inconsistency, s.snapped,
                s.rejected_picks, s.consistency_sweeps, s.last_sweep_inconsistent);
    print_quality(q, true);
    std::printf("wrote        %s.{mesh,sol,vtk,json%s}\n", stem.c_str(), a.picture ? ",svg,png" : "");
  }
  return r.converged && valid.empty() ? 0 : 3;
}

int run_mesh(MeshArgs& a) {
  if (a.domain != "square" && core::is_3d_domain_file(a.domain)) return run_mesh3(a);
  const core::Domain domain = domain_named(a.domain);
  const auto field = core::parse_metric_field(a.metric);
  const std::string stem = a.out.empty() ? "out/mesh/" + (a.domain == "square" ? "square" : file_stem(a.domain)) : a.out;
  std::vector<std::string> outputs = {stem + ".mesh", stem + ".sol", stem + ".vtk", stem + ".json"};
  if (a.picture) outputs.insert(outputs.end(), {stem + ".svg", stem + ".png"});
  for (const auto& o : outputs) check_writable(o, a.force);
  if (const auto dir = std::filesystem::path(stem).parent_path(); !dir.empty()) std::filesystem::create_directories(dir);

  const bool tty = isatty(STDERR_FILENO);
  if (tty)
    a.options.progress = [](std::size_t n) { std::cerr << "\rmeshing: " << n << " vertices" << std::flush; };
  const auto start = std::chrono::steady_clock::now();
  const MeshOutcome r = a.algorithm == "voronoi" ? run_voronoi(domain, *field, a, tty) : run_stars(domain, *field, a);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (tty) std::cerr << "\r\033[K";
  const std::string valid = core::check_triangulation(r.mesh, domain);
  const core::MeshQuality q = core::measure_quality(r.mesh, r.metrics);

  core::write_medit_mesh(stem + ".mesh", r.mesh);
  core::write_medit_sol(stem + ".sol", r.metrics);
  core::write_vtk(stem + ".vtk", r.mesh, r.metrics, &q);
  nlohmann::json j = {
      {"domain", a.domain},
      {"metric", field->describe()},
      {"algorithm", a.algorithm},
      {"status", r.status},
      {"converged", r.converged},
      {"valid_triangulation", valid.empty()},
      {"validation", valid},
      {"vertices", r.mesh.points.size()},
      {"triangles", r.mesh.triangles.size()},
      {"seconds", seconds},
      {"vertices_per_second", static_cast<double>(r.mesh.points.size()) / seconds},
      {"options", r.options},
      {"rules", r.rules},
      {"quality", quality_json(q)},
  };
  std::ofstream(stem + ".json") << j.dump(2) << '\n';
  if (a.picture)
    render_svg_png(stem, 1000, 1000, [&](cairo_t* cr) {
      draw_mesh(cr, r.mesh, q, domain, 1000,
                field->describe() + ": " + std::to_string(r.mesh.points.size()) + " vertices, min angle " +
                    std::to_string(static_cast<int>(q.smallest_angle.min)) + "° in the metric");
    });

  if (a.json) {
    std::cout << j.dump(2) << '\n';
  } else {
    std::printf("mesh         %s, metric %s, algorithm %s\n", a.domain.c_str(), field->describe().c_str(),
                a.algorithm.c_str());
    std::printf("status       %s; %s\n", r.status.c_str(), valid.empty() ? "valid triangulation of the domain" : valid.c_str());
    std::printf("size         %zu vertices, %zu triangles in %.2f s (%.0f vertices/s)\n", r.mesh.points.size(),
                r.mesh.triangles.size(), seconds, static_cast<double>(r.mesh.points.size()) / seconds);
    std::printf("rules        %s\n", r.rules_line.c_str());
    print_quality(q);
    std::printf("wrote        %s.{mesh,sol,vtk,json%s}\n", stem.c_str(), a.picture ? ",svg,png" : "");
  }
  return r.converged && valid.empty() ? 0 : 3;
}

struct MeshQualityArgs {
  std::string mesh;
  std::string metric;
  std::string domain;
  double sliver_bound = core::kSliverBound;
  bool json = false;
};

/// `mesh-quality` of a tetrahedral mesh: the 3D field at its vertices, the 3D report, and with a
/// domain the check of `laguerre mesh`, the boundary being the facets in one tetrahedron (another
/// mesher's surface triangles need not be oriented outward).
int run_mesh_quality3(const MeshQualityArgs& a, core::TetMesh mesh) {
  const auto field = core::parse_metric_field3(a.metric);
  std::vector<core::Metric3> metrics;
  metrics.reserve(mesh.points.size());
  for (const auto& p : mesh.points) metrics.push_back(field->at(p[0], p[1], p[2]));
  const core::MeshQuality q = core::measure_quality(mesh, metrics, a.sliver_bound);
  const bool checked = !a.domain.empty();
  std::string valid;
  if (checked) {
    core::set_boundary_from_tetrahedra(mesh);
    valid = core::check_tetrahedralization(mesh, core::read_polyhedral_domain(a.domain));
  }
  if (a.json) {
    nlohmann::json j = {{"mesh", a.mesh},
                        {"dimension", 3},
                        {"metric", field->describe()},
                        {"vertices", mesh.points.size()},
                        {"tetrahedra", mesh.tetrahedra.size()},
                        {"quality", quality3_json(q)}};
    if (checked) j.update({{"domain", a.domain}, {"valid_tetrahedralization", valid.empty()}, {"validation", valid}});
    std::cout << j.dump(2) << '\n';
  } else {
    std::printf("mesh         %s (3D), metric %s\n", a.mesh.c_str(), field->describe().c_str());
    std::printf("size         %zu vertices, %zu tetrahedra\n", mesh.points.size(), mesh.tetrahedra.size());
    if (checked)
      std::printf("domain       %s: %s\n", a.domain.c_str(), valid.empty() ? "valid tetrahedralization of the domain" : valid.c_str());
    print_quality(q, true);
  }
  return valid.empty() ? 0 : 3;
}

/// `mesh-quality`: another mesher's output measured like `mesh` measures its own.
int run_mesh_quality(const MeshQualityArgs& a) {
  if (core::medit_dimension(a.mesh) == 3)
    if (core::TetMesh solid = core::read_medit_tet_mesh(a.mesh); !solid.tetrahedra.empty())
      return run_mesh_quality3(a, std::move(solid));
  const core::TriangleMesh mesh = core::read_medit_mesh(a.mesh);
  const auto field = core::parse_metric_field(a.metric);
  std::vector<core::Metric> metrics;
  metrics.reserve(mesh.points.size());
  for (const auto& p : mesh.points) metrics.push_back(field->at(p[0], p[1]));
  const core::MeshQuality q = core::measure_quality(mesh, metrics);
  const bool checked = !a.domain.empty();
  const std::string valid = checked ? core::check_triangulation(mesh, domain_named(a.domain)) : "";
  if (a.json) {
    nlohmann::json j = {{"mesh", a.mesh},
                        {"metric", field->describe()},
                        {"vertices", mesh.points.size()},
                        {"triangles", mesh.triangles.size()},
                        {"quality", quality_json(q)}};
    if (checked) j.update({{"domain", a.domain}, {"valid_triangulation", valid.empty()}, {"validation", valid}});
    std::cout << j.dump(2) << '\n';
  } else {
    std::printf("mesh         %s, metric %s\n", a.mesh.c_str(), field->describe().c_str());
    std::printf("size         %zu vertices, %zu triangles\n", mesh.points.size(), mesh.triangles.size());
    if (checked)
      std::printf("domain       %s: %s\n", a.domain.c_str(), valid.empty() ? "valid triangulation of the domain" : valid.c_str());
    print_quality(q);
  }
  return valid.empty() ? 0 : 3;
}

}  // namespace

Action add_mesh_quality_command(CLI::App& app) {
  auto args = std::make_shared<MeshQualityArgs>();
  CLI::App* cmd = app.add_subcommand("mesh-quality", "Quality of a triangle or tetrahedral mesh (e.g. another mesher's) in a metric field.");
  cmd->footer(
      "MESH is an ASCII Medit .mesh file (Dimension 2, or Dimension 3 with z = 0 as gmsh writes it).\n"
      "The metric field (the specifications of 'laguerre mesh --help') is evaluated at every vertex and the\n"
      "report is the one 'laguerre mesh' prints: per triangle the worst over its vertices' metrics of the\n"
      "smallest angle and radius-edge ratio, edge lengths in each endpoint's metric, distortion.\n"
      "With --domain, also checks that the mesh triangulates that domain.\n"
      "A Dimension 3 mesh with tetrahedra is measured in a 3D field (the fields of 'laguerre mesh DOMAIN.off'):\n"
      "smallest dihedral angle, radius-edge ratio, sliverity and slivers (below --sliver), edge lengths and\n"
      "distortion; --domain is then a closed surface (.off) and the check that of a tetrahedralization.\n"
      "Exit status: 0, 3 when --domain is given and the mesh is not a valid triangulation of it, 2 bad input.");
  cmd->add_option("mesh", args->mesh, "Medit .mesh file")->required();
  cmd->add_option("--metric", args->metric, "Metric field specification")->required();
  cmd->add_option("--domain", args->domain, "Domain file, or 'square': check the mesh triangulates it");
  cmd->add_option("--sliver", args->sliver_bound, "3D: the sliverity below which a tetrahedron is counted as a sliver")
      ->check(CLI::Range(0.0, 0.1))->capture_default_str();
  cmd->add_flag("--json", args->json, "Print the JSON report instead of the table");
  return [args] { return run_mesh_quality(*args); };
}

Action add_mesh_command(CLI::App& app) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd = app.add_subcommand("mesh", "Anisotropic mesh of a polygonal domain under a metric field (thesis Parts II-III).");
  cmd->footer(
      "DOMAIN is a domain file (outer polygon, holes, constraint segments: see core/meshing/Domain.hpp)\n"
      "or 'square' for the unit square. Metric fields (see core/meshing/MetricField.hpp):\n"
      "  uniform:H1:H2[:THETA]  shock[:HMIN:HMAX:WIDTH:X0]  thesis[:H:RATIO:WIDTH:Y0]\n"
      "  expr:a=..;b=..;c=..    sizes:h1=..;h2=..;theta=..  mesh:FILE.mesh[:FILE.sol]\n"
      "Writes OUT.mesh + OUT.sol (Medit: mmg, gmsh), OUT.vtk (ParaView), OUT.json and OUT.svg/.png.\n"
      "Algorithms: 'stars' refines locally uniform anisotropic stars (thesis Part III; options --size-bound,\n"
      "--radius-edge, --distortion, --picking, --seed); 'voronoi' refines the anisotropic Voronoi diagram\n"
      "(thesis Part II, rules 1-5 of section 2.7 and a size rule: options --shape-bound, --size-bound;\n"
      "--max-vertices defaults to 20000 there) until its dual triangles triangulate the domain with every\n"
      "Voronoi vertex of radius-edge ratio at most B.\n"
      "3D: a DOMAIN ending in .off, or a .mesh of Dimension 3 (a closed triangle surface; core/meshing/Domain3.hpp),\n"
      "is meshed with tetrahedra by 3D stars (core/meshing/StarMesher3.hpp), --metric then taking 3D fields:\n"
      "  uniform:H1:H2:H3  shock[:HMIN:HMAX:WIDTH:X0] (plane x = X0)  sphere[:HMIN:HMAX:WIDTH:R:CX:CY:CZ]\n"
      "  expr:xx=..;xy=..;xz=..;yy=..;yz=..;zz=..  mesh:FILE.mesh[:FILE.sol] (tetrahedral background)\n"
      "and the picture showing three axis-aligned slices coloured by the smallest dihedral angle.\n"
      "Exit status: 0 converged and valid, 3 stopped early or invalid, 2 bad input.");
  cmd->add_option("domain", args->domain, "Domain file, or 'square'")->required();
  cmd->add_option("--metric", args->metric, "Metric field specification")->capture_default_str();
  cmd->add_option("--algorithm", args->algorithm, "stars (Part III, locally uniform) or voronoi (Part II)")
      ->check(CLI::IsMember({"stars", "voronoi"}))->capture_default_str();
  cmd->add_option("--shape-bound", args->shape_bound,
                  "voronoi: largest radius-edge ratio B of a Voronoi vertex (1 = 30 degrees when isotropic)")
      ->capture_default_str();
  cmd->add_option("--size-bound", args->options.size_bound,
                  "Largest circumradius in the metric (voronoi: largest radius r(v) of a Voronoi vertex)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  args->radius_edge_option =
      cmd->add_option("--radius-edge", args->options.radius_edge_bound,
                      "Largest radius-edge ratio rho0 (1 = 30 degrees; 3D default 2, the regular tetrahedron has 0.61)")
          ->check(CLI::Range(0.58, 100.0))->capture_default_str();
  cmd->add_option("--sliver", args->sliver_bound,
                  "3D: smallest sliverity volume/shortest-edge^3 in the metric (sigma0; regular tetrahedron 0.118)")
      ->check(CLI::Range(0.0, 0.1))->capture_default_str();
  cmd->add_option("--distortion", args->options.distortion_bound, "Distortion bound gamma0")
      ->check(CLI::Range(1.0001, 100.0))->capture_default_str();
  cmd->add_option("--picking", args->options.picking_ratio, "Picking ratio delta")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  args->max_vertices_option =
      cmd->add_option("--max-vertices", args->options.max_vertices, "Stop beyond this many vertices (voronoi: 20000)")
          ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Seed of the picking")->capture_default_str();
  cmd->add_flag("--no-lonely-corners", args->options.no_lonely_corners,
                "Refine every boundary corner left with a single triangle (rule 6, core/meshing/StarMesher.hpp)");
  cmd->add_option("-o,--out", args->out, "Output path stem (default out/mesh/<domain>)");
  cmd->add_flag("!--no-corner-shells", args->corner_shells,
                "voronoi: split at breakpoints also at acute input corners (the thesis rule, which cascades there)");
  cmd->add_flag("--rebuild-diagram", args->rebuild_diagram,
                "voronoi: recompute the whole anisotropic diagram every round instead of updating it (same mesh, "
                "slower; for benchmarks and checks)");
  cmd->add_flag("--force", args->force, "Overwrite existing outputs");
  cmd->add_flag("--json", args->json, "Print the JSON report instead of the table");
  cmd->add_flag("!--no-picture", args->picture, "Skip the SVG/PNG picture");
  return [args] { return run_mesh(*args); };
}

}  // namespace laguerre::tools
