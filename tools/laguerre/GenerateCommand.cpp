// `laguerre generate`: write a random graph of one of the documented families to a file.
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "Commands.hpp"
#include "Common.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/scenarios/Topology.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp generate_help{
    "generate",
    "Write a random planar graph (RandomGraphs.hpp, or the uniform samplers of scenarios/).",
    ""};

struct GenerateArgs {
  std::string family;
  std::size_t size = 50;
  std::uint64_t seed = 1;
  std::string out;
  std::string format = "coords";
  std::size_t count = 1;
  bool force = false;
};

std::string write_coords(const core::GraphInput& in) {
  const core::PlanarGraph& g = in.graph;
  std::ostringstream os;
  os << std::setprecision(17);
  os << "# " << in.name << ": " << g.num_vertices() << " vertices, " << g.num_edges() << " edges\n# outer:";
  for (core::Vertex v : g.boundary_cycle()) os << ' ' << g.id(v);
  os << "\nvertices\n";
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)
    os << g.id(v) << ' ' << in.positions[v].x << ' ' << in.positions[v].y << '\n';
  os << "edges\n";
  for (core::Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) os << g.id(g.tail(d)) << ' ' << g.id(g.head(d)) << '\n';
  return os.str();
}

bool uniform_family(const std::string& family) { return family.rfind("uniform-", 0) == 0; }

// The uniform samplers of scenarios/ (the scenario generators of the same name, default parameters:
// punctured triangulations, 3-connected maps with their largest face outside), with the outer face
// the packing uses; they have no positions. unit-disk-field: the scenario generator `field` with n
// sensors uniform in the unit square joined by LDel² of the unit-disk graph of radius 2.236/√n
// (about 15.7 sensors in range on average, as comparison-5000.yaml's 0.0316 at n = 5000), repaired
// to its 3-connected core.
core::GraphInput make(const GenerateArgs& a, std::uint64_t seed) {
  if (a.family == "unit-disk-field") {
    scenarios::TopologyParams params;
    params.set("n", static_cast<std::int64_t>(a.size));
    params.set("graph", std::string("local-delaunay"));
    params.set("radius", 2.236 / std::sqrt(static_cast<double>(a.size)));
    params.set("repair", std::string("three-connected-core"));
    scenarios::Topology t = scenarios::build_topology("field", params, seed);
    return core::GraphInput{std::move(t.graph), std::move(t.positions), t.name + " seed " + std::to_string(seed)};
  }
  if (uniform_family(a.family)) {
    scenarios::TopologyParams params;
    params.set("n", static_cast<std::int64_t>(a.size));
    scenarios::Topology t = scenarios::build_topology(a.family, params, seed);
    return core::GraphInput{std::move(t.graph), {}, t.name + " seed " + std::to_string(seed)};
  }
  return a.family == "delaunay" ? core::random_delaunay_triangulation(a.size, seed)
                                : core::random_three_connected(a.size, seed);
}

int run_generate(const GenerateArgs& a) {
  if (uniform_family(a.family) && a.format == "coords")
    throw core::InputError("--format", 0, "family " + a.family + " has no vertex positions; use --format edges or planar_code.");
  if (a.count != 1 && a.format != "planar_code")
    throw core::InputError("--count", 0, "greater than 1 needs --format planar_code (the only multi-graph format).");
  std::string text;
  if (a.format == "planar_code") {
    std::vector<core::PlanarGraph> graphs;
    for (std::size_t i = 0; i < a.count; ++i) graphs.push_back(make(a, a.seed + i).graph);
    text = core::write_planar_code(graphs);
  } else {
    const core::GraphInput in = make(a, a.seed);
    text = a.format == "coords" ? write_coords(in) : core::write_edge_list(in.graph);
  }
  if (a.out.empty() || a.out == "-") {
    std::cout << text;
    return 0;
  }
  check_writable(a.out, a.force);
  std::ofstream(a.out, std::ios::binary) << text;
  std::cerr << "wrote " << a.out << ": " << a.count << " graph(s) of " << a.size << " vertices\n";
  return 0;
}
}  // namespace

Action add_generate_command(CLI::App& app) {
  const auto c = add_command<GenerateArgs>(app, generate_help);
  c.cmd->add_option("family", c.args->family,
                  "delaunay (triangulated disc), three-connected, uniform-triangulation (Poulalhon-Schaeffer, punctured) "
                  "uniform-three-connected (Fusy, largest face outside; the uniform ones have no positions) or "
                  "unit-disk-field (n sensors in the unit square, LDel^2 of the unit-disk graph of radius 2.236/sqrt(n), "
                  "3-connected core)")
      ->required()->check(CLI::IsMember({"delaunay", "three-connected", "uniform-triangulation", "uniform-three-connected",
                                         "unit-disk-field"}));
  c.cmd->add_option("--size,-n", c.args->size, "Number of vertices")->check(CLI::Range(4, 100000000))->capture_default_str();
  c.cmd->add_option("--seed", c.args->seed, "Random seed")->check(seed_validator())->capture_default_str();
  c.cmd->add_option("--format", c.args->format, "coords (with positions), edges or planar_code (binary)")
      ->check(CLI::IsMember({"coords", "edges", "planar_code"}))->capture_default_str();
  c.cmd->add_option("--count", c.args->count, "Number of graphs (seeds SEED, SEED+1, ...; planar_code only)")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  c.cmd->add_option("-o,--out", c.args->out, "Output file (default: standard output)");
  c.cmd->add_flag("--force", c.args->force, "Overwrite an existing output file");
  return [args = c.args] { return run_generate(*args); };
}

}  // namespace laguerre::tools
