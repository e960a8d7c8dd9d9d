// Thumbnails in the G-code for printer screens and OctoPrint/Moonraker/Mainsail, in
// PrusaSlicer's comment format (what those tools and Prusa's firmware read):
//   ;
//   ; thumbnail begin 300x300 12345        (thumbnail_QOI for QOI; 12345 = base64 characters)
//   ; iVBORw0KGgo...                       (base64, at most 78 characters a line)
//   ; thumbnail end
//   ;
// Sizes and formats are given as PrusaSlicer's `thumbnails` setting: "16x16/QOI, 300x300/PNG".
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "geometry/preview/image.h"
#include "geometry/preview/raster.h"

namespace tranche::preview {

enum class ThumbnailFormat : uint8_t { Png, Qoi };

struct ThumbnailSpec {
  int width = 0, height = 0;  // px
  ThumbnailFormat format = ThumbnailFormat::Png;
};

inline constexpr int kMaxThumbnailSide = 1024;  // px

// "16x16/QOI, 220x124/PNG" (comma or space separated; the format defaults to PNG). An error
// names the entry that is not WxH[/PNG|/QOI] or whose size is outside 1..1024 px.
Result<std::vector<ThumbnailSpec>> parse_thumbnail_specs(std::string_view text);

// One comment block for an encoded image (PNG or QOI bytes), ending in '\n'.
std::string thumbnail_block(std::string_view encoded, const ThumbnailSpec& spec);

// Encodes `image` (of spec.width × spec.height) as `spec` says, and returns its block.
Result<std::string> thumbnail_block(const Image& image, const ThumbnailSpec& spec);

// Every block of `specs`: for each, a HeightCanvas of its size over `box` (bed mm) is handed to
// `draw` (which adds the toolpaths, or the sliced islands when the toolpaths are not planned yet),
// then shaded and encoded.
using DrawThumbnail = std::function<void(HeightCanvas&)>;
Result<std::string> thumbnails_gcode(BoxMm box, const DrawThumbnail& draw,
                                     std::span<const ThumbnailSpec> specs, const ShadeStyle& style = {});
// The same from the print's toolpaths (render_thumbnail).
Result<std::string> thumbnails_gcode(const PreviewPrint& print, std::span<const ThumbnailSpec> specs,
                                     const ShadeStyle& style = {});

}  // namespace tranche::preview
