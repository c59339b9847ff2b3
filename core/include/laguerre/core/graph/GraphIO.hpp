#pragma once
/// @file
/// Reading and writing planar graphs: edge lists, straight-line drawings ("coords") and plantri's
/// planar_code.
///
/// ## Formats
///
/// **edges** (text). One edge `u v` per line, two non-negative 64-bit integer vertex ids separated by
/// blanks. Blank lines are ignored; `#` starts a comment that runs to the end of the line. One optional
/// directive, a comment line of the form
///
///     # outer: a b c ...
///
/// gives the outer face as a cycle of at least 3 vertex ids in boundary order. Ids are kept as the
/// user's ids; vertex indices are assigned in increasing id order. The embedding is computed by
/// Boost.Graph's Boyer–Myrvold planarity test. With `# outer:`, an apex vertex joined to the listed
/// vertices is embedded with the graph and then removed, which forces that cycle to be a face (this is
/// what makes triangulated discs, whose embedding is otherwise not unique, come out right); the
/// embedding is then oriented so that `PlanarGraph::boundary_cycle()` lists the outer face in the
/// order given. Without it the outer face is `PlanarGraph::default_outer_dart()`'s face and the
/// orientation (a mirror image is as good as the original) is whatever Boyer–Myrvold returns.
///
/// **coords** (text): a straight-line plane drawing. Same comments, blank lines and `# outer:`
/// directive as edges, and two sections introduced by header lines consisting of the single word
/// `vertices` and then `edges`:
///
///     # a unit square with a diagonal
///     vertices
///     1 0 0
///     2 1 0
///     3 1 1
///     4 0 1
///     edges
///     1 2
///     2 3
///     3 4
///     4 1
///     1 3
///
/// A vertex line is `id x y` (id a non-negative 64-bit integer, x and y finite decimal numbers); an edge
/// line is `u v` with declared ids. The rotation at each vertex is the counter-clockwise order of its
/// edges around its position (decided exactly), and the drawing must be plane: distinct positions, no
/// two edges crossing or overlapping, no edge through a vertex (checked exactly). The outer face is the
/// unbounded face (walked clockwise in the drawing) unless `# outer:` names another face, given in either
/// direction; either way `outer_given` is true. Vertex indices follow increasing ids, as for edges. The
/// positions are returned.
///
/// **planar_code** (binary, plantri's format). A header `>>planar_code<<`, `>>planar_code le<<` or
/// `>>planar_code be<<` (optional when the format is requested explicitly), then one or more graphs
/// back to back. A graph is its number of vertices n followed, for each vertex 1..n, by its neighbours
/// in clockwise order and a terminating 0. Entries are single bytes, unless the graph starts with a 0
/// byte: then n and every following entry of that graph are 2-byte integers, little-endian unless the
/// header says `be`. Ids are 1..n as in plantri; the outer face is the default one. Graph i (from 1) of
/// file F is named "F#i". Input without a header and without any 0 byte (every graph has one) is
/// rejected as not planar_code, quoting its start.
///
/// **graphml** (XML, http://graphml.graphdrawing.org). Exactly one `<graph>`, undirected (an edge that
/// is directed, by `edgedefault="directed"` or `directed="true"`, is an error); `<node id=…>` elements
/// and `<edge source=… target=…>` elements between declared nodes (an undeclared node is an error, as
/// are self-loops, repeated edges, nested graphs and hyperedges). Optional node keys whose `attr.name`
/// is `x` and `y` give positions (for every node or for none); with them the graph is read as a
/// drawing (like coords), without them it is embedded like edges. An optional graph key named `outer`
/// (a string of node ids separated by blanks) plays the part of `# outer:`. The XML is parsed by
/// Boost.PropertyTree (the parser Boost.Graph's own read_graphml uses; that reader is not used because
/// it drops node ids and silently creates undeclared nodes). Malformed XML is reported with its line.
/// Elements nested more than `graphml_max_depth` deep are rejected, with the line of the first one too
/// deep, before the (recursive) parser runs.
///
/// **dot** (Graphviz), read by Boost.Graph's read_graphviz: an undirected `graph` (a `digraph` is an
/// error); node names are the DOT node ids; positions from `pos="x,y"` (an optional trailing `!`
/// allowed) or from `x` and `y` attributes; a graph attribute `outer="a b c"` plays the part of
/// `# outer:`. Self-loops and repeated edges are errors. Syntax errors carry Boost's message (Boost
/// gives no line number).
///
/// Node names of GraphML and DOT become user ids: the names themselves if all are non-negative decimal
/// integers; otherwise, if all share a non-numeric prefix followed by distinct decimal numbers without
/// leading zeros (`n0`, `n1`, … as yEd and networkx write), those numbers; otherwise 0, 1, … in file
/// order (GraphML) or in Boost's order of the names (DOT). Messages name nodes by their file names.
///
/// **automatic**: planar_code if the input starts with `>>planar_code`; graphml if it starts (after
/// blanks) with `<?xml`, `<graphml` or an XML comment; dot if its first word (after blanks and `//`,
/// `#` or `/* */` comments) is `graph`, `digraph` or `strict`; coords if a line consists of the word
/// `vertices`; edges otherwise.
///
/// Every problem is reported as a GraphInputError naming the source and, where it applies, the line or
/// the graph index.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/Embedding.hpp"
#include "laguerre/core/graph/GraphError.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// The deepest element nesting the GraphML reader accepts (GraphML itself needs 4 levels; yEd's
/// graphics add about 10).
inline constexpr std::size_t graphml_max_depth = 256;

/// A graph file format (see the file comment for each).
enum class GraphFormat { automatic, edges, planar_code, coords, graphml, dot };

/// Parses "automatic", "edges", "planar_code", "coords", "graphml" or "dot"; throws GraphInputError (source
/// "format") listing them.
GraphFormat parse_graph_format(std::string_view name);

/// Name of a format, as accepted by parse_graph_format.
std::string_view to_string(GraphFormat format);

/// Reads every graph of the file at `path`, opened by core::read_input_file. Throws GraphInputError (also
/// with read_input_file's message if the file is missing, a directory or unreadable).
std::vector<GraphInput> read_graphs(const std::string& path, GraphFormat format = GraphFormat::automatic);

/// Reads every graph of `data` (text, or planar_code bytes); `source_name` is used in names and errors.
std::vector<GraphInput> read_graphs_from_string(std::string_view data, const std::string& source_name = "<input>",
                                                GraphFormat format = GraphFormat::automatic);

/// Writes `g` in the edges format: a comment, a `# outer:` line (boundary_cycle() order) and one
/// `u v` line per edge (user ids, smaller first, sorted). The `# outer:` line is written only when the
/// reader honours it: the boundary is a simple cycle of at least 3 vertices and g is 3-connected or a
/// triangulated disc; else the outer face is left to the reader, so that every output reads back.
std::string write_edge_list(const PlanarGraph& g);

/// Writes `g` as GraphML: nodes with the user ids as GraphML ids, undirected edges sorted as in
/// write_edge_list, a graph key `outer` (boundary_cycle() order; when positions are given, whenever the
/// boundary is a simple cycle of at least 3 vertices, else as in write_edge_list) and, when `positions`
/// is not empty (one per vertex, a drawing of g: a precondition), node keys `x` and `y` with 17
/// significant digits.
std::string write_graphml(const PlanarGraph& g, const std::vector<Point2>& positions = {});

/// Writes `g` as an undirected Graphviz graph: node names are user ids, `pos="x,y"` when `positions`
/// is not empty (one per vertex: a precondition), a graph attribute `outer` (when write_graphml writes
/// its key `outer`), edges sorted as in write_edge_list.
std::string write_dot(const PlanarGraph& g, const std::vector<Point2>& positions = {});

/// Writes graphs in planar_code with the header `>>planar_code le<<`; vertex i becomes i + 1 (user ids
/// are not stored) and neighbours are listed clockwise. Throws GraphInputError (source "planar_code
/// output") beyond 65535 vertices.
std::string write_planar_code(const std::vector<PlanarGraph>& graphs);

}  // namespace laguerre::core
