// The thumbnails' software rasterizer: a top-down height map of the print (the highest z laid
// at each pixel), shaded by its slope under a light from the upper left and tinted by height,
// on a transparent background. Supersampled, then averaged down: edges are anti-aliased and
// a 16×16 icon still shows the shape. Fed either the toolpaths (PreviewLayer: each piece a
// capsule of its width) or the sliced islands (before any toolpath exists, e.g. to write the
// thumbnails at the top of the G-code): both in bed coordinates, mm.
#pragma once

#include <vector>

#include "geometry/core/layer.h"
#include "geometry/preview/colours.h"
#include "geometry/preview/image.h"
#include "geometry/preview/preview.h"

namespace tranche::preview {

struct BoxMm {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return !(x0 < x1) || !(y0 < y1); }
};

struct ShadeStyle {
  Rgb colour{0xed, 0x6b, 0x21};  // the filament: orange, as printer screens usually show it
  float ambient = 0.35f;         // light on faces turned away from the lamp, 0..1
};

class HeightCanvas {
 public:
  // `box` (bed mm) is fitted into width × height pixels with a small margin, aspect kept.
  HeightCanvas(int width_px, int height_px, BoxMm box);

  // A straight bead from a to b, width_mm wide, whose top is at z_mm.
  void add_segment(PointMm a, PointMm b, float width_mm, float z_mm);
  // Every piece of every path of the layer, at the layer's z.
  void add_layer(const PreviewLayer& layer);
  // The island's area (outline minus holes, even-odd) at z_mm; model units offset by (dx, dy) mm
  // into bed coordinates, as the G-code writer places them.
  void add_polygon(const geo::Polygon& poly, double dx_mm, double dy_mm, float z_mm);
  // Every island of a sliced layer at its top (z_top).
  void add_layer(const geo::Layer& layer, double dx_mm, double dy_mm);

  Image shade(const ShadeStyle& style = {}) const;

 private:
  void fill_spans(const std::vector<std::vector<PointMm>>& rings, float z_mm);
  int w_, h_, ss_;          // output size and supersampling factor
  int sw_, sh_;             // the height map's size (output × ss_)
  double scale_, ox_, oy_;  // px per mm, and the pixel of bed (0, 0)
  std::vector<float> z_;    // height map, -1 where nothing was laid
};

// The print's extent (every path point), bed mm; empty when there are no paths.
BoxMm print_box(const PreviewPrint& print);

// A width × height thumbnail of the print's toolpaths (transparent when there are none).
Image render_thumbnail(const PreviewPrint& print, int width, int height, const ShadeStyle& style = {});

}  // namespace tranche::preview
