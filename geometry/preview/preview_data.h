// The preview's data as the viewer reads it (format "tranche-preview", version 1): one JSON
// object holding the tables (kinds and colours, interned strings, the distinct provenance records,
// per-layer counts) and `blob`, the geometry and per-piece values as base64 of zlib-compressed
// varints. Coordinates are quantized to 10 µm and delta-encoded. docs/preview.md specifies it.
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "geometry/preview/preview.h"

namespace tranche::preview {

inline constexpr int kPreviewFormatVersion = 1;
inline constexpr double kCoordQuantumMm = 0.01;

// Encodes a print layer by layer, so the caller keeps only the layer at hand (the pipeline adds
// each layer as it writes its G-code, then frees its toolpaths). Memory: the compressed-to-be
// blob, a few bytes a point, and each distinct provenance record once.
class PreviewEncoder {
 public:
  PreviewEncoder(float bed_x_mm, float bed_y_mm, std::string title);
  ~PreviewEncoder();
  PreviewEncoder(PreviewEncoder&&) noexcept;
  PreviewEncoder& operator=(PreviewEncoder&&) noexcept;

  // Bottom to top. An error names the layer (in the order added) and the path; every later
  // call returns it again, since the data is incomplete.
  Status add_layer(const PreviewLayer& layer);
  // The JSON of every layer added (encode_preview_json's text).
  Result<std::string> finish();
  const std::string& title() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// The JSON text, or an error naming the layer and path that cannot be encoded (non-finite
// coordinates or values, per-piece lists of the wrong length). The text contains no '<', so it
// can sit inside an HTML <script> element as it is.
Result<std::string> encode_preview_json(const PreviewPrint& print);

}  // namespace tranche::preview
