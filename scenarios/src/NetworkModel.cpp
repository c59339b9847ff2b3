#include "laguerre/scenarios/NetworkModel.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include "laguerre/core/Error.hpp"

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

[[noreturn]] void fail(const std::string& source, std::string_view found, std::string_view expected) {
  throw core::InputError(source, 0, "found '" + std::string(found) + "', expected " + std::string(expected));
}

// A decimal user id (no sign, no spaces), or nothing.
std::optional<std::uint64_t> parse_id(std::string_view text) {
  std::uint64_t id = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return id;
}
}  // namespace

sim::Duration parse_duration(std::string_view text, const std::string& source) {
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
    fail(source, s, "a non-negative duration such as 250us, 1ms or 2s");
  return static_cast<sim::Duration>(value * scale + 0.5);
}

sim::LatencyModel parse_latency(std::string_view spec, const std::string& source) {
  const auto parts = split(spec, ':');
  const auto duration = [](const std::string& text) -> std::optional<sim::Duration> {
    try {
      return parse_duration(text);
    } catch (const core::InputError&) {
      return std::nullopt;
    }
  };
  if (parts[0] == "constant" && parts.size() == 2)
    if (const auto d = duration(parts[1])) return sim::LatencyModel::constant(*d);
  if (parts[0] == "uniform" && parts.size() == 3) {
    const auto lo = duration(parts[1]), hi = duration(parts[2]);
    if (lo && hi && *hi < *lo)
      fail(source, spec, "uniform:LO:HI with LO <= HI (" + parts[1] + " is above " + parts[2] + ")");
    if (lo && hi) return sim::LatencyModel::uniform(*lo, *hi);
  }
  if (parts[0] == "distance" && (parts.size() == 3 || parts.size() == 4)) {
    const auto base = duration(parts[1]);
    const auto jitter = parts.size() == 4 ? duration(parts[3]) : std::optional<sim::Duration>(0);
    double per_unit = 0;
    const char* end = parts[2].data() + parts[2].size();
    const auto [ptr, ec] = std::from_chars(parts[2].data(), end, per_unit);
    if (base && jitter && !parts[2].empty() && ec == std::errc() && ptr == end && per_unit >= 0 && std::isfinite(per_unit))
      return sim::LatencyModel::distance(*base, per_unit, *jitter);
  }
  fail(source, spec, latency_forms);
}

CrashSpec parse_crash(std::string_view spec, const std::string& source) {
  const std::size_t at = spec.find('@');
  const auto id = at == std::string_view::npos ? std::nullopt : parse_id(spec.substr(0, at));
  if (!id) fail(source, spec, crash_forms);
  CrashSpec c;
  c.node = *id;
  const std::string_view when = spec.substr(at + 1);
  const std::size_t dash = when.find('-');
  try {
    c.at = parse_duration(when.substr(0, dash));
    if (dash != std::string_view::npos) c.recover_at = parse_duration(when.substr(dash + 1));
  } catch (const core::InputError&) {
    fail(source, spec, crash_forms);
  }
  if (c.recover_at && *c.recover_at <= c.at)
    fail(source, spec, "ID@T1-T2 with the recovery time T2 after the crash time T1");
  return c;
}

void add_recovery(std::vector<CrashSpec>& crashes, std::string_view spec, const std::string& source) {
  const std::size_t at = spec.find('@');
  const auto id = at == std::string_view::npos ? std::nullopt : parse_id(spec.substr(0, at));
  sim::Time t = 0;
  try {
    if (id) t = parse_duration(spec.substr(at + 1));
  } catch (const core::InputError&) {
    fail(source, spec, "ID@TIME such as 17@90ms");
  }
  if (!id) fail(source, spec, "ID@TIME such as 17@90ms");
  CrashSpec* best = nullptr;
  for (CrashSpec& c : crashes)
    if (c.node == *id && !c.recover_at && c.at < t && (!best || c.at > best->at)) best = &c;
  if (!best)
    throw core::InputError(source, 0, std::string(spec) + ": node " + std::to_string(*id) +
                                          " has no crash before that time without a recovery.");
  best->recover_at = t;
}

std::string format_duration(sim::Duration d) {
  if (d != 0 && d % 1000000000 == 0) return std::to_string(d / 1000000000) + "s";
  if (d != 0 && d % 1000000 == 0) return std::to_string(d / 1000000) + "ms";
  if (d != 0 && d % 1000 == 0) return std::to_string(d / 1000) + "us";
  return std::to_string(d) + "ns";
}

}  // namespace laguerre::scenarios
