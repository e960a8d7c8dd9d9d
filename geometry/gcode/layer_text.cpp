#include "geometry/gcode/layer_text.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/gcode/numbers.h"
#include "geometry/plan/context_fill.h"
#include "geometry/plan/walk.h"
#include "geometry/toolpath/flow.h"
#include "runtime/schema/type_names.h"

namespace tranche::gcode {

using schema::Flavor;
using schema::Level;
using schema::PathKind;
using schema::PropId;
using plan::CellPlan;
using plan::IslandPlan;
using plan::LayerPlan;
using plan::Op;
using plan::PathPlan;

std::string fan_command(Flavor flavor, double ratio) {
  ratio = std::clamp(ratio, 0.0, 1.0);
  if (flavor == Flavor::RepRapFirmware) {
    std::string s = "M106 P0 S";
    append_fixed(s, std::llround(ratio * 100), 2);
    return s;
  }
  if (ratio <= 0) return "M107";
  std::string s = "M106 S";
  append_int(s, std::lround(ratio * 255));
  return s;
}

namespace {

class Formatter final : public ctx::LineSink {
 public:
  Formatter(const setup::PrintSetup& s, const ctx::Executors* executors, const LayerPlan& plan)
      : S(s), plan_(plan), ctx_(s.print_ctx), exec_(executors) {
    const auto& P = s.print_props;
    relative_ = P[PropId::RelativeE] != 0;
    retract_ = std::llround(P[PropId::RetractLength] * 1e5);
    retract_f_ = std::lround(P[PropId::RetractSpeed] * 60);
    travel_f_ = std::lround(P[PropId::TravelSpeed] * 60);
    lift_ = P[PropId::RetractLift];
    before_ = P[PropId::RetractBeforeTravel];
    filament_area_ = toolpath::filament_area_mm2(P[PropId::FilamentDiameter]);
    height_ = plan.height;
    z_um_ = std::llround(plan.z * 1000);
    out_.text.reserve(1 << 16);
  }

  Result<LayerText> run() {
    plan::set_layer_fields(ctx_, plan_, static_cast<int>(plan_.islands.size()));
    ctx_.set(schema::FieldId::LayerTime, plan_.time_s);
    ctx_.set_props(&plan_.props);
    if (exec_) islands_view_.bind(ctx_, plan_.islands);
    auto& t = out_.text;
    t += ";LAYER_CHANGE\n;Z:";
    append_fixed(t, z_um_, 3);
    t += "\n;HEIGHT:";
    append_fixed(t, std::llround(plan_.height * 1000), 3);
    t += "\n;LAYER:";
    append_int(t, plan_.index);
    t += '\n';
    hook(Level::Layer, ctx::When::Before);
    mark(LayerText::Mark::Kind::NozzleTemp, plan_.props[PropId::NozzleTemp]);
    mark(LayerText::Mark::Kind::BedTemp, plan_.props[PropId::BedTemp]);
    t += "G92 E0\n";
    // The layer change retracts only if the travel from the previous layer's end is long: that
    // is known when layers are written in order, so it is a mark (before the z move, and the
    // matching unretraction before the first extrusion). E is 0 at the first extrusion either way.
    if (retract_ > 0) {
      mark(LayerText::Mark::Kind::LayerRetract, 0);
      e_int_ = -retract_;
      retracted_ = true;
      layer_change_ = true;
    }
    t += "G1 Z";
    append_fixed(t, z_um_, 3);
    t += " F";
    append_int(t, travel_f_);
    t += '\n';
    mark(LayerText::Mark::Kind::LayerTravel, 0);
    lifted_ = false;
    f_ = travel_f_;
    plan::walk_layer(plan_, *this);
    ctx_.clear_from(Level::Island);
    ctx_.set_props(&plan_.props);
    hook(Level::Layer, ctx::When::After);
    if (!status_) return status_.error();
    out_.e_mm = e_exact_;
    out_.last = pos_;
    out_.ends_retracted = retracted_ && !layer_change_;
    out_.comber = plan_.comber;
    return std::move(out_);
  }

  // LineSink: executor output.
  void line(std::string_view text) override {
    out_.text.append(text);
    out_.text.push_back('\n');
  }

  // walk_layer visitor.
  void island_begin(const IslandPlan& ip) {
    island_ = ip.index;
    ctx_.clear_from(Level::Island);
    plan::set_island_fields(ctx_, ip);
    ctx_.set_props(&ip.props);
    hook(Level::Island, ctx::When::Before);
  }
  void island_end(const IslandPlan& ip) {
    ctx_.clear_from(Level::Cell);
    plan::set_island_fields(ctx_, ip);
    ctx_.set_props(&ip.props);
    hook(Level::Island, ctx::When::After);
  }
  void cell_begin(const IslandPlan& ip, const CellPlan& c) {
    ctx_.clear_from(Level::Cell);
    plan::set_cell_fields(ctx_, c);
    ctx_.set_props(&ip.props);
    hook(Level::Cell, ctx::When::Before);
  }
  void cell_end(const IslandPlan& ip, const CellPlan& c) {
    ctx_.clear_from(Level::Cell);
    plan::set_cell_fields(ctx_, c);
    ctx_.set_props(&ip.props);
    hook(Level::Cell, ctx::When::After);
  }
  void path_begin(const IslandPlan*, const PathPlan& p) {
    path_ = &p;
    if (!exec_) return;
    ctx_.clear_from(Level::Path);
    plan::set_path_fields(ctx_, p);
    ctx_.set_props(&p.props);
    if (exec_->has(Level::Path, ctx::When::Before) || exec_->has(Level::Path, ctx::When::After))
      path_view_.bind(ctx_, p, S.shift);
    hook(Level::Path, ctx::When::Before);
  }
  void path_end(const IslandPlan*, const PathPlan& p) {
    if (!exec_) return;
    ctx_.set_props(&p.props);
    hook(Level::Path, ctx::When::After);
    path_ = nullptr;
  }
  void path_default(const IslandPlan*, const PathPlan& p) {
    if (p.pts.empty()) return;
    fan(p.fan);
    if (!has_pos_ || pos_ != p.pts.front()) {
      bool retract = p.retract || !has_pos_;
      for (const auto& q : p.via) travel(q, retract);  // combing: around holes, inside the part
      travel(p.pts.front(), retract);
    }
    type(p.kind, p.piece_width(0));
    double epm = toolpath::bead_area_mm2(p.width, height_) / filament_area_;
    for (size_t i = 0; i < p.piece_count(); ++i) {
      const auto& pc = p.piece(i);
      if (!p.widths.empty()) {  // a width of its own: ;WIDTH when it changes, E per mm from it
        const float w = p.piece_width(i);
        type(p.kind, w);
        epm = toolpath::bead_area_mm2(w, height_) / filament_area_;
      }
      extrude(p.pts[i + 1], pc.speed, epm * pc.flow * p.piece_scale(i));
    }
  }
  void op(const IslandPlan*, const PathPlan* p, const Op& o) {
    switch (o.kind) {
      case Op::Kind::Text:
        line(o.text);
        break;
      case Op::Kind::Travel: {
        double len =
            has_pos_ ? std::hypot(double(o.to.X - pos_.X), double(o.to.Y - pos_.Y)) * geo::kMmPerUnit : 1e9;
        travel(o.to, len > before_);
        break;
      }
      case Op::Kind::Extrude:
        if (p) fan(p->fan);
        if (!has_pos_) travel(o.to, true);
        type(p ? p->kind : PathKind::Custom, o.width);
        extrude(o.to, o.speed, toolpath::bead_area_mm2(o.width, height_) * o.flow / filament_area_);
        break;
      case Op::Kind::Retract:
        retract();
        break;
      case Op::Kind::Default:
        break;
    }
  }

 private:
  void hook(Level level, ctx::When when) {
    if (!exec_ || !status_ || !exec_->has(level, when)) return;
    if (!S.provenance) {
      status_ = exec_->run(level, when, ctx_, *this);
      return;
    }
    Notes notes(out_, path_, island_);
    ctx_.set_trace(&notes);
    status_ = exec_->run(level, when, ctx_, *this);
    ctx_.set_trace(nullptr);
  }
  // Records each executor's G-code into LayerText::hooks.
  struct Notes final : ctx::Trace {
    LayerText& out;
    const PathPlan* path;
    int island;
    Notes(LayerText& o, const PathPlan* p, int i) : out(o), path(p), island(i) {}
    void step(const ctx::TraceStep&) override {}
    void hook(Level level, ctx::When when, uint32_t rule, std::string_view text) override {
      out.hooks.push_back({path, island, level, when == ctx::When::After, rule, std::string(text)});
    }
  };
  void mark(LayerText::Mark::Kind k, double v) { out_.marks.push_back({out_.text.size(), k, v}); }
  void fan(double v) {
    if (v == fan_) return;
    fan_ = v;
    mark(LayerText::Mark::Kind::Fan, v);
  }
  void type(PathKind k, float width) {
    auto& t = out_.text;
    if (k != type_ || !has_type_) {
      t += ";TYPE:";
      t += schema::gcode_type_name(k);
      t += '\n';
      type_ = k;
      has_type_ = true;
    }
    if (width != width_) {
      t += ";WIDTH:";
      append_fixed(t, std::llround(width * 1000.0), 3);
      t += '\n';
      width_ = width;
    }
  }
  void xy(const geo::Point& p) {
    auto& t = out_.text;
    const int64_t x = round_div(p.X + S.shift.X, 1000), y = round_div(p.Y + S.shift.Y, 1000);
    t += " X";
    append_fixed(t, x, 3);
    t += " Y";
    append_fixed(t, y, 3);
    const double off = S.bed.outside(1e-3 * static_cast<double>(x), 1e-3 * static_cast<double>(y));
    if (off > out_.off_bed_mm)
      out_.off_bed_mm = off, out_.off_bed_x = 1e-3 * static_cast<double>(x), out_.off_bed_y = 1e-3 * static_cast<double>(y);
  }
  static int64_t round_div(int64_t v, int64_t d) { return v >= 0 ? (v + d / 2) / d : -((-v + d / 2) / d); }
  void e_word(int64_t new_int) {
    auto& t = out_.text;
    t += " E";
    append_fixed(t, relative_ ? new_int - e_int_ : new_int, 5);
    e_int_ = new_int;
  }
  // Pulls the filament back (and lifts, with retract_lift) unless it already is; the next
  // extrusion undoes it.
  void retract() {
    if (retracted_ || retract_ <= 0) return;
    auto& t = out_.text;
    t += "G1";
    e_word(e_int_ - retract_);
    t += " F";
    append_int(t, retract_f_);
    t += '\n';
    retracted_ = true;
    ++out_.retractions;
    f_ = retract_f_;
    if (lift_ > 0) {
      t += "G1 Z";
      append_fixed(t, z_um_ + std::llround(lift_ * 1000), 3);
      t += '\n';
      lifted_ = true;
    }
  }
  void travel(const geo::Point& to, bool retract_first) {
    auto& t = out_.text;
    if (retract_first) retract();
    t += "G1";
    xy(to);
    if (f_ != travel_f_) {
      t += " F";
      append_int(t, travel_f_);
      f_ = travel_f_;
    }
    t += '\n';
    if (!out_.any_move) out_.first = to;
    out_.any_move = true;
    ++out_.travels;
    pos_ = to;
    has_pos_ = true;
  }
  void extrude(const geo::Point& to, double speed, double e_per_mm) {
    auto& t = out_.text;
    if (lifted_) {
      t += "G1 Z";
      append_fixed(t, z_um_, 3);
      t += '\n';
      lifted_ = false;
    }
    if (retracted_ && layer_change_) {
      mark(LayerText::Mark::Kind::LayerUnretract, 0);
      e_int_ += retract_;
      f_ = -1;  // the unretraction, if written, changed the feed rate
      retracted_ = false;
      layer_change_ = false;
    }
    if (retracted_) {
      t += "G1";
      e_word(e_int_ + retract_);
      t += " F";
      append_int(t, retract_f_);
      t += '\n';
      f_ = retract_f_;
      retracted_ = false;
    }
    double len = std::hypot(double(to.X - pos_.X), double(to.Y - pos_.Y)) * geo::kMmPerUnit;
    e_exact_ += len * e_per_mm;
    // A move that rounds to where the nozzle already is (to the micrometre written) is not
    // written: its plastic, if any, goes with the next move, whose E is computed from the total.
    if (round_div(to.X, 1000) == round_div(pos_.X, 1000) &&
        round_div(to.Y, 1000) == round_div(pos_.Y, 1000)) {
      pos_ = to;
      return;
    }
    int64_t delta = std::llround(e_exact_ * 1e5) - e_sent_;
    e_sent_ += delta;
    t += "G1";
    xy(to);
    e_word(e_int_ + delta);
    int64_t f = std::lround(speed * 60);
    if (f != f_) {
      t += " F";
      append_int(t, f);
      f_ = f;
    }
    t += '\n';
    pos_ = to;
  }

  const setup::PrintSetup& S;
  const LayerPlan& plan_;
  ctx::Context ctx_;
  const ctx::Executors* exec_ = nullptr;
  plan::PathView path_view_;
  plan::IslandsView islands_view_;
  Status status_ = ok_status();
  LayerText out_;
  bool relative_ = false, retracted_ = false, lifted_ = false, has_pos_ = false, has_type_ = false;
  bool layer_change_ = false;  // retracted_ by the layer change (a mark), not by a travel
  int64_t retract_ = 0, retract_f_ = 0, travel_f_ = 0, f_ = -1, z_um_ = 0;
  int64_t e_int_ = 0;   // absolute E since the layer's G92 E0, 1e-5 mm (relative mode writes its steps)
  int64_t e_sent_ = 0;  // extrusion written so far, 1e-5 mm
  double e_exact_ = 0;  // extrusion so far, mm, unrounded
  double lift_ = 0, before_ = 0, filament_area_ = 1, height_ = 0.2;
  double fan_ = -1;
  PathKind type_ = PathKind::Custom;
  float width_ = -1;
  geo::Point pos_;
  const PathPlan* path_ = nullptr;  // the path being written (provenance of its hooks)
  int island_ = -1;
};

}  // namespace

Result<LayerText> format_layer(const setup::PrintSetup& setup, const ctx::Executors* executors,
                               const LayerPlan& plan) {
  Formatter f(setup, executors, plan);
  return f.run();
}

}  // namespace tranche::gcode
