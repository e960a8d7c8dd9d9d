#include "geometry/polygon/resolve.h"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "geometry/polygon/contacts.h"
#include "geometry/polygon/exact.h"
#include "geometry/polygon/planar_graph.h"
#include "geometry/polygon/unite.h"

namespace tranche::geo {
namespace {

using unite::in_range;
using unite::range_error;
using unite::turns_back;
using unite::without_repeats;

// The place of a problem in messages: the layer, if any, and the point in mm.
std::string where(int layer, const Point& p) {
  if (layer < 0) return fmt::format("at ({:.3f}, {:.3f}) mm", to_mm(p.X), to_mm(p.Y));
  return fmt::format("layer {} at ({:.3f}, {:.3f}) mm", layer, to_mm(p.X), to_mm(p.Y));
}

// Orders points by x, then y.
bool point_less(const Point& a, const Point& b) { return a.X < b.X || (a.X == b.X && a.Y < b.Y); }

// Winding number of the ring around p, both given in doubled coordinates; p is off the ring.
int winding(const Ring& ring, const Point& p) {
  int wn = 0;
  for (size_t i = 0, n = ring.size(); i < n; ++i) {
    const Point a(ring[i].X * 2, ring[i].Y * 2);
    const Point b(ring[(i + 1) % n].X * 2, ring[(i + 1) % n].Y * 2);
    if (a.Y <= p.Y) {
      if (b.Y > p.Y && exact::orientation(a, b, p) > 0) ++wn;
    } else if (b.Y <= p.Y && exact::orientation(a, b, p) < 0) {
      --wn;
    }
  }
  return wn;
}

bool bbox_inside(const BBox2& in, const BBox2& out) {
  return out.min_x <= in.min_x && in.max_x <= out.max_x && out.min_y <= in.min_y && in.max_y <= out.max_y;
}

// Lowest, then leftmost point: a deterministic sort key.
std::pair<coord_t, coord_t> anchor(const Ring& r) {
  std::pair<coord_t, coord_t> best{INT64_MAX, INT64_MAX};
  for (const Point& p : r) best = std::min(best, std::make_pair(p.Y, p.X));
  return best;
}

// Splits a closed walk that may visit a point several times into loops visiting each point once.
void split_walk(const std::vector<int>& walk, std::vector<std::vector<int>>& loops) {
  std::vector<int> stack;
  std::unordered_map<int, size_t> pos;
  for (int v : walk) {
    auto it = pos.find(v);
    if (it == pos.end()) {
      pos.emplace(v, stack.size());
      stack.push_back(v);
      continue;
    }
    const size_t j = it->second;
    loops.emplace_back(stack.begin() + static_cast<std::ptrdiff_t>(j), stack.end());
    for (size_t k = j + 1; k < stack.size(); ++k) pos.erase(stack[k]);
    stack.resize(j + 1);
  }
  loops.push_back(std::move(stack));
}

// Removes vertices where the ring runs straight on (exactly collinear with their neighbours),
// except points in `keep` (shared with another ring: they must stay vertices of both).
void drop_collinear(Ring& ring, const std::vector<Point>& keep) {
  const int n = static_cast<int>(ring.size());
  std::vector<int> prev(n), next(n);
  std::vector<char> alive(n, 1);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto kept = [&](const Point& p) { return std::binary_search(keep.begin(), keep.end(), p, point_less); };
  int count = n;
  std::vector<int> work(n);
  for (int i = 0; i < n; ++i) work[i] = n - 1 - i;
  while (!work.empty() && count > 3) {
    const int v = work.back();
    work.pop_back();
    if (!alive[v] || !exact::strictly_between(ring[prev[v]], ring[v], ring[next[v]]) || kept(ring[v]))
      continue;
    alive[v] = 0;
    --count;
    next[prev[v]] = next[v];
    prev[next[v]] = prev[v];
    work.push_back(prev[v]);
    work.push_back(next[v]);
  }
  if (count == n) return;
  Ring out;
  out.reserve(count);
  for (int i = 0; i < n; ++i) {
    if (alive[i]) out.push_back(ring[i]);
  }
  ring = std::move(out);
}

// The canonical form of islands: no collinear vertices (bar shared points), every ring starting
// at its lowest then leftmost vertex, holes and islands in that order too, areas set. Equal
// regions give equal islands whichever way they were computed.
void finish_islands(std::vector<Island>& islands) {
  for (Island& is : islands) {
    std::vector<Point> all(is.shape.outer.begin(), is.shape.outer.end()), shared;
    for (const Ring& h : is.shape.holes) all.insert(all.end(), h.begin(), h.end());
    std::sort(all.begin(), all.end(), point_less);
    for (size_t i = 1; i < all.size(); ++i) {
      if (all[i] == all[i - 1] && (shared.empty() || !(shared.back() == all[i]))) shared.push_back(all[i]);
    }
    auto canonical = [&](Ring& r) {
      drop_collinear(r, shared);
      const auto first = std::min_element(r.begin(), r.end(), [](const Point& a, const Point& b) {
        return a.Y < b.Y || (a.Y == b.Y && a.X < b.X);
      });
      std::rotate(r.begin(), first, r.end());
    };
    canonical(is.shape.outer);
    for (Ring& h : is.shape.holes) canonical(h);
    std::sort(is.shape.holes.begin(), is.shape.holes.end(),
              [](const Ring& a, const Ring& b) { return anchor(a) < anchor(b); });
    exact::i128 a2 = exact::area2(is.shape.outer);
    for (const Ring& h : is.shape.holes) a2 += exact::area2(h);
    is.area_mm2 = static_cast<double>(a2) * 0.5 * kMmPerUnit * kMmPerUnit;
  }
  std::sort(islands.begin(), islands.end(),
            [](const Island& a, const Island& b) { return anchor(a.shape.outer) < anchor(b.shape.outer); });
}

// Islands from the graph of rings that meet only at shared vertices: its faces, split where they
// pinch (visit a point twice), as outlines and holes; each hole goes to its outline.
Result<std::vector<Island>> islands_from_graph(const PlanarGraph& graph) {
  std::vector<std::vector<int>> faces;
  if (!graph.faces(faces)) return Error{"", "inconsistent polygon boundary after union"};

  std::vector<std::vector<int>> loops;
  for (const auto& f : faces) {
    std::vector<int> walk;
    walk.reserve(f.size());
    for (int h : f) walk.push_back(graph.half_edge(h).from);
    split_walk(walk, loops);
  }
  Rings outers, holes;
  for (const auto& l : loops) {
    if (l.size() < 3) continue;  // what is left of a spike
    Ring r;
    r.reserve(l.size());
    for (int v : l) r.push_back(graph.point(v));
    const exact::i128 a = exact::area2(r);
    if (a > 0) outers.push_back(std::move(r));
    if (a < 0) holes.push_back(std::move(r));
  }

  // Each hole belongs to the smallest outline around it; a hole's edge midpoint is never on
  // another ring (rings meet only at vertices), so the exact winding test decides.
  std::sort(outers.begin(), outers.end(),
            [](const Ring& a, const Ring& b) { return exact::area2(a) < exact::area2(b); });
  std::vector<Island> islands(outers.size());
  std::vector<BBox2> boxes(outers.size());
  for (size_t i = 0; i < outers.size(); ++i) boxes[i] = bbox(outers[i]);
  for (Ring& h : holes) {
    const BBox2 hb = bbox(h);
    const Point mid(h[0].X + h[1].X, h[0].Y + h[1].Y);
    size_t owner = outers.size();
    for (size_t i = 0; i < outers.size() && owner == outers.size(); ++i) {
      if (bbox_inside(hb, boxes[i]) && winding(outers[i], mid) != 0) owner = i;
    }
    if (owner == outers.size()) return Error{"", "a hole lies outside every outline after union"};
    islands[owner].shape.holes.push_back(std::move(h));
  }
  for (size_t i = 0; i < outers.size(); ++i) islands[i].shape.outer = std::move(outers[i]);
  finish_islands(islands);
  return islands;
}

// What the coherence check learns, reused by the resolution.
struct Checked {
  Rings valid;                        // loops with 3+ distinct points, enclosing area
  std::vector<EdgeContact> contacts;  // between the valid loops' edges
  bool spikes = false;
};

Status check(const Rings& loops, const ResolveOptions& options, Report& report,
             std::span<const uint8_t> repaired, Checked& out) {
  std::vector<Warning> found;
  // `what` is wrong; `then` is what happens to it without --strict.
  auto problem = [&](const char* code, const Point& at, const std::string& what, const std::string& then) {
    found.push_back({where(options.layer_index, at), options.strict ? what : what + "; " + then, code});
  };
  Rings& valid = out.valid;
  std::vector<size_t> valid_index;
  for (size_t i = 0; i < loops.size() && (found.empty() || !options.strict); ++i) {
    const Ring r = without_repeats(loops[i]);
    const Point at = loops[i].empty() ? Point(0, 0) : loops[i][0];
    if (i < repaired.size() && repaired[i]) {
      problem("repaired-loop", at, fmt::format("loop {} was closed by joining a gap in the mesh", i),
              "sliced as closed");
    }
    bool flat = true;
    for (size_t k = 2; k < r.size() && flat; ++k) flat = exact::orientation(r[0], r[1], r[k]) == 0;
    if (r.size() < 3 || flat) {
      problem("degenerate-loop", at,
              fmt::format("loop {} {}", i,
                          r.size() < 3 ? "has fewer than 3 distinct points" : "encloses no area"),
              "ignored");
      continue;
    }
    for (size_t k = 0; k < r.size(); ++k) {
      const Point& p = r[(k + r.size() - 1) % r.size()];
      const Point& q = r[(k + 1) % r.size()];
      if (turns_back(p, r[k], q)) {
        out.spikes = true;
        problem("loop-spike", r[k], fmt::format("loop {} runs back over itself (zero-width spike)", i),
                "removed");
        break;
      }
    }
    valid.push_back(r);
    valid_index.push_back(i);
  }
  if (found.empty() || !options.strict) {
    size_t crossings = 0;
    EdgeContact first;
    out.contacts = find_contacts(valid);
    for (const EdgeContact& c : out.contacts) {
      if (c.kind != exact::Contact::Cross) continue;
      if (crossings++ == 0) first = c;
    }
    if (crossings > 0) {
      const size_t a = valid_index[first.a.ring], b = valid_index[first.b.ring];
      const std::string pair =
          a == b ? fmt::format("loop {} crosses itself", a) : fmt::format("loops {} and {} cross", a, b);
      const char* how = options.overlap == OverlapMode::Boolean ? "overlaps cancel (boolean mode)"
                                                                : "resolved as their union (additive mode)";
      problem("intersecting-loops", contact_point(valid, first),
              fmt::format("{} ({} crossing{} in this layer)", pair, crossings, crossings == 1 ? "" : "s"),
              how);
    }
  }
  if (options.strict && !found.empty()) {
    return Error{found[0].where, found[0].message + " (" + found[0].code +
                                     "; --strict makes this an error: repair the model or slice without it)"};
  }
  for (Warning& w : found) report.warn(std::move(w.code), std::move(w.where), std::move(w.message));
  return ok_status();
}

// Islands of loops that are simple and pairwise disjoint (no contacts at all: the usual layer of
// one watertight mesh), exactly and without a boolean operation: each loop's parent is the
// smallest loop around it, the winding number inside a loop is its parent's plus its own turn,
// and a loop is a boundary where the overlap rule differs on its two sides.
std::vector<Island> islands_from_disjoint(const Rings& loops, OverlapMode mode) {
  const size_t n = loops.size();
  std::vector<exact::i128> area(n);
  std::vector<BBox2> box(n);
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) {
    area[i] = exact::area2(loops[i]);
    box[i] = bbox(loops[i]);
    order[i] = i;
  }
  auto mag = [&](size_t i) { return area[i] < 0 ? -area[i] : area[i]; };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return mag(a) > mag(b); });
  auto material = [&](int w) { return mode == OverlapMode::Boolean ? (w % 2 != 0) : w != 0; };
  std::vector<int> parent(n, -1), inside(n, 0), boundary_above(n, -1);
  std::vector<char> boundary(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const size_t i = order[k];
    const Point v(loops[i][0].X * 2, loops[i][0].Y * 2);
    for (size_t m = k; m-- > 0;) {  // smaller candidates first: the first hit is the parent
      const size_t j = order[m];
      if (bbox_inside(box[i], box[j]) && winding(loops[j], v) != 0) {
        parent[i] = static_cast<int>(j);
        break;
      }
    }
    const int outside = parent[i] < 0 ? 0 : inside[parent[i]];
    inside[i] = outside + (area[i] > 0 ? 1 : -1);
    boundary[i] = material(inside[i]) != material(outside);
    // The nearest boundary loop around this one (its island's outline when this is a hole).
    if (parent[i] >= 0) boundary_above[i] = boundary[parent[i]] ? parent[i] : boundary_above[parent[i]];
  }
  std::vector<int> island_of(n, -1);
  std::vector<Island> islands;
  for (size_t k = 0; k < n; ++k) {
    const size_t i = order[k];
    if (!boundary[i] || !material(inside[i])) continue;
    island_of[i] = static_cast<int>(islands.size());
    Island is;
    is.shape.outer = area[i] > 0 ? loops[i] : Ring(loops[i].rbegin(), loops[i].rend());
    islands.push_back(std::move(is));
  }
  for (size_t i = 0; i < n; ++i) {
    if (!boundary[i] || material(inside[i]) || boundary_above[i] < 0) continue;
    islands[island_of[boundary_above[i]]].shape.holes.push_back(
        area[i] < 0 ? loops[i] : Ring(loops[i].rbegin(), loops[i].rend()));
  }
  return islands;
}

}  // namespace

Status check_loops(const Rings& loops, const ResolveOptions& options, Report& report,
                   std::span<const uint8_t> repaired) {
  Checked c;
  return check(loops, options, report, repaired, c);
}

Result<std::vector<Island>> strict_islands(const Rings& rings, OverlapMode mode) {
  if (!in_range(rings)) return range_error();
  PlanarGraph graph;
  if (Status st = unite::union_graph(rings, mode, graph); !st) return st.error();
  return islands_from_graph(graph);
}

Result<std::vector<Island>> resolve_islands(const Rings& loops, const ResolveOptions& options, Report& report,
                                            std::span<const uint8_t> repaired) {
  if (!in_range(loops)) {
    Error e = range_error();
    if (options.layer_index >= 0) e.where = fmt::format("layer {}", options.layer_index);
    return e;
  }
  Checked checked;
  if (Status st = check(loops, options, report, repaired, checked); !st) return st.error();
  if (checked.contacts.empty() && !checked.spikes) {
    std::vector<Island> fast = islands_from_disjoint(checked.valid, options.overlap);
    finish_islands(fast);
    return fast;
  }
  auto islands = strict_islands(loops, options.overlap);
  if (!islands && options.layer_index >= 0) {
    return Error{fmt::format("layer {}", options.layer_index), islands.error().message};
  }
  return islands;
}

Status resolve_layer(Layer& layer, const ResolveOptions& options, Report& report,
                     std::span<const uint8_t> repaired) {
  ResolveOptions o = options;
  o.layer_index = layer.index;
  auto islands = resolve_islands(layer.loops, o, report, repaired);
  if (!islands) return islands.error();
  layer.islands = std::move(*islands);
  return ok_status();
}

}  // namespace tranche::geo
