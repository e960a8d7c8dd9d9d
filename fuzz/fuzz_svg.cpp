// libFuzzer target: SVG import (XML, units, transforms, paths and arcs, styles, the overlap modes,
// layer stacks) on arbitrary text must return polygons or an Error, never crash or hang. The first
// byte picks the overlap mode and the curve tolerance; the rest is the document. Loaded layers
// must hold finite, closed polygons. Seeds: fuzz/corpus/svg/.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "geometry/io/svg_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  tranche::geo::SvgImportOptions options;
  const uint8_t mode = data[0];
  options.overlap = mode % 3 == 0   ? tranche::geo::SvgOverlap::Additive
                    : mode % 3 == 1 ? tranche::geo::SvgOverlap::Boolean
                                    : tranche::geo::SvgOverlap::Subtractive;
  options.tolerance_mm = (mode & 0x80) ? 0.5 : 0.01;
  tranche::Report report;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  auto model = tranche::geo::parse_svg(text, "fuzz.svg", options, report);
  if (!model.ok()) {
    if (model.error().message.empty()) std::abort();
    return 0;
  }
  if (model->layers.empty() || (!model->layer_stack && model->layers.size() != 1)) std::abort();
  for (const auto& layer : model->layers) {
    if (!std::isfinite(layer.z_bottom) || !std::isfinite(layer.z_top)) std::abort();
    for (const auto& p : layer.polygons) {
      if (p.outer.size() < 3) std::abort();
      for (const auto& h : p.holes)
        if (h.size() < 3) std::abort();
    }
  }
  return 0;
}
