#include "geometry/gcode/print.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>

#include "geometry/gcode/layer_text.h"
#include "geometry/gcode/numbers.h"
#include "base/output_file.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/context_fill.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/layer_loop.h"
#include "geometry/toolpath/motion.h"

namespace tranche::gcode {

using schema::FieldId;
using schema::Level;
using schema::PropId;
using schema::Stage;

std::string format_duration(double seconds) {
  long s = std::lround(std::max(0.0, seconds));
  long d = s / 86400, h = s / 3600 % 24, m = s / 60 % 60, sec = s % 60;
  if (d) return fmt::format("{}d {}h {}m {}s", d, h, m, sec);
  if (h) return fmt::format("{}h {}m {}s", h, m, sec);
  if (m) return fmt::format("{}m {}s", m, sec);
  return fmt::format("{}s", sec);
}

namespace {

// Lengths (mm) of the legs of the travel a → via... → b.
std::vector<double> legs_mm(const geo::Point& a, const geo::Ring& via, const geo::Point& b) {
  std::vector<double> out;
  geo::Point prev = a;
  for (const auto& q : via)
    out.push_back(std::hypot(double(q.X - prev.X), double(q.Y - prev.Y)) * geo::kMmPerUnit), prev = q;
  out.push_back(std::hypot(double(b.X - prev.X), double(b.Y - prev.Y)) * geo::kMmPerUnit);
  return out;
}

int64_t round_um(int64_t units) { return units >= 0 ? (units + 500) / 1000 : -((-units + 500) / 1000); }

// A header line whose value is known only at the end: written padded, patched in place.
struct Slot {
  uint64_t offset = 0;
  size_t width = 0;
};

class PrintWriter final : public ctx::LineSink {
 public:
  PrintWriter(const GcodeJob& job, Report& report) : job_(job), report_(report) {}

  Result<GcodeSummary> run() {
    if (job_.layers.empty()) return Error{job_.model_name, "nothing to print: the model has no layers"};
    if (Status s = decide_print(); !s) return s.error();
    auto file = OutputFile::create(job_.output, "the G-code");
    if (!file) return file.error();
    file_ = std::make_unique<OutputFile>(std::move(*file));
    if (Status s = header(); !s) return s.error();
    if (Status s = layers(); !s) return s.error();
    if (Status s = footer(); !s) return s.error();
    if (Status s = file_->commit(); !s) return s.error();
    return summary_;
  }

  void line(std::string_view text) override {
    pending_.append(text);
    pending_.push_back('\n');
  }

 private:
  Status decide(Stage st, ctx::Context& c, ctx::PropertyValues& props) {
    c.set_props(&props);
    if (job_.rules.defaults)
      if (Status s = job_.rules.defaults->decide(st, c, props); !s) return s;
    if (job_.rules.decider)
      if (Status s = job_.rules.decider->decide(st, c, props); !s) return s;
    return ok_status();
  }

  Status decide_print() {
    const auto& layers = job_.layers;
    // Model extent from the layers; the model is centred on the bed.
    geo::BBox2 box = job_.model_box;
    if (box.empty())
      for (const auto& l : layers)
        for (const auto& isl : l.islands)
          for (const auto& p : isl.shape.outer) box.add(p);
    table_ = ctx::LayerTable(layers.size());
    for (size_t i = 0; i < layers.size(); ++i) {
      const auto& l = layers[i];
      double area = 0;
      for (const auto& isl : l.islands) area += geo::area_mm2(isl.shape);
      table_.set(i, FieldId::LayerIndex, static_cast<double>(i));
      table_.set(i, FieldId::LayerZBottom, l.z_bottom);
      table_.set(i, FieldId::LayerZ, l.z_top);
      table_.set(i, FieldId::LayerHeight, l.height());
      table_.set(i, FieldId::LayerArea, area);
      table_.set(i, FieldId::LayerIslands, static_cast<double>(l.islands.size()));
    }
    auto& c = setup_.print_ctx;
    c.set_layers(&table_);
    c.set(FieldId::PrintHeight, layers.back().z_top);
    c.set(FieldId::PrintSizeX, box.empty() ? 0 : geo::to_mm(box.max_x - box.min_x));
    c.set(FieldId::PrintSizeY, box.empty() ? 0 : geo::to_mm(box.max_y - box.min_y));
    c.set(FieldId::PrintVolume, job_.model_volume_mm3);
    c.set(FieldId::PrintLayers, static_cast<double>(layers.size()));
    setup_.print_props = ctx::PropertyValues::schema_defaults();
    if (Status s = decide(Stage::Print, c, setup_.print_props); !s) return s;
    const auto& P = setup_.print_props;
    if (!box.empty()) {
      setup_.shift = geo::Point(geo::to_units(0.5 * P[PropId::BedSizeX]) - (box.min_x + box.max_x) / 2,
                                geo::to_units(0.5 * P[PropId::BedSizeY]) - (box.min_y + box.max_y) / 2);
      if (geo::to_mm(box.max_x - box.min_x) > P[PropId::BedSizeX] ||
          geo::to_mm(box.max_y - box.min_y) > P[PropId::BedSizeY])
        report_.warn("bed-size", job_.model_name,
                     fmt::format("the model ({:.1f} × {:.1f} mm) is larger than the bed ({:g} × {:g} mm)",
                                 geo::to_mm(box.max_x - box.min_x), geo::to_mm(box.max_y - box.min_y),
                                 P[PropId::BedSizeX], P[PropId::BedSizeY]));
    }
    simplify_layers(layers);
    setup_.layers = simplified_;
    setup_.rules = job_.rules;
    // The skirt surrounds the convex hull of the first layer.
    geo::Ring pts;
    for (const auto& isl : layers.front().islands)
      for (const auto& p : isl.shape.outer) pts.push_back(p);
    setup_.skirt_around = convex_hull(pts);
    // Layer-stage values of layer 0, which the print's hooks read ({nozzle_temp}, {bed_temp}).
    ctx::Context c0 = c;
    c0.set(FieldId::LayerIndex, 0);
    c0.set(FieldId::LayerZBottom, layers.front().z_bottom);
    c0.set(FieldId::LayerZ, layers.front().z_top);
    c0.set(FieldId::LayerHeight, layers.front().height());
    c0.set(FieldId::LayerArea, table_.get(0, FieldId::LayerArea));
    c0.set(FieldId::LayerIslands, table_.get(0, FieldId::LayerIslands));
    first_layer_props_ = P;
    if (Status s = decide(Stage::Layer, c0, first_layer_props_); !s) return s;
    first_ctx_ = c0;
    flavor_ = static_cast<schema::Flavor>(static_cast<int>(P[PropId::GcodeFlavor]));
    return ok_status();
  }

  // Each layer's islands are read by its own task and by its neighbours' (skins, support,
  // overhang): simplified once here, in parallel, instead of by every reader. Only what the
  // toolpath stage reads is kept (no slicing loops, no cells).
  void simplify_layers(std::span<const geo::Layer> layers) {
    const geo::coord_t tol = geo::to_units(setup_.simplify_mm);
    simplified_.resize(layers.size());
    tbb::parallel_for(size_t{0}, layers.size(), [&](size_t i) {
      const geo::Layer& src = layers[i];
      geo::Layer& dst = simplified_[i];
      dst.index = src.index;
      dst.z_bottom = src.z_bottom;
      dst.z_top = src.z_top;
      dst.islands.reserve(src.islands.size());
      for (const auto& isl : src.islands) {
        geo::Island out;
        out.shape.outer = toolpath::simplify(isl.shape.outer, tol);
        if (out.shape.outer.empty()) continue;  // narrower than the tolerance
        for (const auto& h : isl.shape.holes)
          if (auto s = toolpath::simplify(h, tol); !s.empty()) out.shape.holes.push_back(std::move(s));
        out.area_mm2 = isl.area_mm2;
        out.fill_angle_deg = isl.fill_angle_deg;
        dst.islands.push_back(std::move(out));
      }
    });
  }

  static geo::Rings convex_hull(geo::Ring pts) {
    if (pts.size() < 3) return {};
    std::sort(pts.begin(), pts.end(), [](const geo::Point& a, const geo::Point& b) {
      return a.X < b.X || (a.X == b.X && a.Y < b.Y);
    });
    auto cross = [](const geo::Point& o, const geo::Point& a, const geo::Point& b) {
      return static_cast<double>(a.X - o.X) * static_cast<double>(b.Y - o.Y) -
             static_cast<double>(a.Y - o.Y) * static_cast<double>(b.X - o.X);
    };
    geo::Ring h(2 * pts.size());
    size_t k = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
      h[k++] = pts[i];
    }
    for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
      while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
      h[k++] = pts[i - 1];
    }
    h.resize(k - 1);
    return {h};
  }

  Status write(std::string_view s) { return file_->write(s); }

  Status slot(std::string_view prefix, size_t width, Slot& s) {
    if (Status st = write(prefix); !st) return st;
    s.offset = file_->offset();
    s.width = width;
    return write(std::string(width, ' ') + "\n");
  }
  Status fill(const Slot& s, const std::string& v) {
    std::string padded = v.substr(0, s.width);
    padded.resize(s.width, ' ');
    return file_->patch(s.offset, padded);
  }

  Status header() {
    const auto& P = setup_.print_props;
    std::string h;
    h += fmt::format("; generated by Tranche {}\n", "0.1.0");
    h += fmt::format("; model: {}\n", job_.model_name);
    if (Status s = write(h); !s) return s;
    if (Status s = slot("; estimated printing time (normal mode) = ", 16, time_slot_); !s) return s;
    if (Status s = slot("; filament used [mm] = ", 14, mm_slot_); !s) return s;
    if (Status s = slot("; filament used [cm3] = ", 12, cm3_slot_); !s) return s;
    if (Status s = slot("; filament used [g] = ", 12, g_slot_); !s) return s;
    h.clear();
    h += fmt::format(";FLAVOR:{}\n", flavor_ == schema::Flavor::RepRapFirmware ? "RepRap"
                                     : flavor_ == schema::Flavor::Klipper      ? "Klipper"
                                                                               : "Marlin");
    if (Status s = write(h); !s) return s;
    if (Status s = slot(";TIME:", 10, cura_time_slot_); !s) return s;
    if (Status s = slot(";Filament used: ", 12, cura_fil_slot_); !s) return s;
    h.clear();
    h += fmt::format(";Layer height: {}\n", P[PropId::LayerHeight]);
    h += fmt::format(";LAYER_COUNT:{}\n", job_.layers.size());
    h += "; settings (print-wide values, and the first layer's for properties decided per element):\n";
    for (const auto& info : schema::properties()) {
      double v = info.stage == Stage::Print ? P[info.id] : first_layer_props_[info.id];
      std::string val;
      if (info.type == schema::Type::Enum)
        val = std::string(schema::enum_value_name(info.enum_type, static_cast<int>(v)));
      else if (info.type == schema::Type::Bool)
        val = v != 0 ? "true" : "false";
      else
        val = fmt::format("{}", info.unit == schema::Unit::Ratio ? v : v);
      auto unit = schema::unit_name(info.unit);
      h += fmt::format(";   {} = {}{}{}\n", info.name, val,
                       unit.empty() || info.unit == schema::Unit::Ratio ? "" : " ",
                       info.unit == schema::Unit::Ratio ? "" : unit);
    }
    for (const auto& note : job_.notes) h += fmt::format("; {}\n", note);
    for (const auto& [k, v] : job_.sets) h += fmt::format("; --set {}={}\n", k, v);
    h += fmt::format("; filament_density = {} g/cm3 (for the weight estimate)\n\n", kFilamentDensity);
    if (Status s = write(h); !s) return s;
    // The start G-code is the `before print` executors (the printer profile's). When it sets
    // no temperature, the first layer's are set and waited for first, as PrusaSlicer does, so
    // that a print never starts cold. Then the E mode.
    if (Status st = write(";TYPE:Custom\n"); !st) return st;
    std::string start;
    if (Status st = executors(Level::Print, ctx::When::Before, first_ctx_, first_layer_props_, &start); !st)
      return st;
    std::string s;
    if (!sets_temperatures(start)) {
      s += fmt::format("M190 S{:g} ; no temperature in the start G-code: heat and wait\n",
                       first_layer_props_[PropId::BedTemp]);
      s += fmt::format("M109 S{:g}\n", first_layer_props_[PropId::NozzleTemp]);
    }
    s += start;
    s += P[PropId::RelativeE] != 0 ? "M83 ; relative extrusion\n" : "M82 ; absolute extrusion\n";
    s += "G92 E0\n";
    if (Status st = write(s); !st) return st;
    fan_ = -1;  // unknown after the start G-code: the first layer sets it
    nozzle_ = first_layer_props_[PropId::NozzleTemp];
    bed_ = first_layer_props_[PropId::BedTemp];
    return ok_status();
  }

  // Whether start G-code heats the nozzle: a temperature command, or a macro that takes one.
  static bool sets_temperatures(std::string_view g) {
    size_t i = 0;
    while (i < g.size()) {
      size_t e = g.find('\n', i);
      std::string_view line = g.substr(i, e == std::string_view::npos ? std::string_view::npos : e - i);
      line = line.substr(0, line.find(';'));
      for (std::string_view w : {"M104", "M109", "G10", "PRINT_START", "START_PRINT", "EXTRUDER="})
        if (line.find(w) != std::string_view::npos) return true;
      if (e == std::string_view::npos) break;
      i = e + 1;
    }
    return false;
  }

  // Runs the hook; its text goes to `into` when given, else to the file.
  Status executors(Level level, ctx::When when, const ctx::Context& c, const ctx::PropertyValues& props,
                   std::string* into = nullptr) {
    if (!job_.rules.executors || !job_.rules.executors->has(level, when)) return ok_status();
    ctx::Context cc = c;
    cc.set_props(&props);
    pending_.clear();
    if (Status s = job_.rules.executors->run(level, when, cc, *this); !s) return s;
    if (into) {
      *into += pending_;
      return ok_status();
    }
    return write(pending_);
  }

  struct Item {
    int index = 0;
    Status status = ok_status();
    LayerText text;
    double time_s = 0;
  };

  Status layers() {
    const int n = static_cast<int>(job_.layers.size());
    std::atomic<int> next{0};
    std::atomic<bool> failed{false};
    Status first_error = ok_status();
    std::unique_ptr<tbb::global_control> limit;
    if (job_.threads > 0)
      limit =
          std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, job_.threads);
    const size_t tokens = static_cast<size_t>(2 * std::max(1, tbb::info::default_concurrency()));
    toolpath::MotionClock clock(setup_.motion);
    bool has_last = false;
    geo::Point last;
    tbb::parallel_pipeline(
        tokens, tbb::make_filter<void, int>(tbb::filter_mode::serial_in_order,
                                            [&](tbb::flow_control& fc) {
                                              int i = next++;
                                              if (i >= n || failed.load()) {
                                                fc.stop();
                                                return 0;
                                              }
                                              return i;
                                            }) &
                    tbb::make_filter<int, std::shared_ptr<Item>>(tbb::filter_mode::parallel,
                                                                 [&](int i) {
                                                                   auto item = std::make_shared<Item>();
                                                                   item->index = i;
                                                                   if (failed.load()) return item;
                                                                   auto plan = toolpath::plan_layer(setup_, i,
                                                                                                    report_);
                                                                   if (!plan) {
                                                                     item->status = plan.error();
                                                                     return item;
                                                                   }
                                                                   item->time_s = plan->time_s;
                                                                   auto text = format_layer(setup_, *plan);
                                                                   if (!text) {
                                                                     item->status = text.error();
                                                                     return item;
                                                                   }
                                                                   item->text = std::move(*text);
                                                                   return item;
                                                                 }) &
                    tbb::make_filter<std::shared_ptr<Item>, void>(
                        tbb::filter_mode::serial_in_order, [&](std::shared_ptr<Item> item) {
                          if (failed.load()) return;
                          Status s = item->status;
                          if (s) s = emit_layer(*item, clock, has_last, last);
                          if (!s) {
                            first_error = s;
                            failed = true;
                          }
                        }));
    if (!first_error) return first_error;
    summary_.layers = n;
    return ok_status();
  }

  Status emit_layer(Item& item, toolpath::MotionClock& clock, bool& has_last, geo::Point& last) {
    const auto& P = setup_.print_props;
    LayerText& t = item.text;
    std::string out;
    out.reserve(t.text.size() + 256);
    size_t at = 0;
    // The layer change retracts when the travel from the previous layer's end is long.
    const double r = P[PropId::RetractLength];
    bool change_retract = false;
    geo::Ring via;  // combing route of the layer change
    if (t.any_move && r > 0) {
      double len = has_last
                       ? std::hypot(double(t.first.X - last.X), double(t.first.Y - last.Y)) * geo::kMmPerUnit
                       : 1e9;
      bool leaves = !has_last || !t.comber || !t.comber->inside(last) || !t.comber->direct(last, t.first);
      if (leaves && has_last && t.comber && len > P[PropId::RetractBeforeTravel]) {
        // From the layer below's last point, which may lie just outside this layer.
        if (auto in = t.comber->enter(last, P[PropId::Width])) {
          if (auto route = t.comber->route(*in, t.first)) {
            if (*in != last) via.push_back(*in);
            via.insert(via.end(), route->begin(), route->end());
            leaves = false;
            len = toolpath::Comber::length_mm(last, via, t.first);
          }
        }
      }
      change_retract = len > P[PropId::RetractLongTravel] || (leaves && len > P[PropId::RetractBeforeTravel]);
    }
    // Still retracted from the layer below (a replacer's retract ended it): this layer's first
    // extrusion unretracts, and the layer change does not retract a second time.
    const bool already = t.any_move && r > 0 && ends_retracted_;
    if (already) change_retract = true;
    const long rf = std::lround(P[PropId::RetractSpeed] * 60);
    const bool rel = P[PropId::RelativeE] != 0;
    for (const auto& m : t.marks) {
      out.append(t.text, at, m.offset - at);
      at = m.offset;
      switch (m.kind) {
        case LayerText::Mark::Kind::Fan:
          if (m.value != fan_) out += fan_command(flavor_, m.value) + "\n";
          fan_ = m.value;
          break;
        case LayerText::Mark::Kind::NozzleTemp:
          if (m.value != nozzle_) out += fmt::format("M104 S{} ; nozzle temperature\n", m.value);
          nozzle_ = m.value;
          break;
        case LayerText::Mark::Kind::BedTemp:
          if (m.value != bed_) out += fmt::format("M140 S{} ; bed temperature\n", m.value);
          bed_ = m.value;
          break;
        case LayerText::Mark::Kind::LayerRetract:
          if (already) {
            if (!rel) {  // the filament is where E = -retract_length after this layer's G92 E0
              out += "G92 E";
              append_fixed(out, -std::llround(r * 1e5), 5);
              out += '\n';
            }
          } else if (change_retract) {
            out += "G1 E";
            append_fixed(out, -std::llround(r * 1e5), 5);
            out += fmt::format(" F{}\n", rf);
            ++summary_.retractions;
          }
          break;
        case LayerText::Mark::Kind::LayerTravel:
          for (const auto& q : via) {
            out += "G1 X";
            append_fixed(out, round_um(q.X + setup_.shift.X), 3);
            out += " Y";
            append_fixed(out, round_um(q.Y + setup_.shift.Y), 3);
            out += '\n';
            ++summary_.travels;
          }
          break;
        case LayerText::Mark::Kind::LayerUnretract:
          if (change_retract) {
            out += "G1 E";
            append_fixed(out, rel ? std::llround(r * 1e5) : 0, 5);
            out += fmt::format(" F{}\n", rf);
          }
          break;
      }
    }
    out.append(t.text, at, std::string::npos);
    if (Status s = write(out); !s) return s;
    // Time: the layer's own estimate, plus the layer change (retract, z, travel, unretract).
    double change = 0;
    if (t.any_move) {
      if (change_retract) change += 2 * r / P[PropId::RetractSpeed];
      change += job_.layers[static_cast<size_t>(item.index)].height() / setup_.motion.z_speed;
      if (has_last) {
        for (double leg : legs_mm(last, via, t.first))
          change += toolpath::trapezoid_time(leg, P[PropId::TravelSpeed], 0, 0, setup_.motion.travel_accel);
      }
      last = t.last;
      has_last = true;
      ends_retracted_ = t.ends_retracted;
    }
    (void)clock;
    summary_.time_s += item.time_s + change;
    summary_.filament_mm += t.e_mm;
    summary_.travels += t.travels;
    summary_.retractions += t.retractions;
    return ok_status();
  }

  Status footer() {
    const auto& P = setup_.print_props;
    // The end G-code: the `after print` executors (the printer profile's).
    if (Status s = write(";TYPE:Custom\n"); !s) return s;
    if (Status s = executors(Level::Print, ctx::When::After, first_ctx_, first_layer_props_); !s) return s;
    summary_.filament_cm3 =
        summary_.filament_mm * toolpath::filament_area_mm2(P[PropId::FilamentDiameter]) / 1000.0;
    summary_.filament_g = summary_.filament_cm3 * kFilamentDensity;
    std::string time = format_duration(summary_.time_s);
    std::string f;
    f += "\n";
    f += fmt::format("; filament used [mm] = {:.2f}\n", summary_.filament_mm);
    f += fmt::format("; filament used [cm3] = {:.2f}\n", summary_.filament_cm3);
    f += fmt::format("; filament used [g] = {:.2f}\n", summary_.filament_g);
    f += fmt::format("; total filament used [g] = {:.2f}\n", summary_.filament_g);
    f += fmt::format("; estimated printing time (normal mode) = {}\n", time);
    f += fmt::format("; travel moves = {}\n; retractions = {}\n", summary_.travels, summary_.retractions);
    if (Status s = write(f); !s) return s;
    if (Status s = fill(time_slot_, time); !s) return s;
    if (Status s = fill(mm_slot_, fmt::format("{:.2f}", summary_.filament_mm)); !s) return s;
    if (Status s = fill(cm3_slot_, fmt::format("{:.2f}", summary_.filament_cm3)); !s) return s;
    if (Status s = fill(g_slot_, fmt::format("{:.2f}", summary_.filament_g)); !s) return s;
    if (Status s = fill(cura_time_slot_, fmt::format("{}", std::lround(summary_.time_s))); !s) return s;
    return fill(cura_fil_slot_, fmt::format("{:.5f}m", summary_.filament_mm / 1000.0));
  }

  const GcodeJob& job_;
  Report& report_;
  toolpath::PrintSetup setup_;
  ctx::LayerTable table_;
  ctx::PropertyValues first_layer_props_;
  ctx::Context first_ctx_;
  schema::Flavor flavor_ = schema::Flavor::Marlin;
  std::unique_ptr<OutputFile> file_;
  std::string pending_;
  Slot time_slot_, mm_slot_, cm3_slot_, g_slot_, cura_time_slot_, cura_fil_slot_;
  double fan_ = -1, nozzle_ = -1, bed_ = -1;
  bool ends_retracted_ = false;  // the last layer written ended retracted (LayerText::ends_retracted)
  GcodeSummary summary_;
  std::vector<geo::Layer> simplified_;  // what setup_.layers shows
};

}  // namespace

Result<GcodeSummary> write_gcode(const GcodeJob& job, Report& report) {
  PrintWriter w(job, report);
  return w.run();
}

}  // namespace tranche::gcode
