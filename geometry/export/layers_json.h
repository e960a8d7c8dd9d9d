// --export-layers: every layer as JSON, format "tranche-layers" version 2 (docs/formats.md): the
// islands, and what the G-code prints on them (paths in print order, the G-code's cells), and on
// request the exact monotone cells (analysis). Streamed layer by layer, never built as a DOM.
#pragma once

#include <fmt/format.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/output_file.h"
#include "base/result.h"
#include "geometry/export/export_layer.h"

namespace tranche::exports {

inline constexpr int kLayersJsonVersion = 2;

class LayersJson {
 public:
  // Opens `path` (atomically replaced at finish()) and writes the header. `source` names the
  // model; `printed`/`exact` say whether layers will carry paths and exact cells.
  static Result<std::unique_ptr<LayersJson>> open(const std::string& path, const std::string& source,
                                                  size_t layer_count, bool printed, bool exact);
  // One element of the "layers" array, without separator. Thread-safe.
  static void append_layer(fmt::memory_buffer& out, const ExportLayer& layer);
  // Writes the next layer's element (from append_layer).
  Status write_layer(const fmt::memory_buffer& element);
  Status finish();

 private:
  explicit LayersJson(OutputFile file) : file_(std::move(file)) {}
  OutputFile file_;
  size_t written_ = 0;
};

// The islands of `layers` only (no plans), in one call.
Status write_layers_json(const std::string& path, const std::vector<geo::Layer>& layers, const std::string& source,
                         const std::function<void(size_t)>& progress = {});

}  // namespace tranche::exports
