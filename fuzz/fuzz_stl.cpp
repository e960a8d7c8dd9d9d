// libFuzzer target: parse_stl on arbitrary bytes must return a mesh or an Error, never crash,
// hang or allocate more than the input allows. A loaded mesh must be well formed.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "geometry/mesh/stl.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tranche::Report report;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto mesh = tranche::geo::parse_stl(bytes, "fuzz.stl", report);
  if (!mesh.ok()) {
    if (mesh.error().message.empty()) std::abort();
    return 0;
  }
  if (mesh->triangles.empty() || mesh->vertices.size() > 3 * mesh->triangles.size()) std::abort();
  for (const auto& t : mesh->triangles) {
    for (uint32_t id : t) {
      if (id >= mesh->vertices.size()) std::abort();
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) std::abort();
  }
  return 0;
}
