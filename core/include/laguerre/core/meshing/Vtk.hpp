#pragma once
/// @file
/// Legacy-format VTK output of triangle meshes (readable by ParaView and VisIt), with per-vertex
/// metrics as tensors and per-cell quality as scalars.

#include "laguerre/core/meshing/MeshQuality.hpp"

#include <string>
#include <vector>

namespace laguerre::core {

/// Writes `mesh` as an ASCII legacy VTK unstructured grid: POINT_DATA "metric" (3×3 tensors with the
/// 2×2 metric in the upper-left block) when `metrics` is non-empty, CELL_DATA "radius_edge",
/// "smallest_angle" and "distortion" when `quality` has one entry per triangle. Throws on I/O errors.
void write_vtk(const std::string& path, const TriangleMesh& mesh, const std::vector<Metric>& metrics,
               const MeshQuality* quality = nullptr);

/// The same for a tetrahedral mesh: POINT_DATA "metric" (3×3 tensors), CELL_DATA "radius_edge",
/// "smallest_dihedral", "sliverity" and "distortion" when `quality` has one entry per tetrahedron.
void write_vtk(const std::string& path, const TetMesh& mesh, const std::vector<Metric3>& metrics,
               const MeshQuality* quality = nullptr);

}  // namespace laguerre::core
