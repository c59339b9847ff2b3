// `laguerre compare SCENARIO.yaml…`: runs the sweeps and compares routing schemes per family × size ×
// network condition, with confidence intervals; writes CSV/JSON and charts.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "Commands.hpp"
#include "Common.hpp"
#include "RunPictures.hpp"
#include "ScenarioCli.hpp"
#include "laguerre/scenarios/Comparison.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp compare_help{
    "compare",
    "Run scenario sweeps and compare routing schemes (delivery with 95% CI, stretch, cost) per family, size and network.",
    "Delivery 95% CI: Student t-interval over repetitions (per-run delivery rates); with one repetition the\n"
    "Wilson interval on that run's pairs (marked w). Exit status: 0 done, 2 bad input."};

namespace fs = std::filesystem;

struct CompareArgs {
  ScenarioRunArgs run;
  bool charts = true;
};

int run_compare(const CompareArgs& a) {
  auto loaded = load_scenarios(a.run.scenarios, a.run.overrides);
  if (!loaded) return 2;
  const std::string dir =
      a.run.out.empty() ? (fs::path("out") / (loaded->size() == 1 ? loaded->front().name + "-compare" : "compare")).string()
                        : a.run.out;
  const bool writes = writes_outputs();  // under mpirun, rank 0 (see `run`)
  if (writes) prepare_output_dir(dir, a.run.force, {"comparison.csv", "comparison.json"});
  std::vector<scenarios::ComparisonRow> rows;
  for (const scenarios::Scenario& s : *loaded) {
    Progress progress(s.name);
    scenarios::RunnerOptions options;
    options.jobs = a.run.jobs;
    set_parallel(a.run, s, options);
    options.on_progress = [&](const scenarios::RunProgress& p) { progress.update(p); };
    const scenarios::ScenarioResults results = scenarios::run_scenario(s, options);
    progress.finish();
    std::size_t bad = 0;
    std::string first;
    for (const auto& r : results.records)
      if (r.status != scenarios::RunStatus::ok) {
        if (bad++ == 0) first = std::string(scenarios::to_string(r.status)) + ": " + r.message;
      }
    std::printf("scenario %s: %zu run(s) in %.2f s%s\n", s.name.c_str(), results.records.size(), results.wall_seconds,
                bad ? (", " + std::to_string(bad) + " not ok (first: " + first + ")").c_str() : "");
    auto more = scenarios::compare_runs(s, results.records);
    rows.insert(rows.end(), more.begin(), more.end());
  }
  std::printf("\n");
  std::fputs(scenarios::comparison_table(rows).c_str(), stdout);
  if (!writes) return 0;
  write_text_file((fs::path(dir) / "comparison.csv").string(), scenarios::comparison_csv(rows));
  write_text_file((fs::path(dir) / "comparison.json").string(), scenarios::comparison_json(rows));
  std::printf("\nwrote %s, %s", (fs::path(dir) / "comparison.csv").c_str(), (fs::path(dir) / "comparison.json").c_str());
  if (a.charts) {
    fs::create_directories(fs::path(dir) / "charts");
    const auto paths = render_comparison_charts(rows, (fs::path(dir) / "charts" / "comparison").string());
    for (const auto& p : paths) std::printf(", %s", p.c_str());
  }
  std::printf("\n");
  return 0;
}
}  // namespace

Action add_compare_command(CLI::App& app) {
  const auto c = add_command<CompareArgs>(app, compare_help);
  add_scenario_run_options(*c.cmd, c.args->run, "scenarios", true, "Result folder (default out/<name>-compare, or out/compare for several files)",
                           "Override a key in every scenario, e.g. --set topology.n=40 (repeatable)");
  c.cmd->add_flag("!--no-charts", c.args->charts, "Do not draw the charts");
  return [args = c.args] { return run_compare(*args); };
}

}  // namespace laguerre::tools
