#pragma once
/// @file
/// Quality of an anisotropic triangle mesh measured in the metrics of its vertices (thesis §2.7, §3.4):
/// per element, the radius–edge ratio and the smallest angle in the metric of each of its three
/// vertices (the worst of the three is reported), and the largest distortion between its vertices;
/// per edge, its length in the metric of each endpoint. Summaries give min/mean/max, the 5th and 95th
/// percentiles (nearest rank) and a histogram.
///
/// Tetrahedral meshes (3D) get the same report, per tetrahedron in the metric of each of its four
/// vertices: radius–edge ratio (√6/4 ≈ 0.61 for the regular tetrahedron), smallest *dihedral* angle
/// (in `smallest_angle`, 70.5° for the regular one), sliverity σ = volume / shortest edge³ (thesis
/// §3.4; 1/(6√2) ≈ 0.118 regular), and slivers counted as the thesis defines them (§3.3.3, Rule 4 of
/// §3.4): tetrahedra whose sliverity in the metric of one of their vertices is below σ₀.

#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/Metric.hpp"

#include <cstddef>
#include <vector>

namespace laguerre::core {

/// One triangle's quality, the worst over the metrics of its vertices.
struct ElementQuality {
  double radius_edge = 0;     ///< largest circumradius / shortest edge (1/√3 for equilateral)
  double smallest_angle = 0;  ///< smallest angle, degrees (3D: smallest dihedral angle)
  double sliverity = 0;       ///< 3D: smallest volume / shortest edge³ (0 for triangles)
  double distortion = 1;      ///< largest γ between two of its vertices
};

/// Summary statistics and a histogram of one quantity.
struct QualitySummary {
  std::size_t count = 0;  ///< number of values
  double min = 0;         ///< smallest value
  double mean = 0;        ///< arithmetic mean
  double max = 0;         ///< largest value
  double p5 = 0;          ///< 5th percentile (nearest rank)
  double p95 = 0;         ///< 95th percentile (nearest rank)
  double bin_start = 0;   ///< left end of the first histogram bin
  double bin_width = 0;   ///< width of each bin
  std::vector<std::size_t> histogram;  ///< counts per bin
};

/// The quality report of a mesh.
struct MeshQuality {
  std::vector<ElementQuality> elements;  ///< one per triangle
  std::vector<double> edge_lengths;      ///< per (edge, endpoint): the edge's length in that endpoint's metric
  QualitySummary radius_edge;            ///< of elements[i].radius_edge
  QualitySummary smallest_angle;         ///< of elements[i].smallest_angle (bins of 5° over [0, 60])
  QualitySummary distortion;             ///< of elements[i].distortion
  QualitySummary edge_length;            ///< of edge_lengths
  QualitySummary sliverity;              ///< 3D: of elements[i].sliverity
  std::size_t slivers = 0;               ///< 3D: tetrahedra of sliverity below sliver_bound
  double sliver_bound = 0;               ///< 3D: the σ₀ slivers were counted with
};

/// Measures `mesh` with one metric per vertex.
MeshQuality measure_quality(const TriangleMesh& mesh, const std::vector<Metric>& metrics);

/// σ₀, the sliverity below which a tetrahedron is a sliver (the 3D star mesher's default bound).
inline constexpr double kSliverBound = 0.02;

/// Measures a tetrahedral mesh with one metric per vertex (see the file comment); slivers are the
/// tetrahedra of sliverity below `sliver_bound` in one of their vertices' metrics.
MeshQuality measure_quality(const TetMesh& mesh, const std::vector<Metric3>& metrics, double sliver_bound = kSliverBound);

/// Summarises `values` with `bins` equal bins over [lo, hi] (values outside go to the end bins).
QualitySummary summarize(std::vector<double> values, double lo, double hi, std::size_t bins);

}  // namespace laguerre::core
