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
///
/// In 3D (`Dimension 3`): `Vertices` are `x y z ref`, and `Tetrahedra` (n, then `i j k l ref`) join
/// `Triangles` and `Edges`; a 3D `.sol` tensor is `m11 m12 m22 m13 m23 m33` (Medit's order).

#include "laguerre/core/Error.hpp"
#include "laguerre/core/meshing/Metric.hpp"
#include "laguerre/core/meshing/Metric3.hpp"

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

/// A tetrahedral mesh (or, without tetrahedra, a triangle surface) of space with Medit references.
struct TetMesh {
  std::vector<std::array<double, 3>> points;             ///< vertex positions
  std::vector<int> point_refs;                           ///< one reference per vertex
  std::vector<std::array<std::size_t, 4>> tetrahedra;    ///< vertex indices (from 0), positively oriented
  std::vector<int> tetrahedron_refs;                     ///< one reference per tetrahedron
  std::vector<std::array<std::size_t, 3>> triangles;     ///< boundary triangles (from 0)
  std::vector<int> triangle_refs;                        ///< one reference per triangle
  std::vector<std::size_t> triangle_lines;               ///< when read: the file line of each triangle
};

/// Reads an ASCII Medit `.mesh` file of dimension 3 (tetrahedra and/or triangles; tetrahedra are
/// reordered to positive orientation). Throws MeshInputError naming the file and line.
TetMesh read_medit_tet_mesh(const std::string& path);

/// The `Dimension` of a Medit `.mesh` file (2 or 3). Throws MeshInputError if there is none.
int medit_dimension(const std::string& path);

/// Reads a 3D `.sol` file (`SolAtVertices` of type 1, a size h read as I/h², or 3, six entries).
std::vector<Metric3> read_medit_sol3(const std::string& path, std::size_t vertex_count);

/// Writes `mesh` as an ASCII Medit `.mesh` file of dimension 3 (indices from 1).
void write_medit_mesh(const std::string& path, const TetMesh& mesh);

/// Writes one 3D tensor metric per vertex as an ASCII Medit `.sol` file.
void write_medit_sol(const std::string& path, const std::vector<Metric3>& metrics);

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
