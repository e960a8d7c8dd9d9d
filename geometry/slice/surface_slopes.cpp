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
  if (p.smoothing < 0)
    return Error{"adaptive_layers",
                 fmt::format("adaptive_smoothing must be 0 (no smoothing) or more layers, got {}", p.smoothing)};
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

double SurfaceSlopes::limit_height(double z, const AdaptiveParams& p, double h) const {
  const double cusp = p.cusp();
  std::vector<std::pair<const Facet*, bool>> near;
  for_each_in(z, z + h, [&](const Facet& f, bool flat) { near.emplace_back(&f, flat); });
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first->zmin < b.first->zmin; });
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
  return std::clamp(h, p.min_height, p.max_height);
}

double SurfaceSlopes::cusp_height(double z0, double z1, const AdaptiveParams& p) const {
  double nz = 0;
  for_each_in(z0, z1, [&](const Facet& f, bool flat) {
    if (!flat) nz = std::max(nz, f.nz);
  });
  const double cusp = p.cusp();
  return nz * p.max_height <= cusp ? p.max_height : std::clamp(cusp / nz, p.min_height, p.max_height);
}

double SurfaceSlopes::adaptive_height(double z, const AdaptiveParams& p, double cap) const {
  double h = limit_height(z, p, std::clamp(cap, p.min_height, p.max_height));
  if (p.smoothing > 0) {
    // Smoothing: the next flat surface up to smoothing + 1 layers up (at most 20) is reached by
    // layers of one height, the distance shared evenly, instead of full layers and a thin one
    // on it; the next ones keep that height while the slopes allow it. (The model's top keeps
    // the rest shared by the last two layers below.)
    const double reach = std::min(p.smoothing + 1, 20) * h;
    double next = 1e300;
    for_each_in(z, z + reach, [&](const Facet& f, bool flat) {
      if (flat && f.zmin - z >= p.min_height - kEps) next = std::min(next, f.zmin);
    });
    const double d = next - z;
    if (d > h + kEps && d <= reach + kEps) {
      const double even = d / std::ceil(d / h - 1e-9);
      if (even >= p.min_height) return even;
    }
  }
  // Near the top: a rest thinner than min_height would be merged into this layer (making it
  // thicker than its slopes allow), so the last two layers share what is left.
  const double rest = top_ - z - h;
  if (rest > kEps && rest < p.min_height) h = std::max(p.min_height, 0.5 * (top_ - z));
  return h;
}

SmoothHeights::SmoothHeights(const SurfaceSlopes& slopes, const AdaptiveParams& p) {
  if (p.smoothing <= 0 || slopes.empty() || !(p.max_height > p.min_height) || !(p.min_height > 0)) return;
  step_ = 0.5 * p.min_height;
  const size_t n = static_cast<size_t>(std::ceil(slopes.top() / step_)) + 2;
  if (n > 10'000'000) return;  // a top out of any printer's reach: no smoothing rather than no memory
  sq_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const double z = static_cast<double>(k) * step_;
    const double c = slopes.cusp_height(z - 0.5 * step_, z + 0.5 * step_, p);
    sq_[k] = c * c;
  }
  // The largest function under the samples whose slope is at most 2d: two sweeps.
  const double rise = 2 * (p.max_height - p.min_height) / p.smoothing * step_;
  for (size_t k = 1; k < n; ++k) sq_[k] = std::min(sq_[k], sq_[k - 1] + rise);
  for (size_t k = n - 1; k-- > 0;) sq_[k] = std::min(sq_[k], sq_[k + 1] + rise);
}

double SmoothHeights::at(double z) const {
  const double x = std::max(0.0, z) / step_;
  const size_t k = std::min(sq_.size() - 1, static_cast<size_t>(x));
  const double t = std::min(1.0, x - static_cast<double>(k));
  const double q = k + 1 < sq_.size() ? sq_[k] + t * (sq_[k + 1] - sq_[k]) : sq_[k];
  return std::sqrt(q);
}

double SmoothHeights::cap(double z) const {
  if (sq_.empty()) return 1e300;
  // The lowest cap over the layer [z, z + h], h shrinking to it: the samples inside and its top.
  double h = at(z);
  for (int round = 0; round < 8; ++round) {
    double m = std::min(h, at(z + h));
    for (double s = (std::floor(z / step_) + 1) * step_; s < z + h; s += step_) m = std::min(m, at(s));
    if (m >= h) break;
    h = m;
  }
  return h;
}

}  // namespace tranche::geo
