// --export-svg: every layer's islands as an SVG contact sheet (format "tranche-layers-svg"
// version 1, specified in docs/formats.md): one <g id="layer-N"> per layer carrying its index
// and z range, laid out in a grid with a caption, viewable in any browser. Inside a layer group,
// path coordinates are the model's (x, −y) in mm, exactly; the group's transform only places the
// layer on the sheet.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "geometry/core/layer.h"
#include "base/result.h"

namespace tranche::geo {

inline constexpr int kLayersSvgVersion = 1;
inline constexpr const char* kTrancheSvgNamespace = "urn:tranche:layers";

// Writes `layers` (bottom to top) to `path` atomically. `source` names the model in the title.
// `progress`, when set, is called with the number of layers written so far.
Status write_layers_svg(const std::string& path, const std::vector<Layer>& layers, const std::string& source,
                        const std::function<void(size_t)>& progress = {});

}  // namespace tranche::geo
