// Where things are in an SVG file (byte offsets -> file:line:col) and the viewport of an <svg>
// element (width, height, viewBox, preserveAspectRatio -> a user-unit-to-px transform).
#pragma once

#include <pugixml.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "geometry/io/svg_style.h"
#include "base/result.h"

namespace tranche::geo::svg {

class SourceMap {
 public:
  SourceMap(std::string_view text, std::string name);
  const std::string& name() const { return name_; }
  // "name:line:col" (1-based) of a byte offset.
  std::string at(size_t offset) const;
  // The start of an element's tag.
  std::string at(pugi::xml_node n) const;
  // Character `index` of the value of attribute `attr` of element `n`; the element's location
  // when the raw text does not map one to one (entities in the value).
  std::string at_attr(pugi::xml_node n, std::string_view attr, size_t index) const;

 private:
  std::string_view text_;
  std::string name_;
  std::vector<size_t> line_starts_;
};

struct Viewport {
  Affine user_to_px;    // maps the element's user units to its parent's px (SVG user units)
  double width_px = 0;  // the viewport size; 0 when neither width/height nor viewBox give it
  double height_px = 0;
  double user_width = 0;  // the same size in the element's own user units (percentages refer to it)
  double user_height = 0;
};

// Reads width, height, viewBox and preserveAspectRatio of an <svg> element. A nested <svg> also
// moves by its x, y. Errors: unknown units, a malformed or empty viewBox, absurd sizes.
Result<Viewport> viewport_of(pugi::xml_node svg_element, const SourceMap& src, bool root);

}  // namespace tranche::geo::svg
