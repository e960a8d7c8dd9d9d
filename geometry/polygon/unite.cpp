#include "geometry/polygon/unite.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "geometry/polygon/contacts.h"
#include "geometry/polygon/exact.h"
#include "geometry/polygon/monotone.h"

namespace tranche::geo {
namespace unite {

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

bool turns_back(const Point& p, const Point& v, const Point& q) {
  return exact::orientation(p, v, q) == 0 && !exact::strictly_between(p, v, q);
}

namespace {

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

// One Clipper union of the rings under the mode's fill rule.
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

// Whether two edges of the rings run along each other.
bool has_overlaps(const Rings& rings) {
  for (const EdgeContact& c : find_contacts(rings)) {
    if (c.kind == exact::Contact::Overlap) return true;
  }
  return false;
}

// Whether two edges of the rings cross or run along each other.
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

}  // namespace

Status union_graph(const Rings& rings, OverlapMode mode, PlanarGraph& graph) {
  Rings input;
  for (const Ring& r : rings) {
    Ring c = without_repeats(r);
    if (c.size() >= 3) input.push_back(std::move(c));  // shorter loops enclose nothing
  }
  auto merged = clipper_union(has_overlaps(input) ? cancel_coincident(std::move(input), mode) : input, mode);
  if (!merged) return merged.error();
  return clean_union(std::move(*merged), graph);
}

}  // namespace unite

Result<Rings> paint(std::span<const PaintedShape> shapes) {
  Rings painted;
  for (const PaintedShape& s : shapes) {
    if (!unite::in_range(s.loops)) return unite::range_error();
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
