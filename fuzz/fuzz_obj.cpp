// libFuzzer target: OBJ input (tinyobjloader and our face checks, triangulation, groups) on
// arbitrary bytes must return objects or an Error, never crash or hang. Loaded objects must be
// well formed. Seeds: fuzz/corpus/obj/.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "geometry/plate/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tranche::Report report;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto objects = tranche::plate::parse_obj(bytes, "fuzz.obj", report);
  if (!objects.ok()) {
    if (objects.error().message.empty()) std::abort();
    return 0;
  }
  if (objects->empty()) std::abort();
  for (const auto& o : *objects) {
    const auto& m = o.mesh;
    for (const auto& t : m.triangles)
      for (uint32_t id : t)
        if (id >= m.vertices.size()) std::abort();
    for (const auto& v : m.vertices)
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
  }
  return 0;
}
