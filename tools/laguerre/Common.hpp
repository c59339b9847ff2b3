#pragma once
/// @file
/// Pieces shared by the subcommands: the graph-file options and loading a graph ready for packing,
/// the option parsers and validators several commands use, output paths, the terminal progress line.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "laguerre/core/EnumNames.hpp"
#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

namespace laguerre::tools {

/// A registered subcommand and the storage its options write to.
template <class Args>
struct Command {
  CLI::App* cmd;               ///< the subcommand
  std::shared_ptr<Args> args;  ///< its options' values, shared with the action
};

/// What `--help` says of a subcommand.
struct CommandHelp {
  const char* name;         ///< the subcommand
  const char* description;  ///< one line
  const char* footer;       ///< after the options (empty: none)
};

/// Registers the subcommand `help` describes, with fresh storage for its options.
template <class Args>
Command<Args> add_command(CLI::App& app, const CommandHelp& help) {
  Command<Args> c{app.add_subcommand(help.name, help.description), std::make_shared<Args>()};
  if (*help.footer) c.cmd->footer(help.footer);
  return c;
}

/// The options naming one graph of a graph file: the file, its format and the graph's index.
struct GraphArgs {
  std::string path;                 ///< the graph file
  std::string format = "automatic";  ///< --format
  std::size_t index = 1;            ///< --index (from 1)
  std::string outer = "face";       ///< --outer (core::outer_rule_names), where add_outer_option offers it
};

/// Registers GraphArgs on `cmd`: the positional `name` (described by `what`), --format and --index.
void add_graph_options(CLI::App& cmd, GraphArgs& args, const std::string& name, const std::string& what);

/// Registers --outer (core::OuterRule by core::outer_rule_names) on `cmd`, stored in args.outer.
void add_outer_option(CLI::App& cmd, GraphArgs& args);

/// A graph read from a file and prepared for packing (kind decided, outer face chosen).
struct LoadedGraph {
  core::GraphInput input;               ///< graph, positions, name
  core::GraphKind kind{};               ///< triangulated disc or 3-connected
  std::vector<std::uint64_t> removed;   ///< ids of the file's vertices --outer puncture removed (not in input)
};

/// Every graph of `path` in `format`, the file opened as core::open_input_file does (core::InputError
/// for a missing file or a folder).
std::vector<core::GraphInput> read_graph_file(const std::string& path, const std::string& format = "automatic");

/// The summary line of the vertices --outer puncture removed ("removed      vertex 17 (...)\n"), or "" if none.
std::string removed_line(const std::vector<std::uint64_t>& removed);

/// Reads graph number `index` (from 1) of `path` in `format` (as read_graph_file) and prepares it for
/// packing under the outer rule `args.outer` (core::prepare_input).
LoadedGraph load_graph(const GraphArgs& args);

/// --scheme (named `option` in messages): one scheme by name (dashes or underscores), or "all".
/// Throws core::InputError.
std::vector<core::Scheme> parse_schemes(const std::string& text, const std::string& option);

/// The routing metrics of one scheme as written by `route --json` and `pack --pairs`: scheme, pairs,
/// delivered, rates, hops, stretch, bytes per coordinate, and the kept failures with g's vertex ids.
nlohmann::json routing_stats_json(const core::PlanarGraph& g, const core::RoutingStats& st);

/// --pairs (named `option` in messages): "all", or a number of pairs in [1, 10^9] sampled with `seed`
/// (as the scenario key routing.pairs). Throws core::InputError.
core::PairSelection parse_pairs(const std::string& text, std::uint64_t seed, const std::string& option);

/// Option `name` bound to `value`, accepting exactly the names of `table` (CLI11 lists them on error).
template <class E, std::size_t N>
CLI::Option* add_choice(CLI::App& cmd, const std::string& name, std::string& value, const core::EnumNames<E, N>& table,
                        const std::string& help) {
  return cmd.add_option(name, value, help)->check(CLI::IsMember(core::names_of(table)))->capture_default_str();
}

/// --accelerate (core::acceleration_names), as `pack` and `thesis-table` offer it.
CLI::Option* add_acceleration_option(CLI::App& cmd, std::string& value);

/// Parses `argv` into `app`, then runs `action`, with the documented exit statuses: CLI11's message
/// and 2 for bad options (0 for --help and --version), "PROGRAM: message" on stderr and 2 for bad
/// input (core::InputError), 1 for a bug (core::InternalError) or any other exception; otherwise
/// what `action` returns.
int run_program(CLI::App& app, int argc, char** argv, const char* program, const std::function<int()>& action);

/// A validator for --seed: an integer in [0, 2^64 − 1], written in decimal without a sign (as the
/// scenario key seed).
CLI::Validator seed_validator();

/// Refuses (core::InputError, a full sentence naming `path` and --force) to overwrite
/// `path` unless `force`.
void check_writable(const std::string& path, bool force);

/// "dir/name.ext" → "name".
std::string file_stem(const std::string& path);

/// The progress line of a long command on stderr, redrawn in place: drawn only when stderr is a
/// terminal (progress is for people watching, not for logs) and, unless forced, at most once a
/// second. The destructor ends a drawn line.
class TerminalLine {
public:
  /// A line, active if stderr is a terminal.
  TerminalLine();
  TerminalLine(const TerminalLine&) = delete;
  TerminalLine& operator=(const TerminalLine&) = delete;
  ~TerminalLine() { finish(); }
  /// Whether anything will ever be drawn (stderr is a terminal).
  bool active() const { return tty_; }
  /// Whether a redraw is due: active, and a second has passed since the last draw (or the construction).
  bool due() const;
  /// Replaces the line with `text` if active and (`force` or) due.
  void draw(const std::string& text, bool force = false);
  /// Ends a drawn line with a newline (the next draw starts a new one).
  void finish();

private:
  bool tty_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace laguerre::tools
