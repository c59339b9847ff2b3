// The topology registry: generator names → planar graphs ready for packing.
#include "laguerre/scenarios/Topology.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <type_traits>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphError.hpp"
#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/meshing/Domain.hpp"
#include "laguerre/core/meshing/MetricField.hpp"
#include "laguerre/core/meshing/StarMesher.hpp"
#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/FieldGraph.hpp"
#include "laguerre/scenarios/fields/SensorNetwork.hpp"
#include "laguerre/core/random/Random.hpp"
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
// Registry: one table of generators, each with its typed parameters (defaults written once, in the
// ParamSpec), its cross-parameter check and its build function. Builders and checks read parameters
// through Args, which falls back to the table's defaults; the documentation comes from the same table.

namespace {

/// Validated parameters, with the defaults of the generator's table entry for the absent ones (and the
/// zero of the type for a parameter with no default, e.g. a radius that only some graph types need).
class Args {
public:
  Args(const std::vector<ParamSpec>& specs, const TopologyParams& given) : specs_(specs), given_(given) {}

  bool has(std::string_view name) const { return given_.has(name); }
  std::int64_t integer(std::string_view name) const { return given_.integer(name, fallback<std::int64_t>(name)); }
  std::size_t size(std::string_view name) const { return static_cast<std::size_t>(integer(name)); }
  double number(std::string_view name) const { return given_.number(name, fallback<double>(name)); }
  bool boolean(std::string_view name) const { return given_.boolean(name, fallback<bool>(name)); }
  std::string text(std::string_view name) const { return given_.text(name, fallback<std::string>(name)); }
  Polygons polygons(std::string_view name) const { return given_.polygons(name); }

private:
  template <class T>
  T fallback(std::string_view name) const {
    for (const ParamSpec& spec : specs_)
      if (spec.name == name) {
        if (!spec.default_value) return T{};
        if (const T* v = std::get_if<T>(&*spec.default_value)) return *v;
        if constexpr (std::is_same_v<T, double>)
          if (const auto* i = std::get_if<std::int64_t>(&*spec.default_value)) return static_cast<double>(*i);
        LAGUERRE_PRECONDITION(false, "the default of '" + std::string(name) + "' has another type");
      }
    LAGUERRE_PRECONDITION(false, "'" + std::string(name) + "' is not a parameter of this generator");
    return T{};
  }

  const std::vector<ParamSpec>& specs_;
  const TopologyParams& given_;
};

/// A parameter spec, built in one expression.
struct Param {
  ParamSpec spec;
  Param(std::string name, ParamType type, std::string help) {
    spec.name = std::move(name);
    spec.type = type;
    spec.help = std::move(help);
  }
  Param& range(double min, double max = std::numeric_limits<double>::infinity()) {
    spec.min = min;
    spec.max = max;
    return *this;
  }
  Param& choices(std::vector<std::string> values) {
    spec.choices = std::move(values);
    return *this;
  }
  Param& required() {
    spec.required = true;
    return *this;
  }
  /// The default builders use, documented as describe(value).
  Param& fallback(ParamValue value) {
    spec.default_text = describe(value);
    spec.default_value = std::move(value);
    return *this;
  }
  /// A default that is no value, documented as `text` (the builder knows it).
  Param& documented_default(std::string text) {
    spec.default_text = std::move(text);
    return *this;
  }
  operator ParamSpec() const { return spec; }  // NOLINT(google-explicit-constructor)
};

Param size_param(double min, double max = 1e7) {
  Param n("n", ParamType::integer, "number of vertices");
  n.range(min, max).required();
  return n;
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

const std::vector<std::string> repair_policies = {"fail", "largest-block", "three-connected-core", "triangulate-faces"};

Topology prepare(core::GraphInput input, std::string name, std::string_view family,
                 core::OuterRule rule = core::OuterRule::face) {
  Topology t;
  try {
    core::PreparedInput prepared = core::prepare_input(input, rule);
    t.graph = std::move(input.graph);
    t.kind = prepared.kind;
    t.removed = std::move(prepared.removed);
  } catch (const std::exception& e) {
    throw TopologyError(name + " cannot be packed: " + e.what());
  }
  for (std::uint64_t id : t.removed)
    t.note += (t.note.empty() ? "" : "; ") + std::string("outer puncture: vertex ") + std::to_string(id) +
              " removed (its neighbours are the boundary; it is not packed and not routed)";
  t.positions = std::move(input.positions);
  t.name = std::move(name);
  t.family = std::string(family);
  return t;
}

/// A topology from a sensor-field graph (field and mesh): the repaired graph and the repair report.
Topology from_field_graph(FieldGraph fg, std::string name, std::string_view family) {
  Topology t;
  t.graph = std::move(fg.input.graph);
  t.kind = fg.kind;
  t.positions = std::move(fg.input.positions);
  t.note = fg.report.summary(name);
  t.name = std::move(name);
  t.family = std::string(family);
  return t;
}

std::string sized_name(std::string_view generator, std::size_t n) {
  return std::string(generator) + "(n=" + std::to_string(n) + ")";
}

// The build functions, one per generator.

Topology build_delaunay(const Args& a, std::uint64_t seed, std::size_t) {
  const std::size_t n = a.size("n");
  return prepare(core::random_delaunay_triangulation(n, seed), sized_name("delaunay", n), "delaunay");
}

Topology build_three_connected(const Args& a, std::uint64_t seed, std::size_t) {
  const std::size_t n = a.size("n");
  return prepare(core::random_three_connected(n, seed, a.number("deletions_per_vertex"), a.size("max_face_size")),
                 sized_name("three-connected", n), "three-connected");
}

Topology build_file(const Args& a, std::uint64_t, std::size_t repetition) {
  const std::string path = a.text("path");
  auto graphs = core::read_graphs(path, core::parse_graph_format(a.text("format")));
  const std::size_t index = a.size("index");
  if (graphs.empty()) throw TopologyError(path + " holds no graph");
  const std::size_t k = index == 0 ? repetition % graphs.size() : index - 1;
  if (k >= graphs.size())
    throw TopologyError("graph index " + std::to_string(index) + " is out of range: " + path + " holds " +
                        std::to_string(graphs.size()) + " graph(s)");
  std::string name = graphs[k].name;
  return prepare(std::move(graphs[k]), std::move(name), "file",
                 core::parse_name(core::outer_rule_names, a.text("outer"), "topology.outer"));
}

Topology build_uniform_triangulation(const Args& a, std::uint64_t seed, std::size_t) {
  const std::size_t n = a.size("n");
  const bool puncture = a.text("outer") == "puncture";
  core::GraphInput in{puncture ? puncture_at_max_degree(uniform_triangulation(n + 1, seed)) : uniform_triangulation(n, seed),
                      {}, "", true};
  return prepare(std::move(in), sized_name("uniform-triangulation", n), "uniform-triangulation");
}

Topology build_uniform_three_connected(const Args& a, std::uint64_t seed, std::size_t) {
  const std::size_t n = a.size("n");
  core::PlanarGraph map = uniform_three_connected(n, seed, a.size("faces"));
  if (a.text("outer") == "largest-face") map = with_largest_outer_face(map);
  core::GraphInput in{std::move(map), {}, "", true};
  return prepare(std::move(in), sized_name("uniform-three-connected", n), "uniform-three-connected");
}

Topology build_mesh(const Args& a, std::uint64_t seed, std::size_t) {
  const core::Domain domain = a.has("domain") ? core::read_domain(a.text("domain")) : core::Domain::unit_square();
  const auto field = core::parse_metric_field(a.text("metric"));
  core::StarMeshOptions options;
  options.size_bound = a.number("size_bound");
  options.max_vertices = a.size("max_vertices");
  options.seed = seed;
  options.no_lonely_corners = a.boolean("refine_corners");
  const core::StarMeshResult mesh = core::mesh_with_stars(domain, *field, options);
  if (!mesh.converged) throw TopologyError("mesh: the refinement did not converge (" + mesh.status + ")");
  std::vector<core::Point2> positions;
  for (const auto& p : mesh.mesh.points) positions.push_back({p[0], p[1]});
  EdgeList edges;
  for (const auto& t : mesh.mesh.triangles)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto u = static_cast<core::Vertex>(t[k]), v = static_cast<core::Vertex>(t[(k + 1) % 3]);
      edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const std::string name = "mesh(" + field->describe() + ", " + std::to_string(positions.size()) + " vertices)";
  // The report and repair of sensor fields (vertex ids = mesh indices). The drawing's unbounded face
  // (the outer boundary) is the outer face, so holes stay inner faces. The mesh is plane by construction.
  Topology t = from_field_graph(
      field_graph_from_edges(positions, edges, parse_repair_policy(a.text("repair")), name, "mesh", false), name, "mesh");
  if (options.no_lonely_corners) t.note += "; " + std::to_string(mesh.stats.corners) + " lonely corner(s) refined";
  return t;
}

/// The field's domain: `domain_file`, else the `domain` polygons, else the unit square.
core::Domain field_domain(const Args& a) {
  if (a.has("domain_file")) return core::read_domain(a.text("domain_file"));
  const Polygons polys = a.polygons("domain");
  return polys.empty() ? core::Domain::unit_square() : core::Domain(polys.front(), Polygons(polys.begin() + 1, polys.end()));
}

/// The largest depth of a sensor hanging on the core (0 if none).
std::uint32_t deepest_attached(const Attachment& at) {
  std::uint32_t deepest = 0;
  for (std::size_t v = 0; v < at.depth.size(); ++v)
    if (at.core_vertex[at.anchor[v]] != core::none) deepest = std::max(deepest, at.depth[v]);
  return deepest;
}

Topology build_field(const Args& a, std::uint64_t seed, std::size_t) {
  const std::size_t n = a.size("n");
  const core::Domain domain = field_domain(a);
  std::vector<core::Point2> points;
  if (a.text("deployment") == "clustered") {
    ClusterOptions co;
    co.clusters = a.size("clusters");
    co.spread = a.number("spread");
    co.shape = a.text("cluster_shape") == "disc" ? ClusterShape::disc : ClusterShape::gaussian;
    points = deploy_clustered(domain, n, co, seed);
  } else {
    points = deploy_uniform(domain, n, seed);
  }
  FieldGraphOptions fo;
  fo.type = parse_field_graph_type(a.text("graph"));
  fo.radius = a.number("radius");
  fo.hops = static_cast<unsigned>(a.integer("hops"));
  fo.repair = parse_repair_policy(a.text("repair"));
  fo.source = "field(" + a.text("graph") + ", n=" + std::to_string(n) + ")";
  const bool quasi = a.text("links") == "quasi-unit-disk";
  if (!quasi && !a.boolean("attach")) return from_field_graph(build_field_graph(domain, points, fo), fo.source, "field");
  // Links of their own (quasi-unit-disk) or every sensor kept (attach): the spanner is cut to the links,
  // its core is packed, and with attach the other sensors hang on it (fields/SensorNetwork.hpp).
  auto net = std::make_shared<SensorNetwork>();
  const LinkOptions lo{quasi, fo.radius, a.number("quasi_inner"), a.number("quasi_probability"), core::splitmix64(seed)};
  net->links = link_edges(points, lo);
  net->planar = common_edges(field_edges(domain, points, fo), net->links);
  std::string type_name(to_string(fo.type));
  type_name += quasi ? " graph on quasi-unit-disk links" : " graph";
  Topology t = from_field_graph(field_graph_from_edges(points, net->planar, fo.repair, fo.source, type_name, false),
                                fo.source, "field");
  if (!a.boolean("attach")) return t;
  net->attachment = attach_to_core(points.size(), net->links, t.graph);
  std::size_t largest_face = 0;  // the holes wider than the links are inner faces of the core
  for (core::Face f = 0; f < t.graph.num_faces(); ++f)
    if (f != t.graph.outer_face()) largest_face = std::max<std::size_t>(largest_face, t.graph.face_size(f));
  t.note += "; largest inner face " + std::to_string(largest_face) + " vertices, outer face " +
            std::to_string(t.graph.face_size(t.graph.outer_face())) + "; attach: " +
            std::to_string(t.graph.num_vertices()) + " core sensors, " +
            std::to_string(net->attachment.attached) + " attached to the core (deepest " +
            std::to_string(deepest_attached(net->attachment)) + " hops), " +
            std::to_string(net->attachment.stray) + " in other link components";
  net->points = std::move(points);
  t.sensors = std::move(net);
  return t;
}

// The cross-parameter checks.

std::vector<ParamIssue> check_uniform_three_connected(const Args& a) {
  std::vector<ParamIssue> out;
  const std::int64_t n = a.integer("n"), f = a.integer("faces");
  if (f != 0 && (n > 2 * f - 4 || f > 2 * n - 4))
    out.push_back({"faces", "'" + std::to_string(f) + "' with n = " + std::to_string(n),
                   "0 or a face count f with n <= 2f - 4 and f <= 2n - 4 (Steinitz)"});
  return out;
}

std::vector<ParamIssue> check_mesh(const Args& a) {
  std::vector<ParamIssue> out;
  try {
    (void)core::parse_metric_field(a.text("metric"));
  } catch (const std::exception& e) {
    out.push_back({"metric", "'" + a.text("metric") + "'", std::string("a metric field (") + e.what() + ")"});
  }
  if (a.has("domain")) try {
      (void)core::read_domain(a.text("domain"));
    } catch (const std::exception& e) {
      out.push_back({"domain", "'" + a.text("domain") + "'", std::string("a valid domain (") + e.what() + ")"});
    }
  return out;
}

std::vector<ParamIssue> check_field(const Args& a) {
  std::vector<ParamIssue> out;
  const std::string graph_type = a.text("graph");
  if (graph_type != "delaunay" && !a.has("radius"))
    out.push_back({"radius", "nothing", "a radius > 0 for graph " + graph_type});
  const bool own_links = a.boolean("attach") || a.text("links") == "quasi-unit-disk";
  if (own_links && (graph_type == "delaunay" || graph_type == "unit-disk" ||
                    (graph_type == "local-delaunay" && a.integer("hops") < 2)))
    out.push_back({"graph", "'" + graph_type + "' with attach or quasi-unit-disk links",
                   "a planar spanner of the links: gabriel, rng, or local-delaunay with hops >= 2"});
  if (own_links && graph_type == "delaunay" && !a.has("radius"))  // other graphs ask for it above
    out.push_back({"radius", "nothing", "a radius > 0 for the links"});
  if (a.has("domain") && a.has("domain_file"))
    out.push_back({"domain_file", "both domain and domain_file", "one of them"});
  if (a.has("domain_file")) try {
      (void)core::read_domain(a.text("domain_file"));
    } catch (const std::exception& e) {
      out.push_back({"domain_file", "'" + a.text("domain_file") + "'", std::string("a valid domain (") + e.what() + ")"});
    }
  if (a.has("domain")) {
    try {
      const Polygons polys = a.polygons("domain");
      (void)core::Domain(polys.front(), Polygons(polys.begin() + 1, polys.end()));
    } catch (const std::exception& e) {
      out.push_back({"domain", "an invalid domain (" + std::string(e.what()) + ")",
                     "a simple outer polygon and disjoint simple holes strictly inside it"});
    }
  }
  return out;
}

using BuildFn = Topology (*)(const Args&, std::uint64_t, std::size_t);
using CheckFn = std::vector<ParamIssue> (*)(const Args&);

GeneratorInfo generator(std::string name, std::string summary, bool positions, std::vector<ParamSpec> params,
                        BuildFn build, CheckFn check = nullptr) {
  GeneratorInfo g;
  g.name = std::move(name);
  g.summary = std::move(summary);
  g.positions = positions;
  g.params = std::move(params);
  // The closures hold a copy of the parameter specs, so the defaults they read are the table's.
  g.build = [specs = g.params, build](const TopologyParams& p, std::uint64_t seed, std::size_t repetition) {
    return build(Args(specs, p), seed, repetition);
  };
  if (check) g.check = [specs = g.params, check](const TopologyParams& p) { return check(Args(specs, p)); };
  return g;
}

std::vector<GeneratorInfo> make_registry() {
  using T = ParamType;
  using I = std::int64_t;
  std::vector<GeneratorInfo> r;
  r.push_back(generator("delaunay",
                        "Delaunay triangulation of n points uniform in the unit disc (core::random_delaunay_triangulation)",
                        true, {size_param(3)}, build_delaunay));
  r.push_back(generator(
      "three-connected",
      "random 3-connected plane graph: a Delaunay triangulation thinned by edge deletions (core::random_three_connected)",
      true,
      {size_param(4),
       Param("deletions_per_vertex", T::number, "edge deletions attempted per vertex").range(0, 3).fallback(0.75),
       Param("max_face_size", T::integer, "largest face a deletion may create").range(4, 1000).fallback(I{8})},
      build_three_connected));
  r.push_back(generator(
      "file", "a graph file (core::read_graphs): edge list, coords, planar_code, and the other formats GraphIO reads",
      false,  // only the formats with positions have them; decided per file
      {Param("path", T::file, "the file, relative to the scenario file's folder").required(),
       Param("format", T::choice, "its format").choices(supported_formats()).fallback(std::string("automatic")),
       Param("index", T::integer, "which graph of a multi-graph file, from 1; 0 = graph (repetition mod count) + 1")
           .range(0, 1e9)
           .fallback(I{1}),
       Param("outer", T::choice,
             "for a triangulated sphere (every face a triangle): face keeps a face outside (the file's '# outer:' "
             "face, else the default one); puncture removes the vertex of largest degree (smallest id on ties), "
             "whose neighbours become the boundary; other graphs are unchanged")
           .choices(core::names_of(core::outer_rule_names))
           .fallback(std::string(core::name_of(core::outer_rule_names, core::OuterRule::face)))},
      build_file));
  r.push_back(generator(
      "uniform-triangulation",
      "uniform random triangulation with n vertices (Poulalhon–Schaeffer); outer face: the link of a punctured vertex, "
      "or the root face",
      false,
      {size_param(3, 1e8),
       Param("outer", T::choice,
             "puncture: sample n + 1 vertices and remove the one of largest degree (its neighbours become the "
             "boundary); root-face: keep the sampler's triangular root face")
           .choices({"puncture", "root-face"})
           .fallback(std::string("puncture"))},
      build_uniform_triangulation));
  r.push_back(generator(
      "uniform-three-connected",
      "uniform random 3-connected planar map with n vertices (Fusy); outer face: its largest face, or the root face",
      false,
      {size_param(4),
       Param("faces", T::integer, "number of faces (0 = any: uniform over all edge counts)").range(0, 2e8).fallback(I{0}),
       Param("outer", T::choice, "largest-face (the map's largest face) or root-face (the sampler's root face)")
           .choices({"largest-face", "root-face"})
           .fallback(std::string("largest-face"))},
      build_uniform_three_connected, check_uniform_three_connected));
  r.push_back(generator(
      "mesh",
      "anisotropic mesh of a polygonal domain under a metric field (core::mesh_with_stars, thesis ch. 3); vertices "
      "keep their physical positions",
      true,
      {Param("domain", T::file,
             "a domain file (core/meshing/Domain.hpp: outer, hole, segment), relative to the scenario file")
           .documented_default("the unit square"),
       Param("metric", T::text,
             "a metric-field specification: uniform:H1:H2[:DEG], shock[:…], thesis[:…], expr:…, sizes:…, mesh:FILE")
           .fallback(std::string("uniform:0.1:0.1")),
       Param("size_bound", T::number, "largest circumradius in the metric").range(1e-6, 1e6).fallback(1.0),
       Param("max_vertices", T::integer, "refuse meshes larger than this").range(3, 1e7).fallback(I{200000}),
       Param("refine_corners", T::boolean,
             "refine every boundary corner left with a single triangle (core::StarMeshOptions::no_lonely_corners), "
             "so that a mesh of a domain with holes is 3-connected (its holes inner faces)")
           .fallback(true),
       Param("repair", T::choice,
             "what to do with a mesh that is neither a triangulated disc nor 3-connected (as for field)")
           .choices(repair_policies)
           .fallback(std::string("fail"))},
      build_mesh, check_mesh));
  r.push_back(generator(
      "field",
      "sensor field: n sensors deployed in a polygonal domain with holes, joined by a proximity graph (restricted "
      "Delaunay, unit-disk, Gabriel, RNG or local Delaunay), repaired if unpackable",
      true,
      {size_param(3),
       Param("graph", T::choice, "the proximity graph")
           .choices({"delaunay", "unit-disk", "gabriel", "rng", "local-delaunay"})
           .fallback(std::string("delaunay")),
       Param("radius", T::number, "unit-disk radius R (required by every graph but delaunay)").range(1e-9),
       Param("hops", T::integer, "k of the local Delaunay graph LDel^(k)").range(1, 10).fallback(I{2}),
       Param("repair", T::choice, "what to do with a graph that is neither a triangulated disc nor 3-connected")
           .choices(repair_policies)
           .fallback(std::string("fail")),
       Param("domain", T::polygons, "outer polygon, then holes: [[[x, y], ...], [[x, y], ...], ...]")
           .documented_default("the unit square [0, 1]^2"),
       Param("domain_file", T::file,
             "a domain file instead of `domain` (core/meshing/Domain.hpp, as for mesh), relative to the scenario file")
           .documented_default("none"),
       Param("links", T::choice,
             "radio links: unit-disk (|uv| <= radius) or quasi-unit-disk (|uv| <= quasi_inner * radius always, up to "
             "radius with probability quasi_probability); the spanner is cut to the links (fields/SensorNetwork.hpp)")
           .choices({"unit-disk", "quasi-unit-disk"})
           .fallback(std::string("unit-disk")),
       Param("quasi_inner", T::number, "quasi-unit-disk: the ratio of the sure-link radius to radius")
           .range(1e-6, 1)
           .fallback(0.75),
       Param("quasi_probability", T::number, "quasi-unit-disk: the probability of a link between the two radii")
           .range(0, 1)
           .fallback(0.5),
       Param("attach", T::boolean,
             "route every sensor: the sensors outside the packed core hang on it by trees in the links "
             "(fields/SensorNetwork.hpp); needs a radius and a planar spanner (gabriel, rng, local-delaunay)")
           .fallback(false),
       Param("deployment", T::choice, "how sensors are placed")
           .choices({"uniform", "clustered"})
           .fallback(std::string("uniform")),
       Param("clusters", T::integer, "number of cluster centres (clustered)").range(1, 1e6).fallback(I{10}),
       Param("spread", T::number, "cluster standard deviation (gaussian) or radius (disc)").range(1e-12).fallback(0.05),
       Param("cluster_shape", T::choice, "cluster shape (clustered)")
           .choices({"gaussian", "disc"})
           .fallback(std::string("gaussian"))},
      build_field, check_field));
  return r;
}

/// The name of a parameter type in generators_help, in ParamType's order.
constexpr std::array<std::string_view, 7> type_names{"integer", "number", "boolean", "choice", "file", "polygons", "text"};

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

std::string generators_help() {
  std::string out;
  for (const GeneratorInfo& g : topology_generators()) {
    out += g.name + ": " + g.summary + (g.positions ? " (with positions)" : "") + "\n";
    for (const ParamSpec& p : g.params) {
      std::string kind(type_names.at(static_cast<std::size_t>(p.type)));
      if (!p.choices.empty()) {
        std::string list;
        for (const std::string& c : p.choices) list += (list.empty() ? "" : "|") + c;
        kind += " " + list;
      } else if (std::isfinite(p.min) || std::isfinite(p.max)) {
        kind += " in [" + describe(p.min) + ", " + (std::isfinite(p.max) ? describe(p.max) : "inf") + "]";
      }
      kind += p.required ? "; required" : p.default_text.empty() ? "" : "; default " + p.default_text;
      out += "  " + p.name + " (" + kind + "): " + p.help + "\n";
    }
  }
  return out;
}

Topology build_topology(std::string_view generator, const TopologyParams& params, std::uint64_t seed,
                        std::size_t repetition) {
  const GeneratorInfo* info = find_generator(generator);
  if (!info) throw TopologyError("unknown topology generator '" + std::string(generator) + "'");
  if (!info->available) throw TopologyError(info->unavailable_reason);
  LAGUERRE_PRECONDITION(info->build, "generator '" + std::string(generator) + "' is registered without a builder");
  try {
    return info->build(params, seed, repetition);
  } catch (const TopologyError&) {
    throw;
  } catch (const std::exception& e) {
    throw TopologyError(std::string(generator) + ": " + e.what());
  }
}

}  // namespace laguerre::scenarios
