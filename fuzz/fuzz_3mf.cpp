// libFuzzer target: parse_3mf (our ZIP reading, the slicers' extra parts, the re-packing of
// model parts, lib3mf, the flattening of components) on arbitrary bytes must return objects or
// an Error, never crash or hang. Loaded objects must be well formed. Seeds: fuzz/make_3mf_corpus.py.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "geometry/plate/threemf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tranche::Report report;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto objects = tranche::plate::parse_3mf(bytes, "fuzz.3mf", report);
  if (!objects.ok()) {
    if (objects.error().message.empty()) std::abort();
    return 0;
  }
  if (objects->empty()) std::abort();
  for (const auto& o : *objects) {
    const auto& m = o.mesh;
    if (m.triangles.empty()) std::abort();
    for (const auto& t : m.triangles) {
      for (uint32_t id : t)
        if (id >= m.vertices.size()) std::abort();
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) std::abort();
    }
    for (const auto& v : m.vertices)
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
    if (!(std::fabs(o.transform.linear().determinant()) > 0)) std::abort();
  }
  return 0;
}
