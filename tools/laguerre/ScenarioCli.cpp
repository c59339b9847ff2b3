#include "ScenarioCli.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "Parallel.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/scenarios/ScenarioLoader.hpp"

namespace laguerre::tools {

namespace fs = std::filesystem;

void add_scenario_run_options(CLI::App& cmd, ScenarioRunArgs& args, const std::string& name, bool several,
                              const std::string& out_help, const std::string& set_help) {
  CLI::Option* files = cmd.add_option(name, args.scenarios, several ? "Scenario files (YAML)" : "Scenario file (YAML)");
  files->required();
  if (!several) files->expected(1);
  cmd.add_option("-o,--output", args.out, out_help);
  cmd.add_option("--jobs,-j", args.jobs, "Worker threads (default: hardware threads)")->check(CLI::Range(1, 4096));
  cmd.add_flag("--force", args.force, "Replace the results in an existing result folder");
  cmd.add_option("--set", args.overrides, set_help);
  cmd.add_option("--mpi-split", args.mpi_split,
                 "Under mpirun: share the runs among the ranks (runs), or run each simulation on the parallel "
                 "kernel (network); auto: runs when there are several")
      ->check(CLI::IsMember({"auto", "runs", "network"}))
      ->capture_default_str();
}

void set_parallel(const ScenarioRunArgs& args, const scenarios::Scenario& scenario, scenarios::RunnerOptions& options) {
  if (mpi_ranks() <= 1) return;
  const bool runs = args.mpi_split == "runs" ||
                    (args.mpi_split == "auto" && scenario.points.size() * scenario.repetitions > 1);
  if (runs)
    options.split = run_split();
  else
    options.host_runner = host_runner();
}

bool writes_outputs() { return host_runner() == nullptr || host_runner()->is_root(); }

std::optional<std::vector<scenarios::Scenario>> load_scenarios(const std::vector<std::string>& files,
                                                              const std::vector<std::string>& overrides) {
  std::vector<scenarios::Scenario> out;
  std::size_t problems = 0;
  for (const std::string& f : files) {
    try {
      out.push_back(scenarios::load_scenario(f, {overrides}));
    } catch (const scenarios::ScenarioError& e) {
      for (const auto& issue : e.issues()) std::cerr << issue << '\n';
      problems += e.issues().size();
    }
  }
  if (problems == 0) return out;
  std::cerr << "laguerre: " << problems << " problem(s) in the scenario file(s); nothing was run.\n";
  return std::nullopt;
}

void prepare_output_dir(const std::string& dir, bool force, const std::vector<std::string>& managed) {
  if (fs::exists(dir)) {
    if (!force)
      throw core::InputError("Refusing to overwrite the result folder " + dir +
                                  " (it exists); pass --force to replace its results or -o to write elsewhere.");
    if (!fs::is_directory(dir)) throw core::InputError(dir, 0, "exists and is not a folder.");
    for (const auto& m : managed) fs::remove(fs::path(dir) / m);
    fs::remove_all(fs::path(dir) / "pictures");
    fs::remove_all(fs::path(dir) / "charts");
  }
  fs::create_directories(dir);
}

Progress::Progress(std::string label) : label_(std::move(label)), tty_(::isatty(STDERR_FILENO) != 0) {}

void Progress::update(const scenarios::RunProgress& p) {
  if (!tty_) return;
  const double frac = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
  const double eta = p.done ? p.elapsed_seconds * (1 - frac) / frac : 0.0;
  std::fprintf(stderr, "\r%s: %zu/%zu runs (%3.0f%%), %.1f s elapsed, ETA %.1f s   ", label_.c_str(), p.done, p.total,
               100 * frac, p.elapsed_seconds, eta);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("Cannot write " + path + ".");
}

}  // namespace laguerre::tools
