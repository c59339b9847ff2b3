#pragma once
/// @file
/// Pieces shared by `laguerre run` and `laguerre compare`: loading scenarios with their messages,
/// the output folder rule, terminal progress and the runner options.

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::tools {

/// The options `laguerre run` and `laguerre compare` share.
struct ScenarioRunArgs {
  std::vector<std::string> scenarios;  ///< the scenario files (YAML)
  std::string out;                     ///< -o: the result folder (empty: the command's default)
  unsigned jobs = 0;                   ///< --jobs (0: hardware threads)
  bool force = false;                  ///< --force: replace the results in an existing folder
  std::vector<std::string> overrides;  ///< --set KEY=VALUE, repeatable
  std::string mpi_split = "auto";      ///< --mpi-split: auto, runs or network (under mpirun)
};

/// Under mpirun (more than one rank), how `options` spreads the work (`--mpi-split`): `runs` shares the
/// scenario's runs among the ranks (RunnerOptions::split, each run sequential), `network` runs every
/// simulation on the parallel kernel (RunnerOptions::host_runner); `auto` is runs when `scenario` has
/// more than one run. Nothing on one rank.
void set_parallel(const ScenarioRunArgs& args, const scenarios::Scenario& scenario, scenarios::RunnerOptions& options);

/// Whether this process writes results: always, except on the MPI ranks other than 0.
bool writes_outputs();

/// Registers the positional scenario file(s) (`name`, at most one unless `several`), -o (described by
/// `out_help`), --jobs, --force and --set (described by `set_help`).
void add_scenario_run_options(CLI::App& cmd, ScenarioRunArgs& args, const std::string& name, bool several,
                              const std::string& out_help, const std::string& set_help);

/// Loads every file with `overrides`; on problems prints them all to stderr and returns nothing.
std::optional<std::vector<scenarios::Scenario>> load_scenarios(const std::vector<std::string>& files,
                                                              const std::vector<std::string>& overrides);

/// Prepares output folder `dir`: refuses (core::InputError, exit 2) if it exists and `force` is
/// false; with `force` removes only the files `laguerre run`/`compare` write (`managed`, and the
/// `pictures` and `charts` subfolders), then creates it.
void prepare_output_dir(const std::string& dir, bool force, const std::vector<std::string>& managed);

/// A progress line with an ETA on stderr, drawn only if stderr is a terminal.
class Progress {
public:
  /// A reporter prefixed by `label`.
  explicit Progress(std::string label);
  /// Redraws the line (runner callback).
  void update(const scenarios::RunProgress& p);
  /// Ends the line.
  void finish();

private:
  std::string label_;
  bool tty_;
  bool drawn_ = false;
};

/// Writes `text` to `path` (throws std::runtime_error with the path on failure).
void write_text_file(const std::string& path, const std::string& text);

}  // namespace laguerre::tools
