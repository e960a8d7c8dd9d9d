#include "geometry/mesh/weld.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
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

std::string too_many(size_t n) { return fmt::format("{} triangles are more than Tranche can load", n); }

// All of `n` triangles degenerate: an error; some: a warning.
Status check_degenerate(size_t degenerate, size_t n, const std::string& where, Report& report) {
  if (degenerate == n)
    return Error{where, fmt::format("all {} triangles are degenerate (two or three corners at the same point): the "
                                    "model has no surface",
                                    n)};
  if (degenerate)
    report.warn("mesh-degenerate", where,
                fmt::format("dropped {} degenerate triangle{} of {} (two corners at the same point)", degenerate,
                            degenerate == 1 ? "" : "s", n));
  return ok_status();
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

void Welder::add(const float* corners, size_t n, uint8_t* dropped) {
  const size_t m = 3 * n;
  batch_keys_.resize(m);
  batch_hashes_.resize(m);
  batch_ids_.resize(m);
  for (size_t j = 0; j < m; ++j) {
    batch_keys_[j] = {bits_of(corners[3 * j]), bits_of(corners[3 * j + 1]), bits_of(corners[3 * j + 2])};
    batch_hashes_[j] = hash_of(batch_keys_[j]);
  }
  // The table is far larger than the cache: fetch the slot a few corners ahead of its lookup.
  constexpr size_t kAhead = 16;
  for (size_t j = 0; j < m; ++j) {
    if (j + kAhead < m) __builtin_prefetch(&slots_[batch_hashes_[j + kAhead] & mask_]);
    const Key& key = batch_keys_[j];
    for (uint64_t i = batch_hashes_[j] & mask_;; i = (i + 1) & mask_) {
      const uint32_t id = slots_[i];
      if (id == kEmpty) {
        slots_[i] = batch_ids_[j] = static_cast<uint32_t>(keys_.size());
        keys_.push_back(key);
        break;
      }
      if (keys_[id] == key) {
        batch_ids_[j] = id;
        break;
      }
    }
  }
  for (size_t t = 0; t < n; ++t) {
    const uint32_t a = batch_ids_[3 * t], b = batch_ids_[3 * t + 1], c = batch_ids_[3 * t + 2];
    dropped[t] = a == b || b == c || a == c;
    if (dropped[t]) {
      ++dropped_;
    } else {
      triangles_.push_back({a, b, c});
    }
  }
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
  batch_keys_ = {};
  batch_hashes_ = {};
  batch_ids_ = {};
  dropped_ = 0;
}

Result<Mesh> weld_corners(const std::vector<float>& corners, const std::string& where, Report& report) {
  const size_t n = corners.size() / 9;
  for (size_t i = 0; i < 9 * n; ++i)
    if (!std::isfinite(corners[i]))
      return Error{where, fmt::format("triangle {} has a coordinate that is not a finite number ({}); repair the "
                                      "model, or check the scale it was given",
                                      i / 9 + 1, corners[i])};
  if (n > Welder::kMaxTriangles) return Error{where, too_many(n)};
  Welder welder(n);
  std::vector<uint8_t> dropped(n);
  // Batches of a few thousand triangles, as the welder prefers.
  for (size_t base = 0; base < n; base += 4096)
    welder.add(corners.data() + 9 * base, std::min<size_t>(4096, n - base), dropped.data() + base);
  size_t degenerate = 0;
  for (uint8_t d : dropped) degenerate += d;
  if (Status st = check_degenerate(degenerate, n, where, report); !st) return st.error();
  Mesh mesh;
  welder.finish(mesh);
  return mesh;
}

Result<Mesh> weld_indexed(const std::vector<float>& vertices, const std::vector<uint32_t>& triangles,
                          const std::string& where, Report& report) {
  std::vector<std::array<uint32_t, 3>> tri(triangles.size() / 3);
  for (size_t t = 0; t < tri.size(); ++t) tri[t] = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
  return weld_indexed(vertices, std::move(tri), where, report);
}

Result<Mesh> weld_indexed(const std::vector<float>& vertices, std::vector<std::array<uint32_t, 3>>&& triangles,
                          const std::string& where, Report& report) {
  const size_t nv = vertices.size() / 3, n = triangles.size();
  bool finite = true;
  for (float f : vertices) finite = finite && std::isfinite(f);
  if (!finite) {  // weld_corners says which triangle, if a triangle uses the vertex
    std::vector<float> corners;
    corners.reserve(9 * n);
    for (const auto& t : triangles)
      for (uint32_t v : t) corners.insert(corners.end(), &vertices[3 * v], &vertices[3 * v] + 3);
    return weld_corners(corners, where, report);
  }
  if (n > Welder::kMaxTriangles) return Error{where, too_many(n)};
  std::vector<Vec3> ordered;
  WeldScratch scratch;
  const size_t degenerate = order_by_first_use(vertices.data(), nv, triangles, ordered, scratch);
  return weld_ordered(std::move(ordered), std::move(triangles), where, report, degenerate);
}

size_t order_by_first_use(const float* vertices, size_t nv, std::vector<std::array<uint32_t, 3>>& triangles,
                          std::vector<Vec3>& out, WeldScratch& scratch) {
  // Two passes: each vertex looked up among those before it (by its bits), in order, its hash
  // computed a few vertices ahead so that the table's slot can be fetched ahead; then the corners,
  // numbering each vertex's value when first used, as the Welder numbers corners. Where no vertex
  // repeats another (as in nearly every file), the second pass numbers the corners' own vertices.
  const auto key = [&](size_t v) {
    return std::array<uint32_t, 3>{bits_of(vertices[3 * v]), bits_of(vertices[3 * v + 1]),
                                   bits_of(vertices[3 * v + 2])};
  };
  const uint64_t capacity = std::bit_ceil(std::max<uint64_t>(16, uint64_t{nv} * 2));
  const int shift = 64 - std::countr_zero(capacity);  // the slot: the hash's high bits
  const uint64_t mask = capacity - 1;
  constexpr uint64_t kFree = UINT64_MAX;
  scratch.first.resize(nv);
  scratch.slots.assign(capacity, kFree);
  uint32_t* first = scratch.first.data();
  uint64_t* slots = scratch.slots.data();
  constexpr size_t kAhead = 16;
  uint64_t ring[kAhead];  // the hashes of vertices v to v + kAhead - 1
  const auto hash = [&](size_t v) { return hash_of(key(v)) * 0x9E3779B97F4A7C15ull; };
  for (size_t v = 0; v < std::min(nv, kAhead); ++v) {
    ring[v] = hash(v);
    __builtin_prefetch(&slots[ring[v] >> shift]);
  }
  size_t dups = 0;  // vertices equal to one before them
  for (size_t v = 0; v < nv; ++v) {
    const uint64_t h = ring[v % kAhead];
    if (v + kAhead < nv) {
      const uint64_t g = hash(v + kAhead);
      ring[v % kAhead] = g;
      __builtin_prefetch(&slots[g >> shift]);
    }
    const uint64_t fingerprint = h & 0xFFFFFFFF00000000ull;  // the slot's own bits are the top ones
    for (uint64_t i = h >> shift;; i = (i + 1) & mask) {
      const uint64_t s = slots[i];
      if (s == kFree) {
        slots[i] = fingerprint | v;
        first[v] = static_cast<uint32_t>(v);
        break;
      }
      if ((s & 0xFFFFFFFF00000000ull) == fingerprint && key(static_cast<uint32_t>(s)) == key(v)) {
        first[v] = static_cast<uint32_t>(s);
        ++dups;
        break;
      }
    }
  }
  scratch.id.assign(nv, kEmpty);
  uint32_t* id = scratch.id.data();
  out.clear();
  out.reserve(nv);
  size_t degenerate = 0;
  if (dups == 0) {
    // (Each triangle's corners read into registers and written back once: the count then waits
    // for no store.)
    const auto number = [&](uint32_t c) {
      uint32_t i = id[c];
      if (i == kEmpty) {
        i = id[c] = static_cast<uint32_t>(out.size());
        const float* p = vertices + 3 * size_t{c};
        out.push_back(Vec3{double{p[0]} + 0.0, double{p[1]} + 0.0, double{p[2]} + 0.0});  // -0 is +0
      }
      return i;
    };
    for (auto& t : triangles) {
      const uint32_t a = number(t[0]), b = number(t[1]), c = number(t[2]);
      t = {a, b, c};
      degenerate += (a == b) | (b == c) | (a == c);
    }
    return degenerate;
  }
  const auto number = [&](uint32_t c) {
    const uint32_t f = first[c];
    if (id[f] == kEmpty) {
      id[f] = static_cast<uint32_t>(out.size());
      const auto k = key(f);
      float p[3];
      std::memcpy(p, k.data(), sizeof p);  // through the bits: -0 is +0
      out.push_back(Vec3{p[0], p[1], p[2]});
    }
    return id[f];
  };
  for (auto& t : triangles) {
    const uint32_t a = number(t[0]), b = number(t[1]), c = number(t[2]);
    t = {a, b, c};
    degenerate += (a == b) | (b == c) | (a == c);
  }
  return degenerate;
}

Result<Mesh> weld_ordered(std::vector<Vec3>&& vertices, std::vector<std::array<uint32_t, 3>>&& triangles,
                          const std::string& where, Report& report, std::optional<size_t> degenerate_known) {
  const size_t n = triangles.size(), nv = vertices.size();
  if (n > Welder::kMaxTriangles) return Error{where, too_many(n)};
  if (degenerate_known == size_t{0} && n > 0) {  // nothing to drop: the mesh as it is
    Mesh mesh;
    mesh.vertices = std::move(vertices);
    mesh.triangles = std::move(triangles);
    return mesh;
  }
  size_t kept = 0;
  for (size_t t = 0; t < n; ++t) {
    const auto c = triangles[t];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    triangles[kept++] = c;
  }
  const size_t degenerate = n - kept;
  if (Status st = check_degenerate(degenerate, n, where, report); !st) return st.error();
  triangles.resize(kept);
  // As Welder::finish: the vertices only dropped triangles use are left out.
  std::vector<uint32_t> new_id;
  if (degenerate > 0) {
    new_id.assign(nv, kEmpty);
    for (const auto& t : triangles)
      for (uint32_t i : t) new_id[i] = 0;
    uint32_t next = 0;
    for (auto& i : new_id)
      if (i != kEmpty) i = next++;
    for (auto& t : triangles)
      for (auto& i : t) i = new_id[i];
  }
  if (degenerate > 0) {
    size_t next = 0;
    for (size_t i = 0; i < nv; ++i)
      if (new_id[i] != kEmpty) vertices[next++] = vertices[i];
    vertices.resize(next);
  }
  Mesh mesh;
  mesh.vertices = std::move(vertices);
  mesh.triangles = std::move(triangles);
  return mesh;
}

}  // namespace tranche::geo
