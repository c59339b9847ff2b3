#pragma once
/// @file
/// Pictures of `laguerre run` and charts of `laguerre compare` (Cairo: SVG and PNG side by side).

#include <cairo.h>

#include <functional>
#include <string>
#include <vector>

#include "laguerre/scenarios/Comparison.hpp"
#include "laguerre/scenarios/Runner.hpp"

namespace laguerre::tools {

/// One picture of a run, four panels of `panel` pixels: the network (physical positions if any, else
/// the packing's centres), the final packing coloured by LPD/GLPD status, the power diagram (local
/// power cells clipped to the unit disc) and sample routes, greedy power (red) vs GFG (blue), drawn on
/// the network. Returns the SVG and PNG paths.
std::vector<std::string> render_run_picture(const scenarios::RunArtifacts& run, const std::string& title,
                                            const std::string& stem, int panel = 560);

/// Charts of a comparison: per family × network condition, the delivery rate (with its 95% interval)
/// and the mean hop stretch against the size, one line per scheme. Writes `stem-delivery` and
/// `stem-stretch` (SVG and PNG) and returns the paths.
std::vector<std::string> render_comparison_charts(const std::vector<scenarios::ComparisonRow>& rows,
                                                  const std::string& stem);

}  // namespace laguerre::tools
