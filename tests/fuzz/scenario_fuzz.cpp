// Fuzz harness: scenario files (scenarios/ScenarioLoader.hpp, load_scenario_from_string), with relative
// paths resolved against the repository's scenarios/ folder (so the seeds' graph and domain files are
// found). Leading lines `#set KEY=VALUE` (YAML comments) become `--set` overrides. On success every
// sweep point has the sweep's values, and no sweep key repeats.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "FuzzTarget.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/scenarios/ScenarioLoader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace scenarios = laguerre::scenarios;
  const std::string_view text = laguerre::fuzz::as_text(data, size);
  scenarios::LoadOptions options;
  for (std::size_t at = 0; text.substr(at, 5) == "#set ";) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    options.overrides.emplace_back(text.substr(at + 5, end - at - 5));
    at = end + 1;
    if (at >= text.size()) break;
  }
  scenarios::Scenario s;
  if (!laguerre::fuzz::parses<scenarios::ScenarioError, laguerre::core::InputError, std::invalid_argument>(
          [&] { s = scenarios::load_scenario_from_string(text, "<fuzz>", LAGUERRE_SOURCE_DIR "/scenarios", options); }))
    return 0;
  LAGUERRE_FUZZ_CHECK(!s.points.empty());
  for (const scenarios::ScenarioPoint& p : s.points) LAGUERRE_FUZZ_CHECK(p.values.size() == s.sweep_keys.size());
  // A key given twice in a mapping is an error, so no sweep key repeats.
  std::vector<std::string> keys = s.sweep_keys;
  std::sort(keys.begin(), keys.end());
  LAGUERRE_FUZZ_CHECK(std::adjacent_find(keys.begin(), keys.end()) == keys.end());
  return 0;
}
