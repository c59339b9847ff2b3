// `laguerre route`: route packets over an embedding and print delivery and stretch per scheme.
#include <cstdio>
#include <iostream>

#include "Commands.hpp"
#include "Common.hpp"
#include "EmbeddingJson.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp route_help{
    "route",
    "Route packets over an embedding and report delivery and hop stretch.",
    "A graph file is first packed to LPD/GLPD; an embedding file from `laguerre pack` is used as is."};

struct RouteArgs {
  GraphArgs input;
  std::string scheme = "all";
  std::string pairs = "all";
  std::uint64_t seed = 1;
  std::string positions = "layout";
  bool json = false;
};

int run_route(const RouteArgs& a) {
  const auto schemes = parse_schemes(a.scheme, "--scheme");
  const core::PairSelection selection = parse_pairs(a.pairs, a.seed, "--pairs");
  core::PlanarGraph g;
  core::CircleEmbedding phi;
  std::string name;
  std::string origin;
  (void)core::open_input_file(a.input.path, "graph or embedding file");
  if (is_embedding_file(a.input.path)) {
    EmbeddedGraph e = read_embedding(a.input.path);
    g = std::move(e.graph);
    phi = std::move(e.circles);
    name = e.name;
    origin = "embedding file";
  } else {
    LoadedGraph loaded = load_graph(a.input);
    g = loaded.input.graph;
    name = loaded.input.name;
    if (a.positions == "input") {
      if (loaded.input.positions.empty())
        throw core::InputError("--positions", 0,
                               "input needs a graph file with coordinates (coords format); " + a.input.path + " has none.");
      for (const auto& p : loaded.input.positions) phi.push_back({p.x, p.y, 0.0});
      origin = "input coordinates (radius 0)";
    } else {
      const core::PackResult r = core::pack(g);
      if (r.status != core::PackStatus::converged)
        std::cerr << "laguerre: warning: the packing did not reach LPD/GLPD (" << core::to_string(r.status)
                  << "); routing on the last layout.\n";
      phi = r.circles;
      origin = "greedy power embedding after " + std::to_string(r.iterations) + " iterations";
    }
  }
  nlohmann::json out = nlohmann::json::array();
  if (!a.json) {
    std::printf("%s: %zu vertices, %zu edges; positions: %s\n", name.c_str(), g.num_vertices(), g.num_edges(),
                origin.c_str());
    std::printf("%-14s %9s %9s %9s %9s %9s %9s %9s\n", "scheme", "pairs", "delivered", "rate", "hops", "stretch",
                "p95", "max");
  }
  bool all_delivered = true;
  for (core::Scheme s : schemes) {
    const core::RoutingStats st = core::evaluate_routing(g, phi, s, selection);
    all_delivered &= st.delivered == st.pairs;
    if (a.json) {
      out.push_back(routing_stats_json(g, st));
      continue;
    }
    std::printf("%-14s %9zu %9zu %8.2f%% %9.2f %9.3f %9.3f %9.3f\n", std::string(core::to_string(s)).c_str(), st.pairs,
                st.delivered, 100 * st.delivery_rate, st.hops_mean, st.stretch_mean, st.stretch_p95, st.stretch_max);
    for (std::size_t i = 0; i < st.failures.size() && i < 3; ++i) {
      const auto& f = st.failures[i];
      std::printf("  %s %llu -> %llu at %llu\n", std::string(core::to_string(f.outcome)).c_str(),
                  static_cast<unsigned long long>(g.id(f.source)), static_cast<unsigned long long>(g.id(f.target)),
                  static_cast<unsigned long long>(f.stuck == core::none ? 0 : g.id(f.stuck)));
    }
  }
  if (a.json) std::cout << nlohmann::json{{"graph", name}, {"positions", origin}, {"schemes", out}}.dump(1) << '\n';
  (void)all_delivered;  // failures are results (e.g. greedy Euclidean dead ends), not errors
  return 0;
}
}  // namespace

Action add_route_command(CLI::App& app) {
  const auto c = add_command<RouteArgs>(app, route_help);
  add_graph_options(*c.cmd, c.args->input, "input", "Graph file, or embedding JSON written by `laguerre pack`");
  c.cmd->add_option("--scheme", c.args->scheme, "greedy-power, greedy-euclid, compass, gfg, hyperbolic (Kleinberg's tree embedding; not in all) or all")->capture_default_str();
  c.cmd->add_option("--pairs", c.args->pairs, "'all' ordered pairs, or a number of pairs sampled with --seed")->capture_default_str();
  c.cmd->add_option("--seed", c.args->seed, "Seed of the pair sample")->check(seed_validator())->capture_default_str();
  c.cmd->add_option("--positions", c.args->positions, "For a graph file: layout (pack first) or input (its coordinates)")
      ->check(CLI::IsMember({"layout", "input"}))->capture_default_str();
  c.cmd->add_flag("--json", c.args->json, "Machine-readable output");
  return [args = c.args] { return run_route(*args); };
}

}  // namespace laguerre::tools
