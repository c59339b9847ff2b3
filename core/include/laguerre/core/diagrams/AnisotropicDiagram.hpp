#pragma once
/// @file
/// Anisotropic ("flower power") diagrams of Labelle and Shewchuk (thesis §2.1.2, §2.5–2.6): site
/// i = (p_i, M_i) with M_i symmetric positive definite, distance d_i(x) = (x − p_i)ᵀ M_i (x − p_i).
/// Bisectors are conics; cells may be disconnected.
///
/// Linearization (thesis Lemma 2.5.1, written out for d = 2, D = 5): lift x = (x, y) to
/// ẋ = (x, y, x², xy, y²) ∈ P ⊂ R⁵ and site i to the sphere σ_i of centre
/// c_i = (M_i p_i, −a_i/2, −b_i, −c_i/2) (M_i = [[a_i, b_i], [b_i, c_i]]) and squared radius
/// |c_i|² − p_iᵀ M_i p_i. Then pow(ẋ, σ_i) = |ẋ|² + d_i(x): the anisotropic diagram is the power
/// diagram of the σ_i in R⁵ restricted to the surface P and projected. A Voronoi vertex with label
/// {a, b, c} lies on the 2-face of that power diagram dual to the triangle abc of the regular complex.
///
/// Construction: (1) the regular triangulation of the σ_i in R⁵ (CGAL's dD Regular_triangulation,
/// exact predicates) gives the candidate triangles abc and, for every site, its regular-complex
/// neighbours; (2) for each candidate, the points of the bisector conics C_ab ∩ C_bc (resultant in y
/// after a fixed rotation, quartic roots as companion-matrix eigenvalues with Eigen, then Newton on the
/// 2 × 2 system); (3) a point is kept when no regular-complex neighbour of a, b or c is strictly closer
/// (the power cell of σ_a is cut out by its neighbours, so this is "no site at all is closer"), with
/// the relative tolerance `AnisotropicOptions::tolerance` on distances. The dual complex is the set of
/// triangles abc that carry a vertex; a triangle can carry several vertices (disconnected cells).
/// Option `all_triples` replaces step (1) by every triple and every site as neighbour (O(n⁴), a check
/// for small inputs). Degenerate inputs: equal sites keep the smallest index (the others are hidden);
/// bisector conics with a common component (e.g. three equal metrics on a line) give no vertex.

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"
#include "laguerre/core/diagrams/Sites.hpp"

namespace laguerre::core {

/// An anisotropic site: d(x) = (x − p)ᵀ M (x − p), M = [[a, b], [b, c]] positive definite.
struct AnisotropicSite {
  double x = 0;  ///< abscissa of p
  double y = 0;  ///< ordinate of p
  double a = 1;  ///< M₁₁
  double b = 0;  ///< M₁₂ = M₂₁
  double c = 1;  ///< M₂₂
};

/// Anisotropic distance (x − p)ᵀ M (x − p) in doubles.
double anisotropic_distance(Point2 q, const AnisotropicSite& s);

/// A conic A x² + B xy + C y² + D x + E y + F = 0, coefficients {A, B, C, D, E, F}.
using Conic = std::array<double, 6>;

/// The bisector conic d_i − d_j = 0 of two sites.
Conic bisector_conic(const AnisotropicSite& i, const AnisotropicSite& j);

/// Real intersection points of two conics (at most 4; none when they share a component), by the
/// resultant in y after a fixed rotation, companion-matrix eigenvalues and Newton refinement.
/// `scale` is the length unit of the problem (coordinates are centred on `centre` and divided by it).
std::vector<Point2> intersect_conics(const Conic& c1, const Conic& c2, Point2 centre = {0, 0}, double scale = 1);

/// A vertex of the anisotropic diagram: equidistant from three sites, no site strictly closer.
struct AnisotropicVertex {
  std::array<SiteIndex, 3> sites{};  ///< the three sites, increasing
  Point2 position;                   ///< the vertex
  double distance = 0;               ///< common distance d_i(position)
};

/// Options of the construction.
struct AnisotropicOptions {
  bool all_triples = false;  ///< candidates: every triple (brute force) instead of the regular complex
  double tolerance = 1e-9;   ///< relative tolerance of "no site strictly closer"
};

/// The anisotropic diagram's vertices and dual complex in the whole plane (plain data; JSON-able).
struct AnisotropicDiagram {
  std::vector<AnisotropicSite> sites;                       ///< input sites, input order
  std::vector<SiteIndex> hidden;                            ///< sites equal to an earlier one
  std::vector<AnisotropicVertex> vertices;                  ///< sorted by (sites, position)
  std::vector<std::array<SiteIndex, 3>> dual_triangles;     ///< triangles carrying a vertex, sorted, unique
  std::vector<std::pair<SiteIndex, SiteIndex>> dual_edges;  ///< pairs of those triangles, sorted, unique
  std::size_t candidate_triangles = 0;                      ///< triangles of the regular complex examined
  int lifted_dimension = -1;                                ///< dimension of the regular triangulation in R⁵

  /// Checks the invariants: hidden sites sorted, unique, each equal to an earlier visible site; every
  /// vertex finite, labelled by three distinct visible sites, equidistant from them and with no site
  /// strictly closer (relative 1e-8), its triple a dual triangle; dual triangles sorted, unique, each
  /// carrying a vertex; dual edges sorted, unique, each a side of a dual triangle. With `verbose`,
  /// writes the first violated invariant on std::cerr.
  bool is_valid(bool verbose = false) const;
};

/// Builds the diagram (see the file comment). Throws InputError for a non-finite site or a
/// matrix that is not positive definite.
AnisotropicDiagram anisotropic_diagram(const std::vector<AnisotropicSite>& sites, const AnisotropicOptions& options = {});

/// The diagram of a growing set of sites, updated instead of rebuilt (the Voronoi mesher's rounds).
/// The regular triangulation in R⁵ is kept and new sites are inserted into it; a site whose
/// regular-complex neighbours changed is one of a full cell created by an insertion, and only the
/// candidate triangles with such a site are filtered again (the others keep their vertices: a
/// triangle's vertices depend only on its three sites and their neighbours); the conic intersections
/// are computed once per triangle, when it appears. diagram() equals
/// anisotropic_diagram(all sites so far, options) field for field: CGAL breaks degenerate
/// configurations by a symbolic perturbation that does not depend on the insertion order.
/// options.all_triples is not supported (InputError).
class AnisotropicDiagramUpdater {
public:
  explicit AnisotropicDiagramUpdater(const AnisotropicOptions& options = {});
  ~AnisotropicDiagramUpdater();
  AnisotropicDiagramUpdater(const AnisotropicDiagramUpdater&) = delete;
  AnisotropicDiagramUpdater& operator=(const AnisotropicDiagramUpdater&) = delete;

  /// Appends `sites` (numbered after the previous ones) and updates the diagram. Throws InputError as
  /// anisotropic_diagram does, before changing anything.
  void add(const std::vector<AnisotropicSite>& sites);
  /// The diagram of every site added so far.
  const AnisotropicDiagram& diagram() const;
  /// How many candidate triangles the last add() filtered (those with a site whose neighbours changed).
  std::size_t filtered_triangles() const;
  /// How many of them were new, their conic intersections computed.
  std::size_t intersected_triangles() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Nearest site of q by brute force (smallest index among exact ties); no_site when empty.
SiteIndex anisotropic_nearest(const std::vector<AnisotropicSite>& sites, Point2 q);

/// Whether q lies in the closed polygon (counter-clockwise or not; even-odd rule, boundary inside).
bool polygon_contains(const Polygon& polygon, Point2 q);

/// The diagram restricted to a domain: its vertices inside, and its edges (conic arcs) sampled.
struct RestrictedAnisotropicDiagram {
  Polygon domain;                          ///< the domain (a box's corners or a simple polygon)
  std::vector<AnisotropicVertex> vertices;  ///< vertices inside the domain
  std::vector<SampledEdge> edges;          ///< conic arcs inside the domain with their two labels
};

/// Restricts `diagram` to `domain`: vertices by point-in-polygon; edges traced on a `resolution`²
/// grid over the domain's bounding box (marching squares on the nearest-site labels, crossings found
/// by bisection of d_a − d_b, arcs ending at the diagram's vertices joined to them), chained into
/// polylines. Brute force labels: O(resolution² · n).
RestrictedAnisotropicDiagram restrict_anisotropic(const AnisotropicDiagram& diagram, const Polygon& domain,
                                                  int resolution = 256);

/// The columns of an anisotropic sites file.
inline constexpr const char* anisotropic_columns = "x y a b c";

/// Reads an anisotropic sites file: one site `x y a b c` per line (M = [[a, b], [b, c]]), blank lines
/// and `#` comments ignored. Throws InputError naming file:line, what was found and what was
/// expected (SitesFile.hpp; also for a matrix that is not positive definite).
std::vector<AnisotropicSite> read_anisotropic_sites(const std::string& path);

}  // namespace laguerre::core
