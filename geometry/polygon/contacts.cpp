#include "geometry/polygon/contacts.h"

#include <algorithm>
#include <cmath>

namespace tranche::geo {
namespace {

struct Span {
  coord_t min_x, max_x, min_y, max_y;
  EdgeRef ref;
  int cx0, cx1, cy0, cy1;  // grid cells covered by the edge's box
};

// Calls visit(e, f) once for every pair of edges whose boxes overlap (stops when it returns
// false). Edges go into a uniform grid of cells a few edge lengths wide; a pair is looked at only
// in the first cell both boxes cover.
template <class Visit>
void sweep_edges(const Rings& rings, Visit&& visit) {
  std::vector<Span> spans;
  BBox2 box;
  double extent = 0;
  for (uint32_t r = 0; r < rings.size(); ++r) {
    const Ring& ring = rings[r];
    for (uint32_t i = 0; i < ring.size(); ++i) {
      const Point& a = ring[i];
      const Point& b = ring[(i + 1) % ring.size()];
      spans.push_back({std::min(a.X, b.X),
                       std::max(a.X, b.X),
                       std::min(a.Y, b.Y),
                       std::max(a.Y, b.Y),
                       {r, i},
                       0,
                       0,
                       0,
                       0});
      box.add(a);
      extent += static_cast<double>(std::max(std::llabs(b.X - a.X), std::llabs(b.Y - a.Y)));
    }
  }
  if (spans.size() < 2) return;
  const double n = static_cast<double>(spans.size());
  const double w = static_cast<double>(box.max_x - box.min_x) + 1,
               h = static_cast<double>(box.max_y - box.min_y) + 1;
  double cell = std::max(1.0, 2 * extent / n);
  cell = std::max(cell, std::sqrt(w * h / (4 * n)));  // at most ~4 grid cells per edge
  const auto nx = static_cast<int64_t>(w / cell) + 1, ny = static_cast<int64_t>(h / cell) + 1;
  // Counting sort of (cell, edge) pairs: first[c] .. first[c + 1] lists the edges of cell c.
  std::vector<int> first(static_cast<size_t>(nx * ny) + 1, 0);
  for (Span& sp : spans) {
    sp.cx0 = static_cast<int>(static_cast<double>(sp.min_x - box.min_x) / cell);
    sp.cx1 = static_cast<int>(static_cast<double>(sp.max_x - box.min_x) / cell);
    sp.cy0 = static_cast<int>(static_cast<double>(sp.min_y - box.min_y) / cell);
    sp.cy1 = static_cast<int>(static_cast<double>(sp.max_y - box.min_y) / cell);
    for (int y = sp.cy0; y <= sp.cy1; ++y) {
      for (int x = sp.cx0; x <= sp.cx1; ++x) ++first[static_cast<size_t>(y * nx + x) + 1];
    }
  }
  for (size_t c = 1; c < first.size(); ++c) first[c] += first[c - 1];
  std::vector<int> members(static_cast<size_t>(first.back()));
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (int i = 0; i < static_cast<int>(spans.size()); ++i) {
    const Span& sp = spans[i];
    for (int y = sp.cy0; y <= sp.cy1; ++y) {
      for (int x = sp.cx0; x <= sp.cx1; ++x) members[fill[static_cast<size_t>(y * nx + x)]++] = i;
    }
  }
  for (int64_t c = 0; c < nx * ny; ++c) {
    const int lo = first[c], hi = first[c + 1];
    if (hi - lo < 2) continue;
    const int cx = static_cast<int>(c % nx), cy = static_cast<int>(c / nx);
    for (int i = lo; i < hi; ++i) {
      const Span& s = spans[members[i]];
      for (int j = i + 1; j < hi; ++j) {
        const Span& t = spans[members[j]];
        if (t.max_x < s.min_x || s.max_x < t.min_x || t.max_y < s.min_y || s.max_y < t.min_y) continue;
        if (std::max(s.cx0, t.cx0) != cx || std::max(s.cy0, t.cy0) != cy) continue;  // seen elsewhere
        if (!visit(s.ref, t.ref)) return;
      }
    }
  }
}

}  // namespace

std::vector<EdgeContact> find_contacts(const Rings& rings, size_t limit) {
  std::vector<EdgeContact> out;
  if (limit == 0) return out;
  sweep_edges(rings, [&](EdgeRef e, EdgeRef f) {
    const Ring& re = rings[e.ring];
    const Ring& rf = rings[f.ring];
    const size_t ne = re.size(), nf = rf.size();
    const Point &a = re[e.index], &b = re[(e.index + 1) % ne];
    const Point &c = rf[f.index], &d = rf[(f.index + 1) % nf];
    exact::Contact k;
    if (e.ring == f.ring && ne > 2 && ((e.index + 1) % ne == f.index || (f.index + 1) % nf == e.index)) {
      // Consecutive edges share their middle vertex; they only matter when they fold back.
      const bool e_first = (e.index + 1) % ne == f.index;
      const Point& p = e_first ? a : c;
      const Point& m = e_first ? b : d;
      const Point& q = e_first ? d : b;
      if (exact::orientation(p, m, q) != 0 || exact::strictly_between(p, m, q)) return true;
      k = exact::Contact::Overlap;
    } else {
      k = exact::contact(a, b, c, d);
      if (k == exact::Contact::None) return true;
    }
    out.push_back({e, f, k});
    return out.size() < limit;
  });
  return out;
}

Point contact_point(const Rings& rings, const EdgeContact& c) {
  const Ring& re = rings[c.a.ring];
  const Ring& rf = rings[c.b.ring];
  const Point &a = re[c.a.index], &b = re[(c.a.index + 1) % re.size()];
  const Point &p = rf[c.b.index], &q = rf[(c.b.index + 1) % rf.size()];
  if (c.kind == exact::Contact::Cross) {
    // Only for messages: a rounded crossing point is fine here.
    const double d1x = static_cast<double>(b.X - a.X), d1y = static_cast<double>(b.Y - a.Y);
    const double d2x = static_cast<double>(q.X - p.X), d2y = static_cast<double>(q.Y - p.Y);
    const double den = d1x * d2y - d1y * d2x;
    const double t = ((static_cast<double>(p.X - a.X)) * d2y - (static_cast<double>(p.Y - a.Y)) * d2x) / den;
    return Point(a.X + static_cast<coord_t>(std::llround(t * d1x)),
                 a.Y + static_cast<coord_t>(std::llround(t * d1y)));
  }
  for (const Point* x : {&p, &q}) {
    if (*x == a || *x == b || exact::strictly_between(a, *x, b)) return *x;
  }
  return exact::strictly_between(p, a, q) ? a : b;
}

size_t split_at_touching_vertices(Rings& rings) {
  // For each edge, the vertices found strictly inside it.
  std::vector<std::vector<std::vector<Point>>> inserts(rings.size());
  for (size_t r = 0; r < rings.size(); ++r) inserts[r].resize(rings[r].size());
  size_t count = 0;
  sweep_edges(rings, [&](EdgeRef e, EdgeRef f) {
    for (int pass = 0; pass < 2; ++pass) {
      const EdgeRef host = pass ? f : e, guest = pass ? e : f;
      const Ring& rh = rings[host.ring];
      const Ring& rg = rings[guest.ring];
      const Point &a = rh[host.index], &b = rh[(host.index + 1) % rh.size()];
      for (const Point* x : {&rg[guest.index], &rg[(guest.index + 1) % rg.size()]}) {
        if (exact::strictly_between(a, *x, b)) {
          auto& list = inserts[host.ring][host.index];
          if (std::find(list.begin(), list.end(), *x) == list.end()) {
            list.push_back(*x);
            ++count;
          }
        }
      }
    }
    return true;
  });
  if (count == 0) return 0;
  for (size_t r = 0; r < rings.size(); ++r) {
    Ring out;
    const Ring& ring = rings[r];
    for (size_t i = 0; i < ring.size(); ++i) {
      out.push_back(ring[i]);
      auto& list = inserts[r][i];
      if (list.empty()) continue;
      const Point& a = ring[i];
      // Along the edge, in order of distance from its start (exact in 128 bits).
      std::sort(list.begin(), list.end(), [&](const Point& p, const Point& q) {
        const exact::i128 dp = static_cast<exact::i128>(p.X - a.X) * (p.X - a.X) +
                               static_cast<exact::i128>(p.Y - a.Y) * (p.Y - a.Y);
        const exact::i128 dq = static_cast<exact::i128>(q.X - a.X) * (q.X - a.X) +
                               static_cast<exact::i128>(q.Y - a.Y) * (q.Y - a.Y);
        return dp < dq;
      });
      out.insert(out.end(), list.begin(), list.end());
    }
    rings[r] = std::move(out);
  }
  return count;
}

}  // namespace tranche::geo
