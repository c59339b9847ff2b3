#pragma once
/// @file
/// Pictures of packings and routes (Cairo: SVG and PNG side by side).

#include <functional>
#include <string>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

struct _cairo;

namespace laguerre::tools {

/// Draws the same picture twice, into `stem.svg` and `stem.png` (width × height pixels), by calling
/// `draw` on each Cairo context; returns the two paths. Throws std::runtime_error if a file cannot be
/// written. Every picture of the CLI goes through here.
std::vector<std::string> render_svg_png(const std::string& stem, int width, int height,
                                        const std::function<void(_cairo*)>& draw);

/// A circle filled green (`ok`, opacity `alpha_ok`) or red (opacity `alpha_bad`) and outlined in dark
/// grey with `line_width` (user units): a vertex's LPD/GLPD status in the packing pictures.
void draw_status_circle(_cairo* cr, double x, double y, double r, bool ok, double alpha_ok, double alpha_bad,
                        double line_width);

/// What a packing picture shows.
struct PackingPicture {
  const core::PlanarGraph* graph = nullptr;              ///< the network
  const core::CircleEmbedding* circles = nullptr;        ///< φ, one circle per vertex
  std::vector<bool> ok;                                  ///< per vertex: LPD/GLPD holds (filled green) or not (red)
  std::vector<std::vector<core::Point2>> cells;          ///< local power cells to outline (may be empty)
  const core::CircleEmbedding* face_circles = nullptr;   ///< orthogonal face circles (dashed), optional
  std::vector<std::vector<core::Vertex>> routes;         ///< paths to draw on top, optional
  std::string title;                                     ///< caption
};

/// Writes `stem.svg` and `stem.png` (size × size pixels) and returns the two paths.
std::vector<std::string> render_packing(const PackingPicture& picture, const std::string& stem, int size = 900);

}  // namespace laguerre::tools
