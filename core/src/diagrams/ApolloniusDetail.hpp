#pragma once
/// @file
/// Internal: helpers shared by the two Apollonius constructions (start, canonical ordering of the
/// result) and the brute-force nearest site of the curved diagrams.

#include <algorithm>
#include <cmath>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"

namespace laguerre::core::detail {

/// The empty diagram of `sites` built by `method`; throws InputError when a site has a non-finite
/// coordinate or weight.
inline ApolloniusDiagram start_apollonius_diagram(const std::vector<ApolloniusSite>& sites, const char* method) {
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const ApolloniusSite& s = sites[i];
    if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(s.w))
      throw InputError("Apollonius site " + std::to_string(i) +
                       " has a non-finite coordinate or weight; expected finite x, y, w.");
  }
  ApolloniusDiagram d;
  d.sites = sites;
  d.method = method;
  return d;
}

/// The site of smallest `distance(i)` among `n` (smallest index among exact ties); no_site if n = 0.
template <class Distance>
SiteIndex nearest_site(std::size_t n, Distance distance) {
  SiteIndex best = no_site;
  double best_d = 0;
  for (SiteIndex i = 0; i < n; ++i) {
    const double d = distance(i);
    if (best == no_site || d < best_d) best = i, best_d = d;
  }
  return best;
}

/// Sorts vertices (triple, then position) and the hidden list; derives the sorted unique dual edges
/// from `extra_edges` plus, when `derive` is set, the pairs of the vertex triples.
inline void canonicalize(ApolloniusDiagram& d, std::vector<std::pair<SiteIndex, SiteIndex>> extra_edges, bool derive) {
  for (ApolloniusVertex& v : d.vertices) std::sort(v.sites.begin(), v.sites.end());
  std::sort(d.vertices.begin(), d.vertices.end(), [](const ApolloniusVertex& a, const ApolloniusVertex& b) {
    if (a.sites != b.sites) return a.sites < b.sites;
    if (a.position.x != b.position.x) return a.position.x < b.position.x;
    return a.position.y < b.position.y;
  });
  std::sort(d.hidden.begin(), d.hidden.end());
  d.hidden.erase(std::unique(d.hidden.begin(), d.hidden.end()), d.hidden.end());
  auto& e = d.dual_edges;
  e = std::move(extra_edges);
  for (const ApolloniusVertex& v : d.vertices) {
    if (!derive) break;
    e.emplace_back(v.sites[0], v.sites[1]);
    e.emplace_back(v.sites[1], v.sites[2]);
    e.emplace_back(v.sites[0], v.sites[2]);
  }
  for (auto& [a, b] : e)
    if (a > b) std::swap(a, b);
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
}

}  // namespace laguerre::core::detail
