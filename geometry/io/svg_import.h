// SVG input: a flat drawing (extruded by the pipeline) or a layer stack written by --export-svg.
// Coordinates: SVG's y axis points down; ours points up. A point (x, y) of the page, in mm, lands
// at (x, H - y) where H is the page height, so the print looks like the drawing seen from above
// (not mirrored) and the page's bottom-left corner is the origin. See docs/svg-input.md.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/geom.h"
#include "geometry/io/svg_paint.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo {

struct SvgImportOptions {
  double tolerance_mm = 0.01;  // largest distance between a curve and its polyline
  SvgOverlap overlap = SvgOverlap::Additive;
  std::string background = "white";  // Subtractive: the colour that erases (any CSS colour)
};

struct SvgLayer {
  double z_bottom = 0, z_top = 0;  // mm; both 0 for a flat drawing
  Polygons polygons;               // material after overlap resolution: outer CCW, holes CW
};

struct SvgModel {
  bool layer_stack = false;      // true: the file is a layer stack written by --export-svg
  std::vector<SvgLayer> layers;  // a flat drawing has exactly one
  double page_width_mm = 0;      // the page (viewport) size; 0 when the file gives none
  double page_height_mm = 0;
};

// Reads an SVG file. Errors (no output is possible) name the file and line:col: not XML, not an
// <svg> document, unknown units, malformed path data or transforms, absurd sizes, nothing to
// fill. Ignored content (text, images, strokes, lines, stylesheets, clip paths) is a warning in
// `report` with its location.
Result<SvgModel> load_svg(const std::string& path, const SvgImportOptions& options, Report& report);

// Same, from text in memory; `name` is used in messages.
Result<SvgModel> parse_svg(std::string_view text, const std::string& name, const SvgImportOptions& options,
                           Report& report);

// True when the file starts like an SVG document (for telling SVG from STL by content).
bool looks_like_svg(std::string_view head);

}  // namespace tranche::geo
