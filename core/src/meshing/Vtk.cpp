#include "laguerre/core/meshing/Vtk.hpp"

#include <fstream>
#include <stdexcept>

namespace laguerre::core {

void write_vtk(const std::string& path, const TriangleMesh& mesh, const std::vector<Metric>& metrics,
               const MeshQuality* quality) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open the file for writing");
  out.precision(17);
  out << "# vtk DataFile Version 3.0\nlaguerre anisotropic mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << mesh.points.size() << " double\n";
  for (const auto& p : mesh.points) out << p[0] << ' ' << p[1] << " 0\n";
  out << "CELLS " << mesh.triangles.size() << ' ' << 4 * mesh.triangles.size() << '\n';
  for (const auto& t : mesh.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  out << "CELL_TYPES " << mesh.triangles.size() << '\n';
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) out << "5\n";  // VTK_TRIANGLE
  if (quality && quality->elements.size() == mesh.triangles.size()) {
    out << "CELL_DATA " << mesh.triangles.size() << '\n';
    out << "SCALARS radius_edge double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.radius_edge << '\n';
    out << "SCALARS smallest_angle double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.smallest_angle << '\n';
    out << "SCALARS distortion double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.distortion << '\n';
  }
  if (metrics.size() == mesh.points.size() && !metrics.empty()) {
    out << "POINT_DATA " << mesh.points.size() << "\nTENSORS metric double\n";
    for (const Metric& m : metrics) out << m.a << ' ' << m.b << " 0\n" << m.b << ' ' << m.c << " 0\n0 0 1\n";
  }
  out.flush();
  if (!out) throw std::runtime_error(path + ": cannot write the file");
}

void write_vtk(const std::string& path, const TetMesh& mesh, const std::vector<Metric3>& metrics,
               const MeshQuality* quality) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open the file for writing");
  out.precision(17);
  out << "# vtk DataFile Version 3.0\nlaguerre anisotropic tetrahedral mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << mesh.points.size() << " double\n";
  for (const auto& p : mesh.points) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  out << "CELLS " << mesh.tetrahedra.size() << ' ' << 5 * mesh.tetrahedra.size() << '\n';
  for (const auto& t : mesh.tetrahedra) out << "4 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  out << "CELL_TYPES " << mesh.tetrahedra.size() << '\n';
  for (std::size_t i = 0; i < mesh.tetrahedra.size(); ++i) out << "10\n";  // VTK_TETRA
  if (quality && quality->elements.size() == mesh.tetrahedra.size()) {
    out << "CELL_DATA " << mesh.tetrahedra.size() << '\n';
    out << "SCALARS radius_edge double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.radius_edge << '\n';
    out << "SCALARS smallest_dihedral double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.smallest_angle << '\n';
    out << "SCALARS sliverity double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.sliverity << '\n';
    out << "SCALARS distortion double 1\nLOOKUP_TABLE default\n";
    for (const auto& e : quality->elements) out << e.distortion << '\n';
  }
  if (metrics.size() == mesh.points.size() && !metrics.empty()) {
    out << "POINT_DATA " << mesh.points.size() << "\nTENSORS metric double\n";
    for (const Metric3& m : metrics)
      out << m.xx << ' ' << m.xy << ' ' << m.xz << '\n' << m.xy << ' ' << m.yy << ' ' << m.yz << '\n'
          << m.xz << ' ' << m.yz << ' ' << m.zz << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error(path + ": cannot write the file");
}

}  // namespace laguerre::core
