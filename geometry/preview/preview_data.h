// The preview's data as the viewer reads it (format "tranche-preview", version 1): one JSON
// object holding the tables (kinds and colours, interned strings, the distinct provenance records,
// per-layer counts) and `blob`, the geometry and per-piece values as base64 of zlib-compressed
// varints. Coordinates are quantized to 10 µm and delta-encoded. docs/preview.md specifies it.
#pragma once

#include <string>

#include "base/result.h"
#include "geometry/preview/preview.h"

namespace tranche::preview {

inline constexpr int kPreviewFormatVersion = 1;
inline constexpr double kCoordQuantumMm = 0.01;

// The JSON text, or an error naming the layer and path that cannot be encoded (non-finite
// coordinates or values, per-piece lists of the wrong length). The text contains no '<', so it
// can sit inside an HTML <script> element as it is.
Result<std::string> encode_preview_json(const PreviewPrint& print);

}  // namespace tranche::preview
