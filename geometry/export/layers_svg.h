// --export-svg: every layer as an SVG contact sheet (format "tranche-layers-svg" version 2,
// docs/formats.md): one <g id="layer-N"> per layer carrying its index and z range, laid out in a
// grid with a caption and a legend, viewable in any browser. A layer group holds its islands
// and, when planned, the paths the G-code prints on them (drawn at their width, coloured by
// kind), and on request the seed's exact monotone cells (an analysis view). Inside a layer
// group, coordinates are the model's (x, −y) in mm, exactly; the group's transform only places
// the layer on the sheet.
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

inline constexpr int kLayersSvgVersion = 2;
inline constexpr const char* kTrancheSvgNamespace = "urn:tranche:layers";

// The contact sheet's grid, in mm of the sheet.
struct Sheet {
  geo::BBox2 model;             // all layers' islands (units)
  double pad = 0, caption = 0;  // mm
  double cell_w = 0, cell_h = 0, legend = 0;
  size_t cols = 1, rows = 1;
};
Sheet sheet_layout(const std::vector<geo::Layer>& layers, bool legend);

class LayersSvg {
 public:
  // Opens `path` (atomically replaced at finish()) and writes the header and, when `printed`,
  // the legend of path kinds.
  static Result<std::unique_ptr<LayersSvg>> open(const std::string& path, const std::string& source,
                                                 size_t layer_count, const Sheet& sheet, bool printed);
  // One layer group, in grid slot `slot`. Thread-safe.
  static void append_layer(fmt::memory_buffer& out, const ExportLayer& layer, size_t slot, const Sheet& sheet);
  Status write_layer(const fmt::memory_buffer& group) { return file_.write({group.data(), group.size()}); }
  Status finish();

 private:
  explicit LayersSvg(OutputFile file) : file_(std::move(file)) {}
  OutputFile file_;
};

// The islands of `layers` only (no plans), in one call.
Status write_layers_svg(const std::string& path, const std::vector<geo::Layer>& layers, const std::string& source,
                        const std::function<void(size_t)>& progress = {});

}  // namespace tranche::exports
