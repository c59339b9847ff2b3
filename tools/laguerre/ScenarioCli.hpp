#pragma once
/// @file
/// Pieces shared by `laguerre run` and `laguerre compare`: loading scenarios with their messages,
/// the output folder rule, terminal progress (also of one protocol simulation, for `laguerre
/// simulate`) and the runner options.

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "Common.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
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

/// The progress text of one protocol simulation: its set-up phase, or the rounds done and the nodes
/// whose check holds; events/s; and what is left: the time until every node holds at the rate of the
/// last ten seconds, and the most it can take (to the iteration cap at the current round rate).
class ProtocolMeter {
public:
  /// A meter of runs with that cap and N (ProtocolSetup::max_iterations, steps_per_round).
  ProtocolMeter(int max_iterations, int steps_per_round);
  /// The text for sample `p` (samples in time order).
  std::string text(const scenarios::ProtocolProgress& p);

private:
  struct Sample {
    double wall;
    std::size_t holds;
    std::uint32_t iterations;
    std::uint64_t events;
  };
  int max_iterations_;
  int steps_;
  std::deque<Sample> window_;  // the last ten seconds of samples
};

/// A progress line with an ETA on stderr, drawn only if stderr is a terminal (TerminalLine): the
/// runs done and, while a run's protocol simulation is long, its ProtocolMeter text.
class Progress {
public:
  /// A reporter prefixed by `label`.
  explicit Progress(std::string label);
  /// Redraws the line (runner callback; report {0, total, 0} first to show the total from the start).
  void update(const scenarios::RunProgress& p);
  /// Redraws the line with the protocol progress of run `plan` (runner callback), whose protocol
  /// has that iteration cap and N.
  void update(const scenarios::RunPlan& plan, const scenarios::ProtocolProgress& p, int max_iterations,
              int steps_per_round);
  /// Ends the line.
  void finish();

private:
  void draw(bool force);
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  TerminalLine line_;
  scenarios::RunProgress runs_;
  std::string protocol_;  // the latest protocol text, "" if none
  std::optional<ProtocolMeter> meter_;
  std::optional<scenarios::RunPlan> metered_;  // the run meter_ follows
};

/// Writes `text` to `path` (throws std::runtime_error with the path on failure).
void write_text_file(const std::string& path, const std::string& text);

}  // namespace laguerre::tools
