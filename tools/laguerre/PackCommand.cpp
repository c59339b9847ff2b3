// `laguerre pack`: compute a greedy power embedding and write it as JSON plus a picture.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include "Commands.hpp"
#include "Common.hpp"
#include "EmbeddingJson.hpp"
#include "Render.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp pack_help{"pack", "Compute a greedy power embedding of a planar graph (thesis §5.3).",
                                "Exit status: 0 converged, 3 not converged (iteration cap, time limit or precision loss), 2 bad input."};

struct PackArgs {
  GraphArgs graph;
  std::string stop = "lpd";
  std::string sweep = "jacobi";
  std::string root = "deepest";
  int steps = 1;
  int max_iterations = 100000;
  double time_limit = 0;
  double epsilon = 1e-9;
  std::string out;
  bool force = false;
  bool json_stdout = false;
  bool no_picture = false;
  std::string accelerate = "plain";
  std::string newton_solver = "cholesky";
  std::string layout_method = "frames";
  std::string layout_arithmetic = "binary64";
  std::string termination = "layout";
  std::string pairs;  // empty: no routing check
  std::uint64_t seed = 1;
};

class ProgressPrinter : public core::PackVisitor {
public:
  explicit ProgressPrinter(std::size_t n) : n_(n), start_(std::chrono::steady_clock::now()) {}
  void on_layout(int /*iteration*/, const core::Layout& layout) override {
    smallest_ = layout.smallest_radius;
    precision_ = layout.precision;
  }
  void on_check(int iteration, double angle_error, std::size_t ok) override {
    if (!line_.due()) return;
    char text[256];
    std::snprintf(text, sizeof text,
                  "  iteration %d, %.0f s: %zu/%zu vertices satisfy LPD, angle error %.3g, smallest radius %.3g%s%s",
                  iteration, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(), ok, n_,
                  angle_error, smallest_, precision_ == core::Precision::ok ? "" : ", precision ",
                  precision_ == core::Precision::ok ? "" : core::name_of(core::precision_names, precision_).data());
    line_.draw(text);
  }

  void on_unchecked(int iteration, double angle_error, core::Precision precision) override {
    if (!line_.due()) return;
    char text[256];
    std::snprintf(text, sizeof text, "  iteration %d, %.0f s: layout %s, LPD not checked, angle error %.3g, smallest radius %.3g",
                  iteration, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(),
                  core::name_of(core::precision_names, precision).data(), angle_error, smallest_);
    line_.draw(text);
  }

private:
  std::size_t n_;
  std::chrono::steady_clock::time_point start_;
  TerminalLine line_;
  double smallest_ = 0;
  core::Precision precision_ = core::Precision::ok;
};

int run_pack(const PackArgs& a) {
  const LoadedGraph loaded = load_graph(a.graph);
  const core::PlanarGraph& g = loaded.input.graph;
  core::PackOptions opt;
  opt.stop = core::parse_name(core::stop_rule_names, a.stop, "--stop");
  opt.sweep = core::parse_name(core::sweep_names, a.sweep, "--sweep");
  opt.root = core::parse_name(core::root_rule_names, a.root, "--root");
  opt.steps_per_check = a.steps;
  opt.max_iterations = a.max_iterations;
  opt.time_limit = a.time_limit;
  opt.angle_epsilon = a.epsilon;
  opt.acceleration = core::parse_name(core::acceleration_names, a.accelerate, "--accelerate");
  opt.newton_solver = core::parse_name(core::newton_solver_names, a.newton_solver, "--newton-solver");
  opt.layout_method = core::parse_name(core::layout_method_names, a.layout_method, "--layout");
  opt.layout_arithmetic = core::parse_name(core::layout_arithmetic_names, a.layout_arithmetic, "--layout-arithmetic");
  opt.termination = core::parse_name(core::termination_names, a.termination, "--termination");
  if (opt.layout_arithmetic == core::LayoutArithmetic::mixed && opt.layout_method != core::LayoutMethod::frames)
    throw core::InputError("--layout-arithmetic", 0,
                           "found 'mixed' with --layout " + a.layout_method + "; expected --layout frames (the mixed "
                           "arithmetic computes the frames' local steps in doubles; the wave has no frames)");
  if (opt.termination != core::Termination::layout && opt.stop != core::StopRule::lpd)
    throw core::InputError("--termination", 0,
                           "found '" + a.termination + "' with --stop " + a.stop +
                               "; expected layout (the radius-only gate serves the LPD/GLPD rule only)");

  const std::optional<core::PairSelection> pairs =
      a.pairs.empty() ? std::nullopt : std::optional(parse_pairs(a.pairs, a.seed, "--pairs"));
  const std::string stem = a.out.empty() ? file_stem(a.graph.path) + "-packing" : a.out;
  if (!a.json_stdout) check_writable(stem + ".json", a.force);
  if (!a.no_picture) {
    check_writable(stem + ".svg", a.force);
    check_writable(stem + ".png", a.force);
  }

  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  core::PackResult r;
  {
    ProgressPrinter progress(g.num_vertices());
    r = core::pack(g, opt, &progress);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;  // all threads of the process

  // Every LPD/GLPD decision is an exact predicate on the stored coordinates (doubles, or the binary128
  // circles a binary128 layout keeps); they are "exact decisions on representable coordinates" when
  // those coordinates carry every circle (docs/precision.md).
  const bool exact_decisions = r.layout.precision == core::Precision::ok || r.layout.precision == core::Precision::degraded;
  // The significand a node would need for every circle to span 2^20 ulps (Layout::degraded_resolution).
  const int bits_needed = core::significand_bits_needed(r.layout);
  const int bytes = core::bytes_per_coordinate(r.layout);
  nlohmann::json doc;
  doc["format"] = "laguerre-embedding";
  doc["version"] = 1;
  doc["name"] = loaded.input.name;
  doc["kind"] = std::string(core::to_string(loaded.kind));
  doc["outer_rule"] = a.graph.outer;
  doc["removed_vertices"] = loaded.removed;
  doc["packing"] = {{"status", std::string(core::to_string(r.status))},
                    {"stop_rule", std::string(core::to_string(r.rule))},
                    {"iterations", r.iterations},
                    {"accelerated_jumps", r.jumps},
                    {"newton_solver", opt.acceleration == core::Acceleration::newton ? nlohmann::json(a.newton_solver) : nlohmann::json()},
                    {"steps_per_check", a.steps},
                    {"newton_krylov", opt.acceleration == core::Acceleration::newton_krylov
                                          ? nlohmann::json{{"cg_iterations", r.linear_iterations},
                                                           {"exchanges", r.exchanges},
                                                           {"tree_sums", r.tree_sums}}
                                          : nlohmann::json()},
                    {"sweep", a.sweep},
                    {"termination", a.termination},
                    {"layouts", r.layouts},
                    {"angle_error", r.angle_error},
                    {"max_tangency_error", r.max_tangency_error},
                    {"local_ok", r.local_ok},
                    {"unchecked_layouts", r.skipped_checks},
                    {"smallest_radius", r.layout.smallest_radius},
                    {"precision", {{"status", std::string(core::name_of(core::precision_names, r.layout.precision))},
                                   {"exact_decisions", exact_decisions},
                                   {"resolution", r.layout.resolution},
                                   {"layout", a.layout_method},
                                   {"arithmetic", a.layout_arithmetic},
                                   {"bytes_per_coordinate", bytes},
                                   {"significand_bits_needed", bits_needed}}},
                    {"root", r.layout.root == core::none ? nlohmann::json() : nlohmann::json(g.id(r.layout.root))},
                    {"seconds", seconds},
                    {"cpu_seconds", cpu_seconds},
                    {"time_limit", a.time_limit > 0 ? nlohmann::json(a.time_limit) : nlohmann::json()},
                    {"phase_seconds", {{"setup", r.phase_seconds.setup},
                                       {"sweeps", r.phase_seconds.sweeps},
                                       {"jacobian", r.phase_seconds.jacobian},
                                       {"solve", r.phase_seconds.solve},
                                       {"line_search", r.phase_seconds.line_search},
                                       {"layout", r.phase_seconds.layout},
                                       {"checks", r.phase_seconds.checks},
                                       {"final", r.phase_seconds.final}}}};
  std::vector<std::string> local;
  local.reserve(g.num_vertices());
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) local.emplace_back(core::to_string(r.local[v]));
  nlohmann::json faces = nlohmann::json::array();
  const core::PackingComplex k = r.face_circles.empty() ? core::PackingComplex{} : core::PackingComplex::from_graph(g);
  for (std::size_t i = 0; i < r.face_circles.size(); ++i) {
    nlohmann::json ids = nlohmann::json::array();
    for (core::Dart d : g.face_darts(k.face_of_vertex[i])) ids.push_back(g.id(g.tail(d)));
    faces.push_back({{"face", ids}, {"x", r.face_circles[i].x}, {"y", r.face_circles[i].y}, {"r", r.face_circles[i].r}});
  }
  doc["face_circles"] = faces;

  // Greedy power routing on the coordinates LPD was decided on (binary128 circles when the layout kept
  // them): the check of the delivery theorem on this embedding, in the arithmetic a node would store.
  std::optional<core::RoutingStats> routing;
  if (pairs && r.layout.precision != core::Precision::unrepresentable) {
    const core::CircleEmbedding128* phi128 = r.circles128.empty() ? nullptr : &r.circles128;
    routing = core::evaluate_routing(g, r.circles, core::Scheme::greedy_power, *pairs, phi128);
    doc["routing"] = routing_stats_json(g, *routing);
    doc["routing"]["seed"] = pairs->seed;
  }

  if (a.json_stdout) {
    write_embedding_json(std::cout, std::move(doc), g, r.circles, local);
    std::cout << '\n';
  } else {
    std::ofstream out(stem + ".json");
    write_embedding_json(out, std::move(doc), g, r.circles, local);
    out << '\n';
  }
  std::vector<std::string> pictures;
  if (!a.no_picture) {
    PackingPicture pic;
    pic.graph = &g;
    pic.circles = &r.circles;
    for (auto c : r.local) pic.ok.push_back(c == core::LocalCondition::holds);
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) pic.cells.push_back(core::local_cell_polygon(g, r.circles, v));
    if (!r.face_circles.empty()) pic.face_circles = &r.face_circles;
    pic.title = std::filesystem::path(loaded.input.name).filename().string() + ": " + std::to_string(r.iterations) + " iterations, " +
                std::string(core::to_string(r.status)) + " (" + a.stop + ")";
    pictures = render_packing(pic, stem);
  }
  std::ostream& os = a.json_stdout ? std::cerr : std::cout;
  os << "graph        " << loaded.input.name << ": " << g.num_vertices() << " vertices, " << g.num_edges()
     << " edges, " << core::to_string(loaded.kind) << ", boundary of " << g.boundary_cycle().size() << '\n'
     << removed_line(loaded.removed)
     << "status       " << core::to_string(r.status) << " (stop rule " << core::to_string(r.rule) << ") after "
     << r.iterations << " iterations, " << seconds << " s (" << cpu_seconds << " s CPU)\n";
  if (r.status == core::PackStatus::iteration_cap)
    os << "             --max-iterations " << a.max_iterations << " reached before the stop rule held\n";
  else if (r.status == core::PackStatus::time_limit)
    os << "             --time-limit " << a.time_limit << " s reached before the stop rule held (the last layout is checked and written)\n";
  else if (r.status == core::PackStatus::precision_loss)
    os << "             the layout is " << core::name_of(core::precision_names, r.layout.precision)
       << (bytes == 16 ? " in binary128 (" : " in doubles (") << (r.layout.precision == core::Precision::collapsed
                                  ? "a circle spans fewer than 16 units in the last place of its coordinates"
                                  : "NaN, infinite or non-positive radius")
       << "): nothing is claimed\n";
  {
    const core::PackPhaseSeconds& p = r.phase_seconds;
    char text[256];
    std::snprintf(text, sizeof text,
                  "phases       setup %.2f, sweeps %.2f, jacobian %.2f, solve %.2f, line search %.2f, layout %.2f, checks %.2f, final %.2f s\n",
                  p.setup, p.sweeps, p.jacobian, p.solve, p.line_search, p.layout, p.checks, p.final);
    os << text;
  }
  if (opt.termination != core::Termination::layout)
    os << "termination  " << a.termination << ": " << r.layouts << " layouts and exact checks for " << r.iterations
       << " iterations\n";
  if (r.skipped_checks > 0)
    os << "             " << r.skipped_checks << " collapsed or unrepresentable layouts mid-run were not checked (the final one is)\n";
  if (opt.acceleration == core::Acceleration::newton)
    os << "newton       linear solver " << a.newton_solver
       << (opt.newton_solver == core::NewtonSolver::cholesky ? " (" + std::string(core::cholesky_backend()) + ")" : "")
       << ", " << r.jumps << " improving Newton steps\n";
  os
     << (loaded.kind == core::GraphKind::triangulated_disc ? "LPD          " : "GLPD         ") << r.local_ok << " / "
     << g.num_vertices() << " vertices\n"
     << "angle error  " << r.angle_error << " rad\n"
     << "tangency     max error " << r.max_tangency_error << " of the smaller radius\n"
     << "radii        smallest " << r.layout.smallest_radius << '\n'
     << "precision    " << core::name_of(core::precision_names, r.layout.precision) << ": every circle spans ≥ "
     << r.layout.resolution << " units in the last place of its coordinates ("
     << (bytes == 16 ? "16-byte binary128, on which LPD was decided" : "8-byte doubles") << "; layout " << a.layout_method
     << ", " << a.layout_arithmetic << "); decisions "
     << (exact_decisions ? "exact on representable coordinates" : "exact on the stored numbers, which do not carry the packing")
     << '\n';
  if (bits_needed > (bytes == 16 ? 113 : 53))
    os << "             coordinates with a " << bits_needed << "-bit significand would carry every circle to 2^-20"
       << (bytes == 16 ? "\n" : " (binary128 has 113: --layout-arithmetic mixed or binary128)\n");
  if (routing)
    os << "routing      greedy power on the " << routing->coordinate_bytes << "-byte coordinates: "
       << routing->delivered << " / " << routing->pairs << " sampled pairs delivered (seed " << pairs->seed
       << "), " << routing->hops_mean << " hops on average, stretch " << routing->stretch_mean << " (max "
       << routing->stretch_max << ")\n";
  else if (pairs)
    os << "routing      not checked: the layout is unrepresentable\n";
  if (!a.json_stdout) os << "wrote        " << stem << ".json\n";
  for (const auto& p : pictures) os << "wrote        " << p << '\n';
  return r.status == core::PackStatus::converged ? 0 : 3;
}
}  // namespace

Action add_pack_command(CLI::App& app) {
  const auto c = add_command<PackArgs>(app, pack_help);
  add_graph_options(*c.cmd, c.args->graph, "graph", "Graph file (edge list, coords or planar_code)");
  add_outer_option(*c.cmd, c.args->graph);
  add_choice(*c.cmd, "--stop", c.args->stop, core::stop_rule_names,
             "Stopping rule: lpd (LPD/GLPD everywhere), exact, angle, cap");
  add_choice(*c.cmd, "--sweep", c.args->sweep, core::sweep_names, "Update order: jacobi or gauss-seidel");
  add_choice(*c.cmd, "--root", c.args->root, core::root_rule_names, "Layout root: deepest or smallest-id");
  c.cmd->add_option("--steps-per-check,-N", c.args->steps, "Thurston sweeps between two layouts and checks")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  c.cmd->add_option("--max-iterations", c.args->max_iterations, "Cap on sweeps")->check(CLI::Range(1, 100000000))->capture_default_str();
  c.cmd->add_option("--time-limit", c.args->time_limit,
                    "Stop after SECONDS of wall time in the packer, tested after every sweep or Newton step: the current "
                    "radii are laid out, checked and written, status time_limit, exit status 3 (default: no limit)")
      ->check(CLI::PositiveNumber)->type_name("SECONDS");
  c.cmd->add_option("--epsilon", c.args->epsilon, "Angle-sum tolerance for --stop angle (radians)")->capture_default_str();
  c.cmd->add_option("-o,--out", c.args->out, "Output path stem (writes STEM.json, STEM.svg, STEM.png); default GRAPHNAME-packing");
  c.cmd->add_flag("--force", c.args->force, "Overwrite existing output files");
  add_acceleration_option(*c.cmd, c.args->accelerate);
  add_choice(*c.cmd, "--newton-solver", c.args->newton_solver, core::newton_solver_names,
             "Linear solver of --accelerate newton: cholesky (sparse Cholesky, CHOLMOD when built with it), pcg "
             "(incomplete-Cholesky conjugate gradients) or lu (the original finite-difference Jacobian with sparse LU)");
  add_choice(*c.cmd, "--layout", c.args->layout_method, core::layout_method_names,
             "Placements of the layout: frames (through each parent's frame: rounding grows about linearly with "
             "the depth) or wave (from two placed positions, what a network node computes; rounding grows "
             "exponentially with the depth, docs/precision.md)");
  add_choice(*c.cmd, "--layout-arithmetic", c.args->layout_arithmetic, core::layout_arithmetic_names,
             "Arithmetic of the layout: binary64 (doubles, what a network node computes), binary128 (quadruple "
             "precision throughout; the circles kept in binary128, LPD decided on them) or mixed (frames only: "
             "frames and circles in binary128, the steps computed from the radii in doubles, several times "
             "faster than binary128; docs/precision.md)");
  add_choice(*c.cmd, "--termination", c.args->termination, core::termination_names,
             "layout: lay out and check LPD/GLPD after every sweep or Newton step; radius-only: only once every "
             "vertex's angle sum is within a gap of 2π (halved at each failed check), which skips the costly "
             "layouts of far-from-converged radii (docs/radius-only.md); radius-flood: the protocol's variant");
  c.cmd->add_option("--pairs", c.args->pairs,
                    "After packing, route greedy power packets between 'all' ordered pairs or N sampled pairs, on "
                    "the coordinates LPD was decided on (binary128 with --layout-arithmetic binary128 or mixed); default: no routing")
      ->type_name("all|N");
  c.cmd->add_option("--seed", c.args->seed, "Seed of the --pairs sample")->check(seed_validator())->capture_default_str();
  c.cmd->add_flag("--json", c.args->json_stdout, "Print the embedding JSON on standard output instead of writing STEM.json");
  c.cmd->add_flag("--no-picture", c.args->no_picture, "Do not draw the SVG/PNG picture");
  return [args = c.args] { return run_pack(*args); };
}

}  // namespace laguerre::tools
