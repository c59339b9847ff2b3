// The topology registry: generator names → planar graphs ready for packing.
#include "laguerre/scenarios/Topology.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "laguerre/core/graph/GraphError.hpp"
#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/meshing/Domain.hpp"
#include "laguerre/core/meshing/MetricField.hpp"
#include "laguerre/core/meshing/StarMesher.hpp"
#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/FieldGraph.hpp"
#include "laguerre/scenarios/generators/UniformThreeConnected.hpp"
#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

namespace laguerre::scenarios {

// ---------------------------------------------------------------------------------------------------
// TopologyParams

void TopologyParams::set(const std::string& name, ParamValue value) {
  for (auto& [k, v] : entries_)
    if (k == name) {
      v = std::move(value);
      return;
    }
  entries_.emplace_back(name, std::move(value));
}

const ParamValue* TopologyParams::find(std::string_view name) const {
  for (const auto& [k, v] : entries_)
    if (k == name) return &v;
  return nullptr;
}

bool TopologyParams::has(std::string_view name) const { return find(name) != nullptr; }

std::int64_t TopologyParams::integer(std::string_view name, std::int64_t fallback) const {
  const ParamValue* v = find(name);
  return v && std::holds_alternative<std::int64_t>(*v) ? std::get<std::int64_t>(*v) : fallback;
}

double TopologyParams::number(std::string_view name, double fallback) const {
  const ParamValue* v = find(name);
  if (v && std::holds_alternative<double>(*v)) return std::get<double>(*v);
  if (v && std::holds_alternative<std::int64_t>(*v)) return static_cast<double>(std::get<std::int64_t>(*v));
  return fallback;
}

bool TopologyParams::boolean(std::string_view name, bool fallback) const {
  const ParamValue* v = find(name);
  return v && std::holds_alternative<bool>(*v) ? std::get<bool>(*v) : fallback;
}

std::string TopologyParams::text(std::string_view name, const std::string& fallback) const {
  const ParamValue* v = find(name);
  return v && std::holds_alternative<std::string>(*v) ? std::get<std::string>(*v) : fallback;
}

Polygons TopologyParams::polygons(std::string_view name) const {
  const ParamValue* v = find(name);
  return v && std::holds_alternative<Polygons>(*v) ? std::get<Polygons>(*v) : Polygons{};
}

std::string TopologyParams::describe(std::string_view name) const {
  const ParamValue* v = find(name);
  return v ? scenarios::describe(*v) : std::string();
}

std::string describe(const ParamValue& value) {
  if (const auto* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&value)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", *d);
    return buf;
  }
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const auto* s = std::get_if<std::string>(&value)) return *s;
  const auto& p = std::get<Polygons>(value);
  return std::to_string(p.size()) + " polygon(s)";
}

// ---------------------------------------------------------------------------------------------------
// Registry

namespace {

ParamSpec size_param(double min) {
  ParamSpec p;
  p.name = "n";
  p.type = ParamType::integer;
  p.help = "number of vertices";
  p.min = min;
  p.max = 1e7;
  p.required = true;
  return p;
}

std::vector<std::string> supported_formats() {
  std::vector<std::string> out;
  for (const char* f : {"automatic", "edges", "coords", "planar_code", "graphml", "dot"}) {
    try {
      (void)core::parse_graph_format(f);
      out.emplace_back(f);
    } catch (const std::exception&) {
    }
  }
  return out;
}

[[maybe_unused]] GeneratorInfo unavailable(std::string name, std::string summary, bool positions, std::string owner) {
  GeneratorInfo g;
  g.name = std::move(name);
  g.summary = std::move(summary);
  g.positions = positions;
  g.available = false;
  g.unavailable_reason = "generator '" + g.name + "' is not available yet (" + owner + " is not wired into the registry)";
  return g;
}

std::vector<GeneratorInfo> make_registry() {
  std::vector<GeneratorInfo> r;
  {
    GeneratorInfo g;
    g.name = "delaunay";
    g.summary = "Delaunay triangulation of n points uniform in the unit disc (core::random_delaunay_triangulation)";
    g.params = {size_param(3)};
    g.positions = true;
    r.push_back(g);
  }
  {
    GeneratorInfo g;
    g.name = "three-connected";
    g.summary = "random 3-connected plane graph: a Delaunay triangulation thinned by edge deletions "
                "(core::random_three_connected)";
    ParamSpec del;
    del.name = "deletions_per_vertex";
    del.type = ParamType::number;
    del.help = "edge deletions attempted per vertex";
    del.min = 0;
    del.max = 3;
    del.default_text = "0.75";
    ParamSpec face;
    face.name = "max_face_size";
    face.type = ParamType::integer;
    face.help = "largest face a deletion may create";
    face.min = 4;
    face.max = 1000;
    face.default_text = "8";
    g.params = {size_param(4), del, face};
    g.positions = true;
    r.push_back(g);
  }
  {
    GeneratorInfo g;
    g.name = "file";
    g.summary = "a graph file (core::read_graphs): edge list, coords, planar_code, and the other formats GraphIO reads";
    ParamSpec path;
    path.name = "path";
    path.type = ParamType::file;
    path.help = "the file, relative to the scenario file's folder";
    path.required = true;
    ParamSpec format;
    format.name = "format";
    format.type = ParamType::choice;
    format.help = "its format";
    format.choices = supported_formats();
    format.default_text = "automatic";
    ParamSpec index;
    index.name = "index";
    index.type = ParamType::integer;
    index.help = "which graph of a multi-graph file, from 1; 0 = graph (repetition mod count) + 1";
    index.min = 0;
    index.max = 1e9;
    index.default_text = "1";
    g.params = {path, format, index};
    g.positions = false;  // only the coords format has positions; decided per file
    r.push_back(g);
  }
  {
    GeneratorInfo g;
    g.name = "uniform-triangulation";
    g.summary = "uniform random triangulation with n vertices (Poulalhon–Schaeffer); outer face: the link of a "
                "punctured vertex, or the root face";
    ParamSpec n = size_param(3);
    n.max = 1e8;
    ParamSpec outer;
    outer.name = "outer";
    outer.type = ParamType::choice;
    outer.help = "puncture: sample n + 1 vertices and remove the one of largest degree (its neighbours become the "
                 "boundary); root-face: keep the sampler's triangular root face";
    outer.choices = {"puncture", "root-face"};
    outer.default_text = "puncture";
    g.params = {n, outer};
    r.push_back(g);
  }
  {
    GeneratorInfo g;
    g.name = "uniform-three-connected";
    g.summary = "uniform random 3-connected planar map with n vertices (Fusy); outer face: its largest face, or the "
                "root face";
    ParamSpec outer;
    outer.name = "outer";
    outer.type = ParamType::choice;
    outer.help = "largest-face (the map's largest face) or root-face (the sampler's root face)";
    outer.choices = {"largest-face", "root-face"};
    outer.default_text = "largest-face";
    ParamSpec faces;
    faces.name = "faces";
    faces.type = ParamType::integer;
    faces.help = "number of faces (0 = any: uniform over all edge counts)";
    faces.min = 0;
    faces.max = 2e8;
    faces.default_text = "0";
    g.params = {size_param(4), faces, outer};
    g.check = [](const TopologyParams& p) {
      std::vector<ParamIssue> out;
      const std::int64_t n = p.integer("n", 4), f = p.integer("faces", 0);
      if (f != 0 && (n > 2 * f - 4 || f > 2 * n - 4))
        out.push_back({"faces", "'" + std::to_string(f) + "' with n = " + std::to_string(n),
                       "0 or a face count f with n <= 2f - 4 and f <= 2n - 4 (Steinitz)"});
      return out;
    };
    r.push_back(g);
  }
  {
    GeneratorInfo g;
    g.name = "mesh";
    g.summary = "anisotropic mesh of a polygonal domain under a metric field (core::mesh_with_stars, thesis ch. 3); "
                "vertices keep their physical positions";
    ParamSpec domain;
    domain.name = "domain";
    domain.type = ParamType::file;
    domain.help = "a domain file (core/meshing/Domain.hpp: outer, hole, segment), relative to the scenario file";
    domain.default_text = "the unit square";
    ParamSpec metric;
    metric.name = "metric";
    metric.type = ParamType::text;
    metric.help = "a metric-field specification: uniform:H1:H2[:DEG], shock[:…], thesis[:…], expr:…, sizes:…, mesh:FILE";
    metric.default_text = "uniform:0.1:0.1";
    ParamSpec bound;
    bound.name = "size_bound";
    bound.type = ParamType::number;
    bound.help = "largest circumradius in the metric";
    bound.min = 1e-6;
    bound.max = 1e6;
    bound.default_text = "1";
    ParamSpec cap;
    cap.name = "max_vertices";
    cap.type = ParamType::integer;
    cap.help = "refuse meshes larger than this";
    cap.min = 3;
    cap.max = 1e7;
    cap.default_text = "200000";
    ParamSpec corners;
    corners.name = "refine_corners";
    corners.type = ParamType::boolean;
    corners.help = "refine every boundary corner left with a single triangle (core::StarMeshOptions::no_lonely_corners), "
                   "so that a mesh of a domain with holes is 3-connected (its holes inner faces)";
    corners.default_text = "true";
    ParamSpec repair;
    repair.name = "repair";
    repair.type = ParamType::choice;
    repair.help = "what to do with a mesh that is neither a triangulated disc nor 3-connected (as for field)";
    repair.choices = {"fail", "largest-block", "three-connected-core", "triangulate-faces"};
    repair.default_text = "fail";
    g.params = {domain, metric, bound, cap, corners, repair};
    g.positions = true;
    g.check = [](const TopologyParams& p) {
      std::vector<ParamIssue> out;
      try {
        (void)core::parse_metric_field(p.text("metric", "uniform:0.1:0.1"));
      } catch (const std::exception& e) {
        out.push_back({"metric", "'" + p.text("metric", "") + "'", std::string("a metric field (") + e.what() + ")"});
      }
      if (p.has("domain")) try {
          (void)core::read_domain(p.text("domain", ""));
        } catch (const std::exception& e) {
          out.push_back({"domain", "'" + p.text("domain", "") + "'", std::string("a valid domain (") + e.what() + ")"});
        }
      return out;
    };
    r.push_back(g);
  }
  {
    GeneratorInfo g;
    g.name = "field";
    g.summary = "sensor field: n sensors deployed in a polygonal domain with holes, joined by a proximity graph "
                "(restricted Delaunay, unit-disk, Gabriel, RNG or local Delaunay), repaired if unpackable";
    ParamSpec graph;
    graph.name = "graph";
    graph.type = ParamType::choice;
    graph.help = "the proximity graph";
    graph.choices = {"delaunay", "unit-disk", "gabriel", "rng", "local-delaunay"};
    graph.default_text = "delaunay";
    ParamSpec radius;
    radius.name = "radius";
    radius.type = ParamType::number;
    radius.help = "unit-disk radius R (required by every graph but delaunay)";
    radius.min = 1e-9;
    ParamSpec hops;
    hops.name = "hops";
    hops.type = ParamType::integer;
    hops.help = "k of the local Delaunay graph LDel^(k)";
    hops.min = 1;
    hops.max = 10;
    hops.default_text = "2";
    ParamSpec repair;
    repair.name = "repair";
    repair.type = ParamType::choice;
    repair.help = "what to do with a graph that is neither a triangulated disc nor 3-connected";
    repair.choices = {"fail", "largest-block", "three-connected-core", "triangulate-faces"};
    repair.default_text = "fail";
    ParamSpec domain;
    domain.name = "domain";
    domain.type = ParamType::polygons;
    domain.help = "outer polygon, then holes: [[[x, y], ...], [[x, y], ...], ...]";
    domain.default_text = "the unit square [0, 1]^2";
    ParamSpec deployment;
    deployment.name = "deployment";
    deployment.type = ParamType::choice;
    deployment.help = "how sensors are placed";
    deployment.choices = {"uniform", "clustered"};
    deployment.default_text = "uniform";
    ParamSpec clusters;
    clusters.name = "clusters";
    clusters.type = ParamType::integer;
    clusters.help = "number of cluster centres (clustered)";
    clusters.min = 1;
    clusters.max = 1e6;
    clusters.default_text = "10";
    ParamSpec spread;
    spread.name = "spread";
    spread.type = ParamType::number;
    spread.help = "cluster standard deviation (gaussian) or radius (disc)";
    spread.min = 1e-12;
    spread.default_text = "0.05";
    ParamSpec shape;
    shape.name = "cluster_shape";
    shape.type = ParamType::choice;
    shape.help = "cluster shape (clustered)";
    shape.choices = {"gaussian", "disc"};
    shape.default_text = "gaussian";
    g.params = {size_param(3), graph, radius, hops, repair, domain, deployment, clusters, spread, shape};
    g.positions = true;
    g.check = [](const TopologyParams& p) {
      std::vector<ParamIssue> out;
      const std::string graph_type = p.text("graph", "delaunay");
      if (graph_type != "delaunay" && !p.has("radius"))
        out.push_back({"radius", "nothing", "a radius > 0 for graph " + graph_type});
      if (p.has("domain")) {
        try {
          const Polygons polys = p.polygons("domain");
          (void)core::Domain(polys.front(), Polygons(polys.begin() + 1, polys.end()));
        } catch (const std::exception& e) {
          out.push_back({"domain", "an invalid domain (" + std::string(e.what()) + ")",
                         "a simple outer polygon and disjoint simple holes strictly inside it"});
        }
      }
      return out;
    };
    r.push_back(g);
  }
  return r;
}

}  // namespace

const std::vector<GeneratorInfo>& topology_generators() {
  static const std::vector<GeneratorInfo> registry = make_registry();
  return registry;
}

const GeneratorInfo* find_generator(std::string_view name) {
  for (const auto& g : topology_generators())
    if (g.name == name) return &g;
  return nullptr;
}

std::string generator_names(bool available_only) {
  std::string out;
  for (const auto& g : topology_generators())
    if (g.available || !available_only) out += (out.empty() ? "" : ", ") + g.name;
  return out;
}

namespace {

Topology prepare(core::GraphInput input, std::string name, std::string_view family) {
  Topology t;
  try {
    t.graph = core::prepare_for_packing(input, &t.kind);
  } catch (const std::exception& e) {
    throw TopologyError(name + " cannot be packed: " + e.what());
  }
  t.positions = std::move(input.positions);
  t.name = std::move(name);
  t.family = std::string(family);
  return t;
}

}  // namespace

Topology build_topology(std::string_view generator, const TopologyParams& params, std::uint64_t seed,
                        std::size_t repetition) {
  const GeneratorInfo* info = find_generator(generator);
  if (!info) throw TopologyError("unknown topology generator '" + std::string(generator) + "'");
  if (!info->available) throw TopologyError(info->unavailable_reason);
  const auto n = static_cast<std::size_t>(params.integer("n", 0));
  try {
    if (generator == "delaunay")
      return prepare(core::random_delaunay_triangulation(n, seed), "delaunay(n=" + std::to_string(n) + ")", generator);
    if (generator == "three-connected")
      return prepare(core::random_three_connected(n, seed, params.number("deletions_per_vertex", 0.75),
                                                  static_cast<std::size_t>(params.integer("max_face_size", 8))),
                     "three-connected(n=" + std::to_string(n) + ")", generator);
    if (generator == "uniform-triangulation") {
      const bool puncture = params.text("outer", "puncture") == "puncture";
      core::GraphInput in{puncture ? puncture_at_max_degree(uniform_triangulation(n + 1, seed)) : uniform_triangulation(n, seed),
                          {}, "", true};
      return prepare(std::move(in), "uniform-triangulation(n=" + std::to_string(n) + ")", generator);
    }
    if (generator == "uniform-three-connected") {
      core::PlanarGraph map = uniform_three_connected(n, seed, static_cast<std::size_t>(params.integer("faces", 0)));
      if (params.text("outer", "largest-face") == "largest-face") map = with_largest_outer_face(map);
      core::GraphInput in{std::move(map), {}, "", true};
      return prepare(std::move(in), "uniform-three-connected(n=" + std::to_string(n) + ")", generator);
    }
    if (generator == "mesh") {
      const core::Domain domain =
          params.has("domain") ? core::read_domain(params.text("domain", "")) : core::Domain::unit_square();
      const auto field = core::parse_metric_field(params.text("metric", "uniform:0.1:0.1"));
      core::StarMeshOptions options;
      options.size_bound = params.number("size_bound", 1);
      options.max_vertices = static_cast<std::size_t>(params.integer("max_vertices", 200000));
      options.seed = seed;
      options.no_lonely_corners = params.boolean("refine_corners", true);
      const core::StarMeshResult mesh = core::mesh_with_stars(domain, *field, options);
      if (!mesh.converged) throw TopologyError("mesh: the refinement did not converge (" + mesh.status + ")");
      std::vector<core::Point2> positions;
      for (const auto& p : mesh.mesh.points) positions.push_back({p[0], p[1]});
      EdgeList edges;
      for (const auto& t : mesh.mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
          const auto a = static_cast<core::Vertex>(t[k]), b = static_cast<core::Vertex>(t[(k + 1) % 3]);
          edges.emplace_back(std::min(a, b), std::max(a, b));
        }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      const std::string name = "mesh(" + field->describe() + ", " + std::to_string(positions.size()) + " vertices)";
      // The report and repair of sensor fields (vertex ids = mesh indices). The drawing's unbounded face
      // (the outer boundary) is the outer face, so holes stay inner faces. The mesh is plane by construction.
      FieldGraph fg = field_graph_from_edges(positions, edges, parse_repair_policy(params.text("repair", "fail")), name,
                                             "mesh", false);
      Topology t;
      t.graph = std::move(fg.input.graph);
      t.kind = fg.kind;
      t.positions = std::move(fg.input.positions);
      t.name = name;
      t.family = std::string(generator);
      t.note = fg.report.summary(name);
      if (options.no_lonely_corners) t.note += "; " + std::to_string(mesh.stats.corners) + " lonely corner(s) refined";
      return t;
    }
    if (generator == "field") {
      const Polygons polys = params.polygons("domain");
      const core::Domain domain = polys.empty() ? core::Domain::unit_square()
                                                : core::Domain(polys.front(), Polygons(polys.begin() + 1, polys.end()));
      std::vector<core::Point2> points;
      if (params.text("deployment", "uniform") == "clustered") {
        ClusterOptions co;
        co.clusters = static_cast<std::size_t>(params.integer("clusters", 10));
        co.spread = params.number("spread", 0.05);
        co.shape = params.text("cluster_shape", "gaussian") == "disc" ? ClusterShape::disc : ClusterShape::gaussian;
        points = deploy_clustered(domain, n, co, seed);
      } else {
        points = deploy_uniform(domain, n, seed);
      }
      FieldGraphOptions fo;
      fo.type = parse_field_graph_type(params.text("graph", "delaunay"));
      fo.radius = params.number("radius", 0);
      fo.hops = static_cast<unsigned>(params.integer("hops", 2));
      fo.repair = parse_repair_policy(params.text("repair", "fail"));
      fo.source = "field(" + params.text("graph", "delaunay") + ", n=" + std::to_string(n) + ")";
      FieldGraph fg = build_field_graph(domain, points, fo);
      Topology t;
      t.graph = std::move(fg.input.graph);
      t.kind = fg.kind;
      t.positions = std::move(fg.input.positions);
      t.name = fo.source;
      t.family = std::string(generator);
      t.note = fg.report.summary(fo.source);
      return t;
    }
    if (generator == "file") {
      const std::string path = params.text("path", "");
      auto graphs = core::read_graphs(path, core::parse_graph_format(params.text("format", "automatic")));
      const auto index = static_cast<std::size_t>(params.integer("index", 1));
      if (graphs.empty()) throw TopologyError(path + " holds no graph");
      const std::size_t k = index == 0 ? repetition % graphs.size() : index - 1;
      if (k >= graphs.size())
        throw TopologyError("graph index " + std::to_string(index) + " is out of range: " + path + " holds " +
                            std::to_string(graphs.size()) + " graph(s)");
      std::string name = graphs[k].name;
      return prepare(std::move(graphs[k]), std::move(name), generator);
    }
  } catch (const TopologyError&) {
    throw;
  } catch (const std::exception& e) {
    throw TopologyError(std::string(generator) + ": " + e.what());
  }
  throw TopologyError("generator '" + std::string(generator) + "' is registered but has no builder");
}

}  // namespace laguerre::scenarios
