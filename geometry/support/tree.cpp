#include "geometry/support/tree.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "geometry/support/overhang.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

namespace tranche::support {

using geo::Rings;

namespace {

struct Node {
  double x, y, r;  // mm, model coordinates
  bool bed_only;
  int id;          // in the forest
};

struct Disc {
  int node;
  double x, y, r;
};

// A bar joining two branches of one layer into one island (see TreeSpec::link_mm).
struct Bar {
  int a, b;  // nodes
  double ax, ay, bx, by, r;
};

// Whether p lies inside `rings` (non-zero: outer rings count +1, holes -1).
bool inside(const Rings& rings, const geo::Point& p) {
  int w = 0;
  for (const geo::Ring& r : rings)
    if (ClipperLib::PointInPolygon(p, r) != 0) w += ClipperLib::Orientation(r) ? 1 : -1;
  return w > 0;
}

// The point of `rings`' edges nearest to (x, y), mm; false when there are none.
bool nearest_on(const Rings& rings, double x, double y, double& qx, double& qy) {
  double best = 1e300;
  for (const geo::Ring& r : rings)
    for (size_t i = 0; i < r.size(); ++i) {
      const double ax = geo::to_mm(r[i].X), ay = geo::to_mm(r[i].Y);
      const double bx = geo::to_mm(r[(i + 1) % r.size()].X), by = geo::to_mm(r[(i + 1) % r.size()].Y);
      const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
      double t = len2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / len2 : 0;
      t = std::clamp(t, 0.0, 1.0);
      const double px = ax + t * dx, py = ay + t * dy, d = (px - x) * (px - x) + (py - y) * (py - y);
      if (d < best) best = d, qx = px, qy = py;
    }
  return best < 1e300;
}

geo::Ring disc(double x, double y, double r) {
  constexpr int kSides = 24;
  geo::Ring ring;
  for (int i = 0; i < kSides; ++i) {
    const double a = 2 * std::numbers::pi * i / kSides;
    ring.push_back(geo::to_point(x + r * std::cos(a), y + r * std::sin(a)));
  }
  return ring;
}

// The ring round the segment a-b grown by r (two half discs and their tangents), counter-clockwise.
geo::Ring capsule(double ax, double ay, double bx, double by, double r) {
  constexpr int kHalf = 12;
  const double t = std::atan2(by - ay, bx - ax);
  geo::Ring ring;
  for (int i = 0; i <= kHalf; ++i) {
    const double a = t - std::numbers::pi / 2 + std::numbers::pi * i / kHalf;
    ring.push_back(geo::to_point(bx + r * std::cos(a), by + r * std::sin(a)));
  }
  for (int i = 0; i <= kHalf; ++i) {
    const double a = t + std::numbers::pi / 2 + std::numbers::pi * i / kHalf;
    ring.push_back(geo::to_point(ax + r * std::cos(a), ay + r * std::sin(a)));
  }
  return ring;
}

// Tips on a grid over `region`, at least one for a region the grid misses.
std::vector<std::pair<double, double>> tips(const Rings& region, double spacing) {
  std::vector<std::pair<double, double>> out;
  const geo::BBox2 b = toolpath::bbox(region);
  if (b.empty()) return out;
  for (double y = std::ceil(geo::to_mm(b.min_y) / spacing) * spacing; y <= geo::to_mm(b.max_y); y += spacing)
    for (double x = std::ceil(geo::to_mm(b.min_x) / spacing) * spacing; x <= geo::to_mm(b.max_x); x += spacing)
      if (inside(region, geo::to_point(x, y))) out.emplace_back(x, y);
  if (out.empty())
    for (const Rings& piece : components(region)) {  // a small contact: one tip at its middle
      const geo::BBox2 pb = toolpath::bbox(piece);
      const double cx = geo::to_mm((pb.min_x + pb.max_x) / 2), cy = geo::to_mm((pb.min_y + pb.max_y) / 2);
      if (inside(piece, geo::to_point(cx, cy))) out.emplace_back(cx, cy);
      else if (!piece.empty() && !piece[0].empty()) out.emplace_back(geo::to_mm(piece[0][0].X), geo::to_mm(piece[0][0].Y));
    }
  return out;
}

// The branches and how they were made: every disc by layer, who merged into whom.
class Forest {
 public:
  explicit Forest(size_t layers) : discs_(layers), bars_(layers) {}

  int node() {
    parents_.emplace_back();
    dead_.push_back(0);
    return static_cast<int>(parents_.size()) - 1;
  }
  int merged(int a, int b) {
    const int c = node();
    parents_[static_cast<size_t>(c)] = {a, b};
    return c;
  }
  void add(size_t layer, const Node& n) { discs_[layer].push_back({n.id, n.x, n.y, n.r}); }
  void link(size_t layer, const Node& a, const Node& b, double r) {
    bars_[layer].push_back({a.id, b.id, a.x, a.y, b.x, b.y, r});
  }
  // Drops node `id` and every branch that fed it (the tree above cannot stand without it).
  void kill(int id) {
    std::vector<int> stack{id};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (dead_[static_cast<size_t>(n)]) continue;
      dead_[static_cast<size_t>(n)] = 1;
      for (int p : parents_[static_cast<size_t>(n)]) stack.push_back(p);
    }
  }
  // Removes the discs of node `id` and of the branches that fed it on layers [from, from + count):
  // the z gap over the part (a branch merged on the layer it ended on left its discs under its
  // parents' names).
  void drop(int id, size_t from, int count) {
    std::vector<int> ids, stack{id};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      ids.push_back(n);
      for (int p : parents_[static_cast<size_t>(n)]) stack.push_back(p);
    }
    const auto gone = [&](int node) { return std::find(ids.begin(), ids.end(), node) != ids.end(); };
    for (size_t k = from; k < discs_.size() && k < from + static_cast<size_t>(count); ++k) {
      std::erase_if(discs_[k], [&](const Disc& d) { return gone(d.node); });
      std::erase_if(bars_[k], [&](const Bar& b) { return gone(b.a) || gone(b.b); });
    }
  }
  // The living branches' discs on layer k, and (`bars`, not united) their bars.
  Rings layer(size_t k, Rings& bars) const {
    Rings out;
    for (const Disc& d : discs_[k])
      if (!dead_[static_cast<size_t>(d.node)]) out.push_back(disc(d.x, d.y, d.r));
    bars.clear();
    for (const Bar& b : bars_[k])
      if (!dead_[static_cast<size_t>(b.a)] && !dead_[static_cast<size_t>(b.b)])
        bars.push_back(capsule(b.ax, b.ay, b.bx, b.by, b.r));
    return toolpath::union_of(out);
  }

 private:
  std::vector<std::vector<int>> parents_;
  std::vector<char> dead_;
  std::vector<std::vector<Disc>> discs_;
  std::vector<std::vector<Bar>> bars_;
};

class Grower {
 public:
  Grower(const ProjectInput& in, const TreeSpec& spec) : in_(in), spec_(spec), forest_(in.layers.size()) {}

  TreeResult run() {
    TreeResult res;
    const size_t n = in_.layers.size();
    for (size_t k = n; k-- > 0;) {
      obstacles_.clear();
      const double h = in_.layers[k].height();
      if (k < in_.contacts.size())
        for (const Contact& c : in_.contacts[k])
          for (auto [x, y] : tips(c.region, spec_.tip_spacing_mm)) {
            nodes_.push_back({x, y, spec_.tip_radius_mm, c.bed_only, forest_.node()});
            ++res.tips;
          }
      step(k, h * std::tan(spec_.branch_angle_deg * std::numbers::pi / 180));
      link(k);
      for (Node& nd : nodes_) {
        forest_.add(k, nd);
        nd.r = std::min(spec_.max_radius_mm, nd.r + spec_.widen_per_mm * h);
      }
    }
    res.trunks_on_bed = static_cast<int>(nodes_.size());
    res.blocked_mm2 = blocked_mm2_;
    res.branches.resize(n);
    const int gap = gap_layers();
    // What a tip placed on a layer touches on the layer above (a contact with no gap and no
    // interface): the part there may lie on it; elsewhere branches leave the part above air.
    std::vector<Rings> touch(n);
    for (size_t k = 0; k < n && k < in_.contacts.size(); ++k)
      for (const Contact& c : in_.contacts[k])
        if (c.touching) touch[k].insert(touch[k].end(), c.region.begin(), c.region.end());
    for (size_t k = 0; k < n; ++k) {
      Rings bars;
      Rings b = forest_.layer(k, bars);
      if (!bars.empty()) {  // a bar spans air: not over the part's top within the z gap
        Rings below;
        for (size_t j = k; j-- > 0 && j + static_cast<size_t>(gap) >= k;) {
          const Rings& ob = j < in_.keep_out.size() && !in_.keep_out[j].empty() ? in_.keep_out[j] : part(j);
          below.insert(below.end(), ob.begin(), ob.end());
        }
        b = toolpath::union_of(b, below.empty() ? bars : toolpath::difference(bars, below));
      }
      if (b.empty()) continue;
      Rings cut = k < in_.keep_out.size() && !in_.keep_out[k].empty() ? in_.keep_out[k] : toolpath::material(in_.layers[k]);
      if (k + 1 < n) {  // the top gap: nothing right under the part of the layer above (a speck of it
                        // a branch passes under, the edge of a slope's next layer)
        Rings above = part_above(toolpath::material(in_.layers[k + 1]), touch[k], toolpath::bbox(b));
        cut.insert(cut.end(), std::make_move_iterator(above.begin()), std::make_move_iterator(above.end()));
      }
      b = toolpath::difference(b, cut);
      if (!in_.bed.empty()) b = toolpath::intersection(b, in_.bed);
      res.branches[k] = std::move(b);
    }
    return res;
  }

 private:
  // Layers of air between the part's top and a branch or bar above it: the spec's, or the
  // support_z_gap's (ProjectInput::bottom_gap_layers) when more.
  int gap_layers() const { return std::max(spec_.bottom_gap_layers, in_.bottom_gap_layers); }

  // The part grown by its gap and a branch of radius r, on the layer being grown.
  const Rings& obstacle(size_t k, double r) {
    const int bucket = static_cast<int>(std::ceil(r / 0.25));
    auto it = obstacles_.find(bucket);
    if (it != obstacles_.end()) return it->second;
    const Rings& base = k < in_.keep_out.size() && !in_.keep_out[k].empty() ? in_.keep_out[k] : part(k);
    return obstacles_.emplace(bucket, toolpath::offset(base, bucket * 0.25)).first->second;
  }
  const Rings& part(size_t k) {
    if (part_layer_ != k) part_ = toolpath::material(in_.layers[k]), part_layer_ = k;
    return part_;
  }

  // Bars joining the layer's branches that stand within link_mm of each other: the edges of their
  // minimum spanning tree (Prim's) no longer than that, so each group of close branches prints as
  // one island, with the fewest bars.
  void link(size_t k) {
    const size_t n = nodes_.size();
    if (spec_.link_mm <= 0 || n < 2) return;
    std::vector<double> best(n, 1e300);
    std::vector<size_t> from(n, 0);
    std::vector<char> in(n, 0);
    size_t cur = 0;
    in[0] = 1;
    for (size_t added = 1; added < n; ++added) {
      for (size_t j = 0; j < n; ++j) {
        if (in[j]) continue;
        const double d = std::hypot(nodes_[j].x - nodes_[cur].x, nodes_[j].y - nodes_[cur].y);
        if (d < best[j]) best[j] = d, from[j] = cur;
      }
      size_t next = n;
      for (size_t j = 0; j < n; ++j)
        if (!in[j] && (next == n || best[j] < best[next])) next = j;
      in[next] = 1;
      cur = next;
      const Node &a = nodes_[next], &b = nodes_[from[next]];
      if (best[next] <= spec_.link_mm && best[next] > std::max(a.r, b.r))
        forest_.link(k, a, b, spec_.link_radius_mm);
    }
  }

  // One layer down: lean toward the nearest branch, merge, get out of the part or end on it.
  void step(size_t k, double reach) {
    for (size_t i = 0; i < nodes_.size(); ++i) {
      Node& a = nodes_[i];
      double bd = 1e300, bx = a.x, by = a.y;
      for (size_t j = 0; j < nodes_.size(); ++j) {
        if (j == i) continue;
        const double d = std::hypot(nodes_[j].x - a.x, nodes_[j].y - a.y);
        if (d < bd) bd = d, bx = nodes_[j].x, by = nodes_[j].y;
      }
      if (bd < 1e300 && bd > 0) {
        const double s = std::min(reach, 0.5 * bd) / bd;
        a.x += (bx - a.x) * s;
        a.y += (by - a.y) * s;
      }
    }
    merge();  // before avoiding the part: a merged branch must get out of it too
    std::vector<Node> kept;
    for (Node& a : nodes_) {
      const geo::Point p = geo::to_point(a.x, a.y);
      const Rings& ob = obstacle(k, a.r);
      if (!inside(ob, p)) {
        kept.push_back(a);
        continue;
      }
      double qx = a.x, qy = a.y;
      const bool found = nearest_on(toolpath::near(ob, {p.X - geo::to_units(2 * reach), p.Y - geo::to_units(2 * reach),
                                                        p.X + geo::to_units(2 * reach), p.Y + geo::to_units(2 * reach)}),
                                    a.x, a.y, qx, qy);
      const double d = std::hypot(qx - a.x, qy - a.y);
      if (found && d <= 2 * reach) {  // out of the way, just past the obstacle's edge
        const double s = d > 0 ? (d + 0.01) / d : 0;
        a.x += (qx - a.x) * s;
        a.y += (qy - a.y) * s;
        kept.push_back(a);
      } else if (inside(part(k), p)) {  // the part is right below: the branch ends on it
        if (a.bed_only) {
          forest_.kill(a.id);
          blocked_mm2_ += std::numbers::pi * a.r * a.r;
        } else {
          forest_.drop(a.id, k + 1, gap_layers());  // the z gap over the part's top
        }
      } else {
        kept.push_back(a);  // squeezed beside a wall: goes on, cut by the gap when printed
      }
    }
    nodes_ = std::move(kept);
  }

  void merge() {
    for (bool again = true; again;) {
      again = false;
      for (size_t i = 0; i < nodes_.size() && !again; ++i)
        for (size_t j = i + 1; j < nodes_.size() && !again; ++j) {
          const Node &a = nodes_[i], &b = nodes_[j];
          if (std::hypot(a.x - b.x, a.y - b.y) >= std::max(a.r, b.r)) continue;
          const double wa = a.r * a.r, wb = b.r * b.r;
          Node c{(a.x * wa + b.x * wb) / (wa + wb), (a.y * wa + b.y * wb) / (wa + wb),
                 std::min(spec_.max_radius_mm, std::max(a.r, b.r) + 0.25 * std::min(a.r, b.r)),
                 a.bed_only || b.bed_only, forest_.merged(a.id, b.id)};
          nodes_[i] = c;
          nodes_.erase(nodes_.begin() + static_cast<long>(j));
          again = true;
        }
    }
  }

  const ProjectInput& in_;
  const TreeSpec& spec_;
  Forest forest_;
  std::vector<Node> nodes_;
  std::map<int, Rings> obstacles_;
  Rings part_;
  size_t part_layer_ = SIZE_MAX;
  double blocked_mm2_ = 0;
};

}  // namespace

TreeResult grow_trees(const ProjectInput& in, const TreeSpec& spec) { return Grower(in, spec).run(); }

}  // namespace tranche::support
