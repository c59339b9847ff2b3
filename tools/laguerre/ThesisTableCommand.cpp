// `laguerre thesis-table`: the experiment of thesis §5.4.1 — iterations to LPD/GLPD versus iterations to
// an exact packing on ~50-vertex random triangulations and 3-connected planar graphs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "Common.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp thesis_table_help{
    "thesis-table",
    "Reproduce the experiment of thesis §5.4.1 (iterations to LPD vs exact packing).",
    "Without graph files: random Delaunay triangulations and 3-connected graphs obtained from them by\n"
    "deleting edges (the interim random families documented in RandomGraphs.hpp), and uniform random\n"
    "triangulations of the sphere (Poulalhon-Schaeffer, every face a triangle; --family picks among them).\n"
    "Every triangulated sphere (the spheres family; a graph file's, every face a triangle) is packed once\n"
    "per --outer rule, the same graphs each time: face keeps a face outside, puncture removes the vertex\n"
    "of largest degree (its neighbours become the boundary; it is counted in removed_vertices)."};

struct TableArgs {
  std::size_t count = 20;
  std::size_t size = 50;
  std::uint64_t seed = 2008;
  int steps = 1;
  std::string sweep = "jacobi";
  int max_iterations = 200000;
  std::vector<std::string> files;
  bool json = false;
  std::string accelerate = "plain";
  std::vector<std::string> families{"delaunay", "three-connected", "spheres"};
  std::vector<std::string> outer{"face", "puncture"};
};

struct Row {
  std::string name;
  std::string group;  ///< the family row it belongs to ("triangulations", "spheres/puncture", ...)
  std::string outer;  ///< the outer rule, for a triangulated sphere; else empty
  std::size_t removed = 0;
  core::GraphKind kind{};
  std::size_t n = 0;
  int to_lpd = -1, to_exact = -1;
  double delivery = 0;
  std::string status;
};

struct Summary {
  double mean = 0, sd = 0, min = 0, max = 0;
};

Summary summarize(const std::vector<double>& v) {
  Summary s;
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / static_cast<double>(v.size() - 1)) : 0;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  return s;
}

Row measure(const core::PlanarGraph& g, core::GraphKind kind, const std::string& name, const TableArgs& a) {
  core::PackOptions opt;
  opt.steps_per_check = a.steps;
  opt.sweep = core::parse_name(core::sweep_names, a.sweep, "--sweep");
  opt.max_iterations = a.max_iterations;
  opt.acceleration = core::parse_name(core::acceleration_names, a.accelerate, "--accelerate");
  Row row;
  row.name = name;
  row.kind = kind;
  row.n = g.num_vertices();
  opt.stop = core::StopRule::lpd;
  const core::PackResult lpd = core::pack(g, opt);
  row.status = std::string(core::to_string(lpd.status));
  if (lpd.status == core::PackStatus::converged) {
    row.to_lpd = lpd.iterations;
    const auto st = core::evaluate_routing(g, lpd.circles, core::Scheme::greedy_power, {});
    row.delivery = st.delivery_rate;
  }
  opt.stop = core::StopRule::exact;
  const core::PackResult exact = core::pack(g, opt);
  if (exact.status == core::PackStatus::converged) row.to_exact = exact.iterations;
  return row;
}

int run_table(const TableArgs& a) {
  std::vector<Row> rows;
  std::vector<std::string> groups;  // in order of appearance
  // Measures `in` under each --outer rule if it is a triangulated sphere (family `family`, or its kind's
  // name when empty), else once.
  auto add = [&](const core::GraphInput& in, const std::string& family) {
    const bool sphere = core::is_triangulated_sphere(in.graph);
    for (const std::string& rule : sphere ? a.outer : std::vector<std::string>{"face"}) {
      core::GraphInput copy = in;
      const core::PreparedInput prepared =
          core::prepare_input(copy, core::parse_name(core::outer_rule_names, rule, "--outer"));
      Row row = measure(copy.graph, prepared.kind, in.name, a);
      row.group = family.empty() ? (prepared.kind == core::GraphKind::triangulated_disc ? "triangulations" : "3-connected")
                                 : family;
      if (sphere) {
        row.outer = rule;
        row.group += "/" + rule;
      }
      row.removed = prepared.removed.size();
      if (std::find(groups.begin(), groups.end(), row.group) == groups.end()) groups.push_back(row.group);
      rows.push_back(std::move(row));
    }
  };
  if (a.files.empty()) {
    std::size_t done = 0;
    const std::size_t total = a.count * a.families.size();
    for (const std::string& family : a.families) {
      for (std::size_t i = 0; i < a.count; ++i) {
        if (family == "spheres") {
          add(core::GraphInput{scenarios::uniform_triangulation(a.size, a.seed + 2000 + i), {},
                               "sphere#" + std::to_string(i + 1), true},
              "spheres");
        } else {  // the hull (Delaunay) or the largest face (3-connected) outside, whatever --outer says
          const bool delaunay = family == "delaunay";
          const core::GraphInput t = delaunay ? core::random_delaunay_triangulation(a.size, a.seed + i)
                                              : core::random_three_connected(a.size, a.seed + 1000 + i);
          core::GraphKind kind{};
          const core::PlanarGraph g = core::prepare_for_packing(t, &kind);
          Row row = measure(g, kind, (delaunay ? "delaunay#" : "3conn#") + std::to_string(i + 1), a);
          row.group = delaunay ? "triangulations" : "3-connected";
          if (std::find(groups.begin(), groups.end(), row.group) == groups.end()) groups.push_back(row.group);
          rows.push_back(std::move(row));
        }
        std::fprintf(stderr, "\r  %zu/%zu graphs", ++done, total);
      }
    }
    std::fprintf(stderr, "\n");
  } else {
    for (const auto& f : a.files)
      for (auto& in : read_graph_file(f)) add(in, "");
  }

  nlohmann::json families = nlohmann::json::array();
  if (!a.json)
    std::printf("Thesis §5.4.1: iterations (Jacobi sweeps, checked every %d) to a greedy power embedding vs an exact "
                "packing\n%-24s %6s %6s %22s %22s %14s %14s %9s %8s\n",
                a.steps, "family", "graphs", "n", "to LPD/GLPD mean±sd", "to exact mean±sd", "ratio(mean)", "ratio(means)",
                "delivery", "removed");
  for (const std::string& fam : groups) {
    std::vector<double> lpd, exact, ratio, n, delivery;
    std::size_t graphs = 0, failed = 0, removed = 0;
    std::string outer;
    for (const Row& r : rows) {
      if (r.group != fam) continue;
      outer = r.outer;
      removed += r.removed;
      ++graphs;
      n.push_back(static_cast<double>(r.n));
      if (r.to_lpd < 0 || r.to_exact < 0) {
        ++failed;
        continue;
      }
      lpd.push_back(r.to_lpd);
      exact.push_back(r.to_exact);
      ratio.push_back(static_cast<double>(r.to_exact) / std::max(1, r.to_lpd));
      delivery.push_back(r.delivery);
    }
    if (graphs == 0) continue;
    const Summary sl = summarize(lpd), se = summarize(exact), sr = summarize(ratio), sn = summarize(n),
                  sd = summarize(delivery);
    const double ratio_of_means = sl.mean > 0 ? se.mean / sl.mean : 0;
    if (a.json) {
      families.push_back({{"family", fam}, {"outer", outer.empty() ? nlohmann::json() : nlohmann::json(outer)},
                          {"removed_vertices", removed}, {"graphs", graphs}, {"not_converged", failed}, {"n_mean", sn.mean},
                          {"to_lpd", {{"mean", sl.mean}, {"sd", sl.sd}, {"min", sl.min}, {"max", sl.max}}},
                          {"to_exact", {{"mean", se.mean}, {"sd", se.sd}, {"min", se.min}, {"max", se.max}}},
                          {"ratio_mean", sr.mean}, {"ratio_of_means", ratio_of_means}, {"greedy_delivery_min", sd.min},
                          {"greedy_delivery_mean", sd.mean}});
      continue;
    }
    char a1[64], a2[64];
    std::snprintf(a1, sizeof a1, "%.1f±%.1f [%g,%g]", sl.mean, sl.sd, sl.min, sl.max);
    std::snprintf(a2, sizeof a2, "%.1f±%.1f [%g,%g]", se.mean, se.sd, se.min, se.max);
    std::printf("%-24s %6zu %6.1f %22s %22s %14.2f %14.2f %8.2f%% %8zu\n", fam.c_str(), graphs, sn.mean, a1, a2, sr.mean,
                ratio_of_means, 100 * sd.min, removed);
    if (failed) std::printf("  (%zu graphs did not converge within %d iterations)\n", failed, a.max_iterations);
  }
  if (a.json) {
    nlohmann::json per_graph = nlohmann::json::array();
    for (const Row& r : rows)
      per_graph.push_back({{"name", r.name}, {"family", r.group}, {"kind", std::string(core::to_string(r.kind))},
                           {"outer", r.outer.empty() ? nlohmann::json() : nlohmann::json(r.outer)},
                           {"removed_vertices", r.removed}, {"n", r.n},
                           {"to_lpd", r.to_lpd}, {"to_exact", r.to_exact}, {"greedy_delivery", r.delivery},
                           {"status", r.status}});
    std::cout << nlohmann::json{{"families", families}, {"graphs", per_graph}}.dump(1) << '\n';
  } else {
    std::printf("Thesis (Fusy's uniform graphs, ~50 vertices): triangulations < 100 iterations, exact/LPD ratio 3.8; "
                "3-connected 100-500 iterations, ratio 1.8.\n"
                "delivery = worst greedy power delivery rate over the family's LPD/GLPD embeddings (all ordered pairs "
                "of the embedded vertices); removed = vertices --outer puncture took out of the family's spheres "
                "(one per graph; not packed, not routed); n counts the vertices packed.\n");
  }
  return 0;
}
}  // namespace

Action add_thesis_table_command(CLI::App& app) {
  const auto c = add_command<TableArgs>(app, thesis_table_help);
  c.cmd->add_option("graphs", c.args->files, "Graph files to use instead of the random families");
  c.cmd->add_option("--count", c.args->count, "Graphs per family")->capture_default_str();
  c.cmd->add_option("--size", c.args->size, "Vertices per random graph")->capture_default_str();
  c.cmd->add_option("--seed", c.args->seed, "Seed of the first random graph")->check(seed_validator())->capture_default_str();
  c.cmd->add_option("--steps-per-check,-N", c.args->steps, "Sweeps between checks")->check(CLI::Range(1, 10000))->capture_default_str();
  add_choice(*c.cmd, "--sweep", c.args->sweep, core::sweep_names, "jacobi or gauss-seidel");
  c.cmd->add_option("--max-iterations", c.args->max_iterations, "Cap on sweeps per run")
      ->check(CLI::Range(1, 100000000))->capture_default_str();
  c.cmd->add_flag("--json", c.args->json, "Machine-readable output");
  add_acceleration_option(*c.cmd, c.args->accelerate);
  c.cmd->add_option("--family", c.args->families,
                    "Random families without graph files: delaunay, three-connected, spheres (uniform random sphere "
                    "triangulations); repeatable")
      ->check(CLI::IsMember({"delaunay", "three-connected", "spheres"}))->capture_default_str();
  c.cmd->add_option("--outer", c.args->outer,
                    "Outer rules a triangulated sphere is packed under, each on the same graphs: face, puncture; "
                    "repeatable")
      ->check(CLI::IsMember(core::names_of(core::outer_rule_names)))->capture_default_str();
  return [args = c.args] { return run_table(*args); };
}

}  // namespace laguerre::tools
