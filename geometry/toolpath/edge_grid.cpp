#include "geometry/toolpath/edge_grid.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tranche::toolpath {

using geo::coord_t;
using geo::Point;

__extension__ typedef __int128 i128;

int orient(const Point& a, const Point& b, const Point& c) {
  i128 v = static_cast<i128>(b.X - a.X) * (c.Y - a.Y) - static_cast<i128>(b.Y - a.Y) * (c.X - a.X);
  return v > 0 ? 1 : v < 0 ? -1 : 0;
}

namespace {
// A vector of doubles on the stack while it holds 16 or fewer.
class SmallVec {
 public:
  void push_back(double v) {
    if (!on_heap_) {
      if (n_ < kInline) {
        inline_[n_++] = v;
        return;
      }
      heap_.assign(inline_, inline_ + n_);
      on_heap_ = true;
    }
    heap_.push_back(v);
    ++n_;
  }
  double* begin() { return on_heap_ ? heap_.data() : inline_; }
  double* end() { return begin() + n_; }
  void resize(size_t n) {  // shrinking only
    n_ = n;
    if (on_heap_) heap_.resize(n);
  }

 private:
  static constexpr size_t kInline = 16;
  double inline_[kInline];
  std::vector<double> heap_;
  size_t n_ = 0;
  bool on_heap_ = false;
};

bool on_segment(const Point& a, const Point& b, const Point& p) {
  return std::min(a.X, b.X) <= p.X && p.X <= std::max(a.X, b.X) && std::min(a.Y, b.Y) <= p.Y &&
         p.Y <= std::max(a.Y, b.Y);
}
}  // namespace

bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  if (std::max(a.X, b.X) < std::min(c.X, d.X) || std::max(c.X, d.X) < std::min(a.X, b.X) ||
      std::max(a.Y, b.Y) < std::min(c.Y, d.Y) || std::max(c.Y, d.Y) < std::min(a.Y, b.Y))
    return false;
  const int o1 = orient(a, b, c), o2 = orient(a, b, d);
  if (o1 == o2 && o1 != 0) return false;  // c and d strictly on one side of ab
  const int o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

EdgeGrid::EdgeGrid(const geo::Rings& rings, coord_t cell) {
  geo::BBox2 box;
  size_t n = 0;
  for (const auto& r : rings) {
    for (const auto& p : r) box.add(p);
    n += r.size();
  }
  if (n == 0) return;
  edges_.reserve(n);
  ring_start_.reserve(rings.size() + 1);
  for (const auto& r : rings) {
    ring_start_.push_back(static_cast<uint32_t>(edges_.size()));
    for (size_t i = 0; i < r.size(); ++i) edges_.push_back({r[i], r[(i + 1) % r.size()]});
  }
  ring_start_.push_back(static_cast<uint32_t>(edges_.size()));
  double w = static_cast<double>(box.max_x - box.min_x) + 1,
         h = static_cast<double>(box.max_y - box.min_y) + 1;
  if (cell <= 0) {
    // About two edges per occupied cell: pitch from the mean edge length and the extent.
    double total = 0;
    for (const auto& e : edges_) total += std::abs(double(e.b.X - e.a.X)) + std::abs(double(e.b.Y - e.a.Y));
    double mean = total / static_cast<double>(edges_.size());
    double by_area = std::sqrt(w * h / static_cast<double>(edges_.size()));
    cell = static_cast<coord_t>(std::max({mean * 2.0, by_area, 1000.0}));
  }
  cell_ = cell;
  x0_ = box.min_x;
  y0_ = box.min_y;
  x1_ = box.max_x;
  y1_ = box.max_y;
  nx_ = static_cast<int>(w / static_cast<double>(cell_)) + 1;
  ny_ = static_cast<int>(h / static_cast<double>(cell_)) + 1;
  size_t cells = static_cast<size_t>(nx_) * static_cast<size_t>(ny_);
  // The cells of each edge, walked once: (cell, edge) in edge order, then sorted by cell
  // (counting, stable: each cell's edges stay in edge order).
  std::vector<uint32_t> count(cells + 1, 0);
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  pairs.reserve(edges_.size() * 2);
  for (uint32_t i = 0; i < edges_.size(); ++i)
    visit_segment_cells(edges_[i].a, edges_[i].b, [&](int x, int y) {
      const auto c = static_cast<uint32_t>(static_cast<size_t>(y) * nx_ + x);
      pairs.emplace_back(c, i);
      ++count[c + 1];
    });
  for (size_t i = 1; i <= cells; ++i) count[i] += count[i - 1];
  start_ = count;
  items_.resize(count[cells]);
  for (const auto& [c, i] : pairs) items_[count[c]++] = i;
  // A cell no edge passes through is wholly inside or wholly outside: its centre's answer, found
  // for a whole row at once (right to left, the crossings of the row's middle line counted in
  // the column that holds them, as inside() counts them), answers inside() there in one step.
  empty_in_.assign(cells, -1);
  for (int row = 0; row < ny_; ++row) {
    const double y = static_cast<double>(y0_) + (row + 0.5) * static_cast<double>(cell_);
    bool in = false;
    for (int c = nx_ - 1; c >= 0; --c) {
      const size_t id = static_cast<size_t>(row) * nx_ + c;
      if (start_[id] == start_[id + 1]) {
        empty_in_[id] = in ? 1 : 0;
        continue;
      }
      const double lo = c == 0 ? -1e300 : static_cast<double>(x0_ + coord_t(c) * cell_);
      const double hi = c + 1 == nx_ ? 1e300 : static_cast<double>(x0_ + coord_t(c + 1) * cell_);
      for (uint32_t k = start_[id]; k < start_[id + 1]; ++k) {
        const Edge& e = edges_[items_[k]];
        const double ay = static_cast<double>(e.a.Y), by = static_cast<double>(e.b.Y);
        if ((ay > y) == (by > y)) continue;
        const double x = static_cast<double>(e.a.X) + (y - ay) * static_cast<double>(e.b.X - e.a.X) / (by - ay);
        if (x >= lo && x < hi) in = !in;
      }
    }
  }
}

int EdgeGrid::cx(coord_t x) const {
  return static_cast<int>(std::clamp<coord_t>((x - x0_) / cell_, 0, nx_ - 1));
}
int EdgeGrid::cy(coord_t y) const {
  return static_cast<int>(std::clamp<coord_t>((y - y0_) / cell_, 0, ny_ - 1));
}

// Every cell the segment passes through (a conservative supercover: per column, the rows
// between the segment's y at the column's two sides).
template <class F>
void EdgeGrid::visit_segment_cells(const Point& a, const Point& b, F&& f) const {
  Point p = a, q = b;
  if (p.X > q.X) std::swap(p, q);
  int c0 = cx(p.X), c1 = cx(q.X);
  double dx = static_cast<double>(q.X - p.X), dy = static_cast<double>(q.Y - p.Y);
  for (int c = c0; c <= c1; ++c) {
    double xa = std::max<double>(static_cast<double>(p.X), static_cast<double>(x0_ + coord_t(c) * cell_));
    double xb = std::min<double>(static_cast<double>(q.X), static_cast<double>(x0_ + coord_t(c + 1) * cell_));
    double ya, yb;
    if (dx == 0) {
      ya = static_cast<double>(p.Y);
      yb = static_cast<double>(q.Y);
    } else {
      ya = static_cast<double>(p.Y) + dy * (xa - static_cast<double>(p.X)) / dx;
      yb = static_cast<double>(p.Y) + dy * (xb - static_cast<double>(p.X)) / dx;
    }
    if (ya > yb) std::swap(ya, yb);
    int r0 = cy(static_cast<coord_t>(std::floor(ya)) - 1), r1 = cy(static_cast<coord_t>(std::ceil(yb)) + 1);
    for (int r = r0; r <= r1; ++r) f(c, r);
  }
}

bool EdgeGrid::crosses(const Point& a, const Point& b) const {
  if (edges_.empty()) return false;
  if (std::max(a.X, b.X) < x0_ || std::max(a.Y, b.Y) < y0_ || std::min(a.X, b.X) > x1_ ||
      std::min(a.Y, b.Y) > y1_)
    return false;  // clear of every edge's bounding box
  // Both ends in one cell (short segments, as a region's edges are): the segment lies in it, and
  // an edge meeting it passes through it, so is listed in it.
  auto in_grid = [&](const Point& p) {
    return p.X >= x0_ && p.Y >= y0_ && p.X < x0_ + coord_t(nx_) * cell_ && p.Y < y0_ + coord_t(ny_) * cell_;
  };
  if (in_grid(a) && in_grid(b)) {
    const int c = cx(a.X), r = cy(a.Y);
    if (c == cx(b.X) && r == cy(b.Y)) {
      const size_t id = static_cast<size_t>(r) * nx_ + c;
      for (uint32_t k = start_[id]; k < start_[id + 1]; ++k)
        if (segments_meet(a, b, edges_[items_[k]].a, edges_[items_[k]].b)) return true;
      return false;
    }
  }
  bool hit = false;
  visit_segment_cells(a, b, [&](int x, int y) {
    if (hit) return;
    size_t c = static_cast<size_t>(y) * nx_ + x;
    for (uint32_t k = start_[c]; k < start_[c + 1] && !hit; ++k) {
      const Edge& e = edges_[items_[k]];
      hit = segments_meet(a, b, e.a, e.b);
    }
  });
  return hit;
}

bool EdgeGrid::along(const Point& a, const Point& b, coord_t tol) const {
  if (edges_.empty()) return false;
  Point m((a.X + b.X) / 2, (a.Y + b.Y) / 2);
  int mx = cx(m.X), my = cy(m.Y);
  double t2 = static_cast<double>(tol) * static_cast<double>(tol);
  auto dist2_line = [](const Edge& e, const Point& p) {
    double ex = double(e.b.X - e.a.X), ey = double(e.b.Y - e.a.Y);
    double len2 = ex * ex + ey * ey;
    double cr = ex * double(p.Y - e.a.Y) - ey * double(p.X - e.a.X);
    return len2 > 0 ? cr * cr / len2
                    : double(p.X - e.a.X) * double(p.X - e.a.X) + double(p.Y - e.a.Y) * double(p.Y - e.a.Y);
  };
  // An edge the segment runs along has the midpoint within tol of its line and its projection
  // within tol of its ends, so within its bounding box grown by 2 tol (and a unit or two for the
  // rounded midpoint): edges farther off are passed by four comparisons.
  const coord_t grow = 2 * tol + 2;
  for (int y = std::max(0, my - 1); y <= std::min(ny_ - 1, my + 1); ++y)
    for (int x = std::max(0, mx - 1); x <= std::min(nx_ - 1, mx + 1); ++x) {
      size_t c = static_cast<size_t>(y) * nx_ + x;
      for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
        const Edge& e = edges_[items_[k]];
        if (m.X < std::min(e.a.X, e.b.X) - grow || m.X > std::max(e.a.X, e.b.X) + grow ||
            m.Y < std::min(e.a.Y, e.b.Y) - grow || m.Y > std::max(e.a.Y, e.b.Y) + grow)
          continue;
        if (dist2_line(e, a) > t2 || dist2_line(e, b) > t2) continue;
        double ex = double(e.b.X - e.a.X), ey = double(e.b.Y - e.a.Y);
        double len2 = ex * ex + ey * ey;
        double t = len2 > 0 ? (ex * double(m.X - e.a.X) + ey * double(m.Y - e.a.Y)) / len2 : 0;
        double slack = len2 > 0 ? static_cast<double>(tol) / std::sqrt(len2) : 1;
        if (t >= -slack && t <= 1 + slack) return true;
      }
    }
  return false;
}

bool EdgeGrid::inside(const Point& p) const {
  if (edges_.empty()) return false;
  if (p.X < x0_ || p.Y < y0_ || p.X > x0_ + coord_t(nx_) * cell_ || p.Y > y0_ + coord_t(ny_) * cell_)
    return false;
  const int row = cy(p.Y), c0 = cx(p.X);
  const size_t base = static_cast<size_t>(row) * nx_;
  if (const int8_t known = empty_in_[base + c0]; known >= 0) return known == 1;
  // A ray along the row to the nearest cell no edge passes through, right or left (beyond the
  // grid: outside): that cell knows whether it is inside (found along the row's middle line; no
  // edge passes through it, so the same at any height in it), and each crossing on the way
  // turns the answer. Each crossing is counted in the one column that contains its x.
  int to = nx_;  // the cell reached: right of c0 (nx_: beyond the grid) ...
  bool right = true;
  for (int d = 1;; ++d) {
    if (c0 + d >= nx_) break;
    if (empty_in_[base + c0 + d] >= 0) {
      to = c0 + d;
      break;
    }
    if (c0 - d < 0) continue;
    if (empty_in_[base + c0 - d] >= 0) {  // ... or left of it
      to = c0 - d;
      right = false;
      break;
    }
  }
  if (right && to == nx_) {  // none to the right: the nearest to the left may still be nearer
    for (int c = c0 - 1; c >= 0 && c0 - c < nx_ - c0; --c)
      if (empty_in_[base + c] >= 0) {
        to = c;
        right = false;
        break;
      }
  }
  bool in = to >= 0 && to < nx_ && empty_in_[base + to] == 1;
  const int from = right ? c0 : to + 1, until = right ? to - 1 : c0;
  for (int c = from; c <= until; ++c) {
    const size_t cell = base + c;
    const double col_lo = c == 0 ? -1e300 : static_cast<double>(x0_ + coord_t(c) * cell_);
    const double col_hi = c + 1 == nx_ ? 1e300 : static_cast<double>(x0_ + coord_t(c + 1) * cell_);
    for (uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
      const Edge& e = edges_[items_[k]];
      if ((e.a.Y > p.Y) == (e.b.Y > p.Y)) continue;
      double x = static_cast<double>(e.a.X) + static_cast<double>(p.Y - e.a.Y) *
                                                  static_cast<double>(e.b.X - e.a.X) /
                                                  static_cast<double>(e.b.Y - e.a.Y);
      // Rightwards the crossings at or right of p (in p's column: all of those), leftwards those
      // left of it.
      const bool ahead = right ? x >= static_cast<double>(p.X) && (c == c0 || x >= col_lo) && x < col_hi
                               : x < static_cast<double>(p.X) && x >= col_lo && (c == c0 || x < col_hi);
      if (ahead) in = !in;
    }
  }
  return in;
}

std::vector<EdgeGrid::Hit> EdgeGrid::hits(const Point& a, const Point& b) const {
  std::vector<Hit> out;
  if (edges_.empty()) return out;
  std::vector<uint32_t> seen;
  visit_segment_cells(a, b, [&](int x, int y) {
    size_t c = static_cast<size_t>(y) * nx_ + x;
    for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
      uint32_t id = items_[k];
      const Edge& e = edges_[id];
      if (!segments_meet(a, b, e.a, e.b)) continue;
      double rx = double(b.X - a.X), ry = double(b.Y - a.Y), sx = double(e.b.X - e.a.X),
             sy = double(e.b.Y - e.a.Y);
      double den = rx * sy - ry * sx;
      if (den == 0) continue;
      if (std::find(seen.begin(), seen.end(), id) != seen.end()) continue;
      seen.push_back(id);
      double t = (double(e.a.X - a.X) * sy - double(e.a.Y - a.Y) * sx) / den;
      auto ring = static_cast<uint32_t>(std::upper_bound(ring_start_.begin(), ring_start_.end(), id) -
                                        ring_start_.begin() - 1);
      out.push_back({std::clamp(t, 0.0, 1.0), ring, id - ring_start_[ring]});
    }
  });
  std::sort(out.begin(), out.end(), [](const Hit& x, const Hit& y) { return x.t < y.t; });
  return out;
}

int EdgeGrid::box_state(coord_t bx0, coord_t by0, coord_t bx1, coord_t by1) const {
  if (edges_.empty()) return 0;
  if (bx1 < x0_ || by1 < y0_ || bx0 > x1_ || by0 > y1_) return 0;  // clear of every edge: outside
  if (bx0 < x0_ || by0 < y0_ || bx1 > x0_ + coord_t(nx_) * cell_ || by1 > y0_ + coord_t(ny_) * cell_) return -1;
  const int c0 = cx(bx0), c1 = cx(bx1), r0 = cy(by0), r1 = cy(by1);
  int state = -2;
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      const int8_t k = empty_in_[static_cast<size_t>(r) * nx_ + c];
      if (k < 0 || (state != -2 && k != state)) return -1;
      state = k;
    }
  return state;
}

bool EdgeGrid::box_clear(coord_t bx0, coord_t by0, coord_t bx1, coord_t by1) const {
  if (edges_.empty() || bx1 < x0_ || by1 < y0_ || bx0 > x1_ || by0 > y1_) return true;
  const int c0 = cx(bx0), c1 = cx(bx1), r0 = cy(by0), r1 = cy(by1);
  const Point corners[4] = {{bx0, by0}, {bx1, by0}, {bx1, by1}, {bx0, by1}};
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      const size_t id = static_cast<size_t>(r) * nx_ + c;
      for (uint32_t k = start_[id]; k < start_[id + 1]; ++k) {
        const Edge& e = edges_[items_[k]];
        if (std::max(e.a.X, e.b.X) < bx0 || std::min(e.a.X, e.b.X) > bx1 || std::max(e.a.Y, e.b.Y) < by0 ||
            std::min(e.a.Y, e.b.Y) > by1)
          continue;  // apart along x or y
        // Apart across the edge's line: every corner strictly on one side.
        const int s = orient(e.a, e.b, corners[0]);
        bool apart = s != 0;
        for (int q = 1; q < 4 && apart; ++q) apart = orient(e.a, e.b, corners[q]) == s;
        if (!apart) return false;
      }
    }
  return true;
}

double EdgeGrid::inside_fraction(const Point& a, const Point& b) const {
  if (edges_.empty()) return 0.0;
  // Both ends in one cell no edge passes through (a bead's width across, deep inside or far
  // outside a layer, as most are): the cell's answer.
  auto in_box = [&](const Point& p) {
    return p.X >= x0_ && p.Y >= y0_ && p.X <= x0_ + coord_t(nx_) * cell_ && p.Y <= y0_ + coord_t(ny_) * cell_;
  };
  if (cx(a.X) == cx(b.X) && cy(a.Y) == cy(b.Y) && in_box(a) && in_box(b))
    if (const int8_t known = empty_in_[static_cast<size_t>(cy(a.Y)) * nx_ + cx(a.X)]; known >= 0) return known;
  // The crossings' parameters: a few (a bead's width across a border), on the stack.
  SmallVec ts;
  visit_segment_cells(a, b, [&](int x, int y) {
    size_t c = static_cast<size_t>(y) * nx_ + x;
    for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
      const Edge& e = edges_[items_[k]];
      if (!segments_meet(a, b, e.a, e.b)) continue;
      double rx = double(b.X - a.X), ry = double(b.Y - a.Y), sx = double(e.b.X - e.a.X),
             sy = double(e.b.Y - e.a.Y);
      double den = rx * sy - ry * sx;
      if (den == 0) continue;  // collinear overlap: on the border, counts as either side
      ts.push_back((double(e.a.X - a.X) * sy - double(e.a.Y - a.Y) * sx) / den);
    }
  });
  std::sort(ts.begin(), ts.end());
  ts.resize(static_cast<size_t>(
      std::unique(ts.begin(), ts.end(), [](double u, double v) { return std::abs(u - v) < 1e-12; }) - ts.begin()));
  // Classify each sub-interval by its midpoint.
  double covered = 0, prev = 0;
  ts.push_back(1.0);
  for (double t : ts) {
    t = std::clamp(t, 0.0, 1.0);
    if (t > prev) {
      double mid = 0.5 * (prev + t);
      Point m(a.X + round_units(mid * double(b.X - a.X)), a.Y + round_units(mid * double(b.Y - a.Y)));
      if (inside(m)) covered += t - prev;
    }
    prev = std::max(prev, t);
  }
  return covered;
}

}  // namespace tranche::toolpath
