#include "geometry/polygon/monotone.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "geometry/polygon/exact.h"

namespace tranche::geo {

FillDirection::FillDirection(double angle_deg) {
  double a = std::fmod(angle_deg, 180.0);
  if (a < 0) a += 180.0;
  const double r = a * M_PI / 180.0;
  constexpr double kScale = 1 << 20;
  // Rounding cos and sin symmetrically keeps 45° and 135° exactly diagonal.
  dx = std::llround(std::cos(r) * kScale);
  dy = std::llround(std::sin(r) * kScale);
}

bool is_monotone(const Ring& ring, double angle_deg) { return is_monotone(ring, FillDirection(angle_deg)); }

namespace {

// Where a chain crosses a fill line: a run of vertices on it, or an edge crossing it.
struct Extent {
  bool run = false;
  Point lo, hi;  // run: its leftmost and rightmost vertex along the fill direction
  Point p, q;    // edge: upper and lower end
};

// -1: a strictly left of b along the fill line, +1 strictly right, 0 they meet.
int compare(const Extent& a, const Extent& b, const FillDirection& dir) {
  if (a.run && b.run) {
    if (dir.along(a.hi) < dir.along(b.lo)) return -1;
    if (dir.along(b.hi) < dir.along(a.lo)) return 1;
    return 0;
  }
  if (!a.run) return -compare(b, a, dir);
  // A point right of the downward edge p -> q turns counter-clockwise from it.
  if (exact::orientation(b.p, b.q, a.hi) < 0) return -1;
  if (exact::orientation(b.p, b.q, a.lo) > 0) return 1;
  return 0;
}

// Vertices of a run must advance strictly along the fill line, or the ring overlaps itself.
bool strictly_along(const std::vector<Point>& pts, size_t from, size_t to, size_t n,
                    const FillDirection& dir) {
  int sense = 0;
  for (size_t i = from; i != to; i = (i + 1) % n) {
    const int64_t a = dir.along(pts[i]), b = dir.along(pts[(i + 1) % n]);
    const int s = a < b ? 1 : -1;  // a != b: the points differ and lie on one fill line
    if (sense != 0 && s != sense) return false;
    sense = s;
  }
  return true;
}

// The ring's points without repeats (nor a last point equal to the first); false when a point is
// beyond the sweep's range or fewer than 3 are left.
bool distinct_points(const Ring& input, std::vector<Point>& pts) {
  pts.reserve(input.size());
  for (const Point& p : input) {
    if (std::llabs(p.X) >= kMaxSweepCoord || std::llabs(p.Y) >= kMaxSweepCoord) return false;
    if (pts.empty() || !(pts.back() == p)) pts.push_back(p);
  }
  while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
  return pts.size() >= 3;
}

// A ring cut at its top run ts..te and bottom run bs..be (forward order) into chain A, descending
// from te to bs, and chain B, walked backward from ts to be so that it also runs downward; with
// each chain vertex's level across the fill lines.
struct Chains {
  size_t ts = 0, te = 0, bs = 0, be = 0;
  int64_t lo_level = 0, hi_level = 0;
  std::vector<Point> a, b;
  std::vector<int64_t> la, lb;
};

// Cuts the ring into its two chains; false when it turns back anywhere else (a second top or
// bottom), has no height, or a top or bottom run overlaps itself.
bool split_chains(const std::vector<Point>& pts, const FillDirection& dir, Chains& ch) {
  const size_t n = pts.size();
  std::vector<int64_t> lv(n);
  for (size_t i = 0; i < n; ++i) lv[i] = dir.across(pts[i]);
  const auto [mn, mx] = std::minmax_element(lv.begin(), lv.end());
  const int64_t lo_level = *mn, hi_level = *mx;
  if (lo_level == hi_level) return false;
  auto nx = [&](size_t i) { return (i + 1) % n; };
  auto pv = [&](size_t i) { return (i + n - 1) % n; };

  size_t ts = static_cast<size_t>(mx - lv.begin()), te = ts;
  while (lv[pv(ts)] == hi_level) ts = pv(ts);
  while (lv[nx(te)] == hi_level) te = nx(te);
  std::vector<Point> a{pts[te]};
  std::vector<int64_t> la{hi_level};
  size_t i = te;
  while (lv[i] != lo_level) {
    const size_t j = nx(i);
    if (lv[j] > lv[i]) return false;
    a.push_back(pts[j]);
    la.push_back(lv[j]);
    i = j;
  }
  const size_t bs = i;
  size_t be = bs;
  while (lv[nx(be)] == lo_level) be = nx(be);
  std::vector<Point> b;
  std::vector<int64_t> lb;
  for (i = ts;; i = pv(i)) {  // walked backward so that B also runs downward
    b.push_back(pts[i]);
    lb.push_back(lv[i]);
    if (i == be) break;
    if (lv[pv(i)] > lv[i]) return false;
  }
  if (!strictly_along(pts, ts, te, n, dir) || !strictly_along(pts, bs, be, n, dir)) return false;
  ch = {ts, te, bs, be, lo_level, hi_level, std::move(a), std::move(b), std::move(la), std::move(lb)};
  return true;
}

// Which side chain A keeps of chain B: every sighting must agree with the first.
class SameSide {
 public:
  // False when s says the chains meet (0) or swapped sides.
  bool agree(int s) {
    if (s == 0 || (side_ != 0 && s != side_)) return false;
    side_ = s;
    return true;
  }

 private:
  int side_ = 0;
};

// Where chain c (levels l, downward) crosses the fill line at `level`, from index k on (k moves
// down to the first vertex at or below the line).
Extent extent(const std::vector<Point>& c, const std::vector<int64_t>& l, size_t& k, int64_t level,
              const FillDirection& dir) {
  while (l[k] > level) ++k;
  Extent e;
  if (l[k] < level) {
    e.p = c[k - 1];
    e.q = c[k];
    return e;
  }
  e.run = true;
  e.lo = e.hi = c[k];
  for (size_t r = k; r < c.size() && l[r] == level; ++r) {
    if (dir.along(c[r]) < dir.along(e.lo)) e.lo = c[r];
    if (dir.along(c[r]) > dir.along(e.hi)) e.hi = c[r];
  }
  return e;
}

// Every fill line through a vertex meets the chains in two extents, strictly apart and always
// on the same sides. Between such lines both chains are single edges, so they never meet.
bool chains_apart(const std::vector<Point>& pts, const Chains& ch, const FillDirection& dir) {
  SameSide side;
  if (ch.ts != ch.te && !side.agree(dir.along(pts[ch.te]) < dir.along(pts[ch.ts]) ? -1 : 1)) return false;
  if (ch.bs != ch.be && !side.agree(dir.along(pts[ch.bs]) < dir.along(pts[ch.be]) ? -1 : 1)) return false;
  std::vector<int64_t> levels;
  for (int64_t l : ch.la) {
    if (l != ch.lo_level && l != ch.hi_level) levels.push_back(l);
  }
  for (int64_t l : ch.lb) {
    if (l != ch.lo_level && l != ch.hi_level) levels.push_back(l);
  }
  std::sort(levels.begin(), levels.end(), std::greater<>());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  size_t ka = 0, kb = 0;
  for (int64_t l : levels) {
    const Extent ea = extent(ch.a, ch.la, ka, l, dir), eb = extent(ch.b, ch.lb, kb, l, dir);
    if (!side.agree(compare(ea, eb, dir))) return false;
  }
  return true;
}

// Runs inside the chains must not fold back over themselves either.
bool runs_straight(const Chains& ch, const FillDirection& dir) {
  for (const auto* c : {&ch.a, &ch.b}) {
    const auto& l = c == &ch.a ? ch.la : ch.lb;
    for (size_t r = 1; r + 1 < c->size(); ++r) {
      if (l[r - 1] == l[r] && l[r] == l[r + 1]) {
        const bool fwd1 = dir.along((*c)[r - 1]) < dir.along((*c)[r]);
        const bool fwd2 = dir.along((*c)[r]) < dir.along((*c)[r + 1]);
        if (fwd1 != fwd2) return false;
      }
    }
  }
  return true;
}

}  // namespace

bool is_monotone(const Ring& input, const FillDirection& dir) {
  std::vector<Point> pts;
  if (!distinct_points(input, pts)) return false;
  Chains ch;
  if (!split_chains(pts, dir, ch)) return false;
  return chains_apart(pts, ch, dir) && runs_straight(ch, dir);
}

}  // namespace tranche::geo
