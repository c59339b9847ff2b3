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
#include <vector>

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

template <class Diagram, class Site>
void check(std::vector<Site> sites, const std::vector<core::Point2>& points) {
  const core::Box box = core::bounding_box(points, 0.15);
  std::optional<Diagram> d;
  if (!laguerre::fuzz::parses<std::invalid_argument, core::InputError>([&] { d.emplace(std::move(sites), box); })) return;
  if (!d->is_valid() && !d->is_valid(true))  // verbose: the broken invariant on stderr
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
