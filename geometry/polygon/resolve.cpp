#include "geometry/polygon/resolve.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "geometry/polygon/contacts.h"
#include "geometry/polygon/exact.h"
#include "geometry/polygon/monotone.h"
#include "geometry/polygon/planar_graph.h"

namespace tranche::geo {
namespace {

std::string where(int layer, const Point& p) {
  if (layer < 0) return fmt::format("at ({:.3f}, {:.3f}) mm", to_mm(p.X), to_mm(p.Y));
  return fmt::format("layer {} at ({:.3f}, {:.3f}) mm", layer, to_mm(p.X), to_mm(p.Y));
}

bool point_less(const Point& a, const Point& b) { return a.X < b.X || (a.X == b.X && a.Y < b.Y); }

bool in_range(const Rings& rings) {
  for (const Ring& r : rings) {
    for (const Point& p : r) {
      if (std::llabs(p.X) >= kMaxSweepCoord || std::llabs(p.Y) >= kMaxSweepCoord) return false;
    }
  }
  return true;
}

Error range_error() {
  return Error{"", "coordinates beyond ±2147 mm: scale or move the model onto the bed before slicing"};
}

Ring without_repeats(const Ring& ring) {
  Ring out;
  out.reserve(ring.size());
  for (const Point& p : ring) {
    if (out.empty() || !(out.back() == p)) out.push_back(p);
  }
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

// Whether the path turns straight back at v (a zero-width spike tip).
bool turns_back(const Point& p, const Point& v, const Point& q) {
  return exact::orientation(p, v, q) == 0 && !exact::strictly_between(p, v, q);
}

// Removes repeated points and spike tips until none is left; returns the spike tips removed.
size_t remove_spikes(Ring& ring) {
  const int n = static_cast<int>(ring.size());
  if (n == 0) return 0;
  std::vector<int> prev(n), next(n);
  std::vector<char> alive(n, 1);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  int count = n;
  size_t spikes = 0;
  std::vector<int> work(n);
  for (int i = 0; i < n; ++i) work[i] = n - 1 - i;
  while (!work.empty() && count >= 3) {
    const int v = work.back();
    work.pop_back();
    if (!alive[v]) continue;
    const int p = prev[v], q = next[v];
    const bool repeat = ring[p] == ring[v];
    if (!repeat && !turns_back(ring[p], ring[v], ring[q])) continue;
    spikes += !repeat;
    alive[v] = 0;
    --count;
    next[p] = q;
    prev[q] = p;
    work.push_back(p);
    work.push_back(q);
  }
  Ring out;
  if (count >= 3) {
    int start = 0;
    while (!alive[start]) ++start;
    int v = start;
    do {
      out.push_back(ring[v]);
      v = next[v];
    } while (v != start);
  }
  ring = std::move(out);
  return spikes;
}

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

Result<Rings> clipper_union_once(const Rings& rings, OverlapMode mode) {
  const auto fill = mode == OverlapMode::Boolean ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero;
  Rings out;
  try {
    ClipperLib::Clipper c;
    // Clipper's StrictlySimple mode gives wrong regions on some inputs with coincident edges;
    // pinch points are split by our own face walk instead (islands_from_union).
    if (!c.AddPaths(rings, ClipperLib::ptSubject, true)) return out;  // nothing with an area
    if (!c.Execute(ClipperLib::ctUnion, out, fill, fill)) return Error{"", "polygon union failed"};
  } catch (const std::exception& e) {
    return Error{"", fmt::format("polygon union failed: {}", e.what())};
  }
  return out;
}

// Clipper can fail to order the crossings of dense input; snap-rounded input has none.
Result<Rings> clipper_union(const Rings& rings, OverlapMode mode) {
  auto out = clipper_union_once(rings, mode);
  if (out) return out;
  Rings clean;
  for (const Ring& r : rings) {
    Ring c = without_repeats(r);
    if (c.size() >= 2) clean.push_back(std::move(c));
  }
  return clipper_union_once(exact::snap_round(clean), mode);
}

// Directed edges of the rings once coincident pieces cancel (opposite directions for nonzero,
// pairs for even-odd), chained again into closed loops. Coincident edges are where Clipper's
// region evaluation goes wrong; after this the union sees none that cancel.
Rings cancel_coincident(Rings rings, OverlapMode mode) {
  split_at_touching_vertices(rings);
  using Key = std::pair<std::pair<coord_t, coord_t>, std::pair<coord_t, coord_t>>;
  std::map<Key, int> net;  // (lower point, higher point) -> count lower->higher minus higher->lower
  for (const Ring& r : rings) {
    for (size_t i = 0; i < r.size(); ++i) {
      const Point& a = r[i];
      const Point& b = r[(i + 1) % r.size()];
      if (a == b) continue;
      const auto pa = std::make_pair(a.X, a.Y), pb = std::make_pair(b.X, b.Y);
      if (pa < pb)
        ++net[{pa, pb}];
      else
        --net[{pb, pa}];
    }
  }
  // Remaining edges as an adjacency list, then walked into closed loops (in = out everywhere).
  std::map<std::pair<coord_t, coord_t>, std::vector<Point>> out;
  for (const auto& [k, n] : net) {
    int copies = mode == OverlapMode::Boolean ? (n % 2 != 0) : std::abs(n);
    const bool up = mode == OverlapMode::Boolean || n > 0;
    const Point lo(k.first.first, k.first.second), hi(k.second.first, k.second.second);
    for (; copies > 0; --copies) {
      if (up)
        out[k.first].push_back(hi);
      else
        out[k.second].push_back(lo);
    }
  }
  if (mode == OverlapMode::Boolean) {
    // Even-odd ignores direction: make every vertex balanced by walking edges either way.
    std::map<std::pair<coord_t, coord_t>, std::vector<Point>> undirected;
    for (const auto& [from, tos] : out) {
      for (const Point& to : tos) {
        undirected[from].push_back(to);
        undirected[{to.X, to.Y}].push_back(Point(from.first, from.second));
      }
    }
    Rings loops;
    for (auto& [start, list] : undirected) {
      while (!list.empty()) {
        Ring loop;
        Point at(start.first, start.second);
        do {
          loop.push_back(at);
          auto& here = undirected[{at.X, at.Y}];
          const Point to = here.back();
          here.pop_back();
          auto& back = undirected[{to.X, to.Y}];
          back.erase(std::find(back.begin(), back.end(), at));
          at = to;
        } while (!(at == Point(start.first, start.second)));
        loops.push_back(std::move(loop));
      }
    }
    return loops;
  }
  Rings loops;
  for (auto& [start, list] : out) {
    while (!list.empty()) {
      Ring loop;
      Point at(start.first, start.second);
      do {
        loop.push_back(at);
        auto& here = out[{at.X, at.Y}];
        const Point to = here.back();
        here.pop_back();
        at = to;
      } while (!(at == Point(start.first, start.second)));
      loops.push_back(std::move(loop));
    }
  }
  return loops;
}

bool has_overlaps(const Rings& rings) {
  for (const EdgeContact& c : find_contacts(rings)) {
    if (c.kind == exact::Contact::Overlap) return true;
  }
  return false;
}

bool has_crossings(const Rings& rings) {
  for (const EdgeContact& c : find_contacts(rings)) {
    if (c.kind == exact::Contact::Cross || c.kind == exact::Contact::Overlap) return true;
  }
  return false;
}

// Rings whose only contacts are shared vertices, from a union result, and their graph.
// Rounding intersection points to the grid can leave crossings (between edges, or through a
// shared vertex): another union usually removes them; if not, snap rounding makes the edges
// meet only at vertices, and a union of those computes no new points.
Status clean_union(Rings rings, PlanarGraph& graph) {
  for (int attempt = 0;; ++attempt) {
    Rings kept;
    for (Ring& r : rings) {
      remove_spikes(r);
      if (r.size() >= 3 && exact::area2(r) != 0) kept.push_back(std::move(r));
    }
    split_at_touching_vertices(kept);
    if (!has_crossings(kept)) {
      graph = PlanarGraph(kept);
      if (graph.boundary_alternates()) return ok_status();
    }
    if (attempt == 3) return Error{"", "polygon union left crossing edges, even after snap rounding"};
    auto again = clipper_union(attempt == 0 ? kept : exact::snap_round(kept), OverlapMode::Additive);
    if (!again) return again.error();
    rings = std::move(*again);
  }
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

Result<std::vector<Island>> islands_from_union(Rings rings) {
  PlanarGraph graph;
  if (Status st = clean_union(std::move(rings), graph); !st) return st.error();
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
  Rings input;
  for (const Ring& r : rings) {
    Ring c = without_repeats(r);
    if (c.size() >= 3) input.push_back(std::move(c));  // shorter loops enclose nothing
  }
  auto merged = clipper_union(has_overlaps(input) ? cancel_coincident(std::move(input), mode) : input, mode);
  if (!merged) return merged.error();
  return islands_from_union(std::move(*merged));
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

Result<Rings> paint(std::span<const PaintedShape> shapes) {
  Rings painted;
  for (const PaintedShape& s : shapes) {
    if (!in_range(s.loops)) return range_error();
    try {
      ClipperLib::Clipper c;
      c.AddPaths(painted, ClipperLib::ptSubject, true);
      c.AddPaths(s.loops, ClipperLib::ptClip, true);
      Rings out;
      const auto own = s.even_odd ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero;
      if (!c.Execute(s.erase ? ClipperLib::ctDifference : ClipperLib::ctUnion, out, ClipperLib::pftNonZero,
                     own)) {
        return Error{"", "painting a shape failed"};
      }
      painted = std::move(out);
    } catch (const std::exception& e) {
      return Error{"", fmt::format("painting a shape failed: {}", e.what())};
    }
  }
  return painted;
}

}  // namespace tranche::geo
