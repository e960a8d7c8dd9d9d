// A legend for the layer SVG export (--export-svg): an SVG fragment (a <g>) listing what each
// class of mark means. The exporter calls it with its own classes and places the fragment
// where it has room; the fragment's size is returned so the viewBox can make that room.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace tranche::preview {

enum class Swatch : uint8_t {
  Fill,  // a filled square (islands, regions)
  Line,  // a solid stroke (borders, toolpaths)
  Dash,  // a dashed stroke (cuts)
};

struct LegendEntry {
  std::string css_class;  // the class the drawing uses for these marks; the swatch gets it too
  std::string colour;     // "#rrggbb"; empty: the swatch takes its colour from the class's CSS
  std::string label;      // what the marks are ("artificial edge: a cut of the decomposition")
  Swatch swatch = Swatch::Fill;
};

struct LegendLayout {
  double x = 0, y = 0;  // top left corner, in the SVG's user units
  double font = 12;     // text size, user units
  std::string title = "Legend";
};

struct SvgLegend {
  std::string svg;               // <g class="legend" ...>...</g>, ending in '\n'
  double width = 0, height = 0;  // its extent, user units
};

SvgLegend svg_legend(std::span<const LegendEntry> entries, const LegendLayout& layout = {});

// The path kinds in the G-code preview's colours (PrusaSlicer's), classes "kind-<name>".
std::vector<LegendEntry> kind_legend_entries();

}  // namespace tranche::preview
