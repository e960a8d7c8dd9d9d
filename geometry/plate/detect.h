// What a model file is, from its first bytes rather than its name: a 3MF named .stl still loads,
// and a file that is no model at all is named for what it is ("this is a PNG image").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace tranche::plate {

enum class Format {
  Stl,      // binary or ASCII STL, or bytes no other format claims (the STL loader explains)
  ThreeMf,  // a ZIP archive (3MF packages are ZIP archives)
  Obj,      // Wavefront OBJ text
  Svg,      // an SVG drawing (sliced by geometry/io, not loaded as a mesh)
  Other,    // a known format that is no model we read; `what` says which
};

struct Detected {
  Format format = Format::Stl;
  std::string what;   // "a ZIP archive (3MF?)", "an OBJ file", "a PNG image", ...
  bool sure = true;   // false: no format claimed the bytes (Stl, for the STL loader to explain)
};

Detected detect_format(std::string_view bytes);

// Same, from the first bytes of a file (a few kilobytes are enough) and its whole size.
Detected detect_format(std::string_view head, uint64_t size);

}  // namespace tranche::plate
