// --export-layers: every layer's islands as JSON, format "tranche-layers" version 1. The format
// is specified in docs/formats.md; it is streamed layer by layer, never built as a DOM.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "geometry/core/layer.h"
#include "base/result.h"

namespace tranche::geo {

inline constexpr int kLayersJsonVersion = 1;

// Writes `layers` (bottom to top) to `path` atomically (a temporary file renamed at the end).
// `source` names the model in the header (e.g. its file name).
// `progress`, when set, is called with the number of layers written so far.
Status write_layers_json(const std::string& path, const std::vector<Layer>& layers, const std::string& source,
                         const std::function<void(size_t)>& progress = {});

// One element of the "layers" array, without a trailing comma or newline.
void append_layer_json(fmt::memory_buffer& out, const Layer& layer);

}  // namespace tranche::geo
