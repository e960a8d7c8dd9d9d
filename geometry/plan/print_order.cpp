#include "geometry/plan/print_order.h"

#include <algorithm>
#include <cmath>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/order.h"

namespace tranche::plan {

using schema::Border;
using schema::PathKind;
using schema::PropId;
using toolpath::dist2;

geo::Point layer_start(const std::vector<IslandPlan>& islands) {
  geo::BBox2 all;
  for (const auto& ip : islands)
    for (const auto& r : ip.shape)
      for (const auto& q : r) all.add(q);
  return all.empty() ? geo::Point(0, 0) : geo::Point((all.min_x + all.max_x) / 2, all.max_y);
}

void order_skirt(std::vector<PathPlan>& skirt, geo::Point& pos) {
  for (auto& sk : skirt) {
    if (!sk.closed) {  // a piece of brim cut by an island: from its nearer end
      auto d2 = [&](const geo::Point& q) { return double(q.X - pos.X) * double(q.X - pos.X) + double(q.Y - pos.Y) * double(q.Y - pos.Y); };
      if (!sk.pts.empty() && d2(sk.pts.back()) < d2(sk.pts.front())) std::reverse(sk.pts.begin(), sk.pts.end());
      sk.border.assign(sk.piece_count(), Border::None);
      if (!sk.pts.empty()) pos = sk.pts.back();
      continue;
    }
    size_t seam = toolpath::choose_seam(sk.pts, schema::Seam::Rear, pos);
    sk.pts = toolpath::open_loop_at(sk.pts, seam);
    sk.border.assign(sk.piece_count(), Border::None);
    pos = sk.pts.front();
  }
}

std::vector<size_t> island_order(const std::vector<IslandPlan>& islands, const geo::Point& from, int layer_index) {
  std::vector<size_t> seq;
  std::vector<char> used(islands.size(), 0);
  std::vector<geo::BBox2> boxes;
  for (const auto& ip : islands) boxes.push_back(toolpath::bbox(ip.shape));
  geo::Point at = from;
  for (size_t step = 0; step < islands.size(); ++step) {
    double bd = 1e300;
    size_t bi = 0;
    for (size_t i = 0; i < islands.size(); ++i) {
      if (used[i]) continue;
      const geo::BBox2& b = boxes[i];
      double dx = std::max<double>({0.0, double(b.min_x - at.X), double(at.X - b.max_x)});
      double dy = std::max<double>({0.0, double(b.min_y - at.Y), double(at.Y - b.max_y)});
      double d = b.empty() ? 1e299 : dx * dx + dy * dy;
      if (d < bd) bd = d, bi = i;
    }
    used[bi] = 1;
    seq.push_back(bi);
    const geo::BBox2& b = boxes[bi];
    if (!b.empty()) at = geo::Point((b.min_x + b.max_x) / 2, (b.min_y + b.max_y) / 2);
  }
  if (layer_index % 2 == 1) std::reverse(seq.begin(), seq.end());
  return seq;
}

namespace {

// One island's ordering: its loops and zig-zags taken apart, then emitted into `out`.
class IslandOrder {
 public:
  IslandOrder(IslandPlan& ip, const std::vector<FillGrid>& regions, double height_mm, geo::Point& pos,
              const SeamFrame& frame)
      : ip_(ip), regions_(regions), height_(height_mm), pos_(pos), frame_(frame) {
    outer_first_ = ip.props[PropId::OuterFirst] != 0;
    seam_ = static_cast<schema::Seam>(static_cast<int>(ip.props[PropId::Seam]));
    if (seam_ == schema::Seam::Point) {
      const geo::Point bed = geo::to_point(ip.props[PropId::SeamX], ip.props[PropId::SeamY]);
      toward_ = geo::Point(bed.X - frame.shift.X, bed.Y - frame.shift.Y);
    }
    for (auto& p : ip.paths)
      (p.closed ? loops_ : p.kind == PathKind::Ironing ? irons_ : fills_).push_back(std::move(p));
    // Loops: by depth (innermost first unless outer_first), nearest seam first within a depth.
    std::stable_sort(loops_.begin(), loops_.end(), [&](const PathPlan& a, const PathPlan& b) {
      return outer_first_ ? a.perimeter < b.perimeter : a.perimeter > b.perimeter;
    });
    deepest_ = loops_.empty() ? 0 : std::max(loops_.front().perimeter, loops_.back().perimeter);
  }

  void run() {
    if (ip_.props[PropId::InfillFirst] != 0 && !fills_.empty()) {
      emit_fills(true);
      emit_loops(true);
    } else {
      emit_loops(false);
      emit_fills(false);
    }
    emit_irons();
    if (!out_.empty() && !out_.back().pts.empty()) pos_ = out_.back().pts.back();
    for (size_t i = 0; i < out_.size(); ++i) out_[i].index = static_cast<int>(i);
    ip_.paths = std::move(out_);
  }

 private:
  // `link`: the infill was printed just before. The first loop, if it is an innermost one,
  // starts at its point nearest the infill's end (inner seams do not show), and the infill's
  // last path reaches it by a short extrusion instead of a travel.
  void emit_loops(bool link) {
    for (size_t i = 0; i < loops_.size();) {
      size_t j = i;
      while (j < loops_.size() && loops_[j].perimeter == loops_[i].perimeter) ++j;
      std::vector<size_t> seams(j - i);
      for (size_t k = i; k < j; ++k) seams[k - i] = seam_of(k);
      std::vector<char> used(j - i, 0);
      for (size_t step = i; step < j; ++step) {
        size_t bk = link && step == 0 && loops_[i].perimeter == deepest_ ? link_first(i, j, seams)
                                                                         : nearest_seam(i, j, seams, used);
        used[bk - i] = 1;
        PathPlan& p = loops_[bk];
        p.pts = toolpath::open_loop_at(p.pts, seams[bk - i]);
        p.border.assign(p.piece_count(), Border::Real);
        pos_ = p.pts.front();
        out_.push_back(std::move(p));
      }
      i = j;
    }
  }

  // The loop of [i, j) nearest the infill's end, with a vertex inserted there as its seam; the
  // infill's last path is extended to it when that is a short step.
  size_t link_first(size_t i, size_t j, std::vector<size_t>& seams) {
    double bd = 1e300;
    size_t bk = i;
    geo::Point at;
    for (size_t k = i; k < j; ++k) {
      auto [d, q] = toolpath::nearest_on_loop(loops_[k].pts, pos_);
      if (d < bd) bd = d, bk = k, at = q;
    }
    seams[bk - i] = toolpath::insert_vertex(loops_[bk].pts, at);
    PathPlan& f = out_.back();
    double limit = 1.5 * std::max(f.width, loops_[bk].width) * geo::kUnitsPerMm;
    if (bd > 0 && bd <= limit * limit && !f.pts.empty() && f.pts.back() == pos_ && f.widths.empty()) {
      f.pts.push_back(loops_[bk].pts[seams[bk - i]]);
      f.border.push_back(Border::Artificial);
    }
    return bk;
  }

  // Where loop k (an index into loops_, fixed once sorted) starts. A random seam is a vertex
  // inserted at the drawn point (found again, not inserted twice, when asked again).
  size_t seam_of(size_t k) {
    if (seam_ == schema::Seam::Random) {
      const double u = toolpath::seam_fraction(toolpath::seam_seed(frame_.layer, ip_.index, k));
      return toolpath::insert_vertex(loops_[k].pts, toolpath::point_at_fraction(loops_[k].pts, u));
    }
    toolpath::SeamOptions o;
    o.mode = seam_;
    o.toward = toward_;
    return toolpath::choose_seam(loops_[k].pts, o, pos_);
  }

  // The unused loop of [i, j) whose seam is nearest.
  size_t nearest_seam(size_t i, size_t j, std::vector<size_t>& seams, const std::vector<char>& used) {
    double bd = 1e300;
    size_t bk = i;
    for (size_t k = i; k < j; ++k) {
      if (used[k - i]) continue;
      size_t s = seam_ == schema::Seam::Nearest ? seam_of(k) : seams[k - i];
      seams[k - i] = s;
      double d = dist2(pos_, loops_[k].pts[s]);
      if (d < bd) bd = d, bk = k;
    }
    return bk;
  }

  // Whether zig-zag b may start by a short extrusion from `from` (where a ends) to `to`: same
  // kind and width, close, and the step stays inside their fill region.
  bool joinable(const PathPlan& a, const PathPlan& b, const geo::Point& from, const geo::Point& to) const {
    if (a.kind != b.kind || a.width != b.width) return false;
    const toolpath::EdgeGrid* grid = nullptr;
    for (const auto& r : regions_)
      if (r.kind == b.kind) grid = &r.grid;
    const double limit = join_reach_mm(b) * geo::kUnitsPerMm;
    return grid && dist2(from, to) <= limit * limit && !grid->crosses(from, to);
  }
  // The longest short extrusion that may start zig-zag b (mm).
  double join_reach_mm(const PathPlan& b) const {
    double s = toolpath::bead_spacing_mm(b.width, height_);
    double pitch =
        b.kind == PathKind::Infill ? s / std::max(1e-3, std::min(1.0, b.props[PropId::InfillDensity])) : s;
    return std::max(2.5 * s, 1.5 * pitch);
  }

  // Zig-zags (one per cell): the order with the fewest and shortest travels, either end may
  // start. A zig-zag that starts right next to where the previous one of the same region ended
  // is joined to it by a short extrusion (across the gap between their line ends) instead of a
  // travel.
  void emit_fills(bool before_loops) {
    // A travel costs its length plus this (mm): fewer travels first, then shorter ones.
    constexpr double kTravelMm = 10;
    // Before the loops, the infill should end where the innermost loop will start next to the
    // outer loop's seam, so that the step from one loop to the next is short.
    std::vector<geo::Point> seams_out;
    if (before_loops && seam_ != schema::Seam::Nearest)
      for (size_t k = 0; k < loops_.size(); ++k)
        if (loops_[k].perimeter == 0) seams_out.push_back(loops_[k].pts[seam_of(k)]);
    toolpath::EndCost end_cost;
    if (!seams_out.empty())
      end_cost = [&](const geo::Point& e) {
        double bd = 1e300;
        for (const auto& q : seams_out) bd = std::min(bd, dist2(e, q));
        return std::sqrt(bd) * geo::kMmPerUnit;
      };
    auto step = [&](size_t i, const geo::Point& a, size_t j, const geo::Point& b) {
      if (i != toolpath::kStart && joinable(fills_[i], fills_[j], a, b)) return 0.0;
      return std::sqrt(dist2(a, b)) * geo::kMmPerUnit + kTravelMm;
    };
    std::vector<const geo::Ring*> ends;
    for (const auto& f : fills_) ends.push_back(&f.pts);
    // A step costs its length plus kTravelMm unless it joins (then nothing, and it is at most
    // `reach` long): with many zig-zags (a lightning layer's branches) the greedy order looks at
    // the nearest ones first.
    double reach = 0;
    for (const auto& f : fills_) reach = std::max(reach, join_reach_mm(f));
    auto lower = [reach](double d) { return d > reach ? d + kTravelMm : 0.0; };
    const size_t first_fill = out_.size();
    for (const toolpath::Visit& v :
         toolpath::chain_open_best(ends, pos_, step, 48, end_cost, lower, std::max(reach, 2.0))) {
      PathPlan& p = fills_[v.index];
      if (v.reversed) {
        std::reverse(p.pts.begin(), p.pts.end());
        std::reverse(p.border.begin(), p.border.end());
        std::reverse(p.widths.begin(), p.widths.end());
      }
      out_.push_back(std::move(p));
    }
    for (size_t i = first_fill + 1; i < out_.size(); ++i) {
      PathPlan& prev = out_[i - 1];
      PathPlan& p = out_[i];
      if (prev.pts.empty() || p.pts.empty()) continue;
      const geo::Point a = prev.pts.back();
      if (!joinable(prev, p, a, p.pts.front())) continue;
      p.pts.insert(p.pts.begin(), a);
      p.border.insert(p.border.begin(), Border::Artificial);
      if (!p.widths.empty()) p.widths.insert(p.widths.begin(), p.width);
    }
    if (out_.size() > first_fill && !out_.back().pts.empty()) pos_ = out_.back().pts.back();
  }

  // Ironing last, once the walls and the top are printed: its zig-zags in the order with the
  // fewest and shortest travels.
  void emit_irons() {
    if (irons_.empty()) return;
    std::vector<const geo::Ring*> ends;
    for (const auto& f : irons_) ends.push_back(&f.pts);
    auto step = [&](size_t, const geo::Point& a, size_t, const geo::Point& b) {
      return std::sqrt(dist2(a, b)) * geo::kMmPerUnit + 10.0;
    };
    for (const toolpath::Visit& v : toolpath::chain_open_best(ends, pos_, step)) {
      PathPlan& p = irons_[v.index];
      if (v.reversed) {
        std::reverse(p.pts.begin(), p.pts.end());
        std::reverse(p.border.begin(), p.border.end());
      }
      out_.push_back(std::move(p));
    }
    if (!out_.empty() && !out_.back().pts.empty()) pos_ = out_.back().pts.back();
  }

  IslandPlan& ip_;
  const std::vector<FillGrid>& regions_;
  double height_;
  geo::Point& pos_;
  SeamFrame frame_;
  geo::Point toward_;
  bool outer_first_ = false;
  schema::Seam seam_ = schema::Seam::Aligned;
  int deepest_ = 0;
  std::vector<PathPlan> loops_, fills_, irons_, out_;
};

}  // namespace

void order_island(IslandPlan& ip, const std::vector<FillGrid>& regions, double height_mm, geo::Point& pos,
                  const SeamFrame& frame) {
  if (ip.replaced && ip.paths.empty()) return;
  IslandOrder(ip, regions, height_mm, pos, frame).run();
}

}  // namespace tranche::plan
