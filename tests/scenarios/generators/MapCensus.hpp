#pragma once
// Test helpers for the uniform samplers: canonical codes of rooted maps, a census of samples by
// isomorphism class of (map, outer face), a chi-square test of the census against uniformity on
// rooted maps, and a triangle count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::test {

/// Canonical code of the map g rooted at dart d: breadth-first numbering from tail(d), each vertex
/// listing its degree and its neighbours' numbers counter-clockwise from the dart it was reached by.
/// Two rooted maps have the same code iff an orientation-preserving isomorphism maps root to root.
inline std::vector<std::uint32_t> rooted_code(const core::PlanarGraph& g, core::Dart d) {
  std::vector<std::uint32_t> label(g.num_vertices(), core::none), code;
  std::vector<core::Dart> entry;  // entry dart of each labelled vertex, in label order
  label[g.tail(d)] = 0;
  entry.push_back(d);
  for (std::size_t i = 0; i < entry.size(); ++i) {
    const core::Dart e = entry[i];
    code.push_back(g.degree(g.tail(e)));
    core::Dart x = e;
    do {
      const core::Vertex w = g.head(x);
      if (label[w] == core::none) {
        label[w] = static_cast<std::uint32_t>(entry.size());
        entry.push_back(g.twin(x));
      }
      code.push_back(label[w]);
      x = g.next_ccw(x);
    } while (x != e);
  }
  return code;
}

/// Samples grouped by isomorphism class of (map, outer face); each class remembers how many rooted
/// maps (root dart on the outer face, the outer face to its left) it contains.
struct Census {
  struct Class {
    std::size_t count = 0;     // samples in the class
    std::size_t rootings = 0;  // distinct rooted maps in the class
  };
  std::map<std::vector<std::uint32_t>, Class> classes;
  std::size_t samples = 0;

  void add(const core::PlanarGraph& g) {
    std::set<std::vector<std::uint32_t>> codes;
    for (core::Dart d : g.face_darts(g.outer_face())) codes.insert(rooted_code(g, d));
    Class& c = classes[*codes.begin()];
    ++c.count;
    c.rootings = codes.size();
    ++samples;
  }
  /// Total number of rooted maps over the classes seen.
  std::size_t rooted_maps_seen() const {
    std::size_t total = 0;
    for (const auto& [code, c] : classes) total += c.rootings;
    return total;
  }
  /// Pearson's chi-square statistic against "every rooted map equally likely" among `rooted_total`.
  double chi_square(double rooted_total) const {
    double chi2 = 0;
    for (const auto& [code, c] : classes) {
      const double expected = static_cast<double>(samples) * static_cast<double>(c.rootings) / rooted_total;
      const double diff = static_cast<double>(c.count) - expected;
      chi2 += diff * diff / expected;
    }
    return chi2;
  }
};

/// Upper quantile of the chi-square distribution with `dof` degrees of freedom at significance 10^-3
/// (Wilson–Hilferty approximation, z_{0.999} = 3.0902).
inline double chi_square_critical_0_001(double dof) {
  const double a = 2.0 / (9.0 * dof);
  const double t = 1.0 - a + 3.0902 * std::sqrt(a);
  return dof * t * t * t;
}

/// Checks a census against uniformity on `rooted_total` rooted maps: every class was seen (the rooted
/// maps of the classes seen add up to the known total) and the chi-square statistic is below the
/// 10^-3 critical value. Prints the statistic.
inline void expect_uniform(const Census& census, std::size_t rooted_total, const std::string& what) {
  EXPECT_EQ(census.rooted_maps_seen(), rooted_total) << what << ": some classes never appeared";
  const double chi2 = census.chi_square(static_cast<double>(rooted_total));
  const double dof = static_cast<double>(census.classes.size()) - 1.0;
  if (dof >= 1) {
    const double critical = chi_square_critical_0_001(dof);
    EXPECT_LT(chi2, critical) << what;
    std::printf(
        "[ census   ] %s: %zu samples, %zu classes, %zu rooted maps, chi2 = %.2f (dof %.0f, "
        "critical %.2f at 1e-3)\n",
        what.c_str(), census.samples, census.classes.size(), rooted_total, chi2, dof, critical);
  }
}

/// Number of triangles (3-cycles) of g.
inline std::size_t count_triangles(const core::PlanarGraph& g) {
  std::vector<std::uint8_t> mark(g.num_vertices(), 0);
  std::size_t count = 0;
  for (core::Vertex u = 0; u < g.num_vertices(); ++u) {
    for (core::Vertex w : g.neighbours(u)) mark[w] = 1;
    for (core::Vertex v : g.neighbours(u))
      if (v > u)
        for (core::Vertex w : g.neighbours(v))
          if (w > v && mark[w]) ++count;
    for (core::Vertex w : g.neighbours(u)) mark[w] = 0;
  }
  return count;
}

}  // namespace laguerre::test
