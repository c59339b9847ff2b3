#pragma once
/// @file
/// Proximity graphs of a deployment: Delaunay restricted to a domain, the unit-disk graph and its
/// planar spanners (Gabriel, relative neighbourhood, k-localized Delaunay).
///
/// All functions take pairwise distinct points and return edges as index pairs (u < v), sorted. Every
/// geometric decision is exact (core/geometry/Predicates.hpp and Delaunay.hpp). Unit-disk neighbours
/// are found with a uniform grid of cell size ≈ R, so the cost is O(n + Σ deg²) rather than O(n²).
///
/// Definitions (R the radius, |·| the Euclidean distance; closed means "including the boundary"):
///  - UDG(R): uv is an edge iff |uv| ≤ R.
///  - Gabriel ∩ UDG: uv ∈ UDG and no other point lies in the *closed* disc with diameter uv
///    ((u − w)·(v − w) > 0 for every other w).
///  - RNG ∩ UDG (relative neighbourhood graph): uv ∈ UDG and no other point lies in the *open* lune
///    {w : |uw| < |uv| and |vw| < |uv|}.
///    With these conventions RNG ∩ UDG ⊆ Gabriel ∩ UDG ⊆ Del ∩ UDG for every Delaunay triangulation Del
///    (a point in the closed diametral disc is in the open lune; an empty closed diametral disc is an
///    empty circle through u and v), also for degenerate (cocircular) inputs.
///  - LDel^(k) (k-localized Delaunay graph of Li, Calinescu, Wan and Wang, "Localized Delaunay
///    triangulation with application in ad hoc wireless networks", IEEE TPDS 14(10), 2003): a triangle
///    uvw is k-localized Delaunay if its three edges are in UDG(R) and the open disc of its circumcircle
///    contains no point within k hops (in UDG(R)) of u, v or w; LDel^(k) is the union of Gabriel ∩ UDG
///    and the edges of all k-localized Delaunay triangles. It contains Gabriel ∩ UDG, and it is planar
///    for k ≥ 2 (ibid.); LDel^(1) may have crossing edges (Li et al. then planarize it into PLDel, which
///    is not implemented here). Candidate triangles are the triangles at u of the Delaunay triangulation
///    of u's closed UDG neighbourhood (a k-localized triangle is one of them for k ≥ 1); points are
///    assumed in general position (no four cocircular), as in the paper.
///  - restricted Delaunay: the triangles of the Delaunay triangulation of the points whose interior lies
///    inside the domain (no boundary point of the domain in the open triangle, core::Domain::triangle_inside;
///    constraint segments of the domain, if any, count as walls),
///    and their edges. Points must lie strictly inside the domain.

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/meshing/Domain.hpp"

namespace laguerre::scenarios {

/// Undirected edges as vertex index pairs (first < second), sorted.
using EdgeList = std::vector<std::pair<core::Vertex, core::Vertex>>;

/// Edges of the Delaunay triangulation (all of it, the convex hull included).
EdgeList delaunay_edges(std::span<const core::Point2> points);

/// Edges of the Delaunay triangulation restricted to the domain (see the file comment).
/// Precondition: every point is strictly inside the domain.
EdgeList restricted_delaunay_edges(const core::Domain& domain, std::span<const core::Point2> points);

/// Edges of the unit-disk graph UDG(R), R > 0 finite.
EdgeList unit_disk_edges(std::span<const core::Point2> points, double radius);

/// Edges of Gabriel ∩ UDG(R). Cost O(Σ_u deg(u)²).
EdgeList gabriel_edges(std::span<const core::Point2> points, double radius);

/// Edges of RNG ∩ UDG(R). Cost O(Σ_u deg(u)²).
EdgeList relative_neighbourhood_edges(std::span<const core::Point2> points, double radius);

/// Edges of LDel^(k) on UDG(R), k ≥ 1 (planar for k ≥ 2). Cost O(n d log d) for the local
/// triangulations plus, per candidate triangle, the points within k R of it.
EdgeList local_delaunay_edges(std::span<const core::Point2> points, double radius, unsigned k = 2);

}  // namespace laguerre::scenarios
