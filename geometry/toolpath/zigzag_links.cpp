#include "geometry/toolpath/zigzag_ring.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace tranche::toolpath::zigzag_detail {
namespace {

using schema::Border;

// A stretch of a ring as (start, length) in arc length from the ring's vertex 0, forward.
struct Stretch {
  double start, len;
};

// The best link found from one polyline's end to another's.
struct Link {
  double len = 1e300;
  size_t poly = 0;
  bool at_end = false;  // reaches the other polyline's last point (it is then reversed)
  std::vector<UV> pts;
  std::vector<Border> kinds;
  Stretch st{0, 0};
};

// Turns a polyline round.
void reverse(Poly& P) {
  std::reverse(P.pts.begin(), P.pts.end());
  std::reverse(P.border.begin(), P.border.end());
  std::swap(P.first, P.last);
}

// Links along the border between polylines, and the stretches of the rings they cover.
class BorderLinker {
 public:
  BorderLinker(const std::vector<Ring2>& rings, double limit, bool index)
      : index_(index), rings_(rings), limit_(limit) {}

  std::vector<Poly> chain(std::vector<Poly> polys);
  void anchor(std::vector<Poly>& chains, double length, double clearance);

 private:
  void measure_rings();
  double param(uint32_t r, uint32_t edge, UV x) const;
  double arc(uint32_t r, uint32_t edge, UV x) const;
  Stretch stretch(uint32_t r, double sa, double sb, bool forward, bool whole) const;
  bool overlaps(uint32_t r, const Stretch& x) const;
  double walk(const End& from, const End& b, std::vector<UV>& pts, std::vector<Border>& kinds, Stretch& st,
              double bound) const;
  Link best_link(const Poly& cur, const std::vector<Poly>& polys, const std::vector<char>& used) const;
  void index_ends(const std::vector<Poly>& polys);
  std::vector<UV> run_on(const End& e, bool forward, double len, std::vector<Border>& kinds) const;

  // The polylines' ends on a hash grid of cells `limit_` wide (when that is fine enough to
  // help): a link is at most limit_ long, so its other end lies in the 3 × 3 cells round its
  // start. Each entry: polyline index × 2 + (1 for its last point).
  static uint64_t cell_key(int64_t x, int64_t y) {
    return (static_cast<uint64_t>(x) << 32) ^ static_cast<uint64_t>(static_cast<uint32_t>(y));
  }
  int64_t cell_of(double v) const { return static_cast<int64_t>(std::floor(v / limit_)); }
  bool index_ = true, indexed_ = false;
  std::unordered_map<uint64_t, std::vector<size_t>> ends_;

  const std::vector<Ring2>& rings_;
  const double limit_;                    // longest link, units
  std::vector<std::vector<double>> cum_;  // per ring: arc length at each vertex, then the total
  // Stretches of each ring that links lie on: a link may not run over another one. (It may run
  // over the lines' own connectors, as PrusaSlicer's infill anchors do: along the island's border
  // a solid link and connector are both laid at half flow.)
  std::vector<std::vector<Stretch>> covered_;
};

// Arc length of each ring at each vertex, then its total; no stretch covered yet.
void BorderLinker::measure_rings() {
  cum_.assign(rings_.size(), {});
  covered_.assign(rings_.size(), {});
  for (size_t r = 0; r < rings_.size(); ++r) {
    const auto& pts = rings_[r].pts;
    cum_[r].assign(1, 0.0);
    for (size_t i = 0; i < pts.size(); ++i) {
      const UV &p0 = pts[i], &p1 = pts[(i + 1) % pts.size()];
      cum_[r].push_back(cum_[r].back() + std::hypot(p1.u - p0.u, p1.v - p0.v));
    }
  }
}

// Where x lies along the edge: 0 at its start, 1 at its end.
double BorderLinker::param(uint32_t r, uint32_t edge, UV x) const {
  const auto& pts = rings_[r].pts;
  const UV &p = pts[edge], &q = pts[(edge + 1) % pts.size()];
  double du = q.u - p.u, dv = q.v - p.v, l2 = du * du + dv * dv;
  return l2 > 0 ? std::clamp(((x.u - p.u) * du + (x.v - p.v) * dv) / l2, 0.0, 1.0) : 0.0;
}

// Arc length of x on the edge from the ring's vertex 0.
double BorderLinker::arc(uint32_t r, uint32_t edge, UV x) const {
  return cum_[r][edge] + param(r, edge, x) * (cum_[r][edge + 1] - cum_[r][edge]);
}

// The stretch walked from a to b (forward: increasing vertex indices), `whole` when the walk
// goes all the way round.
Stretch BorderLinker::stretch(uint32_t r, double sa, double sb, bool forward, bool whole) const {
  const double L = cum_[r].back();
  double from = forward ? sa : sb, to = forward ? sb : sa;
  double len = whole ? L : std::fmod(to - from + L, L);
  return Stretch{from, len};
}

// std::fmod(v, L) for 0 ≤ v ≤ 2L, bit for bit (v − L is exact there: Sterbenz), without its
// cost: overlaps() takes two per covered stretch for every walk, on a pattern's many links.
double wrap2(double v, double L) {
  if (v < L) return v;
  v -= L;
  return v < L ? v : v - L;
}

// Whether x runs over a stretch of ring r that a link already covers. Starts lie in [0, L].
bool BorderLinker::overlaps(uint32_t r, const Stretch& x) const {
  const double L = cum_[r].back(), eps = 1e3;  // 1 µm
  for (const Stretch& other : covered_[r]) {
    if (wrap2(other.start - x.start + L, L) < x.len - eps) return true;
    if (wrap2(x.start - other.start + L, L) < other.len - eps) return true;
  }
  return false;
}

// Links along the border: the walk from `from` to `b` on their common ring, the shorter way
// round of those that run over no other link, if it is at most `limit` units long (points
// after `from`, up to and including `b`; `st`: the stretch it covers). Returns its length.
// Walks longer than `bound` (the best link found so far) are not walked: their length along the
// ring, from the rings' measured arcs, tells it first. (The walk's own sum differs from that by
// rounding only; kSlack keeps every walk that could tie with the bound.)
double BorderLinker::walk(const End& from, const End& b, std::vector<UV>& pts, std::vector<Border>& kinds,
                          Stretch& st, double bound) const {
  const double limit = limit_;
  constexpr double kNo = 1e300, kSlack = 1e4;  // 10 µm
  if (from.ring != b.ring) return kNo;
  // Ends certainly further apart than the limit or the bound are left at once, without hypot:
  // the squared distance over the squared cap, with room for both roundings (most candidates
  // of a pattern's many ends are).
  const double du = b.p.u - from.p.u, dv = b.p.v - from.p.v, cap = std::min(limit, bound + kSlack);
  if (du * du + dv * dv > cap * cap * (1 + 1e-9)) return kNo;
  const double chord = std::hypot(b.p.u - from.p.u, b.p.v - from.p.v);
  if (chord > limit || chord > bound + kSlack) return kNo;
  const uint32_t r = from.ring;
  const Ring2& ring = rings_[r];
  const uint32_t n = static_cast<uint32_t>(ring.pts.size());
  const double ta = param(r, from.edge, from.p), tb = param(r, b.edge, b.p);
  const double sa = arc(r, from.edge, from.p), sb = arc(r, b.edge, b.p);
  double best = kNo;
  for (int dir : {1, -1}) {
    bool direct = from.edge == b.edge && (dir > 0 ? ta <= tb : ta >= tb);
    uint32_t count = direct ? 0 : steps(n, from.edge, b.edge, dir > 0);
    if (!direct && count == 0) count = n;  // same edge, the wrong way: all the way round
    Stretch here = stretch(r, sa, sb, dir > 0, count == n);
    if (here.len > limit || here.len > std::min(bound, best) + kSlack || overlaps(r, here)) continue;
    std::vector<UV> p;
    std::vector<Border> k;
    double len = 0;
    UV at = from.p;
    auto step = [&](UV to, uint32_t edge) {
      len += std::hypot(to.u - at.u, to.v - at.v);
      p.push_back(to);
      k.push_back(border_of(ring.kinds[edge]));
      at = to;
    };
    walk_ring(n, from.edge, count, dir > 0, [&](uint32_t v, uint32_t edge) {
      step(ring.pts[v], edge);
      return len <= limit;
    });
    step(b.p, b.edge);
    if (len <= limit && len < best) best = len, pts = std::move(p), kinds = std::move(k), st = here;
  }
  return best;
}

// Many polylines (a lightning layer's branches, a large region's lines): their ends on the
// grid, so that best_link looks at the few near cur's end instead of all of them.
void BorderLinker::index_ends(const std::vector<Poly>& polys) {
  constexpr size_t kMany = 64;
  indexed_ = index_ && polys.size() > kMany && limit_ >= 1e3 && limit_ <= 1e9;  // 1 µm to 1 m
  if (!indexed_) return;
  for (size_t j = 0; j < polys.size(); ++j)
    for (bool at_end : {false, true}) {
      const UV& p = (at_end ? polys[j].last : polys[j].first).p;
      ends_[cell_key(cell_of(p.u), cell_of(p.v))].push_back(2 * j + (at_end ? 1 : 0));
    }
}

// The shortest link from cur's last point to either end of an unused polyline (of equal ones,
// the one of the lowest index, its first point before its last).
Link BorderLinker::best_link(const Poly& cur, const std::vector<Poly>& polys,
                             const std::vector<char>& used) const {
  Link best;
  std::vector<UV> tp;
  std::vector<Border> tk;
  Stretch ts{0, 0};
  auto consider = [&](size_t j, bool at_end) {
    double l = walk(cur.last, at_end ? polys[j].last : polys[j].first, tp, tk, ts, best.len);
    if (l < best.len || (l == best.len && l < 1e300 && (j < best.poly || (j == best.poly && !at_end && best.at_end))))
      best = {l, j, at_end, std::move(tp), std::move(tk), ts};
  };
  if (!indexed_) {
    for (size_t j = 0; j < polys.size(); ++j) {
      if (used[j]) continue;
      for (bool at_end : {false, true}) consider(j, at_end);
    }
    return best;
  }
  const int64_t cx = cell_of(cur.last.p.u), cy = cell_of(cur.last.p.v);
  for (int64_t x = cx - 1; x <= cx + 1; ++x)
    for (int64_t y = cy - 1; y <= cy + 1; ++y) {
      auto it = ends_.find(cell_key(x, y));
      if (it == ends_.end()) continue;
      for (size_t e : it->second)
        if (!used[e / 2]) consider(e / 2, (e & 1) != 0);
    }
  return best;
}

// Polylines joined end to start by links along the border, greedily from each unused one.
std::vector<Poly> BorderLinker::chain(std::vector<Poly> polys) {
  measure_rings();
  if (!(limit_ > 0 && polys.size() > 1)) return polys;
  index_ends(polys);
  std::vector<Poly> chains;
  std::vector<char> used(polys.size(), 0);
  for (size_t i = 0; i < polys.size(); ++i) {
    if (used[i]) continue;
    used[i] = 1;
    Poly cur = std::move(polys[i]);
    for (int flipped = 0; flipped < 2;) {
      Link link = best_link(cur, polys, used);
      if (link.len > limit_) {  // nothing from this end: try the other one, once
        reverse(cur);
        ++flipped;
        continue;
      }
      used[link.poly] = 1;
      covered_[cur.last.ring].push_back(link.st);
      Poly& nx = polys[link.poly];
      if (link.at_end) reverse(nx);
      // The walk ends on nx's first point.
      cur.pts.insert(cur.pts.end(), link.pts.begin(), link.pts.end());
      cur.border.insert(cur.border.end(), link.kinds.begin(), link.kinds.end());
      cur.pts.insert(cur.pts.end(), nx.pts.begin() + 1, nx.pts.end());
      cur.border.insert(cur.border.end(), nx.border.begin(), nx.border.end());
      cur.last = nx.last;
      cur.area += nx.area;
      cur.runs += nx.runs;
    }
    chains.push_back(std::move(cur));
  }
  return chains;
}

// The points `len` along the ring from end e (forward: increasing vertex indices), the last one
// `len` from e; `kinds`: the border kind of each piece.
std::vector<UV> BorderLinker::run_on(const End& e, bool forward, double len,
                                     std::vector<Border>& kinds) const {
  const Ring2& ring = rings_[e.ring];
  const uint32_t n = static_cast<uint32_t>(ring.pts.size());
  std::vector<UV> pts;
  UV at = e.p;
  double left = len;
  walk_ring(n, e.edge, n, forward, [&](uint32_t v, uint32_t edge) {
    const UV to = ring.pts[v];
    const double d = std::hypot(to.u - at.u, to.v - at.v);
    kinds.push_back(border_of(ring.kinds[edge]));
    if (d >= left) {
      const double t = left / d;
      pts.push_back({at.u + t * (to.u - at.u), at.v + t * (to.v - at.v)});
      left = 0;
      return false;
    }
    pts.push_back(to);
    left -= d;
    at = to;
    return true;
  });
  return pts;
}

// Anchors: each chain end on a ring runs on along it, the way with more free room (to the next
// end, link or anchor on the ring), by up to `length` and `clearance` short of that obstacle.
void BorderLinker::anchor(std::vector<Poly>& chains, double length, double clearance) {
  if (!(length > 0) || cum_.size() != rings_.size()) return;
  // Per ring: the arc position of every chain end (index × 2 + 1 for a last point).
  std::vector<std::vector<std::pair<double, size_t>>> ends(rings_.size());
  for (size_t c = 0; c < chains.size(); ++c)
    for (int last = 0; last < 2; ++last) {
      const End& e = last ? chains[c].last : chains[c].first;
      if (e.ring < rings_.size()) ends[e.ring].push_back({arc(e.ring, e.edge, e.p), 2 * c + last});
    }
  for (size_t c = 0; c < chains.size(); ++c)
    for (int last = 0; last < 2; ++last) {
      Poly& P = chains[c];
      const End e = last ? P.last : P.first;
      if (e.ring >= rings_.size() || rings_[e.ring].pts.size() < 2) continue;
      const uint32_t r = e.ring;
      const double L = cum_[r].back(), s = arc(r, e.edge, e.p);
      if (!(L > 0)) continue;
      // Free room forward (increasing arc) and backward from s.
      double fwd = L, back = L;
      for (const auto& [a, id] : ends[r]) {
        if (id == 2 * c + last) continue;
        fwd = std::min(fwd, std::fmod(a - s + 2 * L, L));
        back = std::min(back, std::fmod(s - a + 2 * L, L));
      }
      for (const Stretch& st : covered_[r]) {
        const double into = std::fmod(s - st.start + 2 * L, L);
        if (into < st.len) fwd = back = 0;  // on a link already
        fwd = std::min(fwd, std::fmod(st.start - s + 2 * L, L));
        back = std::min(back, std::fmod(s - (st.start + st.len) + 3 * L, L));
      }
      const bool forward = fwd >= back;
      const double len = std::min(length, (forward ? fwd : back) - clearance);
      if (!(len > 1e3)) continue;  // a micrometre
      std::vector<Border> kinds;
      std::vector<UV> pts = run_on(e, forward, len, kinds);
      if (pts.empty()) continue;
      covered_[r].push_back(forward ? Stretch{s, len} : Stretch{std::fmod(s - len + L, L), len});
      if (last) {
        P.pts.insert(P.pts.end(), pts.begin(), pts.end());
        P.border.insert(P.border.end(), kinds.begin(), kinds.end());
      } else {  // walked away from the first point: put in front, turned round
        std::reverse(pts.begin(), pts.end());
        std::reverse(kinds.begin(), kinds.end());
        P.pts.insert(P.pts.begin(), pts.begin(), pts.end());
        P.border.insert(P.border.begin(), kinds.begin(), kinds.end());
      }
    }
}

}  // namespace

std::vector<Poly> link_along_border(std::vector<Poly> polys, const std::vector<Ring2>& rings, double limit,
                                    bool index, double anchor, double clearance) {
  BorderLinker linker(rings, limit, index);
  std::vector<Poly> chains = linker.chain(std::move(polys));
  linker.anchor(chains, anchor, clearance);
  return chains;
}

}  // namespace tranche::toolpath::zigzag_detail
