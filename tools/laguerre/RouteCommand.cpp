// `laguerre route`: route packets over an embedding and print delivery and stretch per scheme.
#include <cstdio>
#include <iostream>

#include "Commands.hpp"
#include "Common.hpp"
#include "EmbeddingJson.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

namespace laguerre::tools {

namespace {
struct RouteArgs {
  std::string input;
  std::string format = "automatic";
  std::size_t index = 1;
  std::string scheme = "all";
  std::string pairs = "all";
  std::uint64_t seed = 1;
  std::string positions = "layout";
  bool json = false;
};

std::vector<core::Scheme> parse_schemes(const std::string& s) {
  if (s == "all") return {core::all_schemes.begin(), core::all_schemes.end()};
  std::string name = s;
  for (char& c : name)
    if (c == '-') c = '_';
  if (auto sc = core::parse_scheme(name)) return {*sc};
  throw std::invalid_argument("Unknown routing scheme '" + s + "'; expected greedy-power, greedy-euclid, compass, gfg or all.");
}

core::PairSelection parse_pairs(const std::string& s, std::uint64_t seed) {
  if (s == "all") return {0, seed};
  try {
    std::size_t used = 0;
    const unsigned long long n = std::stoull(s, &used);
    if (used == s.size() && n > 0) return {static_cast<std::size_t>(n), seed};
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("--pairs expects 'all' or a positive number of sampled pairs, found '" + s + "'.");
}

int run_route(const RouteArgs& a) {
  const auto schemes = parse_schemes(a.scheme);
  const core::PairSelection selection = parse_pairs(a.pairs, a.seed);
  core::PlanarGraph g;
  core::CircleEmbedding phi;
  std::string name;
  std::string origin;
  if (is_embedding_file(a.input)) {
    EmbeddedGraph e = read_embedding(a.input);
    g = std::move(e.graph);
    phi = std::move(e.circles);
    name = e.name;
    origin = "embedding file";
  } else {
    LoadedGraph loaded = load_graph(a.input, a.format, a.index);
    g = loaded.input.graph;
    name = loaded.input.name;
    if (a.positions == "input") {
      if (loaded.input.positions.empty())
        throw std::invalid_argument("--positions input needs a graph file with coordinates (coords format); " + a.input +
                                    " has none.");
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
      nlohmann::json fails = nlohmann::json::array();
      for (const auto& f : st.failures)
        fails.push_back({{"source", g.id(f.source)},
                         {"target", g.id(f.target)},
                         {"stuck", f.stuck == core::none ? nlohmann::json() : nlohmann::json(g.id(f.stuck))},
                         {"outcome", std::string(core::to_string(f.outcome))}});
      out.push_back({{"scheme", std::string(core::to_string(s))},
                     {"pairs", st.pairs},
                     {"delivered", st.delivered},
                     {"delivery_rate", st.delivery_rate},
                     {"hops_mean", st.hops_mean},
                     {"stretch_mean", st.stretch_mean},
                     {"stretch_p95", st.stretch_p95},
                     {"stretch_max", st.stretch_max},
                     {"failures_total", st.failures_total},
                     {"failures", fails}});
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
  auto args = std::make_shared<RouteArgs>();
  CLI::App* cmd = app.add_subcommand("route", "Route packets over an embedding and report delivery and hop stretch.");
  cmd->footer("A graph file is first packed to LPD/GLPD; an embedding file from `laguerre pack` is used as is.");
  cmd->add_option("input", args->input, "Graph file, or embedding JSON written by `laguerre pack`")->required()->check(CLI::ExistingFile);
  cmd->add_option("--format", args->format, "Graph format: automatic, edges, coords, planar_code")->capture_default_str();
  cmd->add_option("--index", args->index, "Which graph of a multi-graph file (from 1)")->capture_default_str();
  cmd->add_option("--scheme", args->scheme, "greedy-power, greedy-euclid, compass, gfg or all")->capture_default_str();
  cmd->add_option("--pairs", args->pairs, "'all' ordered pairs, or a number of pairs sampled with --seed")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Seed of the pair sample")->capture_default_str();
  cmd->add_option("--positions", args->positions, "For a graph file: layout (pack first) or input (its coordinates)")
      ->check(CLI::IsMember({"layout", "input"}))->capture_default_str();
  cmd->add_flag("--json", args->json, "Machine-readable output");
  return [args] { return run_route(*args); };
}

}  // namespace laguerre::tools
