#include "geometry/preview/colours.h"

#include <algorithm>
#include <cmath>

#include "runtime/schema/type_names.h"

namespace tranche::preview {

using schema::PathKind;

Rgb kind_colour(PathKind k) {
  switch (k) {
    case PathKind::OuterPerimeter:
      return {0xff, 0x7d, 0x38};
    case PathKind::InnerPerimeter:
      return {0xff, 0xe6, 0x4d};
    case PathKind::Infill:
      return {0xb0, 0x30, 0x29};
    case PathKind::SolidInfill:
    case PathKind::BottomSolid:  // the G-code marks both "Solid infill"
      return {0x96, 0x54, 0xcc};
    case PathKind::TopSolid:
      return {0xf0, 0x40, 0x40};
    case PathKind::Bridge:
      return {0x4d, 0x80, 0xba};
    case PathKind::Skirt:
      return {0x00, 0x87, 0x6e};
    case PathKind::Ironing:
      return {0xff, 0x8c, 0x69};
    case PathKind::Custom:
      return {0x5e, 0xd1, 0x94};
    case PathKind::Support:
      return {0x00, 0xff, 0x00};  // PrusaSlicer's support colours
    case PathKind::SupportInterface:
      return {0x00, 0x80, 0x00};
    case PathKind::Brim:
      return {0x00, 0x87, 0x6e};
    case PathKind::GapFill:
      return {0xa0, 0xa0, 0xa0};  // grey: PrusaSlicer's white would vanish on the white page
  }
  return {0x80, 0x80, 0x80};
}

std::string_view kind_label(PathKind k) {
  // The G-code's name, but bottom skins told apart from internal solid infill.
  return k == PathKind::BottomSolid ? "Bottom solid infill" : schema::gcode_type_name(k);
}

const std::array<Rgb, kRangeColourCount>& range_colours() {
  static const std::array<Rgb, kRangeColourCount> k = {{{0x0b, 0x2c, 0x7a},
                                                        {0x13, 0x59, 0x85},
                                                        {0x1c, 0x88, 0x91},
                                                        {0x04, 0xd6, 0x0f},
                                                        {0xaa, 0xf2, 0x00},
                                                        {0xfc, 0xf9, 0x03},
                                                        {0xf5, 0xce, 0x0a},
                                                        {0xe3, 0x88, 0x20},
                                                        {0xd1, 0x68, 0x30},
                                                        {0xc2, 0x52, 0x3c},
                                                        {0x94, 0x26, 0x16}}};
  return k;
}

Rgb range_colour(double t) {
  if (!(t > 0)) t = 0;  // NaN too
  const int i = static_cast<int>(std::lround(std::min(t, 1.0) * (kRangeColourCount - 1)));
  return range_colours()[i];
}

Rgb category_colour(int i) {
  // Tableau's 10 plus two, chosen to stay apart from one another on a dark background.
  static const Rgb k[kCategoryColourCount] = {{0x4e, 0x79, 0xa7}, {0xf2, 0x8e, 0x2b}, {0xe1, 0x57, 0x59},
                                              {0x76, 0xb7, 0xb2}, {0x59, 0xa1, 0x4f}, {0xed, 0xc9, 0x48},
                                              {0xb0, 0x7a, 0xa1}, {0xff, 0x9d, 0xa7}, {0x9c, 0x75, 0x5f},
                                              {0xba, 0xb0, 0xac}, {0x17, 0xbe, 0xcf}, {0xbc, 0xbd, 0x22}};
  return k[((i % kCategoryColourCount) + kCategoryColourCount) % kCategoryColourCount];
}

std::string to_hex(Rgb c) {
  static const char* d = "0123456789abcdef";
  std::string s = "#";
  for (uint8_t v : {c.r, c.g, c.b}) {
    s.push_back(d[v >> 4]);
    s.push_back(d[v & 15]);
  }
  return s;
}

}  // namespace tranche::preview
