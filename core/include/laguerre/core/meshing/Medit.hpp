#pragma once
/// @file
/// Triangle meshes in the Medit formats read by mmg and gmsh: `.mesh` (vertices, triangles, edges)
/// and `.sol` (one metric per vertex). Used to read background metric fields and to write meshes.
///
/// Reading accepts the ASCII form: the `MeshVersionFormatted` and `Dimension 2` headers (or
/// `Dimension 3` with every vertex at z = 0, as gmsh writes a planar mesh: `x y z ref`), then the
/// sections `Vertices` (n, then `x y ref` per line), `Triangles` (n, then `i j k ref`, indices from 1),
/// `Edges` (n, then `i j ref`), optional others (skipped by their counts), and `End`. Keywords and
/// numbers may be split over lines as Medit allows; `#` starts a comment. A `.sol` file has
/// `SolAtVertices`, n, then `1 t` with t = 1 (a scalar size h, read as the metric I/h²) or t = 3 (a
/// symmetric tensor m11 m12 m22), then n lines of values.

#include "laguerre/core/Error.hpp"
#include "laguerre/core/meshing/Metric.hpp"

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace laguerre::core {

/// Bad mesh or solution input; `what()` reads "<file>:<line>: <message>".
class MeshInputError : public InputError {
public:
  using InputError::InputError;
};

/// A planar triangle mesh with Medit references (labels) on vertices, triangles and edges.
struct TriangleMesh {
  std::vector<std::array<double, 2>> points;           ///< vertex positions
  std::vector<int> point_refs;                         ///< one reference per vertex
  std::vector<std::array<std::size_t, 3>> triangles;  ///< vertex indices (from 0), counter-clockwise
  std::vector<int> triangle_refs;                      ///< one reference per triangle
  std::vector<std::array<std::size_t, 2>> edges;       ///< boundary/constraint edges (from 0)
  std::vector<int> edge_refs;                          ///< one reference per edge
};

/// Reads an ASCII Medit `.mesh` file (2D). Throws MeshInputError naming the file and line.
TriangleMesh read_medit_mesh(const std::string& path);

/// Reads an ASCII Medit `.sol` file with one solution per vertex of a mesh of `vertex_count` vertices;
/// scalar sizes h become I/h². Throws MeshInputError if the count differs or a value is not a metric.
std::vector<Metric> read_medit_sol(const std::string& path, std::size_t vertex_count);

/// Writes `mesh` as an ASCII Medit `.mesh` file (indices from 1). Throws std::runtime_error on I/O errors.
void write_medit_mesh(const std::string& path, const TriangleMesh& mesh);

/// Writes one tensor metric per vertex as an ASCII Medit `.sol` file.
void write_medit_sol(const std::string& path, const std::vector<Metric>& metrics);

}  // namespace laguerre::core
