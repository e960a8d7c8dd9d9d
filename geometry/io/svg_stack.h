// Layer stacks: the SVG that --export-svg writes (format "tranche-layers-svg", docs/formats.md)
// holds one group per layer with its z range. Telling one from a flat drawing, and finding its
// layers.
#pragma once

#include <pugixml.hpp>

#include <string>
#include <vector>

#include "geometry/io/svg_source.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo::svg {

inline constexpr const char* kStackNamespace = "urn:tranche:layers";
inline constexpr const char* kStackFormat = "tranche-layers-svg";
inline constexpr int kStackVersion = 2;  // the newest version this reader knows (2 adds printed paths)

struct StackLayer {
  pugi::xml_node node;             // the layer's group; its transform only places it on the sheet
  double z_bottom = 0, z_top = 0;  // mm
};

struct Stack {
  bool is_stack = false;           // the root carries the tranche namespace and format
  std::vector<StackLayer> layers;  // bottom to top
};

// Finds the layer groups of a layer stack. The namespace is matched by URI, not prefix. Errors:
// an unknown format or version, units other than mm, a layer group without a readable z range,
// layers out of order or overlapping, a stack without layers. A z gap between two layers (a
// layer group deleted in an editor) is a warning.
Result<Stack> read_stack(pugi::xml_node root, const SourceMap& src, Report& report);

// True when the element's class attribute lists `cls`.
bool has_class(pugi::xml_node n, std::string_view cls);

}  // namespace tranche::geo::svg
