// The preview's colours, shared by the HTML viewer (written into its data), the thumbnails and
// the SVG legend. Path kinds take PrusaSlicer's G-code viewer colours, value ranges its 11-step
// blue-to-red scale, so a user who knows that viewer reads ours at a glance.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "runtime/schema/schema.h"

namespace tranche::preview {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};

// Every schema::PathKind value (the viewer looks a path's kind up by its value: a kind left out
// had no colour or label, support and brim included).
inline constexpr int kPathKindCount = static_cast<int>(schema::PathKind::GapFill) + 1;
Rgb kind_colour(schema::PathKind k);
// The G-code's ;TYPE: name of a kind ("External perimeter"), as PrusaSlicer labels it.
std::string_view kind_label(schema::PathKind k);

inline constexpr int kRangeColourCount = 11;
// The range scale's colours, lowest value first.
const std::array<Rgb, kRangeColourCount>& range_colours();
// Colour of t in [0, 1] on the range scale (clamped), stepped as the legend shows it.
Rgb range_colour(double t);

// Distinct colours for categories (deciding rules), cycled when there are more.
inline constexpr int kCategoryColourCount = 12;
Rgb category_colour(int i);

std::string to_hex(Rgb c);  // "#rrggbb"

}  // namespace tranche::preview
