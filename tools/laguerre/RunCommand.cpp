// `laguerre run SCENARIO.yaml`: every sweep point × repetition of a scenario, in parallel; a summary
// table, results.json / results.csv and one picture per sweep point.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "Commands.hpp"
#include "Common.hpp"
#include "Parallel.hpp"
#include "RunPictures.hpp"
#include "ScenarioCli.hpp"
#include "laguerre/scenarios/Results.hpp"
#include "laguerre/scenarios/Topology.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp run_help{
    "run",
    "Run a scenario file: every sweep point and repetition, with results and pictures.",
    "The scenario schema is documented in scenarios/README.md. Each run's seed is derived from the\n"
    "scenario's seed, the sweep point and the repetition, so results do not depend on --jobs.\n"
    "Exit status: 0 every run ended ok, 3 some run did not (not converged, failed, unsupported), 2 bad input."};

namespace fs = std::filesystem;

struct RunArgs {
  ScenarioRunArgs run;
};

int run_run(const RunArgs& a) {
  auto loaded = load_scenarios(a.run.scenarios, a.run.overrides);
  if (!loaded) return 2;
  const scenarios::Scenario& s = loaded->front();
  const std::string dir = a.run.out.empty() ? (fs::path("out") / s.name).string() : a.run.out;
  // Under mpirun every rank runs the scenario (its share of the runs, or every simulation on the
  // parallel kernel: --mpi-split); rank 0 alone prepares the folder and writes.
  const bool writes = writes_outputs();
  if (writes) prepare_output_dir(dir, a.run.force, {"results.json", "results.csv"});
  const scenarios::OutputSpec& outputs = s.points.front().config.outputs;
  Progress progress(s.name);
  scenarios::RunnerOptions options;
  options.jobs = a.run.jobs;
  set_parallel(a.run, s, options);
  options.on_progress = [&](const scenarios::RunProgress& p) { progress.update(p); };
  options.on_protocol_progress = [&](const scenarios::RunPlan& plan, const scenarios::ProtocolProgress& p) {
    const scenarios::ProtocolSpec& protocol = s.points[plan.point].config.protocol;
    progress.update(plan, p, protocol.max_iterations, protocol.steps_per_round);
  };
  progress.update(scenarios::RunProgress{0, scenarios::plan_runs(s).size(), 0});
  options.keep_artifacts = [&](const scenarios::RunPlan& p) {
    return p.repetition == 0 && s.points[p.point].config.outputs.pictures;
  };
  const scenarios::ScenarioResults results = scenarios::run_scenario(s, options);
  progress.finish();

  std::printf("scenario %s: %zu point(s) x %zu repetition(s) = %zu run(s) in %.2f s\n", s.name.c_str(), s.points.size(),
              s.repetitions, results.records.size(), results.wall_seconds);
  std::fputs(scenarios::summary_table(s, results.records).c_str(), stdout);
  if (!writes) {
    for (const auto& r : results.records)
      if (r.status != scenarios::RunStatus::ok) return 3;
    return 0;
  }
  std::vector<std::string> written;
  if (outputs.json) {
    write_text_file((fs::path(dir) / "results.json").string(), scenarios::results_json(s, results.records));
    written.push_back((fs::path(dir) / "results.json").string());
  }
  if (outputs.csv) {
    write_text_file((fs::path(dir) / "results.csv").string(), scenarios::results_csv(s, results.records));
    written.push_back((fs::path(dir) / "results.csv").string());
  }
  std::size_t pictures = 0, skipped = 0;
  for (std::size_t i = 0; i < results.records.size(); ++i) {
    if (!results.artifacts[i]) continue;
    const auto& rec = results.records[i];
    const auto& art = *results.artifacts[i];
    if (art.topology.graph.num_vertices() > s.points[rec.plan.point].config.outputs.picture_max_nodes) {
      ++skipped;
      continue;
    }
    fs::create_directories(fs::path(dir) / "pictures");
    char stem[64];
    std::snprintf(stem, sizeof stem, "point-%03zu", rec.plan.point);
    std::string title = s.name + " " + stem + ": " + rec.topology + ", " + std::to_string(rec.nodes) + " nodes, " +
                        std::to_string(rec.iterations) + " iterations";
    for (const auto& [k, v] : s.points[rec.plan.point].values) title += "  " + k + "=" + v;
    const auto paths = render_run_picture(art, title, (fs::path(dir) / "pictures" / stem).string());
    ++pictures;
    if (pictures == 1) written.push_back(paths.back());
  }
  std::printf("\nwrote");
  for (const auto& w : written) std::printf(" %s", w.c_str());
  if (pictures) std::printf(" (and %zu picture(s) in %s, SVG and PNG)", pictures, (fs::path(dir) / "pictures").c_str());
  if (skipped) std::printf(" (%zu picture(s) skipped: more than outputs.picture_max_nodes nodes)", skipped);
  std::printf("\n");
  for (const auto& r : results.records)
    if (r.status != scenarios::RunStatus::ok) return 3;
  return 0;
}
}  // namespace

Action add_run_command(CLI::App& app) {
  const auto c = add_command<RunArgs>(app, run_help);
  add_scenario_run_options(*c.cmd, c.args->run, "scenario", false, "Result folder (default out/<scenario name>)",
                           "Override a key for every sweep point, e.g. --set topology.n=40 --set repetitions=1 (repeatable)");
  c.cmd->footer("\nTopology generators (topology.generator, with their keys):\n" + scenarios::generators_help());
  return [args = c.args] { return run_run(*args); };
}

}  // namespace laguerre::tools
