#pragma once
/// @file
/// Result tables of a scenario run: one row per run (JSON, CSV) and the per-point summary that
/// `laguerre run` prints.

#include <string>
#include <vector>

#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::scenarios {

/// The network condition of a configuration, e.g. "constant:1ms" or "uniform:1ms:5ms loss=0.2 crashes=1".
std::string network_label(const NetworkSpec& network);

/// The size of a point: its `topology.n` if set, else "-".
std::string size_label(const ScenarioConfig& config);

/// results.json: the scenario (name, source, seed, repetitions, sweep keys, seed rule), then one object
/// per run in plan order with its point's swept values, status, graph, protocol figures and a
/// `routing` object per scheme. Undefined statistics (NaN) are written as null.
std::string results_json(const Scenario& scenario, const std::vector<RunRecord>& records);

/// results.csv: one line per (run, scheme) with the run's columns repeated, header first; a run
/// without routing has one line with empty scheme columns. Fields are quoted when needed (RFC 4180).
std::string results_csv(const Scenario& scenario, const std::vector<RunRecord>& records);

/// The summary printed by `laguerre run`: per sweep point, the runs' status, mean iterations, rounds,
/// messages per node and simulated time, and per scheme the pooled delivery rate and mean stretch;
/// plus, when iterations to an exact packing were measured, the thesis-style comparison per family.
std::string summary_table(const Scenario& scenario, const std::vector<RunRecord>& records);

}  // namespace laguerre::scenarios
