#pragma once
/// @file
/// Locally uniform anisotropic meshes in 3D by refinement of stars (thesis §3.3–3.4; Boissonnat,
/// Wormser, Yvinec, SoCG 2008): the 3D counterpart of StarMesher.hpp, over a PolyhedralDomain.
///
/// Every site v carries M_v = field(v) and its star S_v: the tetrahedra incident to v in the Delaunay
/// triangulation of the sites for M_v (core/src/meshing/detail/LocalDelaunay3.hpp), restricted to Ω.
/// A star is computed from the sites of a growing M_v-ball around v and certified when every kept
/// tetrahedron's M_v-circumball lies in the ball and v's link in the kept tetrahedra is closed (every
/// facet at v in two kept tetrahedra or on the boundary).
///
/// The boundary (thesis §3.3.4: "all constraints are inserted in all stars, and the Gabriel property
/// is maintained in each star for the corresponding metric"). The domain's faces are its planes of
/// coplanar input triangles; the constraint edges are the input edges between non-coplanar triangles,
/// kept as subsegments. A facet (v, x, y) of a star is a *boundary facet* when its three sites lie on a
/// face plane (exact orientation on the input points) and its centroid on that face (exact 2D
/// orientations in the projected face); which tetrahedra are in Ω is then combinatorial: a tetrahedron
/// on a boundary facet at v is inside iff its fourth vertex is on the inner side of the face (exact),
/// and the side only changes across boundary facets (flood fill around v); a star with no boundary
/// facet is inside. There is no separate surface triangulation: the boundary triangles of the mesh
/// are the boundary facets the stars agree on.
///
/// Rules, in priority order (a rule applies only when no earlier one does), after §3.4:
///   1. encroachment: a constraint edge with a site strictly inside its diametral ball in the metric
///      of an endpoint or of the site, longer than 2·size_bound or with distortion ≥ γ₀ is split at
///      its midpoint; a boundary facet of S_v with a site strictly inside its M_v-equatorial ball,
///      M_v-circumradius above size_bound or distortion ≥ γ₀ is refined at its M_v-circumcentre in its
///      plane ("insert or snap": a constraint edge that point encroaches is split instead, and the
///      nearest constraint edge when the point falls off the face);
///   2. distortion: a tetrahedron of S_v with γ ≥ γ₀ (between v and its other vertices, and the
///      metric at its M_v-circumcentre);
///   3. size: M_v-circumradius above size_bound;
///   4. radius–edge ratio above ρ₀ (in M_v);
///   5. sliverity: σ = volume / (shortest edge)³ below σ₀ (in M_v);
///   6. inconsistency: a tetrahedron of S_v missing from the star of one of its other vertices (the
///      thesis's cosphericity rule: by its Lemma 3.3.3 such a tetrahedron is part of a
///      γ₀-cospherical configuration), or a tetrahedron at the gap of a star whose link is not closed.
/// Rules 2–6 refine τ ∈ S_v by a point picked in its picking region, the M_v-ball of radius δ·R around
/// its M_v-circumcentre: up to `picking_tries` picks are drawn and the first that creates no
/// inconsistency is taken (for rule 5 also no sliver), else the one creating the fewest (the thesis's
/// Pick_valid and Pick_valid_for_sliver). A pick p creates an inconsistency when a tetrahedron of its
/// own star (in M_p, among the current sites) has a site strictly inside its circumsphere in the metric
/// of another of its vertices, or when p is strictly inside the M_w-circumsphere of a tetrahedron of S_w
/// but not inside its M_u-circumsphere for another vertex u whose star holds it: both are the
/// γ₀-cospherical configurations of p with four sites that §3.3.2 forbids, decided with the exact metric
/// in-sphere predicate. Insert or snap: a pick that encroaches a
/// constraint edge splits it; one inside the equatorial ball of a boundary facet of a star whose
/// conflict zone holds it refines that facet; one outside Ω refines the boundary facet crossed on
/// the way from the tetrahedron's centroid (or the nearest one).
///
/// When no rule applies every star is consistent and the merged mesh (each tetrahedron once) is
/// checked with check_tetrahedralization before the result is called converged.
///
/// Honest gaps: boundary points are midpoints and in-plane circumcentres, not random points of the
/// restricted picking regions of §3.3.3 (random points in the facet's disc, tried with the same
/// validity test, made the face cascade below worse); stars are M_v-Delaunay exactly
/// (LocalDelaunay3.hpp: exact metric predicates on the input points); points on a face that is not
/// axis-aligned are rounded off its plane (the bundled domains are axis-aligned, where midpoints and
/// in-plane circumcentres keep the constant coordinate exactly). Termination is the thesis's theorem
/// only under its hypotheses (dihedral input angles of at least 90° in the metric, small δ and σ₀, γ₀
/// close to 1); otherwise `max_vertices` turns a cascade into a status.
/// Measured (tools/bench/mesh3.sh, README core/meshing): the inconsistencies that cascaded were not
/// rare near-cospherical configurations but 10–40% of all star tetrahedra, between vertices whose
/// metrics differ by γ = 1.2–1.5, and the old picks (a sliver test only) created as many as they
/// removed; with the validity test the smoothly graded `expr` field converges (cube: 2 506 vertices at
/// γ₀ = 1.5, where it had not at 10 000). A sphere shock layer around a sphere smaller than one
/// element (sphere:0.15:0.4:0.5:0.3, the former bench field) cascades at every γ₀ tried: its strong
/// direction turns by ~1 rad per element, outside the thesis's hypothesis (docs/star-mesher3.md, with
/// the distortion measured by tools/bench/field_distortion); a curved layer that turns by ~0.2 rad per
/// element (sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5, the bench field now) converges on both bundled domains.

#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/MeshQuality.hpp"
#include "laguerre/core/meshing/MetricField.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace laguerre::core {

/// Parameters of the 3D star refinement (see the file comment).
struct StarMesh3Options {
  double size_bound = 1.0;          ///< largest M_v-circumradius of a tetrahedron
  double radius_edge_bound = 2.0;   ///< ρ₀ (a regular tetrahedron has √6/4 ≈ 0.61)
  double distortion_bound = 1.5;    ///< γ₀
  double sliver_bound = kSliverBound;  ///< σ₀: smallest volume / shortest-edge³ (regular: 1/(6√2) ≈ 0.118)
  double picking_ratio = 0.1;       ///< δ
  int picking_tries = 8;            ///< picks drawn for rules 5–6 before settling for the best
  std::size_t max_vertices = 200000;  ///< stop (not converged) beyond this many sites
  std::uint64_t seed = 1;           ///< seed of the picking
  std::function<void(std::size_t)> progress;  ///< called with the vertex count every 1000 insertions
};

/// How many times each rule refined something, and the work done.
struct StarMesh3Stats {
  std::size_t edge_splits = 0;      ///< rule 1, constraint edges
  std::size_t facet_splits = 0;     ///< rule 1, boundary facets refined
  std::size_t distortion = 0;       ///< rule 2 insertions
  std::size_t size = 0;             ///< rule 3
  std::size_t shape = 0;            ///< rule 4
  std::size_t sliver = 0;           ///< rule 5
  std::size_t inconsistency = 0;    ///< rule 6
  std::size_t snapped = 0;          ///< picks replaced by a boundary split
  std::size_t rejected_picks = 0;   ///< picks discarded because their star had a sliver
  std::size_t star_updates = 0;     ///< star recomputations
  std::size_t consistency_sweeps = 0;  ///< full passes looking for inconsistent tetrahedra
  /// Inconsistent tetrahedra (and open stars) the most recent sweep queued: 0 once converged; for a
  /// run stopped at the cap, how far from consistent it still was at its last sweep.
  std::size_t last_sweep_inconsistent = 0;
};

/// The result: the merged mesh (tetrahedra and boundary subfacets), one metric per vertex.
struct StarMesh3Result {
  TetMesh mesh;                  ///< vertices, consistent tetrahedra (positive), boundary subfacets (outward)
  std::vector<Metric3> metrics;  ///< M_v per vertex
  StarMesh3Stats stats;          ///< rule counts
  bool converged = false;        ///< every star consistent, no rule applies, check_tetrahedralization passes
  std::string status;            ///< "converged", or why not
};

/// Meshes `domain` for `field` by 3D star refinement. Deterministic for a given seed.
StarMesh3Result mesh_with_stars(const PolyhedralDomain& domain, const MetricField3& field,
                                const StarMesh3Options& options = {});

/// Replaces `mesh.triangles` by the facets that are in exactly one tetrahedron, each oriented with its
/// tetrahedron on the inner side (exact orientation), in sorted order, reference 1: the boundary of the
/// union of the tetrahedra (what the mesher's merge and `mesh-quality` of another mesher's output use).
void set_boundary_from_tetrahedra(TetMesh& mesh);

/// Checks that `mesh` is a tetrahedralization of `domain` with boundary `mesh.triangles`: every
/// tetrahedron positively oriented (exact), every facet in one or two tetrahedra, two tetrahedra at a
/// facet on opposite sides of it (exact), the facets in one tetrahedron exactly the boundary
/// triangles, each once with the tetrahedron on its inner side, the boundary triangles' area that of
/// the domain's surface and the volumes summing to the domain's volume (relative 1e-9). Returns "" when
/// valid, else the first problem found.
std::string check_tetrahedralization(const TetMesh& mesh, const PolyhedralDomain& domain);

}  // namespace laguerre::core
