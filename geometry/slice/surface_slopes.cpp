#include "geometry/slice/surface_slopes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace tranche::geo {
namespace {

constexpr double kEps = 1e-6;  // mm: a facet only touching a slab's bottom is not in it
constexpr double kFlat = 1e-9;  // 1 - |n_z| below this: a horizontal facet
// Total bucket entries allowed: tall sloped facets are entered in every bucket they span.
constexpr double kMaxEntries = 2e7;

}  // namespace

Status check_adaptive(const AdaptiveParams& p) {
  for (auto [name, v] : {std::pair{"min_layer_height", p.min_height}, std::pair{"max_layer_height", p.max_height}})
    if (!std::isfinite(v) || v < 0.001)
      return Error{"adaptive_layers", fmt::format("{} must be at least 0.001 mm, got {} mm", name, v)};
  if (p.min_height > p.max_height)
    return Error{"adaptive_layers",
                 fmt::format("min_layer_height ({} mm) is more than max_layer_height ({} mm): the planner has no "
                             "height to choose; lower min_layer_height or raise max_layer_height",
                             p.min_height, p.max_height)};
  if (!std::isfinite(p.quality) || p.quality < 0 || p.quality > 1)
    return Error{"adaptive_layers",
                 fmt::format("adaptive_quality must be between 0 (coarsest) and 1 (finest), got {}", p.quality)};
  return ok_status();
}

void SurfaceSlopes::add(const Mesh& mesh) {
  for (const auto& v : mesh.vertices) top_ = std::max(top_, v.z);
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0) || !std::isfinite(len)) continue;  // degenerate: no surface
    const double cz = std::abs(nz) / len;
    if (cz < 1e-9) continue;  // vertical: no cusp, no slope
    facets_.push_back({std::min({a.z, b.z, c.z}), std::max({a.z, b.z, c.z}), std::min(1.0, cz)});
  }
  rebuild_index();
}

void SurfaceSlopes::rebuild_index() {
  buckets_.clear();
  if (facets_.empty()) return;
  double top = 0, spans = 0;
  for (const auto& f : facets_) top = std::max(top, f.zmax), spans += f.zmax - f.zmin;
  const double n = static_cast<double>(facets_.size());
  step_ = std::max({0.05, top / 4096, spans / std::max(1.0, kMaxEntries - 2 * n)});
  buckets_.resize(static_cast<size_t>(std::max(0.0, top) / step_) + 1);
  auto bucket = [&](double z) {
    return std::min(buckets_.size() - 1, static_cast<size_t>(std::max(0.0, z) / step_));
  };
  for (uint32_t i = 0; i < facets_.size(); ++i)
    for (size_t b = bucket(facets_[i].zmin), e = bucket(facets_[i].zmax); b <= e; ++b) buckets_[b].push_back(i);
}

template <class F>
void SurfaceSlopes::for_each_in(double z0, double z1, F&& f) const {
  if (buckets_.empty() || z1 < 0) return;
  auto bucket = [&](double z) {
    return std::min(buckets_.size() - 1, static_cast<size_t>(std::max(0.0, z) / step_));
  };
  for (size_t b = bucket(z0), e = bucket(z1); b <= e; ++b)
    for (uint32_t i : buckets_[b]) {
      const Facet& x = facets_[i];
      const bool flat = 1 - x.nz < kFlat || x.zmax - x.zmin < kEps;
      // A sloped facet reaching above z0; a flat one strictly above it.
      if (x.zmin <= z1 && (flat ? x.zmin > z0 + kEps : x.zmax > z0 + kEps)) f(x, flat);
    }
}

double SurfaceSlopes::max_slope_deg(double z0, double z1) const {
  double nz = 0;
  for_each_in(z0, z1, [&](const Facet& f, bool flat) { nz = std::max(nz, flat ? 1.0 : f.nz); });
  return std::asin(std::min(1.0, nz)) * 180 / std::numbers::pi;
}

double SurfaceSlopes::adaptive_height(double z, const AdaptiveParams& p) const {
  const double cusp = p.cusp();
  std::vector<std::pair<const Facet*, bool>> near;
  for_each_in(z, z + p.max_height, [&](const Facet& f, bool flat) { near.emplace_back(&f, flat); });
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first->zmin < b.first->zmin; });
  double h = p.max_height;
  for (const auto& [f, flat] : near) {
    const double start = f->zmin - z;  // ≤ 0 for a facet already crossing z
    if (start >= h - kEps) break;      // starts above the layer as it now stands
    if (flat) {
      if (start >= p.min_height) h = start;  // end the layer on the flat surface
      continue;
    }
    const double limit = cusp / f->nz;
    if (limit >= h) continue;
    // Too flat for h: the layer ends below it if it can (where it starts), else is thin enough.
    h = std::max(limit, start);
  }
  h = std::clamp(h, p.min_height, p.max_height);
  // Near the top: a rest thinner than min_height would be merged into this layer (making it
  // thicker than its slopes allow), so the last two layers share what is left.
  const double rest = top_ - z - h;
  if (rest > kEps && rest < p.min_height) h = std::max(p.min_height, 0.5 * (top_ - z));
  return h;
}

}  // namespace tranche::geo
