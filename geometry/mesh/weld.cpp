#include "geometry/mesh/weld.h"

#include <bit>
#include <cstring>

namespace tranche::geo {
namespace {

constexpr uint32_t kEmpty = UINT32_MAX;

// -0 and +0 are the same point; every other value is compared by its bits.
uint32_t bits_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u == 0x80000000u ? 0u : u;
}

uint64_t hash_of(const std::array<uint32_t, 3>& k) {
  uint64_t h = (uint64_t{k[0]} * 0x9E3779B97F4A7C15ull) ^ (uint64_t{k[1]} * 0xC2B2AE3D27D4EB4Full) ^
               (uint64_t{k[2]} * 0x165667B19E3779F9ull);
  return h ^ (h >> 29);
}

}  // namespace

Welder::Welder(size_t triangles) {
  // Load factor stays at most 0.75 even if every corner is a distinct vertex.
  const uint64_t capacity = std::bit_ceil(std::max<uint64_t>(16, uint64_t{triangles} * 4));
  slots_.assign(capacity, kEmpty);
  mask_ = capacity - 1;
  keys_.reserve(std::min<uint64_t>(uint64_t{triangles} * 3, uint64_t{triangles} / 2 + 1024));
  triangles_.reserve(triangles);
}

uint32_t Welder::id_of(const float* p) {
  const std::array<uint32_t, 3> key{bits_of(p[0]), bits_of(p[1]), bits_of(p[2])};
  for (uint64_t i = hash_of(key) & mask_;; i = (i + 1) & mask_) {
    const uint32_t id = slots_[i];
    if (id == kEmpty) {
      slots_[i] = static_cast<uint32_t>(keys_.size());
      keys_.push_back(key);
      return slots_[i];
    }
    if (keys_[id] == key) return id;
  }
}

bool Welder::add(const float* a, const float* b, const float* c) {
  const uint32_t ia = id_of(a), ib = id_of(b), ic = id_of(c);
  if (ia == ib || ib == ic || ia == ic) {
    ++dropped_;
    return false;
  }
  triangles_.push_back({ia, ib, ic});
  return true;
}

void Welder::finish(Mesh& mesh) {
  // Corners of dropped triangles may belong to no kept triangle: renumber without them.
  std::vector<uint32_t> new_id;
  if (dropped_ > 0) {
    new_id.assign(keys_.size(), kEmpty);
    for (const auto& t : triangles_) {
      for (uint32_t id : t) new_id[id] = 0;
    }
    uint32_t next = 0;
    for (auto& id : new_id) {
      if (id != kEmpty) id = next++;
    }
    for (auto& t : triangles_) {
      for (auto& id : t) id = new_id[id];
    }
  }
  mesh.vertices.clear();
  mesh.vertices.reserve(keys_.size());
  for (size_t i = 0; i < keys_.size(); ++i) {
    if (!new_id.empty() && new_id[i] == kEmpty) continue;
    float f[3];
    std::memcpy(f, keys_[i].data(), sizeof f);
    mesh.vertices.push_back(Vec3{f[0], f[1], f[2]});
  }
  mesh.triangles = std::move(triangles_);
  keys_ = {};
  slots_ = {};
  triangles_ = {};
  dropped_ = 0;
}

}  // namespace tranche::geo
