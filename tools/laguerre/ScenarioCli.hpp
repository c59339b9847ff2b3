#pragma once
/// @file
/// Pieces shared by `laguerre run` and `laguerre compare`: loading scenarios with their messages,
/// the output folder rule, terminal progress and the runner options.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::tools {

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
