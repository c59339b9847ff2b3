#include "laguerre/core/meshing/Medit.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string_view>

#include "laguerre/core/InputFile.hpp"

namespace laguerre::core {

namespace {

/// Whitespace-separated tokens with their line numbers; `#` comments run to the end of the line.
class Tokens {
public:
  Tokens(const std::string& path, std::string_view what) : path_(path), in_(open_input_file(path, what)) {}

  /// The next token, or "" at the end of the file.
  std::string next() {
    while (pos_ >= words_.size()) {
      std::string text;
      if (!std::getline(in_, text)) return {};
      ++line_;
      if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
      std::istringstream words(text);
      words_.clear();
      pos_ = 0;
      for (std::string w; words >> w;) words_.push_back(w);
    }
    return words_[pos_++];
  }

  /// The next token as a count (a non-negative integer).
  std::size_t count(const char* what) { return whole<std::size_t>(what, "a non-negative integer"); }

  /// The next token as an integer.
  long integer(const char* what) { return whole<long>(what, "an integer"); }

  /// The next token as a finite real number.
  double real(const char* what) {
    const std::string t = next();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v))
      fail("expected " + std::string(what) + " (a finite number), found '" + t + "'");
    return v;
  }

  /// The next section keyword, or "" at `End`; fails at the end of the file.
  std::string keyword() {
    const std::string key = next();
    if (key.empty()) fail("missing 'End' keyword");
    return key == "End" ? "" : key;
  }

  /// Consumes the records every Medit file may start with (`MeshVersionFormatted V`, `Dimension D`
  /// with D one of `accepted`, setting `dimension`; `note` ends the message for another dimension);
  /// false for any other keyword.
  bool header(const std::string& key, const std::string& note, long& dimension, std::initializer_list<long> accepted = {2}) {
    if (key == "MeshVersionFormatted") {
      integer("a format version");
      return true;
    }
    if (key != "Dimension") return false;
    dimension = integer("a dimension");
    if (std::find(accepted.begin(), accepted.end(), dimension) == accepted.end()) {
      std::string expected;
      for (const long d : accepted) expected += (expected.empty() ? "" : " or ") + ("'Dimension " + std::to_string(d) + "'");
      fail("expected " + expected + ", found " + std::to_string(dimension) + note);
    }
    return true;
  }

  /// The line of the last token read.
  std::size_t line() const { return line_; }

  [[noreturn]] void fail(const std::string& message) const { throw MeshInputError(path_, line_, message); }

private:
  /// The next token as an integer of type T (`kind` names it in the message).
  template <class T>
  T whole(const char* what, const char* kind) {
    const std::string t = next();
    T v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || p != t.data() + t.size())
      fail("expected " + std::string(what) + " (" + kind + "), found '" + t + "'");
    return v;
  }

  std::string path_;
  std::ifstream in_;
  std::vector<std::string> words_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

/// Skips `count` records of `per_record` tokens (sections we do not use, e.g. Corners, Normals).
void skip_records(Tokens& t, std::size_t count, std::size_t per_record) {
  for (std::size_t i = 0; i < count * per_record; ++i)
    if (t.next().empty()) t.fail("the file ends inside a section");
}

/// Skips the sections both readers pass over (Corners, RequiredVertices, RequiredEdges, Ridges: one index
/// per record; Quadrilaterals); false if `key` is not one of them.
bool skip_unused_section(Tokens& t, const std::string& key) {
  if (key == "Corners" || key == "RequiredVertices" || key == "RequiredEdges" || key == "Ridges") {
    skip_records(t, t.count("a count"), 1);
    return true;
  }
  if (key != "Quadrilaterals") return false;
  skip_records(t, t.count("a quadrilateral count"), 5);
  return true;
}

/// Fails on `key`, naming the keywords a reader accepts: the header, `sections` and the skipped ones.
[[noreturn]] void unknown_keyword(const Tokens& t, const std::string& key, const char* sections) {
  t.fail("unknown Medit keyword '" + key + "' (expected MeshVersionFormatted, Dimension, " + sections +
         ", Corners, RequiredVertices, RequiredEdges, Ridges, Quadrilaterals or End)");
}

/// Reads a vertex index written from 1 and returns it from 0.
std::size_t vertex_index(Tokens& t, std::size_t vertex_count) {
  const long v = t.integer("a vertex index");
  if (v < 1 || static_cast<std::size_t>(v) > vertex_count)
    t.fail("vertex index " + std::to_string(v) + " is out of range 1.." + std::to_string(vertex_count));
  return static_cast<std::size_t>(v - 1);
}

/// Reads a section of elements (a count, then per element its vertex indices and a reference).
template <std::size_t N>
void read_elements(Tokens& t, std::size_t vertex_count, const char* count, const char* reference,
                   std::vector<std::array<std::size_t, N>>& elements, std::vector<int>& refs,
                   std::vector<std::size_t>* lines = nullptr) {
  const std::size_t n = t.count(count);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<std::size_t, N> element{};
    for (auto& v : element) v = vertex_index(t, vertex_count);
    if (lines) lines->push_back(t.line());
    elements.push_back(element);
    refs.push_back(static_cast<int>(t.integer(reference)));
  }
}

/// Reads a `Vertices` section: the count, then per vertex its coordinates (`point(i)`, which reads them
/// into a value of the mesh's point type) and its reference.
template <class Point, class ReadPoint>
void read_vertices(Tokens& t, std::vector<Point>& points, std::vector<int>& refs, const ReadPoint& point) {
  const std::size_t n = t.count("a vertex count");
  points.resize(n);
  refs.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    points[i] = point(i);
    refs[i] = static_cast<int>(t.integer("a vertex reference"));
  }
}

/// Opens `path` and writes the header of a Medit file of `dimension`, at full precision.
std::ofstream open_medit_output(const std::string& path, std::size_t dimension) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open the file for writing");
  out.precision(17);
  out << "MeshVersionFormatted 2\nDimension " << dimension << "\n\n";
  return out;
}

/// Writes `End` and throws std::runtime_error with the path if anything failed.
void finish_medit_output(std::ofstream& out, const std::string& path) {
  out << "\nEnd\n";
  out.flush();
  if (!out) throw std::runtime_error(path + ": cannot write the file");
}

/// A section of elements to write: its keyword, vertex indices (from 0) and references.
template <std::size_t N>
struct ElementSection {
  const char* name;
  const std::vector<std::array<std::size_t, N>>& items;
  const std::vector<int>& refs;  ///< 0 is written where it has no entry
};

template <std::size_t N>
void write_section(std::ostream& out, const ElementSection<N>& s) {
  out << '\n' << s.name << '\n' << s.items.size() << '\n';
  for (std::size_t i = 0; i < s.items.size(); ++i) {
    for (const std::size_t v : s.items[i]) out << v + 1 << ' ';
    out << (i < s.refs.size() ? s.refs[i] : 0) << '\n';
  }
}

/// A mesh file of dimension D: the vertices (coordinates, then the reference, 0 where `refs` has none),
/// the `boundary` section when it is not empty, then the `elements` section (indices written from 1).
template <std::size_t D, std::size_t B, std::size_t E>
void write_mesh_file(const std::string& path, const std::vector<std::array<double, D>>& points,
                     const std::vector<int>& refs, const ElementSection<B>& boundary, const ElementSection<E>& elements) {
  std::ofstream out = open_medit_output(path, D);
  out << "Vertices\n" << points.size() << '\n';
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (const double x : points[i]) out << x << ' ';
    out << (i < refs.size() ? refs[i] : 0) << '\n';
  }
  if (!boundary.items.empty()) write_section(out, boundary);
  write_section(out, elements);
  finish_medit_output(out, path);
}

/// A solution file of one symmetric-tensor field (type 3), each metric written as `entries` gives it.
template <class M, class Entries>
void write_sol_file(const std::string& path, std::size_t dimension, const std::vector<M>& metrics, Entries entries) {
  std::ofstream out = open_medit_output(path, dimension);
  out << "SolAtVertices\n" << metrics.size() << "\n1 3\n";
  for (const M& m : metrics) {
    const auto e = entries(m);
    for (std::size_t k = 0; k < e.size(); ++k) out << e[k] << (k + 1 < e.size() ? ' ' : '\n');
  }
  finish_medit_output(out, path);
}

}  // namespace

TriangleMesh read_medit_mesh(const std::string& path) {
  Tokens t(path, "Medit mesh file");
  TriangleMesh mesh;
  bool have_dimension = false;
  long dimension = 2;
  for (std::string key = t.keyword(); !key.empty(); key = t.keyword()) {
    if (t.header(key, " (only planar meshes are read)", dimension, {2, 3})) {
      have_dimension = have_dimension || key == "Dimension";
    } else if (key == "Vertices") {
      read_vertices(t, mesh.points, mesh.point_refs, [&](std::size_t i) {
        const std::array<double, 2> p{t.real("a vertex abscissa"), t.real("a vertex ordinate")};
        if (dimension == 3)
          if (const double z = t.real("a vertex z"); z != 0)
            t.fail("vertex " + std::to_string(i + 1) + " has z = " + std::to_string(z) +
                   "; expected 0 (only planar meshes are read)");
        return p;
      });
    } else if (key == "Triangles") {
      read_elements(t, mesh.points.size(), "a triangle count", "a triangle reference", mesh.triangles, mesh.triangle_refs);
    } else if (key == "Edges") {
      read_elements(t, mesh.points.size(), "an edge count", "an edge reference", mesh.edges, mesh.edge_refs);
    } else if (!skip_unused_section(t, key)) {
      unknown_keyword(t, key, "Vertices, Triangles, Edges");
    }
  }
  if (!have_dimension) throw MeshInputError(path, 0, "missing 'Dimension 2'");
  // Orient every triangle counter-clockwise, as the rest of the library assumes.
  for (auto& tri : mesh.triangles) {
    const auto& p = mesh.points[tri[0]];
    const auto& q = mesh.points[tri[1]];
    const auto& r = mesh.points[tri[2]];
    if ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]) < 0) std::swap(tri[1], tri[2]);
  }
  return mesh;
}

int medit_dimension(const std::string& path) {
  Tokens t(path, "Medit mesh file");
  for (std::string key = t.keyword(); !key.empty(); key = t.keyword()) {
    if (key == "MeshVersionFormatted") {
      t.integer("a format version");
    } else if (key == "Dimension") {
      const long d = t.integer("a dimension");
      if (d != 2 && d != 3) t.fail("expected 'Dimension 2' or 'Dimension 3', found " + std::to_string(d));
      return static_cast<int>(d);
    } else {
      break;
    }
  }
  throw MeshInputError(path, t.line(), "missing 'Dimension' before the first section");
}

TetMesh read_medit_tet_mesh(const std::string& path) {
  Tokens t(path, "Medit mesh file");
  TetMesh mesh;
  bool have_dimension = false;
  for (std::string key = t.keyword(); !key.empty(); key = t.keyword()) {
    if (long dimension = 0; t.header(key, " (a 3D mesh was expected)", dimension, {3})) {
      have_dimension = have_dimension || key == "Dimension";
    } else if (key == "Vertices") {
      read_vertices(t, mesh.points, mesh.point_refs, [&](std::size_t) {
        return std::array<double, 3>{t.real("a vertex x"), t.real("a vertex y"), t.real("a vertex z")};
      });
    } else if (key == "Triangles") {
      read_elements(t, mesh.points.size(), "a triangle count", "a triangle reference", mesh.triangles,
                    mesh.triangle_refs, &mesh.triangle_lines);
    } else if (key == "Tetrahedra") {
      read_elements(t, mesh.points.size(), "a tetrahedron count", "a tetrahedron reference", mesh.tetrahedra,
                    mesh.tetrahedron_refs);
    } else if (key == "Edges") {
      skip_records(t, t.count("an edge count"), 3);
    } else if (!skip_unused_section(t, key)) {
      unknown_keyword(t, key, "Vertices, Triangles, Tetrahedra, Edges");
    }
  }
  if (!have_dimension) throw MeshInputError(path, 0, "missing 'Dimension 3'");
  for (auto& tet : mesh.tetrahedra) {
    const auto& a = mesh.points[tet[0]];
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k)
      u[k] = mesh.points[tet[1]][k] - a[k], v[k] = mesh.points[tet[2]][k] - a[k], w[k] = mesh.points[tet[3]][k] - a[k];
    const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    if (det < 0) std::swap(tet[2], tet[3]);
  }
  return mesh;
}

namespace {

/// The metric 1/h² of a scalar size h (solution type 1), which must be positive.
double size_metric(Tokens& t) {
  const double h = t.real("a size");
  if (!(h > 0)) t.fail("a size must be positive, found " + std::to_string(h));
  return 1 / (h * h);
}

/// A Medit .sol file of `vertex_count` values in `dimension` (`note` ends the message for another):
/// one `SolAtVertices` section of one field, scalar sizes (type 1) or symmetric tensors (type 3), each
/// value read by `value(tokens, type)` and checked symmetric positive definite.
template <class M, class ReadValue>
std::vector<M> read_solution(const std::string& path, std::size_t vertex_count, long dimension, const std::string& note,
                             ReadValue value) {
  Tokens t(path, "Medit solution file");
  std::vector<M> metrics;
  bool have_solution = false;
  for (std::string key = t.keyword(); !key.empty(); key = t.keyword()) {
    if (long d = 0; t.header(key, note, d, {dimension})) continue;
    if (key != "SolAtVertices")
      t.fail("unknown keyword '" + key + "' (expected MeshVersionFormatted, Dimension, SolAtVertices or End)");
    const std::size_t n = t.count("a vertex count");
    if (n != vertex_count)
      t.fail("the solution has " + std::to_string(n) + " values but the mesh has " + std::to_string(vertex_count) +
             " vertices");
    if (const long fields = t.integer("a field count"); fields != 1)
      t.fail("expected exactly 1 solution field, found " + std::to_string(fields));
    const long type = t.integer("a solution type");
    if (type != 1 && type != 3)
      t.fail("expected solution type 1 (scalar size) or 3 (symmetric tensor), found " + std::to_string(type));
    metrics.resize(n);
    for (M& m : metrics) {
      m = value(t, type);
      if (type == 3 && !is_metric(m)) t.fail("the tensor is not symmetric positive definite");
    }
    have_solution = true;
  }
  if (!have_solution) throw MeshInputError(path, 0, "missing 'SolAtVertices' section");
  return metrics;
}

}  // namespace

std::vector<Metric3> read_medit_sol3(const std::string& path, std::size_t vertex_count) {
  return read_solution<Metric3>(path, vertex_count, 3, " (a 3D solution was expected)", [](Tokens& t, long type) {
    if (type == 1) {
      const double l = size_metric(t);
      return Metric3{l, 0, 0, l, 0, l};
    }
    const double m11 = t.real("m11"), m12 = t.real("m12"), m22 = t.real("m22");
    const double m13 = t.real("m13"), m23 = t.real("m23"), m33 = t.real("m33");
    return Metric3{m11, m12, m13, m22, m23, m33};
  });
}

void write_medit_mesh(const std::string& path, const TetMesh& mesh) {
  write_mesh_file(path, mesh.points, mesh.point_refs, ElementSection<3>{"Triangles", mesh.triangles, mesh.triangle_refs},
                  ElementSection<4>{"Tetrahedra", mesh.tetrahedra, mesh.tetrahedron_refs});
}

void write_medit_sol(const std::string& path, const std::vector<Metric3>& metrics) {
  write_sol_file(path, 3, metrics, [](const Metric3& m) { return std::array<double, 6>{m.xx, m.xy, m.yy, m.xz, m.yz, m.zz}; });
}

std::vector<Metric> read_medit_sol(const std::string& path, std::size_t vertex_count) {
  return read_solution<Metric>(path, vertex_count, 2, "", [](Tokens& t, long type) {
    if (type == 1) {
      const double l = size_metric(t);
      return Metric{l, 0, l};
    }
    const double m11 = t.real("m11"), m12 = t.real("m12"), m22 = t.real("m22");
    return Metric{m11, m12, m22};
  });
}

void write_medit_mesh(const std::string& path, const TriangleMesh& mesh) {
  write_mesh_file(path, mesh.points, mesh.point_refs, ElementSection<2>{"Edges", mesh.edges, mesh.edge_refs},
                  ElementSection<3>{"Triangles", mesh.triangles, mesh.triangle_refs});
}

void write_medit_sol(const std::string& path, const std::vector<Metric>& metrics) {
  write_sol_file(path, 2, metrics, [](const Metric& m) { return std::array<double, 3>{m.a, m.b, m.c}; });
}

}  // namespace laguerre::core
