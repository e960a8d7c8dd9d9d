#include "geometry/slice/slicer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <tuple>

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace tranche::geo {

std::optional<TriangleCut> cut_triangle(const std::array<Vec3, 3>& v, double z) {
  const bool below[3] = {v[0].z < z, v[1].z < z, v[2].z < z};
  const int n_below = below[0] + below[1] + below[2];
  if (n_below == 0 || n_below == 3) return std::nullopt;
  // Going around the triangle, the cut starts where the boundary goes down through the plane and
  // ends where it comes back up: that puts the material (inside) on the left seen from above.
  int down = 0, up = 0;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (!below[k] && below[k1]) down = k;
    if (below[k] && !below[k1]) up = k;
  }
  auto crossing = [&](int k) {
    const int k1 = (k + 1) % 3;
    const int lo = below[k] ? k : k1, hi = below[k] ? k1 : k;
    if (v[hi].z == z) return Crossing{Crossing::Vertex, hi, v[hi].x, v[hi].y};
    const double t = (z - v[lo].z) / (v[hi].z - v[lo].z);
    return Crossing{Crossing::Edge, k, v[lo].x + t * (v[hi].x - v[lo].x), v[lo].y + t * (v[hi].y - v[lo].y)};
  };
  TriangleCut cut{crossing(down), crossing(up)};
  // One vertex on the plane with both others below: the triangle only touches the plane.
  if (cut.from.kind == Crossing::Vertex && cut.to.kind == Crossing::Vertex && cut.from.index == cut.to.index)
    return std::nullopt;
  return cut;
}

namespace {

constexpr uint32_t kNone = MeshTopology::kNone;
constexpr double kMaxCoordMm = 1e6;

// Topological identity of a crossing: an edge id or a vertex id, tagged in the low bit.
uint64_t edge_key(uint32_t e) { return static_cast<uint64_t>(e) << 1; }
uint64_t vertex_key(uint32_t v) { return (static_cast<uint64_t>(v) << 1) | 1; }

struct Segment {
  uint64_t from, to;
  Point a, b;
  uint32_t next_tri;  // the triangle across the exit edge when exactly two share it, else kNone
};

// A gap wider than the tolerance bridged by a straight edge.
struct OpenLoop {
  Point end, start;  // a chain stops at `end`; the bridging edge goes to the `start` of a chain
};

struct LayerOut {
  size_t segments = 0, gaps_joined = 0;
  std::vector<OpenLoop> open;
};

// Per-thread buffers, reused from layer to layer.
struct Scratch {
  std::vector<uint32_t> seg_of_tri;  // segment of each triangle in the current layer, else kNone
  std::vector<Segment> segs;
  std::vector<char> used;
  std::vector<std::pair<uint64_t, uint32_t>> by_key;  // starts not reachable through a 2-triangle edge
};

double dist(const Point& p, const Point& q) {
  return std::hypot(static_cast<double>(p.X - q.X), static_cast<double>(p.Y - q.Y));
}

struct Candidate {
  double d;
  uint32_t from, to;       // chain `from`'s end to chain `to`'s start
  bool other_rim = false;  // the two ends do not lie on the same hole of the mesh
  // Ends on the same hole first, then nearest first; at equal distance another chain before the
  // chain's own start (a chain closed on itself across a hole is usually a sliver).
  bool operator<(const Candidate& o) const {
    return std::tuple(other_rim, d, from == to, from, to) <
           std::tuple(o.other_rim, o.d, o.from == o.to, o.from, o.to);
  }
};

// An open chain and the mesh holes (rims) its two ends lie on (kNone: not on a hole, e.g. at a
// flipped triangle).
struct Chain {
  Ring pts;
  uint32_t front_rim = kNone, back_rim = kNone;
};

// Greedy matching of ends to starts, nearest pair first: next[i] = the chain after chain i.
void match(std::vector<Candidate>& cand, std::vector<uint32_t>& next, std::vector<uint32_t>& prev) {
  std::sort(cand.begin(), cand.end());
  for (const auto& c : cand) {
    if (next[c.from] != kNone || prev[c.to] != kNone) continue;
    next[c.from] = c.to;
    prev[c.to] = c.from;
  }
}

// Concatenates chains along `next` from `head` (marking them done).
Chain follow(const std::vector<Chain>& chains, const std::vector<uint32_t>& next, uint32_t head,
             std::vector<char>& done) {
  Chain out;
  out.front_rim = chains[head].front_rim;
  for (uint32_t c = head; c != kNone && !done[c]; c = next[c]) {
    done[c] = 1;
    out.pts.insert(out.pts.end(), chains[c].pts.begin(), chains[c].pts.end());
    out.back_rim = chains[c].back_rim;
  }
  return out;
}

// Beyond this many open chains in one layer (after joining small gaps) every chain is closed on
// itself instead of being matched with the others: keeps a shredded mesh from costing k².
constexpr size_t kMaxMatchedChains = 512;

// Closes open chains into loops. First, ends closer than `tol` (units) to a start are joined,
// nearest pair first, silently. Then the chains still open are joined end → start whatever the
// distance (a chain's own start is a candidate too), ends on the same hole of the mesh first
// (the plane crosses a hole's rim an even number of times: its crossings belong together),
// then nearest pair first: each such joint is a straight edge across a hole in the mesh,
// recorded for an "open-loop" warning.
void close_gaps(std::vector<Chain>& chains, double tol, Rings& loops, LayerOut& out) {
  const size_t n = chains.size();
  auto front = [&](uint32_t c) -> const Point& { return chains[c].pts.front(); };
  std::vector<uint32_t> by_x(n);
  for (uint32_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(),
            [&](uint32_t a, uint32_t b) { return std::tie(front(a).X, a) < std::tie(front(b).X, b); });
  std::vector<Candidate> cand;
  for (uint32_t i = 0; i < n; ++i) {
    const Point& e = chains[i].pts.back();
    auto lo = std::lower_bound(by_x.begin(), by_x.end(), e.X - static_cast<coord_t>(tol),
                               [&](uint32_t c, coord_t x) { return front(c).X < x; });
    for (auto it = lo; it != by_x.end() && front(*it).X <= e.X + static_cast<coord_t>(tol); ++it) {
      double d = dist(e, front(*it));
      if (d <= tol) cand.push_back({d, i, *it});
    }
  }
  std::vector<uint32_t> next(n, kNone), prev(n, kNone);
  match(cand, next, prev);
  for (uint32_t i = 0; i < n; ++i)
    if (next[i] != kNone && dist(chains[i].pts.back(), front(next[i])) > 0) ++out.gaps_joined;

  // Cycles are done; paths (heads without a predecessor) go on to the second round.
  std::vector<char> done(n, 0);
  std::vector<Chain> paths;
  for (uint32_t i = 0; i < n; ++i)
    if (prev[i] == kNone) paths.push_back(follow(chains, next, i, done));
  for (uint32_t i = 0; i < n; ++i)
    if (!done[i]) loops.push_back(follow(chains, next, i, done).pts);
  if (paths.empty()) return;

  const size_t k = paths.size();
  std::vector<uint32_t> next2(k, kNone), prev2(k, kNone);
  cand.clear();
  if (k <= kMaxMatchedChains) {
    for (uint32_t i = 0; i < k; ++i)
      for (uint32_t j = 0; j < k; ++j) {
        const uint32_t rim = paths[i].back_rim;
        cand.push_back({dist(paths[i].pts.back(), paths[j].pts.front()), i, j,
                        rim == kNone || rim != paths[j].front_rim});
      }
  } else {
    for (uint32_t i = 0; i < k; ++i) cand.push_back({0, i, i});
  }
  match(cand, next2, prev2);
  for (uint32_t i = 0; i < k; ++i) {
    const Point& from = paths[i].pts.back();
    const Point& to = paths[next2[i]].pts.front();
    if (dist(from, to) > tol)
      out.open.push_back({from, to});
    else if (dist(from, to) > 0)
      ++out.gaps_joined;
  }
  std::vector<char> done2(k, 0);
  for (uint32_t i = 0; i < k; ++i)
    if (!done2[i]) loops.push_back(follow(paths, next2, i, done2).pts);
}

// Removes repeated consecutive points (a cut through a vertex can round onto its neighbour) and
// drops loops that enclose nothing.
void clean(Rings& loops) {
  size_t kept = 0;
  for (size_t i = 0; i < loops.size(); ++i) {
    Ring& ring = loops[i];
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    if (ring.size() < 3) continue;
    if (kept != i) loops[kept] = std::move(ring);
    ++kept;
  }
  loops.resize(kept);
}

// The segments where triangles `tris` cross the plane at height z, in `s.segs` (each triangle's in
// `s.seg_of_tri`); those not found through a shared edge are also indexed by their start in
// `s.by_key` (unsorted).
void cut_segments(const Mesh& mesh, const MeshTopology& topo, const uint32_t* tris, size_t n_tris, double z,
                  Scratch& s) {
  s.segs.clear();
  s.by_key.clear();
  for (size_t i = 0; i < n_tris; ++i) {
    const uint32_t t = tris[i];
    const auto& tri = mesh.triangles[t];
    auto cut = cut_triangle({mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]}, z);
    if (!cut) continue;
    const MeshTopology::Links& links = topo.triangles[t];
    auto key = [&](const Crossing& c) {
      return c.kind == Crossing::Vertex ? vertex_key(tri[c.index]) : edge_key(links.edge[c.index]);
    };
    const uint32_t next_tri = cut->to.kind == Crossing::Edge ? links.neighbor[cut->to.index] : kNone;
    Segment seg{key(cut->from), key(cut->to), to_point(cut->from.x, cut->from.y),
                to_point(cut->to.x, cut->to.y), next_tri};
    s.seg_of_tri[t] = static_cast<uint32_t>(s.segs.size());
    // Entered through an edge shared by exactly two triangles: found through that neighbour.
    const bool by_edge = cut->from.kind == Crossing::Edge && links.neighbor[cut->from.index] != kNone;
    if (!by_edge) s.by_key.emplace_back(seg.from, static_cast<uint32_t>(s.segs.size()));
    s.segs.push_back(seg);
  }
}

LayerOut slice_layer(const Mesh& mesh, const MeshTopology& topo, const uint32_t* tris, size_t n_tris,
                     Layer& layer, double gap_tol_mm, Scratch& s) {
  LayerOut out;
  cut_segments(mesh, topo, tris, n_tris, layer.z_slice(), s);
  std::sort(s.by_key.begin(), s.by_key.end());
  out.segments = s.segs.size();
  s.used.assign(s.segs.size(), 0);

  // The segment that continues `cur`: across its exit edge into the neighbouring triangle, or,
  // at a vertex or an edge not shared by exactly two triangles, any unused segment starting
  // there (back to `first` if possible: it closes the loop).
  auto next = [&](uint32_t cur, uint32_t first) -> uint32_t {
    const Segment& c = s.segs[cur];
    if (c.next_tri != kNone) {
      const uint32_t n = s.seg_of_tri[c.next_tri];
      if (n != kNone && s.segs[n].from == c.to && (n == first || !s.used[n])) return n;
      return kNone;
    }
    auto it = std::lower_bound(s.by_key.begin(), s.by_key.end(), std::make_pair(c.to, uint32_t{0}));
    uint32_t found = kNone;
    for (; it != s.by_key.end() && it->first == c.to; ++it) {
      if (it->second == first) return first;
      if (found == kNone && !s.used[it->second]) found = it->second;
    }
    return found;
  };

  Rings loops;
  std::vector<Chain> open;
  // The hole an open chain's end lies on: the rim of a boundary edge, or of a vertex on the plane.
  auto rim = [&](uint64_t key) {
    const auto id = static_cast<uint32_t>(key >> 1);
    return key & 1 ? topo.vertex_rim(id) : topo.edge_rim(id);
  };
  for (uint32_t s0 = 0; s0 < s.segs.size(); ++s0) {
    if (s.used[s0]) continue;
    Ring pts{s.segs[s0].a};
    s.used[s0] = 1;
    uint32_t cur = s0;
    bool closed = false;
    for (;;) {
      const uint32_t n = next(cur, s0);
      if (n == s0) {
        closed = true;
        break;
      }
      if (n == kNone) break;
      s.used[n] = 1;
      pts.push_back(s.segs[n].a);
      cur = n;
    }
    if (closed) {
      loops.push_back(std::move(pts));
    } else {
      pts.push_back(s.segs[cur].b);
      open.push_back({std::move(pts), rim(s.segs[s0].from), rim(s.segs[cur].to)});
    }
  }
  for (size_t i = 0; i < n_tris; ++i) s.seg_of_tri[tris[i]] = kNone;

  if (!open.empty()) close_gaps(open, gap_tol_mm * kUnitsPerMm, loops, out);
  clean(loops);
  layer.loops = std::move(loops);
  return out;
}

}  // namespace

Result<SliceStats> slice_mesh(const Mesh& mesh, const MeshTopology& topo, std::vector<Layer>& layers,
                              const SliceParams& params, Report& report) {
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    if (!(std::abs(v.x) <= kMaxCoordMm && std::abs(v.y) <= kMaxCoordMm && std::abs(v.z) <= kMaxCoordMm))
      return Error{
          fmt::format("vertex {}", i),
          fmt::format("coordinate ({}, {}, {}) mm is not finite or beyond ±{} mm; repair or scale the model",
                      v.x, v.y, v.z, kMaxCoordMm)};
  }
  for (size_t i = 1; i < layers.size(); ++i)
    if (!(layers[i].z_slice() > layers[i - 1].z_slice()))
      return Error{fmt::format("layer {}", i), "layers must be planned bottom to top"};
  SliceStats stats;
  if (layers.empty()) return stats;

  // Bucket every triangle into the layers whose plane z satisfies z_min < z <= z_max (the only
  // planes it can cut): memory proportional to the output, no layers × triangles scan.
  const size_t nl = layers.size(), nt = mesh.triangles.size();
  std::vector<double> plane(nl);
  for (size_t i = 0; i < nl; ++i) plane[i] = layers[i].z_slice();
  std::vector<uint32_t> first(nt), last(nt);  // layer range [first, last), empty when first == last
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 8192), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t != r.end(); ++t) {
      const auto& tri = mesh.triangles[t];
      double lo = mesh.vertices[tri[0]].z, hi = lo;
      for (int k = 1; k < 3; ++k)
        lo = std::min(lo, mesh.vertices[tri[k]].z), hi = std::max(hi, mesh.vertices[tri[k]].z);
      first[t] = static_cast<uint32_t>(std::upper_bound(plane.begin(), plane.end(), lo) - plane.begin());
      last[t] = static_cast<uint32_t>(std::upper_bound(plane.begin(), plane.end(), hi) - plane.begin());
      if (topo.triangles[t].edge[0] == kNone) last[t] = first[t];  // degenerate
    }
  });
  std::vector<size_t> offset(nl + 1, 0);
  for (size_t t = 0; t < nt; ++t)
    for (uint32_t l = first[t]; l < last[t]; ++l) ++offset[l + 1];
  for (size_t l = 0; l < nl; ++l) offset[l + 1] += offset[l];
  std::vector<uint32_t> bucket(offset[nl]);
  {
    std::vector<size_t> cursor(offset.begin(), offset.end() - 1);
    for (size_t t = 0; t < nt; ++t)
      for (uint32_t l = first[t]; l < last[t]; ++l) bucket[cursor[l]++] = static_cast<uint32_t>(t);
  }
  first = {};
  last = {};

  tbb::enumerable_thread_specific<Scratch> scratch([&] {
    Scratch s;
    s.seg_of_tri.assign(nt, kNone);
    return s;
  });
  std::vector<LayerOut> outs(nl);
  std::atomic<size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nl, 1), [&](const tbb::blocked_range<size_t>& r) {
    Scratch& s = scratch.local();
    for (size_t l = r.begin(); l != r.end(); ++l) {
      const double tol = params.gap_tolerance >= 0 ? params.gap_tolerance : 2 * layers[l].height();
      outs[l] =
          slice_layer(mesh, topo, bucket.data() + offset[l], offset[l + 1] - offset[l], layers[l], tol, s);
      const size_t n = ++done;
      if (params.progress) params.progress(n);
    }
  });

  for (size_t l = 0; l < nl; ++l) {
    stats.segments += outs[l].segments;
    stats.loops += layers[l].loops.size();
    stats.gaps_joined += outs[l].gaps_joined;
    stats.open_loops += outs[l].open.size();
    for (const auto& o : outs[l].open)
      report.warn(
          "open-loop",
          fmt::format("layer {} at ({:.3f}, {:.3f}) mm", layers[l].index, to_mm(o.end.X), to_mm(o.end.Y)),
          fmt::format("open loop: a {:.3f} mm gap bridged with a straight edge to ({:.3f}, {:.3f}) mm; the "
                      "mesh has a hole or a crack here",
                      dist(o.end, o.start) * kMmPerUnit, to_mm(o.start.X), to_mm(o.start.Y)));
  }
  return stats;
}

Result<SliceStats> slice_mesh(const Mesh& mesh, std::vector<Layer>& layers, const SliceParams& params,
                              Report& report) {
  return slice_mesh(mesh, build_topology(mesh), layers, params, report);
}

}  // namespace tranche::geo
