#include "laguerre/scenarios/NetworkModel.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace laguerre::scenarios {

namespace {
std::vector<std::string> split(std::string_view text, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == sep) {
      parts.emplace_back(text.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}
}  // namespace

sim::Duration parse_duration(std::string_view text) {
  const std::string s(text);
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const std::string unit = used ? s.substr(used) : "";
  double scale = 0;
  if (unit.empty() || unit == "ns") scale = 1;
  else if (unit == "us") scale = 1e3;
  else if (unit == "ms") scale = 1e6;
  else if (unit == "s") scale = 1e9;
  if (used == 0 || scale == 0 || !(value >= 0) || !std::isfinite(value * scale) || value * scale > 9e18)
    throw std::invalid_argument("expected a non-negative duration such as 250us, 1ms or 2s, found '" + s + "'");
  return static_cast<sim::Duration>(value * scale + 0.5);
}

sim::LatencyModel parse_latency(std::string_view spec) {
  const auto parts = split(spec, ':');
  const std::string expected =
      "expected constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER] (durations like 1ms), found '" +
      std::string(spec) + "'";
  try {
    if (parts[0] == "constant" && parts.size() == 2) return sim::LatencyModel::constant(parse_duration(parts[1]));
    if (parts[0] == "uniform" && parts.size() == 3) {
      const sim::Duration lo = parse_duration(parts[1]), hi = parse_duration(parts[2]);
      if (hi < lo) throw std::invalid_argument("");
      return sim::LatencyModel::uniform(lo, hi);
    }
    if (parts[0] == "distance" && (parts.size() == 3 || parts.size() == 4)) {
      std::size_t used = 0;
      const double per_unit = std::stod(parts[2], &used);
      if (used != parts[2].size() || !(per_unit >= 0) || !std::isfinite(per_unit)) throw std::invalid_argument("");
      return sim::LatencyModel::distance(parse_duration(parts[1]), per_unit,
                                         parts.size() == 4 ? parse_duration(parts[3]) : 0);
    }
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(expected);
}

CrashSpec parse_crash(std::string_view spec) {
  const std::string s(spec);
  const std::size_t at = s.find('@');
  std::size_t used = 0;
  CrashSpec c;
  try {
    if (at != std::string::npos && at > 0 && s[0] != '-') c.node = std::stoull(s.substr(0, at), &used);
    if (used == at) c.at = parse_duration(s.substr(at + 1));
  } catch (const std::exception&) {
    used = 0;
  }
  if (at == std::string::npos || used == 0 || used != at)
    throw std::invalid_argument("expected ID@TIME such as 17@40ms, found '" + s + "'");
  return c;
}

std::string format_duration(sim::Duration d) {
  if (d != 0 && d % 1000000000 == 0) return std::to_string(d / 1000000000) + "s";
  if (d != 0 && d % 1000000 == 0) return std::to_string(d / 1000000) + "ms";
  if (d != 0 && d % 1000 == 0) return std::to_string(d / 1000) + "us";
  return std::to_string(d) + "ns";
}

}  // namespace laguerre::scenarios
