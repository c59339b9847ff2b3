#include "ScenarioCli.hpp"

#include <chrono>
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

ProtocolMeter::ProtocolMeter(int max_iterations, int steps_per_round)
    : max_iterations_(max_iterations), steps_(steps_per_round) {}

namespace {
std::string seconds_text(double s) {
  char out[32];
  if (s < 90) std::snprintf(out, sizeof out, "%.0f s", s);
  else if (s < 5400) std::snprintf(out, sizeof out, "%.0f min", s / 60);
  else std::snprintf(out, sizeof out, "%.1f h", s / 3600);
  return out;
}
}  // namespace

std::string ProtocolMeter::text(const scenarios::ProtocolProgress& p) {
  window_.push_back({p.wall_seconds, p.holds_nodes, p.iterations, p.events});
  while (window_.size() > 2 && window_.back().wall - window_[1].wall >= 10) window_.pop_front();
  const Sample& old = window_.front();
  const Sample& now = window_.back();
  const double dt = now.wall - old.wall;
  const double events_rate = dt > 0 ? static_cast<double>(now.events - old.events) / dt
                                    : (now.wall > 0 ? static_cast<double>(now.events) / now.wall : 0.0);
  char head[160];
  if (p.phase < protocols::PackingPhase::rounds) {
    std::snprintf(head, sizeof head, "set-up (%s), %.1f M events, %.2f M events/s, %s",
                  p.phase == protocols::PackingPhase::depth      ? "depth"
                  : p.phase == protocols::PackingPhase::election ? "election"
                  : p.phase == protocols::PackingPhase::wave     ? "layout wave"
                                                                 : "starting",
                  static_cast<double>(p.events) / 1e6, events_rate / 1e6, seconds_text(p.wall_seconds).c_str());
    return head;
  }
  std::snprintf(head, sizeof head, "round %u (iteration %u), %zu/%zu nodes hold, %.2f M events/s, %s", p.rounds,
                p.iterations, p.holds_nodes, p.nodes, events_rate / 1e6, seconds_text(p.wall_seconds).c_str());
  std::string text = head;
  if (dt <= 0) return text;
  const double holds_rate = (static_cast<double>(now.holds) - static_cast<double>(old.holds)) / dt;
  const double step_rate = static_cast<double>(now.iterations - old.iterations) / dt;
  if (holds_rate > 0) text += "; ~" + seconds_text(static_cast<double>(p.nodes - p.holds_nodes) / holds_rate) + " left at this rate";
  if (step_rate > 0 && static_cast<double>(max_iterations_) > now.iterations)
    text += "; at most " + seconds_text((max_iterations_ - static_cast<double>(now.iterations)) / step_rate) + " (cap of " +
            std::to_string(max_iterations_) + " steps, N = " + std::to_string(steps_) + ")";
  return text;
}

Progress::Progress(std::string label) : label_(std::move(label)), start_(std::chrono::steady_clock::now()) {}

void Progress::update(const scenarios::RunProgress& p) {
  runs_ = p;
  if (metered_) {  // that run may be the one that finished: its text goes until the next report
    protocol_.clear();
    metered_.reset();
    meter_.reset();
  }
  draw(p.done > 0);
}

void Progress::update(const scenarios::RunPlan& plan, const scenarios::ProtocolProgress& p, int max_iterations,
                      int steps_per_round) {
  // With several runs in parallel the line follows one of them (the first to report) until it ends.
  if (metered_ && (metered_->point != plan.point || metered_->repetition != plan.repetition)) return;
  if (!metered_) {
    metered_ = plan;
    meter_.emplace(max_iterations, steps_per_round);
  }
  protocol_ = "point " + std::to_string(plan.point) + " rep " + std::to_string(plan.repetition) + ": " + meter_->text(p);
  draw(false);
}

void Progress::draw(bool force) {
  const double frac = runs_.total ? static_cast<double>(runs_.done) / static_cast<double>(runs_.total) : 0.0;
  const double eta = runs_.done ? runs_.elapsed_seconds * (1 - frac) / frac : 0.0;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  char head[200];
  std::snprintf(head, sizeof head, "%s: %zu/%zu runs (%3.0f%%), %.1f s elapsed", label_.c_str(), runs_.done, runs_.total,
                100 * frac, elapsed);
  std::string text = head;
  if (runs_.done) {
    std::snprintf(head, sizeof head, ", ETA %.1f s", eta);
    text += head;
  }
  if (!protocol_.empty()) text += " | " + protocol_;
  line_.draw(text, force);
}

void Progress::finish() { line_.finish(); }

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("Cannot write " + path + ".");
}

}  // namespace laguerre::tools
