#pragma once
/// @file
/// The summary `laguerre simulate` prints of a protocol run (packing, then forwarding per scheme),
/// shared with `laguerre live`.

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "Common.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"

namespace laguerre::tools {

/// One protocol run, as the summary needs it.
struct ProtocolSummary {
  const LoadedGraph& loaded;                                 ///< the graph
  const scenarios::ProtocolSetup& setup;                     ///< how the protocol ran
  const std::string& mode;                                   ///< --mode, as given
  const std::string& outer;                                  ///< --outer, as given
  const scenarios::ProtocolOutcome& po;                      ///< the packing run
  const std::vector<scenarios::ForwardingResult>& results;   ///< forwarding, one per scheme
  const std::vector<core::Scheme>& schemes;                  ///< the schemes asked for
  const std::string* verify = nullptr;                       ///< the --verify verdict, if asked
  std::string time_line;   ///< replaces the simulator's "time" line when not empty
  nlohmann::json extra;    ///< merged into the JSON document
  std::string forwarding_skipped;  ///< why no packet was forwarded (scenarios::forwarding_blocker), or ""
};

/// A packing outcome's name in the summary.
std::string_view outcome_name(protocols::PackingOutcome o);

/// Prints `s` (JSON with `json`) to standard output; returns the documented exit status: 0 if every
/// node converged, else 3.
int print_protocol_summary(const ProtocolSummary& s, bool json);

}  // namespace laguerre::tools
