// --export-preview: the toolpaths as one self-contained HTML file (no network, no server; opens
// from file:// in Chromium and Firefox): a layer slider, zoom and pan, colours by kind, speed,
// flow, width, fan, temperature, volumetric rate or deciding rule, travels and retractions, a
// stacked view of the layers below, and each path's provenance on click. docs/preview.md.
#pragma once

#include <string>

#include "base/result.h"
#include "geometry/preview/preview.h"
#include "geometry/preview/preview_data.h"

namespace tranche::preview {

// Writes the page to `path` atomically (OutputFile): the viewer (geometry/preview/viewer,
// embedded at build time) and the data of preview_data.h.
Status write_preview_html(const std::string& path, const PreviewPrint& print);

// The same from an encoder every layer was added to (the streaming form: the pipeline adds
// each layer as it goes and keeps none).
Status write_preview_html(const std::string& path, PreviewEncoder& encoder);

// The page as a string (what write_preview_html writes).
Result<std::string> preview_html(const PreviewPrint& print);
Result<std::string> preview_html(PreviewEncoder& encoder);

}  // namespace tranche::preview
