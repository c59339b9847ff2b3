#include "Common.hpp"

#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::tools {

void add_graph_options(CLI::App& cmd, GraphArgs& args, const std::string& name, const std::string& what) {
  cmd.add_option(name, args.path, what)->required();
  cmd.add_option("--format", args.format, "Graph format: automatic, edges, coords, planar_code")->capture_default_str();
  cmd.add_option("--index", args.index, "Which graph of a multi-graph file (from 1)")->capture_default_str();
}

void add_outer_option(CLI::App& cmd, GraphArgs& args) {
  add_choice(cmd, "--outer", args.outer, core::outer_rule_names,
             "Outer face of a triangulated sphere (every face a triangle): face keeps one (the file's '# outer:', else "
             "the default face); puncture removes the vertex of largest degree (smallest id on ties), its neighbours "
             "become the boundary, and it is reported as removed (not packed, not routed). Other graphs: unchanged");
}

std::string removed_line(const std::vector<std::uint64_t>& removed) {
  if (removed.empty()) return {};
  std::string line = "removed      " + std::to_string(removed.size()) + " vertex";
  for (std::uint64_t id : removed) line += " " + std::to_string(id);
  return line + " (--outer puncture: its neighbours are the boundary; it is not in the embedding, gets no circle, "
                "sends and receives no packet)\n";
}

std::vector<core::GraphInput> read_graph_file(const std::string& path, const std::string& format) {
  (void)core::open_input_file(path, "graph file");  // the one message for a missing file or a folder
  return core::read_graphs(path, core::parse_graph_format(format));
}

LoadedGraph load_graph(const GraphArgs& args) {
  auto graphs = read_graph_file(args.path, args.format);
  if (args.index < 1 || args.index > graphs.size())
    throw core::InputError("--index", 0,
                           "graph index " + std::to_string(args.index) + " is out of range: " + args.path + " holds " +
                               std::to_string(graphs.size()) + " graph(s).");
  LoadedGraph out{std::move(graphs[args.index - 1]), {}, {}};
  core::PreparedInput prepared = core::prepare_input(out.input, core::parse_name(core::outer_rule_names, args.outer, "--outer"));
  out.kind = prepared.kind;
  out.removed = std::move(prepared.removed);
  return out;
}

std::vector<core::Scheme> parse_schemes(const std::string& text, const std::string& option) {
  if (text == "all") return {core::all_schemes.begin(), core::all_schemes.end()};
  std::string name = text;  // the underscore spelling of the outputs is accepted too
  for (char& c : name)
    if (c == '_') c = '-';
  if (const auto s = core::find_name(scenarios::scheme_names, name)) return {*s};
  throw core::InputError(option, 0,
                         "found '" + text + "', expected " + core::listed_names(scenarios::scheme_names) + ", or all.");
}

nlohmann::json routing_stats_json(const core::PlanarGraph& g, const core::RoutingStats& st) {
  nlohmann::json fails = nlohmann::json::array();
  for (const auto& f : st.failures)
    fails.push_back({{"source", g.id(f.source)},
                     {"target", g.id(f.target)},
                     {"stuck", f.stuck == core::none ? nlohmann::json() : nlohmann::json(g.id(f.stuck))},
                     {"outcome", std::string(core::to_string(f.outcome))}});
  return {{"scheme", std::string(core::to_string(st.scheme))},
          {"pairs", st.pairs},
          {"delivered", st.delivered},
          {"delivery_rate", st.delivery_rate},
          {"hops_mean", st.hops_mean},
          {"stretch_mean", st.stretch_mean},
          {"stretch_p95", st.stretch_p95},
          {"stretch_max", st.stretch_max},
          {"bytes_per_coordinate", st.coordinate_bytes},
          {"failures_total", st.failures_total},
          {"failures", fails}};
}

core::PairSelection parse_pairs(const std::string& text, std::uint64_t seed, const std::string& option) {
  if (text == "all") return {0, seed};
  std::uint64_t n = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (!text.empty() && ec == std::errc() && ptr == text.data() + text.size() && n >= 1 && n <= 1000000000)
    return {static_cast<std::size_t>(n), seed};
  throw core::InputError(option, 0, "found '" + text + "', expected 'all' or a number of sampled pairs in [1, 1000000000].");
}

CLI::Option* add_acceleration_option(CLI::App& cmd, std::string& value) {
  return add_choice(cmd, "--accelerate", value, core::acceleration_names,
                    "Sweep acceleration: plain, superstep (Collins-Stephenson), anderson, newton (damped Newton steps "
                    "on the angle sums instead of sweeps; an iteration is then a Newton step), or the local ones "
                    "the protocol runs too: chebyshev (adaptive second-order iteration per vertex) and "
                    "local-superstep (Collins-Stephenson with each vertex's own ratio)");
}

int run_program(CLI::App& app, int argc, char** argv, const char* program, const std::function<int()>& action) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's message, then the documented status: 0 for --help and --version, 2 for bad input.
    const int status = app.exit(e);
    return e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success) ? status : 2;
  }
  try {
    return action();
  } catch (const core::InputError& e) {  // every bad-input error (core/Error.hpp, tier 1)
    std::cerr << program << ": " << e.what() << '\n';
    return 2;
  } catch (const core::InternalError& e) {  // a broken precondition or invariant: a bug (tier 2)
    std::cerr << program << ": internal error (please report): " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << '\n';
    return 1;
  }
}

CLI::Validator seed_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t x = 0;
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
        if (!text.empty() && ec == std::errc() && ptr == text.data() + text.size()) return {};
        return "found '" + text + "', expected an integer in [0, 18446744073709551615]";
      },
      "UINT64");
}

void check_writable(const std::string& path, bool force) {
  if (!force && std::filesystem::exists(path))
    throw core::InputError("Refusing to overwrite " + path + "; pass --force to replace it or -o to write elsewhere.");
}

std::string file_stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

TerminalLine::TerminalLine() : tty_(::isatty(STDERR_FILENO) != 0), last_(std::chrono::steady_clock::now()) {}

bool TerminalLine::due() const { return tty_ && std::chrono::steady_clock::now() - last_ >= std::chrono::seconds(1); }

void TerminalLine::draw(const std::string& text, bool force) {
  if (!tty_ || (!force && !due())) return;
  std::fprintf(stderr, "\r%s\033[K", text.c_str());  // \033[K: erase the rest of a longer previous line
  std::fflush(stderr);
  drawn_ = true;
  last_ = std::chrono::steady_clock::now();
}

void TerminalLine::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace laguerre::tools
