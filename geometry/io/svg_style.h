// The attribute values SVG input needs besides path data: transforms, lengths with units,
// colours and the `style` attribute's declarations.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/io/svg_path.h"
#include "base/result.h"

namespace tranche::geo::svg {

// x' = a x + c y + e, y' = b x + d y + f (the SVG matrix(a b c d e f)).
struct Affine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;

  Vec2 apply(Vec2 p) const { return {a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
  // (*this) ∘ t: applies t first, then *this.
  Affine operator*(const Affine& t) const;
  // The largest factor by which the map stretches a length (its largest singular value).
  double max_scale() const;
  static Affine translate(double tx, double ty) { return {1, 0, 0, 1, tx, ty}; }
  static Affine scale(double sx, double sy) { return {sx, 0, 0, sy, 0, 0}; }
  static Affine rotate_deg(double deg);
};

// Parses a transform list: matrix, translate, scale, rotate (with optional centre), skewX, skewY,
// separated by whitespace and/or commas. On error sets *error_offset (index in `s`).
Result<Affine> parse_transform(std::string_view s, size_t* error_offset = nullptr);

// Lengths: a number and an optional unit, converted to CSS px (SVG user units: 96 px per inch).
// Units: none, px, mm, cm, in, pt, pc, Q. Percentages and font-relative units (em, ex) have no
// meaning without a viewport or font here: the error says so.
Result<double> parse_length_px(std::string_view s);
inline constexpr double kMmPerPx = 25.4 / 96;

// An RGB colour, 0xRRGGBB.
using Rgb = uint32_t;

// A `fill` value: none, a colour, currentColor, or a paint server reference (url(#...)).
struct Paint {
  enum class Kind : uint8_t { None, Color, CurrentColor, Url };
  Kind kind = Kind::Color;
  Rgb rgb = 0;  // black, the SVG initial fill
};

// Parses a CSS colour: a name, #rgb, #rrggbb, rgb(r, g, b) with numbers or percentages (rgba and
// #rrggbbaa accepted, alpha ignored). nullopt if not a colour.
std::optional<Rgb> parse_color(std::string_view s);
// Parses a fill: `none`, `currentColor`, `url(#id) [fallback]`, or a colour.
std::optional<Paint> parse_paint(std::string_view s);

// The declarations of a `style` attribute, in order, names lower-cased and values trimmed.
std::vector<std::pair<std::string, std::string>> parse_style(std::string_view s);

std::string_view trim(std::string_view s);

}  // namespace tranche::geo::svg
