#pragma once
/// @file
/// Apollonius (additively weighted Voronoi) diagrams, thesis §2.1.3: site i = (p_i, w_i), distance
/// δ_i(x) = |x − p_i| − w_i (for w_i ≥ 0 the signed Euclidean distance to the circle of centre p_i and
/// radius w_i). The cell of i is {x : δ_i(x) ≤ δ_j(x) ∀ j}; it is star-shaped from p_i and bounded by arcs
/// of hyperbola branches. Adding the same constant to every weight does not change the diagram.
///
/// Two independent constructions, cross-checked by the tests:
/// - `apollonius_diagram_cgal`: CGAL's Apollonius_graph_hierarchy_2 (exact filtered predicates);
/// - `apollonius_diagram_linearized`: thesis Algorithm 1 (Aurenhammer). The graph of δ_i is the half-cone
///   C_i : z = |x − p_i| − w_i, and F_i(x, z) = |x − p_i|² − (z + w_i)² differs from the power of (x, z)
///   with respect to the sphere Σ_i of R³ (centre (p_i, w_i), squared radius 2w_i²) by 2z², the same for
///   every i. So (x, δ_i(x)) lies in the power cell L(Σ_i) ⇔ F_j(x, δ_i(x)) ≥ 0 ∀ j, which implies
///   δ_i(x) ≤ δ_j(x); the converse holds unless the disc of some j lies strictly inside the disc of i.
///   Hence: (1) build CGAL's Regular_triangulation_3 of the Σ_i; (2) drop, until none is left, every
///   site whose disc lies strictly inside another disc (detected exactly: the apex (p_k, −w_k) of its
///   cone is strictly closer in power to a neighbour) — those sites are hidden in the Apollonius
///   diagram; (3) the Apollonius vertices are the points of C_i on the power edges dual to triangles ijk
///   of the regular triangulation (a line meets the half-cones in at most two points), the dual edges
///   are the pairs of these triangles. Vertex positions are double constructions; the end tests of the power
///   edges use a relative tolerance (1e-10 on F values of size r², r the distance to the sites, and
///   1e-9·r on the half-cone sides); the triangulation and the containment tests are exact.
///
/// Hidden sites: a site with an empty cell (its disc inside another disc, in the shifted sense above;
/// equal discs keep the one of smallest index). Degenerate inputs: fewer than 3 visible sites give no
/// vertex (one dual edge for two sites); collinear centres with equal weights give parallel
/// lines, no vertex.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/diagrams/Sites.hpp"

namespace laguerre::core {

/// An Apollonius site: δ(x) = |x − p| − w.
struct ApolloniusSite {
  double x = 0;  ///< abscissa of p
  double y = 0;  ///< ordinate of p
  double w = 0;  ///< additive weight (radius of the circle when non-negative)
};

/// Apollonius distance |q − p| − w in doubles (oracles, pictures; not for decisions).
double apollonius_distance(Point2 q, const ApolloniusSite& s);

/// A vertex of an Apollonius diagram: the centre of a circle tangent to the three site circles.
struct ApolloniusVertex {
  std::array<SiteIndex, 3> sites{};  ///< the three sites, increasing
  Point2 position;                   ///< the vertex
  double distance = 0;               ///< common value δ_i(position) of the three sites
};

/// A curved edge of a diagram, sampled for pictures: the points where sites a and b are the nearest.
struct SampledEdge {
  SiteIndex a = 0;                            ///< first label (a < b)
  SiteIndex b = 0;                            ///< second label
  std::vector<std::vector<Point2>> polylines;  ///< connected pieces, each an open polyline
};

/// The combinatorial Apollonius diagram (plain data; the CLI writes it as JSON).
struct ApolloniusDiagram {
  std::vector<ApolloniusSite> sites;                        ///< the input sites, input order
  std::vector<SiteIndex> hidden;                            ///< sites with an empty cell, increasing
  std::vector<std::pair<SiteIndex, SiteIndex>> dual_edges;  ///< pairs (a < b) of adjacent cells, sorted, unique
  std::vector<ApolloniusVertex> vertices;                   ///< sorted by (sites, position)
  std::string method;                                       ///< "cgal" or "linearized"

  /// Checks the invariants: hidden sites sorted, unique, in range, and each strictly inside (or equal
  /// to) another site's disc in the shifted sense, i.e. some site is at most as far from its centre,
  /// while every visible site's centre lies in its own cell; dual edges sorted, unique, between visible
  /// sites; every vertex finite, labelled by three distinct visible sites whose pairs are dual edges,
  /// equidistant from them (relative 1e-8) with no site strictly closer. With `verbose`, writes the
  /// first violated invariant on std::cerr.
  bool is_valid(bool verbose = false) const;
};

/// The diagram through CGAL's Apollonius_graph_hierarchy_2. Throws InputError on
/// non-finite input.
ApolloniusDiagram apollonius_diagram_cgal(const std::vector<ApolloniusSite>& sites);

/// The diagram through the linearization (thesis Algorithm 1, see the file comment). Throws
/// InputError on non-finite input.
ApolloniusDiagram apollonius_diagram_linearized(const std::vector<ApolloniusSite>& sites);

/// Nearest site of q by brute force (smallest index among exact double ties); no_site if empty.
SiteIndex apollonius_nearest(const std::vector<ApolloniusSite>& sites, Point2 q);

/// Samples the hyperbola arcs of the diagram inside `box`: each dual edge (a, b) gives the parts of the
/// bisector branch {δ_a = δ_b} where no dual neighbour of a or b is strictly closer, as polylines of
/// about `samples` points per branch.
std::vector<SampledEdge> apollonius_edges(const ApolloniusDiagram& diagram, const Box& box, int samples = 400);

/// The columns of an Apollonius sites file.
inline constexpr const char* apollonius_columns = "x y w";

/// Reads an Apollonius sites file: one site `x y w` per line; blank lines and `#` comments ignored.
/// Throws InputError naming file:line, what was found and what was expected (SitesFile.hpp).
std::vector<ApolloniusSite> read_apollonius_sites(const std::string& path);

}  // namespace laguerre::core
