#include "geometry/preview/raster.h"

#include <algorithm>
#include <cmath>

namespace tranche::preview {

namespace {
constexpr float kEmpty = -1;
constexpr double kMargin = 0.04;  // of the thumbnail's size, on each side
}  // namespace

HeightCanvas::HeightCanvas(int width_px, int height_px, BoxMm box)
    : w_(std::max(1, width_px)), h_(std::max(1, height_px)) {
  ss_ = std::clamp(1024 / std::max(w_, h_), 1, 4);  // supersampling: small icons get more
  sw_ = w_ * ss_;
  sh_ = h_ * ss_;
  z_.assign(static_cast<size_t>(sw_) * static_cast<size_t>(sh_), kEmpty);
  if (box.empty()) box = {box.x0 - 1, box.y0 - 1, box.x0 + 1, box.y0 + 1};
  const double bw = box.x1 - box.x0, bh = box.y1 - box.y0;
  scale_ = (1 - 2 * kMargin) * std::min(sw_ / bw, sh_ / bh);
  ox_ = sw_ / 2.0 - (box.x0 + bw / 2) * scale_;
  oy_ = sh_ / 2.0 + (box.y0 + bh / 2) * scale_;  // image rows run down, bed y runs up
}

namespace {

struct Span {
  double lo = 1e300, hi = -1e300;
  void add(double a, double b) { lo = std::min(lo, a), hi = std::max(hi, b); }
};

// x-interval where a·x + c lies in [lo, hi] (the whole line when a = 0 and c does).
bool solve(double a, double c, double lo, double hi, double& x0, double& x1) {
  if (std::fabs(a) < 1e-12) {
    if (c < lo || c > hi) return false;
    x0 = -1e300, x1 = 1e300;
    return true;
  }
  x0 = (lo - c) / a, x1 = (hi - c) / a;
  if (x0 > x1) std::swap(x0, x1);
  return true;
}

}  // namespace

void HeightCanvas::add_segment(PointMm a, PointMm b, float width_mm, float z_mm) {
  const double ax = ox_ + a.x * scale_, ay = oy_ - a.y * scale_, bx = ox_ + b.x * scale_,
               by = oy_ - b.y * scale_;
  const double r = std::max(0.5 * width_mm * scale_, 0.6);  // thin beads stay visible
  const double len = std::hypot(bx - ax, by - ay);
  const double ux = len > 0 ? (bx - ax) / len : 1, uy = len > 0 ? (by - ay) / len : 0, nx = -uy, ny = ux;
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(ay, by) - r)));
  const int y1 = std::min(sh_ - 1, static_cast<int>(std::ceil(std::max(ay, by) + r)));
  // The capsule is convex, so each row meets it in one interval: the union of the rectangle's
  // and the two end discs' intervals. Rows cost O(1) and only covered pixels are visited.
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    Span span;
    double p0, p1, q0, q1;
    if (solve(nx, (py - ay) * ny - ax * nx, -r, r, p0, p1) &&
        solve(ux, (py - ay) * uy - ax * ux, 0, len, q0, q1) && std::max(p0, q0) <= std::min(p1, q1))
      span.add(std::max(p0, q0), std::min(p1, q1));
    for (const auto& [cx, cy] : {std::pair{ax, ay}, std::pair{bx, by}}) {
      const double h = r * r - (py - cy) * (py - cy);
      if (h >= 0) span.add(cx - std::sqrt(h), cx + std::sqrt(h));
    }
    if (span.lo > span.hi) continue;
    const int x0 = std::max(0, static_cast<int>(std::ceil(span.lo - 0.5)));
    const int x1 = std::min(sw_ - 1, static_cast<int>(std::floor(span.hi - 0.5)));
    float* row = &z_[static_cast<size_t>(y) * static_cast<size_t>(sw_)];
    for (int x = x0; x <= x1; ++x) row[x] = std::max(row[x], z_mm);
  }
}

void HeightCanvas::add_layer(const PreviewLayer& layer) {
  for (const PreviewPath& p : layer.paths)
    for (size_t i = 0; i < p.piece_count(); ++i)
      add_segment(p.points[i], p.points[i + 1], p.width_at(i), layer.z);
}

void HeightCanvas::fill_spans(const std::vector<std::vector<PointMm>>& rings, float z_mm) {
  // A scanline fill with an edge table: each edge is visited only on the rows it spans.
  struct Edge {
    int row0, row1;   // first and last row whose centre it crosses
    double x0, dxdr;  // x (px) at row0's centre, and per row
  };
  std::vector<Edge> edges;
  for (const auto& ring : rings)
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
      double ax = ox_ + ring[i].x * scale_, ay = oy_ - ring[i].y * scale_;
      double bx = ox_ + ring[(i + 1) % n].x * scale_, by = oy_ - ring[(i + 1) % n].y * scale_;
      if (ay == by) continue;
      if (ay > by) std::swap(ax, bx), std::swap(ay, by);
      // Rows whose centre y + 0.5 lies in [ay, by): half-open, so a vertex is counted once.
      const int r0 = std::max(0, static_cast<int>(std::ceil(ay - 0.5))),
                r1 = std::min(sh_ - 1, static_cast<int>(std::ceil(by - 0.5)) - 1);
      if (r0 > r1) continue;
      const double dxdr = (bx - ax) / (by - ay);
      edges.push_back({r0, r1, ax + (r0 + 0.5 - ay) * dxdr, dxdr});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.row0 < b.row0; });
  std::vector<const Edge*> active;
  std::vector<double> xs;
  size_t next = 0;
  const int first = edges.empty() ? sh_ : edges.front().row0;
  for (int y = first; y < sh_ && (next < edges.size() || !active.empty()); ++y) {
    while (next < edges.size() && edges[next].row0 == y) active.push_back(&edges[next++]);
    std::erase_if(active, [y](const Edge* e) { return e->row1 < y; });
    xs.clear();
    for (const Edge* e : active) xs.push_back(e->x0 + (y - e->row0) * e->dxdr);
    std::sort(xs.begin(), xs.end());
    float* row = &z_[static_cast<size_t>(y) * static_cast<size_t>(sw_)];
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {  // even-odd: outline minus holes
      const int x0 = std::max(0, static_cast<int>(std::ceil(xs[k] - 0.5)));
      const int x1 = std::min(sw_ - 1, static_cast<int>(std::floor(xs[k + 1] - 0.5)));
      for (int x = x0; x <= x1; ++x) row[x] = std::max(row[x], z_mm);
    }
  }
}

void HeightCanvas::add_polygon(const geo::Polygon& poly, double dx_mm, double dy_mm, float z_mm) {
  std::vector<std::vector<PointMm>> rings;
  auto add = [&](const geo::Ring& r) {
    auto& out = rings.emplace_back();
    for (const geo::Point& p : r)
      out.push_back(
          {static_cast<float>(geo::to_mm(p.X) + dx_mm), static_cast<float>(geo::to_mm(p.Y) + dy_mm)});
  };
  add(poly.outer);
  for (const geo::Ring& h : poly.holes) add(h);
  fill_spans(rings, z_mm);
}

void HeightCanvas::add_layer(const geo::Layer& layer, double dx_mm, double dy_mm) {
  for (const geo::Island& island : layer.islands)
    add_polygon(island.shape, dx_mm, dy_mm, static_cast<float>(layer.z_top));
}

Image HeightCanvas::shade(const ShadeStyle& style) const {
  const size_t n = z_.size();
  float zmin = 1e30f, zmax = -1e30f;
  for (float z : z_)
    if (z != kEmpty) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
  // Smooth the terraces of the layers (a box blur over one output pixel) before taking slopes.
  std::vector<float> ground(n), tmp(n), smooth(n);
  for (size_t i = 0; i < n; ++i) ground[i] = z_[i] == kEmpty ? 0.0f : z_[i];
  const int r = ss_;
  auto blur = [&](const std::vector<float>& in, std::vector<float>& out, bool rows) {
    const int len = rows ? sw_ : sh_, lines = rows ? sh_ : sw_;
    for (int l = 0; l < lines; ++l) {
      auto at = [&](int i) -> size_t {
        i = std::clamp(i, 0, len - 1);
        return rows ? static_cast<size_t>(l) * sw_ + i : static_cast<size_t>(i) * sw_ + l;
      };
      double sum = 0;
      for (int i = -r; i <= r; ++i) sum += in[at(i)];
      for (int i = 0; i < len; ++i) {
        out[at(i)] = static_cast<float>(sum / (2 * r + 1));
        sum += in[at(i + r + 1)] - in[at(i - r)];
      }
    }
  };
  blur(ground, tmp, true);
  blur(tmp, smooth, false);
  const double lx = -0.5, ly = 0.5, lz = 0.7071;  // the lamp: upper left (bed -x, +y), 45° up
  Image img(w_, h_);
  for (int oy = 0; oy < h_; ++oy)
    for (int ox = 0; ox < w_; ++ox) {
      double sum[3] = {0, 0, 0};
      int covered = 0;
      for (int sy = oy * ss_; sy < (oy + 1) * ss_; ++sy)
        for (int sx = ox * ss_; sx < (ox + 1) * ss_; ++sx) {
          const size_t i = static_cast<size_t>(sy) * sw_ + sx;
          if (z_[i] == kEmpty) continue;
          auto Z = [&](int x, int y) {
            return smooth[static_cast<size_t>(std::clamp(y, 0, sh_ - 1)) * sw_ + std::clamp(x, 0, sw_ - 1)];
          };
          const double gx = (Z(sx + 1, sy) - Z(sx - 1, sy)) * scale_ / 2;  // dz/dx, bed
          const double gy = (Z(sx, sy - 1) - Z(sx, sy + 1)) * scale_ / 2;  // dz/dy, bed (rows run down)
          const double len = std::sqrt(gx * gx + gy * gy + 1);
          const double diffuse = std::max(0.0, (-gx * lx - gy * ly + lz) / len);
          const double height = zmax > zmin ? (z_[i] - zmin) / (zmax - zmin) : 1.0;
          const double k = (style.ambient + (1 - style.ambient) * diffuse / lz) * (0.72 + 0.28 * height);
          sum[0] += std::min(255.0, style.colour.r * k);
          sum[1] += std::min(255.0, style.colour.g * k);
          sum[2] += std::min(255.0, style.colour.b * k);
          ++covered;
        }
      uint8_t* px = img.at(ox, oy);
      if (!covered) continue;
      for (int c = 0; c < 3; ++c) px[c] = static_cast<uint8_t>(std::lround(sum[c] / covered));
      px[3] = static_cast<uint8_t>(std::lround(255.0 * covered / (ss_ * ss_)));
    }
  return img;
}

BoxMm print_box(const PreviewPrint& print) {
  BoxMm b{1e30f, 1e30f, -1e30f, -1e30f};
  for (const PreviewLayer& l : print.layers)
    for (const PreviewPath& p : l.paths)
      for (PointMm q : p.points) {
        b.x0 = std::min(b.x0, q.x), b.y0 = std::min(b.y0, q.y);
        b.x1 = std::max(b.x1, q.x), b.y1 = std::max(b.y1, q.y);
      }
  return b;
}

Image render_thumbnail(const PreviewPrint& print, int width, int height, const ShadeStyle& style) {
  const BoxMm box = print_box(print);
  if (box.x0 > box.x1) return Image(std::max(1, width), std::max(1, height));  // nothing printed
  HeightCanvas canvas(width, height, box);
  for (const PreviewLayer& l : print.layers) canvas.add_layer(l);
  return canvas.shade(style);
}

}  // namespace tranche::preview
