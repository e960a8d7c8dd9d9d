#include "geometry/polygon/contacts.h"

#include <algorithm>
#include <cmath>

namespace tranche::geo {
namespace {

struct Span {
  coord_t min_x, max_x, min_y, max_y;
  EdgeRef ref;
};

template <class Visit>
void sweep_edges(const Rings& rings, Visit&& visit) {
  std::vector<Span> spans;
  for (uint32_t r = 0; r < rings.size(); ++r) {
    const Ring& ring = rings[r];
    for (uint32_t i = 0; i < ring.size(); ++i) {
      const Point& a = ring[i];
      const Point& b = ring[(i + 1) % ring.size()];
      spans.push_back(
          {std::min(a.X, b.X), std::max(a.X, b.X), std::min(a.Y, b.Y), std::max(a.Y, b.Y), {r, i}});
    }
  }
  std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.min_x < b.min_x; });
  std::vector<const Span*> active;
  for (const Span& s : spans) {
    std::erase_if(active, [&](const Span* t) { return t->max_x < s.min_x; });
    for (const Span* t : active) {
      if (t->max_y < s.min_y || s.max_y < t->min_y) continue;
      if (!visit(t->ref, s.ref)) return;
    }
    active.push_back(&s);
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
    const exact::Contact k = exact::contact(a, b, c, d);
    if (k == exact::Contact::None) return true;
    if (e.ring == f.ring && k == exact::Contact::Touch) {
      // Consecutive edges always share their common vertex; that alone is no contact.
      const bool consecutive = (e.index + 1) % ne == f.index || (f.index + 1) % nf == e.index;
      if (consecutive) {
        const bool both = ne == 2;  // a two-point ring: its edges meet at both ends
        if (!both) return true;
      }
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
