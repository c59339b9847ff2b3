#pragma once
/// @file
/// Reading and validating scenario files. Validation happens entirely before anything runs: unknown
/// keys, wrong types, out-of-range values, unknown generators and missing files are all collected and
/// reported together, one line each, as
///
///     FILE:LINE:COLUMN: key.path: found X, expected Y
///
/// (line and column from 1). A problem in a `--set` override is located as `--set KEY=VALUE`.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::scenarios {

/// Every problem found in a scenario, one formatted message each, in file order.
class ScenarioError : public core::InputError {
public:
  /// An error listing `issues` (what() joins them with newlines).
  explicit ScenarioError(std::vector<std::string> issues);
  /// The messages, one per problem.
  const std::vector<std::string>& issues() const { return issues_; }

private:
  std::vector<std::string> issues_;
};

/// Options of the loader.
struct LoadOptions {
  /// "key.path=VALUE" overrides (VALUE is YAML: `40`, `[0, 0.1]`, `gfg`), applied to every sweep point
  /// after the sweep's own values; a swept key that is overridden is no longer swept. `sweep.KEY=[…]`
  /// replaces (or adds) the sweep list of KEY; `name`, `seed` and `repetitions` are accepted too.
  std::vector<std::string> overrides;
};

/// Reads and validates the scenario file at `path`; relative file paths inside are resolved against
/// its folder. Throws ScenarioError listing every problem.
Scenario load_scenario(const std::string& path, const LoadOptions& options = {});

/// As load_scenario, from `text`; `source_name` prefixes messages and `base_dir` resolves relative paths.
Scenario load_scenario_from_string(std::string_view text, const std::string& source_name, const std::string& base_dir,
                                   const LoadOptions& options = {});

}  // namespace laguerre::scenarios
