// Fuzz harness: sites files as `laguerre diagram` reads them (one site per line, `#` comments): lines of
// 2 numbers `x y` give a Voronoi diagram, 3 `x y w` a power diagram, 4 `x y lambda mu` a Möbius
// diagram, clipped to the sites' bounding box grown by 15% (the command's default). Inputs that are
// not such a file are skipped; on the others the diagram must build (or refuse with
// std::invalid_argument or core::InputError) and pass its is_valid() check.
#include <charconv>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <vector>

#include <boost/multiprecision/cpp_int.hpp>

#include "FuzzTarget.hpp"
#include "laguerre/core/diagrams/MobiusDiagram.hpp"
#include "laguerre/core/diagrams/PowerDiagram.hpp"
#include "laguerre/core/diagrams/SitesFile.hpp"
#include "laguerre/core/diagrams/VoronoiDiagram.hpp"

namespace {

namespace core = laguerre::core;

constexpr std::size_t max_sites = 200;

// The numbers of the file, row by row; empty if a field is not a finite number or rows differ in length.
std::vector<std::vector<double>> numbers(std::string_view text) {
  std::vector<std::vector<double>> rows;
  while (!text.empty() && rows.size() <= max_sites) {
    std::string_view line = text.substr(0, text.find('\n'));
    text.remove_prefix(std::min(text.size(), line.size() + 1));
    line = line.substr(0, line.find('#'));
    std::vector<double> row;
    for (std::size_t at = line.find_first_not_of(" \t\r"); at != std::string_view::npos;
         at = line.find_first_not_of(" \t\r", at)) {
      const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
      double v = 0;
      const auto [ptr, ec] = std::from_chars(line.data() + at, line.data() + end, v);
      if (ec != std::errc() || ptr != line.data() + end || !std::isfinite(v)) return {};
      // Outside the sites reader's range (SitesFile.hpp): the diagrams' contract starts where its checks end.
      if (std::abs(v) > core::max_site_magnitude || (v != 0 && std::abs(v) < core::min_site_magnitude)) return {};
      row.push_back(v);
      at = end;
    }
    if (row.empty()) continue;
    if (!rows.empty() && row.size() != rows[0].size()) return {};
    rows.push_back(std::move(row));
  }
  return rows;
}

// Open finding sites-6 (tests/fuzz/open/README.md): three Möbius sites with one common bisector (δ_i − δ_j
// and δ_i − δ_k proportional, neither identically 0, e.g. (0, 0, 1, 1), (2, 0, 1, 1), (1, 0, 1, 0)), so
// that one cell has no interior. Decided exactly (rationals), and only for a diagram that failed
// is_valid.
bool shared_bisector(const std::vector<core::MobiusSite>& s) {
  using Q = boost::multiprecision::cpp_rational;
  auto diff = [&](std::size_t i, std::size_t j) {
    const Q li(s[i].lambda), lj(s[j].lambda), xi(s[i].x), yi(s[i].y), xj(s[j].x), yj(s[j].y);
    return std::array<Q, 4>{li - lj, li * xi - lj * xj, li * yi - lj * yj,
                            li * (xi * xi + yi * yi) - Q(s[i].mu) - lj * (xj * xj + yj * yj) + Q(s[j].mu)};
  };
  auto zero = [](const std::array<Q, 4>& a) { return a[0] == 0 && a[1] == 0 && a[2] == 0 && a[3] == 0; };
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const auto a = diff(i, j);
      if (zero(a)) continue;
      for (std::size_t k = j + 1; k < s.size(); ++k) {
        const auto b = diff(i, k);
        bool parallel = !zero(b);
        for (int u = 0; u < 4 && parallel; ++u)
          for (int v = u + 1; v < 4 && parallel; ++v) parallel = a[u] * b[v] == a[v] * b[u];
        if (parallel) return true;
      }
    }
  return false;
}

template <class Diagram, class Site>
void check(std::vector<Site> sites, const std::vector<core::Point2>& points) {
  const core::Box box = core::bounding_box(points, 0.15);
  std::optional<Diagram> d;
  const std::vector<Site> copy = sites;
  if (!laguerre::fuzz::parses<std::invalid_argument, core::InputError>([&] { d.emplace(std::move(sites), box); })) return;
  if (d->is_valid()) return;
  if constexpr (std::is_same_v<Site, core::MobiusSite>)
    if (shared_bisector(copy)) return;  // open finding sites-6
  if (!d->is_valid(true))  // verbose: the broken invariant on stderr
    laguerre::fuzz::fail("the diagram is not valid (see the line above)");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto rows = numbers(laguerre::fuzz::as_text(data, size));
  if (rows.empty() || rows.size() > max_sites || rows[0].size() < 2 || rows[0].size() > 4) return 0;
  std::vector<core::Point2> points;
  for (const auto& r : rows) points.push_back({r[0], r[1]});
  switch (rows[0].size()) {
    case 2: check<core::VoronoiDiagram>(points, points); break;
    case 3: {
      std::vector<core::WeightedPoint> sites;
      for (const auto& r : rows) sites.push_back({r[0], r[1], r[2]});
      check<core::PowerDiagram>(std::move(sites), points);
      break;
    }
    case 4: {
      std::vector<core::MobiusSite> sites;
      for (const auto& r : rows) sites.push_back({r[0], r[1], r[2], r[3]});
      check<core::MobiusDiagram>(std::move(sites), points);
      break;
    }
    default: break;
  }
  return 0;
}
