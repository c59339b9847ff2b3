// Reading and validating scenario files (yaml-cpp stays inside this file).
#include "laguerre/scenarios/ScenarioLoader.hpp"

#include <yaml-cpp/yaml.h>

#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/packing/PackingNames.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <algorithm>
#include <limits>
#include <tuple>
#include <sstream>

namespace laguerre::scenarios {

ScenarioError::ScenarioError(std::vector<std::string> issues)
    : core::InputError([&] {
        std::string s;
        for (const auto& i : issues) s += (s.empty() ? "" : "\n") + i;
        return s;
      }()),
      issues_(std::move(issues)) {}

namespace {

namespace fs = std::filesystem;

constexpr std::size_t max_points = 100000;

/// A `--set` override's parsed value and how to name it in messages.
struct Override {
  std::vector<std::string> path;
  std::string key;
  YAML::Node value;
  std::string label;  // "--set KEY=VALUE"
};

bool contains(const YAML::Node& root, const YAML::Node& n) {
  if (root.is(n)) return true;
  if (root.IsSequence()) {
    for (const auto& c : root)
      if (contains(c, n)) return true;
  } else if (root.IsMap()) {
    for (auto it = root.begin(); it != root.end(); ++it)
      if (contains(it->first, n) || contains(it->second, n)) return true;
  }
  return false;
}

std::string format_number(double x) {
  if (std::abs(x) < 1e15 && x == std::floor(x)) return std::to_string(static_cast<long long>(x));
  std::ostringstream o;
  o << x;
  return o.str();
}

/// Collects problems as "where: path: found X, expected Y".
class Checker {
public:
  Checker(std::string source, const std::vector<Override>* overrides) : source_(std::move(source)), overrides_(overrides) {}

  /// Where node `n` was written ("" if it was created by the loader).
  std::string where(const YAML::Node& n) const {
    if (!n.IsDefined()) return "";
    if (overrides_)
      for (const auto& o : *overrides_)
        if (contains(o.value, n)) return o.label;
    const YAML::Mark m = n.Mark();
    if (m.is_null()) return "";
    return source_ + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
  }

  void report(const YAML::Node& at, const YAML::Node& fallback, const std::string& path, const std::string& found,
              const std::string& expected) {
    report_message(at, fallback, path, "found " + found + ", expected " + expected);
  }
  void report(const YAML::Node& at, const std::string& path, const std::string& found, const std::string& expected) {
    report(at, YAML::Node(), path, found, expected);
  }
  /// As report, with the "found X, expected Y" part already written (a parser's InputError message).
  void report_message(const YAML::Node& at, const YAML::Node& fallback, const std::string& path,
                      const std::string& message) {
    std::string w = where(at);
    YAML::Mark mark = at.IsDefined() ? at.Mark() : YAML::Mark::null_mark();
    if (w.empty()) {
      w = where(fallback);
      mark = fallback.IsDefined() ? fallback.Mark() : YAML::Mark::null_mark();
    }
    if (w.empty()) w = source_;
    std::string msg = w + ": " + path + ": " + message;
    // Messages in file order: by line and column; overrides and unlocated messages last.
    const bool in_file = w.rfind(source_ + ":", 0) == 0 && !mark.is_null();
    add(in_file ? mark.line : std::numeric_limits<int>::max(), in_file ? mark.column : 0, std::move(msg));
  }
  /// A message not tied to a node.
  void report_plain(const std::string& msg) { add(std::numeric_limits<int>::max(), 0, msg); }

  /// The messages so far, in file order.
  std::vector<std::string> issues() {
    std::stable_sort(located_.begin(), located_.end(),
                     [](const auto& a, const auto& b) { return std::tie(a.line, a.column) < std::tie(b.line, b.column); });
    std::vector<std::string> out;
    for (auto& l : located_) out.push_back(l.text);
    return out;
  }
  bool empty() const { return located_.empty(); }
  const std::string& source() const { return source_; }

private:
  std::string source_;
  const std::vector<Override>* overrides_;
  struct Located {
    int line, column;
    std::string text;
  };
  void add(int line, int column, std::string msg) {
    if (seen_.insert(msg).second) located_.push_back({line, column, std::move(msg)});
  }
  std::vector<Located> located_;
  std::set<std::string> seen_;
};

std::string found(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  return "a mapping";
}

std::string join(const std::vector<std::string>& v, const std::string& last_sep = " or ") {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i == 0 ? "" : i + 1 == v.size() ? last_sep : ", ") + v[i];
  return s;
}

std::string key_of(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

/// The value of `key` in map `m`, or an undefined node (never inserts).
YAML::Node lookup(const YAML::Node& m, const std::string& key) {
  if (m.IsMap())
    for (auto it = m.begin(); it != m.end(); ++it)
      if (it->first.IsScalar() && it->first.Scalar() == key) return it->second;
  return YAML::Node(YAML::NodeType::Undefined);
}

/// Reports every key of map `m` not in `allowed`.
void check_keys(Checker& c, const YAML::Node& m, const std::string& path, const std::vector<std::string>& allowed) {
  if (!m.IsMap()) return;
  for (auto it = m.begin(); it != m.end(); ++it) {
    const std::string k = it->first.IsScalar() ? it->first.Scalar() : "?";
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == k;
    if (!ok) c.report(it->first, it->second, key_of(path, k), "an unknown key", "one of " + join(allowed));
  }
}

/// Reports every key that repeats an earlier key of the same mapping, at any depth of `n` (yaml-cpp keeps
/// both entries, and lookup would silently take the first).
void check_duplicate_keys(Checker& c, const YAML::Node& n, const std::string& path) {
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) check_duplicate_keys(c, n[i], path + "[" + std::to_string(i) + "]");
    return;
  }
  if (!n.IsMap()) return;
  std::vector<YAML::Node> keys;
  for (auto it = n.begin(); it != n.end(); ++it) {
    const YAML::Node key = it->first;
    const std::string k = key.IsScalar() ? key.Scalar() : "?";
    const auto first = std::find_if(keys.begin(), keys.end(),
                                    [&](const YAML::Node& e) { return key.IsScalar() && e.IsScalar() && e.Scalar() == k; });
    if (first != keys.end())
      c.report(key, it->second, key_of(path, k), "a duplicate key (first at line " + std::to_string(first->Mark().line + 1) + ")",
               "each key once in a mapping");
    keys.push_back(key);
    check_duplicate_keys(c, it->second, key_of(path, k));
  }
}

bool expect_map(Checker& c, const YAML::Node& n, const std::string& path) {
  if (n.IsMap()) return true;
  c.report(n, path, found(n), "a mapping of keys to values");
  return false;
}

std::string range_text(const char* what, double lo, double hi) {
  if (std::isinf(hi) && std::isinf(lo)) return what;
  if (std::isinf(hi)) return std::string(what) + " >= " + format_number(lo);
  return std::string(what) + " in [" + format_number(lo) + ", " + format_number(hi) + "]";
}

bool read_integer(Checker& c, const YAML::Node& n, const std::string& path, double lo, double hi, std::int64_t& out) {
  const std::string expected = range_text("an integer", lo, hi);
  if (!n.IsScalar()) {
    c.report(n, path, found(n), expected);
    return false;
  }
  const std::string& s = n.Scalar();
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size() || static_cast<double>(v) < lo || static_cast<double>(v) > hi) {
    c.report(n, path, found(n), expected);
    return false;
  }
  out = v;
  return true;
}

bool read_number(Checker& c, const YAML::Node& n, const std::string& path, double lo, double hi, double& out,
                 bool open_hi = false) {
  std::string expected = range_text("a number", lo, hi);
  if (open_hi) expected.back() = ')';
  if (!n.IsScalar()) {
    c.report(n, path, found(n), expected);
    return false;
  }
  const std::string& s = n.Scalar();
  double v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v) || v < lo || v > hi ||
      (open_hi && v >= hi)) {
    c.report(n, path, found(n), expected);
    return false;
  }
  out = v;
  return true;
}

bool read_bool(Checker& c, const YAML::Node& n, const std::string& path, bool& out) {
  if (n.IsScalar() && (n.Scalar() == "true" || n.Scalar() == "false")) {
    out = n.Scalar() == "true";
    return true;
  }
  c.report(n, path, found(n), "true or false");
  return false;
}

bool read_text(Checker& c, const YAML::Node& n, const std::string& path, const std::string& expected, std::string& out) {
  if (n.IsScalar() && !n.Scalar().empty()) {
    out = n.Scalar();
    return true;
  }
  c.report(n, path, found(n), expected);
  return false;
}

bool read_choice(Checker& c, const YAML::Node& n, const std::string& path, const std::vector<std::string>& choices,
                 std::string& out) {
  if (n.IsScalar())
    for (const auto& ch : choices)
      if (n.Scalar() == ch) {
        out = ch;
        return true;
      }
  c.report(n, path, found(n), join(choices));
  return false;
}

// ---------------------------------------------------------------------------------------------------
// Sections

struct Context {
  Checker& c;
  std::string base_dir;
};

void parse_topology(Context& ctx, const YAML::Node& t, TopologySpec& out) {
  Checker& c = ctx.c;
  if (!t.IsDefined()) {
    c.report_plain(c.source() + ": topology: found nothing, expected a topology section (generator: " +
                   generator_names(true) + ")");
    return;
  }
  if (!expect_map(c, t, "topology")) return;
  const YAML::Node g = lookup(t, "generator");
  if (!g.IsDefined()) {
    c.report(t, "topology.generator", "nothing", "a generator name (" + generator_names(true) + ")");
    return;
  }
  if (!g.IsScalar() || !find_generator(g.Scalar())) {
    c.report(g, "topology.generator", found(g), "one of " + generator_names(true));
    return;
  }
  const GeneratorInfo& info = *find_generator(g.Scalar());
  if (!info.available) {
    c.report(g, "topology.generator", found(g), "an available generator (" + info.unavailable_reason + "; available: " +
                                                     generator_names(true) + ")");
    return;
  }
  out.generator = info.name;
  std::vector<std::string> allowed{"generator"};
  for (const auto& p : info.params) allowed.push_back(p.name);
  check_keys(c, t, "topology", allowed);
  for (const ParamSpec& p : info.params) {
    const YAML::Node v = lookup(t, p.name);
    const std::string path = "topology." + p.name;
    if (!v.IsDefined()) {
      if (p.required) c.report(t, path, "nothing", "a value (" + p.help + ") for generator " + info.name);
      continue;
    }
    switch (p.type) {
      case ParamType::integer: {
        std::int64_t x = 0;
        if (read_integer(c, v, path, p.min, p.max, x)) out.params.set(p.name, x);
        break;
      }
      case ParamType::number: {
        double x = 0;
        if (read_number(c, v, path, p.min, p.max, x)) out.params.set(p.name, x);
        break;
      }
      case ParamType::boolean: {
        bool x = false;
        if (read_bool(c, v, path, x)) out.params.set(p.name, x);
        break;
      }
      case ParamType::choice: {
        std::string x;
        if (read_choice(c, v, path, p.choices, x)) out.params.set(p.name, x);
        break;
      }
      case ParamType::text: {
        std::string x;
        if (read_text(c, v, path, "a text (" + p.help + ")", x)) out.params.set(p.name, x);
        break;
      }
      case ParamType::file: {
        std::string x;
        if (!read_text(c, v, path, "a file path", x)) break;
        fs::path f(x);
        if (f.is_relative()) f = fs::path(ctx.base_dir) / f;
        std::error_code ec;
        if (!fs::is_regular_file(f, ec))
          c.report(v, path, found(v) + " (no such file: " + f.lexically_normal().string() + ")", "an existing file");
        else
          out.params.set(p.name, f.lexically_normal().string());
        break;
      }
      case ParamType::polygons: {
        Polygons polys;
        bool ok = v.IsSequence() && v.size() > 0;
        if (!ok) c.report(v, path, found(v), "a list of polygons, each a list of at least 3 points [x, y]");
        for (std::size_t i = 0; ok && i < v.size(); ++i) {
          const YAML::Node poly = v[i];
          const std::string pp = path + "[" + std::to_string(i) + "]";
          if (!poly.IsSequence() || poly.size() < 3) {
            c.report(poly, v, pp, found(poly), "a polygon: a list of at least 3 points [x, y]");
            ok = false;
            break;
          }
          std::vector<core::Point2> pts;
          for (std::size_t j = 0; j < poly.size(); ++j) {
            const YAML::Node q = poly[j];
            const std::string qp = pp + "[" + std::to_string(j) + "]";
            double x = 0, y = 0;
            if (!q.IsSequence() || q.size() != 2) {
              c.report(q, poly, qp, found(q), "a point [x, y]");
              ok = false;
              break;
            }
            const double inf = std::numeric_limits<double>::infinity();
            ok = read_number(c, q[0], qp + "[0]", -inf, inf, x) && read_number(c, q[1], qp + "[1]", -inf, inf, y);
            if (!ok) break;
            pts.push_back({x, y});
          }
          polys.push_back(std::move(pts));
        }
        if (ok) out.params.set(p.name, std::move(polys));
        break;
      }
    }
  }
  if (info.check)
    for (const ParamIssue& issue : info.check(out.params)) {
      const YAML::Node at = lookup(t, issue.param);
      c.report(at.IsDefined() ? at : t, "topology." + issue.param, issue.found, issue.expected);
    }
}

void parse_network(Context& ctx, const YAML::Node& n, NetworkSpec& out) {
  Checker& c = ctx.c;
  if (!n.IsDefined()) return;
  if (!expect_map(c, n, "network")) return;
  check_keys(c, n, "network", {"latency", "loss", "duplication", "crashes", "retransmit_after"});
  if (const YAML::Node v = lookup(n, "latency"); v.IsDefined()) {
    if (!v.IsScalar()) {
      c.report(v, "network.latency", found(v), std::string(latency_forms));
    } else {
      try {
        out.latency = parse_latency(v.Scalar());
        out.latency_text = v.Scalar();
      } catch (const core::InputError& e) {
        c.report_message(v, YAML::Node(), "network.latency", e.message());
      }
    }
  }
  if (const YAML::Node v = lookup(n, "loss"); v.IsDefined()) read_number(c, v, "network.loss", 0, 1, out.loss, true);
  if (const YAML::Node v = lookup(n, "duplication"); v.IsDefined())
    read_number(c, v, "network.duplication", 0, 1, out.duplication);
  if (const YAML::Node v = lookup(n, "crashes"); v.IsDefined()) {
    if (!v.IsSequence()) {
      c.report(v, "network.crashes", found(v), "a list of crashes " + std::string(crash_forms));
    } else {
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string path = "network.crashes[" + std::to_string(i) + "]";
        if (!v[i].IsScalar()) {
          c.report(v[i], v, path, found(v[i]), "a crash " + std::string(crash_forms));
          continue;
        }
        try {
          out.crashes.push_back(parse_crash(v[i].Scalar()));
        } catch (const core::InputError& e) {
          c.report_message(v[i], v, path, e.message());
        }
      }
    }
  }
  if (const YAML::Node v = lookup(n, "retransmit_after"); v.IsDefined()) {
    std::optional<sim::Duration> d;
    try {
      if (v.IsScalar()) d = parse_duration(v.Scalar());
    } catch (const core::InputError&) {
    }
    if (d && *d > 0)
      out.retransmit_after = d;
    else
      c.report(v, "network.retransmit_after", found(v), "a positive duration such as 250us, 1ms or 2s");
  }
}

void parse_protocol(Context& ctx, const YAML::Node& n, ProtocolSpec& out) {
  Checker& c = ctx.c;
  if (!n.IsDefined()) return;
  if (!expect_map(c, n, "protocol")) return;
  check_keys(c, n, "protocol",
             {"mode", "steps_per_round", "stop", "max_iterations", "root", "exact_reference", "acceleration",
              "termination"});
  std::string s;
  if (const YAML::Node v = lookup(n, "mode");
      v.IsDefined() && read_choice(c, v, "protocol.mode", core::names_of(protocol_mode_names), s)) {
    out.asynchronous = *core::find_name(protocol_mode_names, s) == ProtocolMode::async;
    out.central = *core::find_name(protocol_mode_names, s) == ProtocolMode::central;
  }
  if (const YAML::Node v = lookup(n, "acceleration"); v.IsDefined()) {
    if (read_choice(c, v, "protocol.acceleration", core::names_of(core::acceleration_names), s))
      out.acceleration = *core::find_name(core::acceleration_names, s);
    if (out.asynchronous && out.acceleration != core::Acceleration::plain)
      c.report(v, "protocol.acceleration", "'" + s + "' with mode async",
               "plain, or mode sync for the accelerations (chebyshev, local-superstep, newton-krylov: they need "
               "consistent synchronous iterates)");
    else if (!out.central && !core::runs_in_network(out.acceleration))
      c.report(v, "protocol.acceleration", "'" + s + "' with mode sync",
               "plain, chebyshev, local-superstep or newton-krylov, or mode central (the distributed protocol "
               "runs local accelerations and newton-krylov only)");
  }
  if (const YAML::Node v = lookup(n, "termination"); v.IsDefined()) {
    if (read_choice(c, v, "protocol.termination", core::names_of(core::termination_names), s))
      out.termination = *core::find_name(core::termination_names, s);
    if (out.asynchronous && out.termination != core::Termination::layout)
      c.report(v, "protocol.termination", "'" + s + "' with mode async", "layout, or mode sync or central for radius-only");
    else if (out.acceleration == core::Acceleration::newton_krylov && out.termination != core::Termination::layout)
      c.report(v, "protocol.termination", "'" + s + "' with acceleration newton-krylov",
               "layout (a Newton step already lays out and checks once per step)");
  }
  std::int64_t i = 0;
  if (const YAML::Node v = lookup(n, "steps_per_round");
      v.IsDefined() && read_integer(c, v, "protocol.steps_per_round", 1, 10000, i))
    out.steps_per_round = static_cast<int>(i);
  if (const YAML::Node v = lookup(n, "stop");
      v.IsDefined() && read_choice(c, v, "protocol.stop", core::names_of(stop_spec_names), s))
    out.stop = *core::find_name(stop_spec_names, s);
  if (const YAML::Node v = lookup(n, "max_iterations");
      v.IsDefined() && read_integer(c, v, "protocol.max_iterations", 1, 100000000, i))
    out.max_iterations = static_cast<int>(i);
  if (const YAML::Node v = lookup(n, "root");
      v.IsDefined() && read_choice(c, v, "protocol.root", core::names_of(core::root_rule_names), s))
    out.root = *core::find_name(core::root_rule_names, s);
  if (const YAML::Node v = lookup(n, "exact_reference"); v.IsDefined())
    read_bool(c, v, "protocol.exact_reference", out.exact_reference);
}

void parse_routing(Context& ctx, const YAML::Node& n, RoutingSpec& out) {
  Checker& c = ctx.c;
  if (!n.IsDefined()) return;
  if (!expect_map(c, n, "routing")) return;
  check_keys(c, n, "routing", {"schemes", "pairs", "positions", "sample_routes"});
  const std::vector<std::string> names = core::names_of(scheme_names);
  if (const YAML::Node v = lookup(n, "schemes"); v.IsDefined()) {
    if (v.IsScalar() && v.Scalar() == "all") {
      // default: all four
    } else if (!v.IsSequence() || v.size() == 0) {
      c.report(v, "routing.schemes", found(v), "'all' or a non-empty list of " + join(names, " and "));
    } else {
      out.schemes.clear();
      for (std::size_t i = 0; i < v.size(); ++i) {
        std::string s;
        const std::string path = "routing.schemes[" + std::to_string(i) + "]";
        if (!read_choice(c, v[i], path, names, s)) continue;
        const core::Scheme sc = *core::find_name(scheme_names, s);
        bool dup = false;
        for (auto x : out.schemes) dup = dup || x == sc;
        if (dup)
          c.report(v[i], v, path, found(v[i]) + " a second time", "each scheme at most once");
        else
          out.schemes.push_back(sc);
      }
    }
  }
  if (const YAML::Node v = lookup(n, "pairs"); v.IsDefined()) {
    std::int64_t k = 0;
    if (v.IsScalar() && v.Scalar() == "all")
      out.pairs = 0;
    else if (v.IsScalar() && std::from_chars(v.Scalar().data(), v.Scalar().data() + v.Scalar().size(), k).ptr ==
                                 v.Scalar().data() + v.Scalar().size() &&
             k >= 1 && k <= 1000000000)
      out.pairs = static_cast<std::size_t>(k);
    else
      c.report(v, "routing.pairs", found(v), "'all' or a number of sampled pairs in [1, 1000000000]");
  }
  std::string s;
  if (const YAML::Node v = lookup(n, "positions");
      v.IsDefined() && read_choice(c, v, "routing.positions", core::names_of(positions_names), s))
    out.positions = *core::find_name(positions_names, s);
  std::int64_t k = 0;
  if (const YAML::Node v = lookup(n, "sample_routes");
      v.IsDefined() && read_integer(c, v, "routing.sample_routes", 0, 20, k))
    out.sample_routes = static_cast<std::size_t>(k);
}

void parse_outputs(Context& ctx, const YAML::Node& n, OutputSpec& out) {
  Checker& c = ctx.c;
  if (!n.IsDefined()) return;
  if (!expect_map(c, n, "outputs")) return;
  check_keys(c, n, "outputs", {"tables", "pictures", "picture_max_nodes"});
  if (const YAML::Node v = lookup(n, "tables"); v.IsDefined()) {
    std::vector<YAML::Node> items;
    if (v.IsScalar()) items.push_back(v);
    else if (v.IsSequence())
      for (const auto& x : v) items.push_back(x);
    else
      c.report(v, "outputs.tables", found(v), "a list of json and csv");
    out.json = out.csv = false;
    for (std::size_t i = 0; i < items.size(); ++i) {
      std::string s;
      if (read_choice(c, items[i], v.IsScalar() ? "outputs.tables" : "outputs.tables[" + std::to_string(i) + "]",
                      {"json", "csv"}, s))
        (s == "json" ? out.json : out.csv) = true;
    }
  }
  if (const YAML::Node v = lookup(n, "pictures"); v.IsDefined()) read_bool(c, v, "outputs.pictures", out.pictures);
  std::int64_t k = 0;
  if (const YAML::Node v = lookup(n, "picture_max_nodes");
      v.IsDefined() && read_integer(c, v, "outputs.picture_max_nodes", 1, 10000000, k))
    out.picture_max_nodes = static_cast<std::size_t>(k);
}

/// Cross-field rules of one configuration.
void check_config(Context& ctx, const YAML::Node& doc, const ScenarioConfig& cfg) {
  const GeneratorInfo* info = find_generator(cfg.topology.generator);
  if (!info || cfg.topology.generator == "file") return;  // files: decided when read
  const YAML::Node net = lookup(doc, "network");
  if (cfg.network.latency.kind == sim::LatencyKind::distance && !info->positions)
    ctx.c.report(lookup(net, "latency"), "network.latency", "'" + cfg.network.latency_text + "' with generator " + info->name,
                 "a generator with physical positions for a distance latency");
  const YAML::Node routing = lookup(doc, "routing");
  if (cfg.routing.positions == GeometricPositions::physical && !info->positions)
    ctx.c.report(lookup(routing, "positions"), "routing.positions", "'physical' with generator " + info->name,
                 "a generator with physical positions (or auto / packing)");
}

ScenarioConfig parse_config(Context& ctx, const YAML::Node& doc) {
  ScenarioConfig cfg;
  parse_topology(ctx, lookup(doc, "topology"), cfg.topology);
  parse_network(ctx, lookup(doc, "network"), cfg.network);
  parse_protocol(ctx, lookup(doc, "protocol"), cfg.protocol);
  parse_routing(ctx, lookup(doc, "routing"), cfg.routing);
  parse_outputs(ctx, lookup(doc, "outputs"), cfg.outputs);
  check_config(ctx, doc, cfg);
  return cfg;
}

// ---------------------------------------------------------------------------------------------------
// Paths (documents are never mutated: a point's document shares unchanged nodes with the file's).

std::vector<std::string> split_path(const std::string& key) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= key.size(); ++i)
    if (i == key.size() || key[i] == '.') {
      out.push_back(key.substr(start, i - start));
      start = i + 1;
    }
  return out;
}

/// Makes documents that differ from the file's in a few entries and share every other node with it.
/// yaml-cpp keeps the nodes of a document in one memory set, and a map made by YAML::Node(type)
/// starts a set of its own that copies the whole set of the first node inserted into it; as every
/// point's document joins the file's set, building N points cost O(N²) (a 1156-point sweep took 2 CPU
/// seconds to load: fuzz finding scenario-1). So each new map is first appended to `anchor_`, a list
/// in the file's set, which makes it join that set at the cost of its own (empty) one.
class Splicer {
public:
  explicit Splicer(const YAML::Node& doc) { anchor_.push_back(doc); }

  /// `map` with `key` set to `value` (replaced in place, or appended).
  YAML::Node with_entry(const YAML::Node& map, const std::string& key, const YAML::Node& value) {
    YAML::Node out(YAML::NodeType::Map);
    anchor_.push_back(out);
    bool replaced = false;
    if (map.IsMap())
      for (auto it = map.begin(); it != map.end(); ++it) {
        if (!replaced && it->first.IsScalar() && it->first.Scalar() == key) {
          out.force_insert(it->first, value);
          replaced = true;
        } else {
          out.force_insert(it->first, it->second);
        }
      }
    if (!replaced) out.force_insert(key, value);
    return out;
  }

  /// `root` with the entry at path[i..] set to `value`.
  YAML::Node with_path(const YAML::Node& root, const std::vector<std::string>& path, std::size_t i,
                       const YAML::Node& value) {
    if (i + 1 == path.size()) return with_entry(root, path[i], value);
    return with_entry(root, path[i], with_path(lookup(root, path[i]), path, i + 1, value));
  }

private:
  YAML::Node anchor_{YAML::NodeType::Sequence};
};

const std::vector<std::string> sections{"topology", "network", "protocol", "routing", "outputs"};

bool valid_path(const std::vector<std::string>& p) {
  bool ok = p.size() <= 2 && !p.empty();
  for (const auto& s : p) ok = ok && !s.empty();
  if (!ok) return false;
  for (const auto& s : sections)
    if (s == p[0]) return true;
  return false;
}

std::string flow_text(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

Scenario load(const YAML::Node& doc, const std::string& source, const std::string& base_dir, const LoadOptions& options) {
  std::vector<Override> overrides;
  Checker c(source, &overrides);
  Context ctx{c, base_dir};
  // Overrides first (their syntax), so that their values can be located in messages.
  for (const std::string& o : options.overrides) {
    const std::size_t eq = o.find('=');
    Override ov;
    ov.label = "--set " + o;
    if (eq == std::string::npos) {
      c.report_plain(ov.label + ": found no '=', expected KEY.PATH=VALUE such as topology.n=40");
      continue;
    }
    ov.key = o.substr(0, eq);
    ov.path = split_path(ov.key);
    const bool top = ov.path.size() == 1 && (ov.key == "seed" || ov.key == "repetitions" || ov.key == "name");
    const bool sweep = ov.key.rfind("sweep.", 0) == 0;  // replaces (or adds) one sweep list
    if (sweep) ov.path = {"sweep", ov.key.substr(6)};
    if (!top && !sweep && !valid_path(ov.path)) {
      c.report_plain(ov.label + ": " + ov.key + ": found an unknown key path, expected name, seed, repetitions, sweep.KEY or SECTION.KEY with SECTION one of " + join(sections));
      continue;
    }
    try {
      ov.value = YAML::Load(o.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      c.report_plain(ov.label + ": " + ov.key + ": found invalid YAML (" + e.msg + "), expected a value");
      continue;
    }
    if (!ov.value.IsDefined() || ov.value.IsNull()) ov.value = YAML::Node(std::string());
    overrides.push_back(std::move(ov));
  }

  Scenario s;
  s.source = source;
  YAML::Node root = doc;
  Splicer splice(doc);
  if (!doc.IsMap()) {
    c.report(doc, "(top level)", found(doc), "a mapping with name, seed, repetitions, topology, …");
    throw ScenarioError(c.issues());
  }
  check_duplicate_keys(c, doc, "");
  // Top-level overrides apply to the base document.
  for (const auto& o : overrides) {
    if (o.path.size() == 1 && (o.key == "seed" || o.key == "repetitions" || o.key == "name"))
      root = splice.with_entry(root, o.key, o.value);
    if (o.path.size() == 2 && o.path[0] == "sweep")
      root = splice.with_entry(root, "sweep", splice.with_entry(lookup(root, "sweep"), o.path[1], o.value));
  }
  check_keys(c, root, "", {"name", "description", "seed", "repetitions", "topology", "network", "protocol", "routing",
                           "outputs", "sweep"});
  const YAML::Node name = lookup(root, "name");
  if (!name.IsDefined()) {
    c.report(root, "name", "nothing", "a scenario name (letters, digits, '.', '_', '-')");
  } else if (read_text(c, name, "name", "a scenario name (letters, digits, '.', '_', '-')", s.name)) {
    bool ok = s.name[0] != '.';
    for (char ch : s.name) ok = ok && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-');
    if (!ok) c.report(name, "name", found(name), "a scenario name (letters, digits, '.', '_', '-'; not starting with '.')");
  }
  if (const YAML::Node d = lookup(root, "description"); d.IsDefined() && !d.IsScalar())
    c.report(d, "description", found(d), "a text");
  if (const YAML::Node v = lookup(root, "seed"); v.IsDefined()) {
    std::uint64_t x = 0;
    const std::string t = v.IsScalar() ? v.Scalar() : "";
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (!v.IsScalar() || t.empty() || ec != std::errc() || ptr != t.data() + t.size())
      c.report(v, "seed", found(v), "an integer in [0, 18446744073709551615]");
    else
      s.seed = x;
  }
  if (const YAML::Node v = lookup(root, "repetitions"); v.IsDefined()) {
    std::int64_t x = 0;
    if (read_integer(c, v, "repetitions", 1, 100000, x)) s.repetitions = static_cast<std::size_t>(x);
  }

  // Sweep keys and lists.
  struct Axis {
    std::string key;
    std::vector<std::string> path;
    std::vector<YAML::Node> values;
  };
  std::vector<Axis> axes;
  if (const YAML::Node sw = lookup(root, "sweep"); sw.IsDefined() && expect_map(c, sw, "sweep")) {
    for (auto it = sw.begin(); it != sw.end(); ++it) {
      const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
      Axis a{key, split_path(key), {}};
      if (!valid_path(a.path)) {
        c.report(it->first, "sweep." + key, "'" + key + "'",
                 "a key path SECTION or SECTION.KEY with SECTION one of " + join(sections));
        continue;
      }
      if (!it->second.IsSequence() || it->second.size() == 0) {
        c.report(it->second, "sweep." + key, found(it->second), "a non-empty list of values");
        continue;
      }
      bool overridden = false;
      for (const auto& o : overrides) overridden = overridden || o.key == key;
      if (overridden) continue;  // --set fixes this key at every point
      // Copy the node first: iterating `it->second` directly would iterate a member of the temporary
      // that yaml-cpp's iterator proxy returns, destroyed before the loop body runs (before C++23).
      const YAML::Node list = it->second;
      for (const auto& v : list) a.values.push_back(v);
      axes.push_back(std::move(a));
    }
  }
  std::size_t count = 1;
  for (const auto& a : axes) {
    count *= a.values.size();
    if (count > max_points) {
      c.report(lookup(root, "sweep"), "sweep", "more than " + std::to_string(max_points) + " points",
               "a smaller Cartesian product");
      throw ScenarioError(c.issues());
    }
  }
  for (const auto& a : axes) s.sweep_keys.push_back(a.key);
  // Every point: the base document with the point's values, then the overrides.
  for (std::size_t p = 0; p < count; ++p) {
    ScenarioPoint point;
    point.index = p;
    YAML::Node d = root;
    std::size_t rest = p;
    std::vector<std::size_t> digit(axes.size());
    for (std::size_t k = axes.size(); k-- > 0;) {  // last axis varies fastest
      digit[k] = rest % axes[k].values.size();
      rest /= axes[k].values.size();
    }
    for (std::size_t k = 0; k < axes.size(); ++k) {
      const YAML::Node& v = axes[k].values[digit[k]];
      d = splice.with_path(d, axes[k].path, 0, v);
      point.values.emplace_back(axes[k].key, flow_text(v));
    }
    for (const auto& o : overrides)
      if (o.path[0] != "sweep" && valid_path(o.path)) d = splice.with_path(d, o.path, 0, o.value);
    point.config = parse_config(ctx, d);
    s.points.push_back(std::move(point));
  }
  if (!c.empty()) throw ScenarioError(c.issues());
  return s;
}

}  // namespace

Scenario load_scenario_from_string(std::string_view text, const std::string& source_name, const std::string& base_dir,
                                   const LoadOptions& options) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    throw ScenarioError({source_name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                         ": (syntax): found invalid YAML (" + e.msg + "), expected a YAML mapping"});
  }
  return load(doc, source_name, base_dir, options);
}

Scenario load_scenario(const std::string& path, const LoadOptions& options) {
  std::string text;
  try {
    text = core::read_input_file(path, "scenario file (YAML)");
  } catch (const core::InputError& e) {
    throw ScenarioError({e.what()});
  }
  const fs::path parent = fs::path(path).parent_path();
  return load_scenario_from_string(text, path, parent.empty() ? "." : parent.string(), options);
}

}  // namespace laguerre::scenarios
