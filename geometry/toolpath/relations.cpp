#include "geometry/toolpath/relations.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

using schema::PathKind;

geo::Rings material(const geo::Layer& layer) {
  geo::Rings out;
  for (const auto& isl : layer.islands) {
    out.push_back(isl.shape.outer);
    for (const auto& h : isl.shape.holes) out.push_back(h);
  }
  return out;
}

bool covers(const geo::Rings& m, const EdgeGrid& g, const geo::Rings& region, const EdgeGrid& region_grid) {
  for (const auto& r : region) {
    if (r.empty()) continue;
    if (!g.inside(r.front())) return false;
    for (size_t j = 0; j < r.size(); ++j)
      if (g.crosses(r[j], r[(j + 1) % r.size()])) return false;
  }
  // No boundary crossing and every region ring inside: only a hole of the layer lying wholly
  // within the region could still uncover part of it.
  for (const auto& r : m)
    if (!r.empty() && !ClipperLib::Orientation(r) && region_grid.inside(r.front())) return false;
  return true;
}

namespace {
LayerCache::Eroded erode(const geo::Rings& m, double mm) {
  LayerCache::Eroded e;
  e.rings = offset_coarse(m, -mm);
  e.grid = EdgeGrid(e.rings);
  return e;
}
}  // namespace

LayerCache::LayerCache(std::span<const geo::Layer> layers) : layers_(layers), slots_(new Slot[layers.size()]) {}

const geo::Rings& LayerCache::material_locked(size_t i, Slot& s) {
  if (!s.has_material) {
    s.material = toolpath::material(layers_[i]);
    s.has_material = true;
  }
  return s.material;
}

const geo::Rings& LayerCache::material(size_t i) {
  Slot& s = slots_[i];
  std::lock_guard lock(s.mutex);
  return material_locked(i, s);
}

const EdgeGrid& LayerCache::grid(size_t i) {
  Slot& s = slots_[i];
  std::lock_guard lock(s.mutex);
  if (!s.has_grid) {
    s.grid = EdgeGrid(material_locked(i, s));
    s.has_grid = true;
  }
  return s.grid;
}

const LayerCache::Eroded& LayerCache::eroded_locked(size_t i, Slot& s, double mm) {
  for (const auto& [d, e] : s.eroded)
    if (d == mm) return *e;
  s.eroded.emplace_back(mm, std::make_unique<Eroded>(erode(material_locked(i, s), mm)));
  return *s.eroded.back().second;
}

const LayerCache::Eroded& LayerCache::eroded(size_t i, double mm) {
  Slot& s = slots_[i];
  std::lock_guard lock(s.mutex);
  return eroded_locked(i, s, mm);
}

const geo::Rings& LayerCache::eroded_window(size_t first, int n, double mm) {
  // Holds layer `first`'s lock while asking the layers above it for theirs: locks are always
  // taken upwards, so two windows being computed cannot wait for each other.
  Slot& s = slots_[first];
  std::lock_guard lock(s.mutex);
  const auto key = std::make_pair(n, mm);
  for (const auto& [k, w] : s.windows)
    if (k == key) return *w;
  geo::Rings w = eroded_locked(first, s, mm).rings;
  for (int k = 1; k < n && !w.empty(); ++k) w = intersection(w, eroded(first + static_cast<size_t>(k), mm).rings);
  s.windows.emplace_back(key, std::make_unique<geo::Rings>(std::move(w)));
  return *s.windows.back().second;
}

void LayerCache::release(size_t i) {
  if (i >= layers_.size()) return;
  Slot& s = slots_[i];
  std::lock_guard lock(s.mutex);
  s.has_material = s.has_grid = false;
  geo::Rings().swap(s.material);
  s.grid = EdgeGrid();
  s.eroded.clear();
  s.windows.clear();
}

Neighbours::Neighbours(std::span<const geo::Layer> layers, int index, LayerCache* cache)
    : layers_(layers), index_(index), cache_(cache && cache->size() == layers.size() ? cache : nullptr) {}

const geo::Rings& Neighbours::layer(int k) {
  int i = index_ + k;
  const bool in = i >= 0 && static_cast<size_t>(i) < layers_.size();
  if (in && cache_) return cache_->material(static_cast<size_t>(i));
  auto it = material_.find(i);
  if (it != material_.end()) return it->second;
  geo::Rings m;
  if (in) m = material(layers_[static_cast<size_t>(i)]);
  return material_.emplace(i, std::move(m)).first->second;
}

const EdgeGrid& Neighbours::grid(int k) {
  const int i = index_ + k;
  if (cache_ && i >= 0 && static_cast<size_t>(i) < layers_.size()) return cache_->grid(static_cast<size_t>(i));
  auto it = grids_.find(k);
  if (it != grids_.end()) return it->second;
  return grids_.emplace(k, EdgeGrid(layer(k))).first->second;
}

bool Neighbours::covers(int k, const geo::Rings& region, const EdgeGrid& region_grid) {
  int i = index_ + k;
  if (i < 0 || static_cast<size_t>(i) >= layers_.size()) return false;
  return toolpath::covers(layer(k), grid(k), region, region_grid);
}

const LayerCache::Eroded* Neighbours::eroded(int k, double mm) {
  const int i = index_ + k;
  if (i < 0 || static_cast<size_t>(i) >= layers_.size()) return nullptr;
  if (cache_) return &cache_->eroded(static_cast<size_t>(i), mm);
  auto key = std::make_pair(k, mm);
  auto it = eroded_.find(key);
  if (it != eroded_.end()) return &it->second;
  return &eroded_.emplace(key, erode(layer(k), mm)).first->second;
}

const geo::Rings* Neighbours::all_eroded(int sign, int n, double mm) {
  if (n < 1) return nullptr;
  // Layers first .. first + n - 1, from the lowest up.
  const int first = sign > 0 ? index_ + 1 : index_ - n;
  if (first < 0 || static_cast<size_t>(first + n) > layers_.size()) return nullptr;
  if (cache_) return &cache_->eroded_window(static_cast<size_t>(first), n, mm);
  const auto key = std::make_tuple(first, n, mm);
  if (auto it = windows_.find(key); it != windows_.end()) return &it->second;
  geo::Rings w = eroded(first - index_, mm)->rings;
  for (int k = 1; k < n && !w.empty(); ++k) w = intersection(w, eroded(first + k - index_, mm)->rings);
  return &windows_.emplace(key, std::move(w)).first->second;
}

std::vector<float> overhang_fractions(const geo::Ring& pts, double width_mm, const EdgeGrid& below) {
  const size_t n = pts.size() < 2 ? 0 : pts.size() - 1;
  std::vector<float> out(n, 0.0f);
  const double half = 0.5 * width_mm * geo::kUnitsPerMm;
  for (size_t i = 0; i < n; ++i) {
    const geo::Point &a = pts[i], &b = pts[i + 1];
    double dx = double(b.X - a.X), dy = double(b.Y - a.Y), len = std::hypot(dx, dy);
    if (len <= 0) continue;
    // A bead wholly inside (outside) the layer below's cells that hold no edge: 0 (1).
    const geo::coord_t h = static_cast<geo::coord_t>(std::ceil(half)) + 1;
    const geo::coord_t bx0 = std::min(a.X, b.X) - h, by0 = std::min(a.Y, b.Y) - h, bx1 = std::max(a.X, b.X) + h,
                       by1 = std::max(a.Y, b.Y) + h;
    if (const int s = below.box_state(bx0, by0, bx1, by1); s >= 0) {
      out[i] = s == 1 ? 0.0f : 1.0f;
      continue;
    }
    // No edge of the layer below meets that box (a wall beside the border, not over it): every
    // sample across the bead, and every point at which they are classified, lies in it, on the
    // side its corner is.
    if (below.box_clear(bx0, by0, bx1, by1)) {
      out[i] = below.inside(geo::Point(bx0, by0)) ? 0.0f : 1.0f;
      continue;
    }
    double nx = -dy / len * half, ny = dx / len * half;
    // Across the bead at a quarter, half and three quarters of the piece; at its middle only
    // when it is shorter than a bead (a curved wall's many short pieces: their neighbours are
    // sampled a bead away already, and this was a tenth of a run's time).
    constexpr double ts3[] = {0.25, 0.5, 0.75}, ts1[] = {0.5};
    const bool short_piece = len < width_mm * geo::kUnitsPerMm;
    const std::span<const double> ts = short_piece ? std::span<const double>(ts1) : std::span<const double>(ts3);
    double miss = 0;
    for (double t : ts) {
      double mx = double(a.X) + dx * t, my = double(a.Y) + dy * t;
      geo::Point l(round_units(mx + nx), round_units(my + ny)), r(round_units(mx - nx), round_units(my - ny));
      miss += 1.0 - below.inside_fraction(l, r);
    }
    out[i] = static_cast<float>(miss / static_cast<double>(ts.size()));
  }
  return out;
}

std::vector<float> average_along(const std::vector<float>& values, const geo::Ring& pts, double window_mm) {
  const size_t n = values.size();
  if (n == 0 || pts.size() != n + 1) return values;
  // at[i]: arc length (mm) where piece i starts; sum[i]: integral of the values up to there.
  std::vector<double> at(n + 1, 0.0), sum(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const double len = std::hypot(double(pts[i + 1].X - pts[i].X), double(pts[i + 1].Y - pts[i].Y)) / geo::kUnitsPerMm;
    at[i + 1] = at[i] + len;
    sum[i + 1] = sum[i] + len * double(values[i]);
  }
  const double total = at[n];
  if (total <= 0) return values;
  // Integral of the values from 0 to arc length s.
  auto integral = [&](double s) {
    s = std::clamp(s, 0.0, total);
    size_t k = static_cast<size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin());
    k = std::clamp<size_t>(k, 1, n);  // piece k - 1 holds s
    return sum[k - 1] + (s - at[k - 1]) * double(values[k - 1]);
  };
  std::vector<float> out(n);
  for (size_t i = 0; i < n; ++i) {
    const double len = at[i + 1] - at[i];
    if (len >= window_mm) {
      out[i] = values[i];
      continue;
    }
    const double w = std::min(window_mm, total);
    double lo = 0.5 * (at[i] + at[i + 1]) - 0.5 * w;
    lo = std::clamp(lo, 0.0, total - w);
    // Rounded to 1e-4, so that a bead wholly in the air stays exactly 1 (and one on the layer 0).
    const double mean = std::round((integral(lo + w) - integral(lo)) / w * 1e4) * 1e-4;
    out[i] = static_cast<float>(std::clamp(mean, 0.0, 1.0));
  }
  return out;
}

double fraction_on(const geo::Rings& island, const geo::Rings& other) {
  double a = area_mm2(island);
  if (a <= 0) return 0;
  double on = area_mm2(intersection(island, near(other, bbox(island))));
  return std::clamp(on / a, 0.0, 1.0);
}

namespace {
// Drops rings of tiny area (slivers left by booleans), and holes whose outer went with them
// cannot occur: Clipper nests holes inside outers larger than them.
geo::Rings drop_small(geo::Rings r, double min_mm2) {
  const double min_units = min_mm2 * geo::kUnitsPerMm * geo::kUnitsPerMm;
  r.erase(std::remove_if(r.begin(), r.end(),
                         [&](const geo::Ring& x) { return std::abs(ClipperLib::Area(x)) < min_units; }),
          r.end());
  return r;
}
}  // namespace

geo::Rings solid_region(const geo::Rings& fill, const EdgeGrid& fill_grid, Neighbours& nb, const SolidSpec& spec) {
  const geo::BBox2 box = bbox(fill);
  if (spec.shell_mm > 0) {
    // The fill within shell_mm of a neighbour's border lies under (over) its perimeters: solid.
    // That is the fill outside the neighbours shrunk by shell_mm (a disc lies in all of them iff
    // it lies in each): each layer is shrunk once for the print (LayerCache), not once per
    // island and neighbour. Arcs to 25 µm: what is made solid is a band a bead or more wide.
    // A layer shrunk lies within the layer, so this holds all of the fill a neighbour leaves
    // uncovered: solid = fill − (∩ above shrunk ∩ ∩ below shrunk), two booleans at most.
    const double s = spec.shell_mm;
    const geo::Rings* inner[2];
    int sides = 0;
    for (const auto& [sign, n] : {std::pair{1, spec.top_layers}, std::pair{-1, spec.bottom_layers}}) {
      if (n <= 0) continue;
      bool covered = true;  // every layer on this side, shrunk, covers the fill (cheap exact tests)
      for (int k = 1; k <= n && covered; ++k) {
        const LayerCache::Eroded* e = nb.eroded(sign * k, s);
        covered = e && covers(e->rings, e->grid, fill, fill_grid);
      }
      if (covered) continue;
      const geo::Rings* w = nb.all_eroded(sign, n, s);
      if (!w) return fill;  // a neighbour outside the print (a top or the bottom): all solid
      inner[sides++] = w;
    }
    if (sides == 0) return {};
    if (sides == 1) return difference(fill, near(*inner[0], box));
    return difference(fill, intersection(near(*inner[0], box), near(*inner[1], box)));
  }
  // Solid wherever one of the next top_layers or of the bottom_layers below does not cover
  // the fill: the union of fill − layer over the layers that do not cover it (cheap exact
  // tests find those; deep inside the part there are none).
  geo::Rings solid;
  auto consider = [&](int k) {
    if (nb.covers(k, fill, fill_grid)) return;
    geo::Rings part = difference(fill, near(nb.layer(k), box));
    solid = solid.empty() ? std::move(part) : union_of(solid, part);
  };
  for (int k = 1; k <= spec.top_layers; ++k) consider(k);
  for (int k = 1; k <= spec.bottom_layers; ++k) consider(-k);
  return solid;
}

std::vector<FillRegion> split_fill(const geo::Rings& fill, Neighbours& nb, const SolidSpec& spec) {
  std::vector<FillRegion> out;
  if (fill.empty()) return out;
  const double w = spec.width;
  const double tiny = w * w;  // mm²: smaller pieces are not worth a path of their own
  if (nb.index() == 0) {
    out.push_back({PathKind::BottomSolid, fill});
    return out;
  }
  const bool all_solid = spec.density >= 1.0 - 1e-9;
  const EdgeGrid fill_grid(fill);
  geo::Rings solid = solid_region(fill, fill_grid, nb, spec);
  // Strips narrower than half a bead (steep slopes) are left to the sparse fill.
  geo::Rings core = drop_small(offset(drop_small(std::move(solid), tiny), -0.25 * w), 0.05 * tiny);
  if (core.empty() && !all_solid) {
    out.push_back({PathKind::Infill, fill});
    return out;
  }
  // Skins are anchored one bead into the sparse region around them.
  geo::Rings grown = all_solid ? fill : intersection(offset(core, 0.25 * w + w), fill);
  geo::Rings skin = offset(core, 0.25 * w);
  geo::BBox2 sbox = bbox(skin);
  geo::Rings bridge, top;
  // Bridges where the layer below does not cover the fill, tops where the one above does not.
  const bool open_below = spec.bottom_layers > 0 && !skin.empty() && !nb.covers(-1, fill, fill_grid);
  const bool open_above = spec.top_layers > 0 && !skin.empty() && !nb.covers(1, fill, fill_grid);
  if (open_below) bridge = drop_small(difference(skin, near(nb.layer(-1), sbox)), tiny);
  if (open_above) {
    geo::Rings clip = near(nb.layer(1), sbox);
    clip.insert(clip.end(), bridge.begin(), bridge.end());  // non-zero union of both as the clip
    top = drop_small(difference(skin, clip), tiny);
  }
  geo::Rings exposed = bridge;
  exposed.insert(exposed.end(), top.begin(), top.end());
  geo::Rings internal = drop_small(exposed.empty() ? grown : difference(grown, exposed), tiny);
  if (!bridge.empty()) out.push_back({PathKind::Bridge, std::move(bridge)});
  if (!internal.empty()) out.push_back({PathKind::SolidInfill, std::move(internal)});
  if (!top.empty()) out.push_back({PathKind::TopSolid, std::move(top)});
  if (!all_solid) {
    geo::Rings sparse = drop_small(difference(fill, grown), tiny);
    if (!sparse.empty()) out.push_back({PathKind::Infill, std::move(sparse)});
  }
  return out;
}

}  // namespace tranche::toolpath
