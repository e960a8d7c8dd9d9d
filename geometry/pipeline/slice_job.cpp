#include "geometry/pipeline/slice_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <new>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "base/memory.h"
#include "base/run_files.h"
#include "geometry/fillangle/fill_angle.h"
#include "geometry/io/svg_import.h"
#include "geometry/mesh/stl.h"
#include "geometry/pipeline/driver.h"
#include "geometry/pipeline/explain_slice.h"
#include "geometry/pipeline/load_plate.h"
#include "geometry/pipeline/progress.h"
#include "geometry/pipeline/sequential.h"
#include "geometry/plan/support_pass.h"
#include "geometry/preview/preview_html.h"
#include "geometry/preview/thumbnails.h"
#include "geometry/polygon/layers.h"
#include "geometry/setup/print_setup.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"
#include "geometry/support/raft.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"

namespace tranche::pipeline {
namespace {

bool writes_files(const SliceOptions& o) {
  return !o.output_gcode.empty() || !o.export_svg.empty() || !o.export_layers.empty() || !o.export_preview.empty();
}

// Options that later stages will honour; until then the user hears that they were ignored.
void warn_unapplied(const SliceOptions& o, bool svg, Report& report) {
  if (o.overlap == OverlapMode::Subtractive && !svg)
    report.warn("overlap-svg-only", "",
                "--overlap subtractive applies to SVG drawings only; overlapping shells are united "
                "(additive)");
}

// The top (mm) of the first `n` layers the cascade plans: a drawing extruded by layer count.
Result<double> height_of_layers(const ctx::Cascade& cascade, const PrintStage& print, int n) {
  int64_t z = 0;
  for (int i = 0; i < n; ++i) {
    auto h = cascade.layer_height(print.ctx, print.props, i, static_cast<double>(z) / geo::kUnitsPerMm);
    if (!h) return h.error();
    if (!(*h >= 0.001) || !std::isfinite(*h))
      return Error{fmt::format("layer {}", i), fmt::format("layer height must be at least 0.001 mm, got {} mm", *h)};
    z += geo::to_units(*h);
  }
  return static_cast<double>(z) / geo::kUnitsPerMm;
}

// XY extent of the layers' loops (a drawing's).
geo::BBox2 loops_box(const std::vector<geo::Layer>& layers) {
  geo::BBox2 box;
  for (const auto& l : layers)
    for (const auto& r : l.loops)
      for (const auto& p : r) box.add(p);
  return box;
}

// SVG input: a layer stack keeps its own layers; a flat drawing is repeated on every layer of a
// prism --svg-height mm high, or of --svg-layers layers (10 by default), its heights planned by
// the cascade like an STL's. The print stage of a drawing extruded by layer count is decided
// before its height is known: there, print.height reads 0 (docs/architecture.md).
Result<SlicedPlate> load_svg(const SliceOptions& o, const ctx::Cascade& cascade, Report& report) {
  geo::SvgImportOptions so;
  so.tolerance_mm = o.svg_tolerance_mm;
  so.overlap = o.overlap == OverlapMode::Boolean       ? geo::SvgOverlap::Boolean
               : o.overlap == OverlapMode::Subtractive ? geo::SvgOverlap::Subtractive
                                                       : geo::SvgOverlap::Additive;
  so.background = o.background;
  auto model = geo::load_svg(o.model, so, report);
  if (!model) return model.error();
  SlicedPlate out;
  out.facts.objects = {o.model};
  out.facts.names = {std::filesystem::path(o.model).stem().string()};
  if (model->layer_stack) {
    if (o.svg_layers > 0 || o.svg_height_mm > 0)
      report.warn("svg-stack-height", o.model,
                  "--svg-layers and --svg-height are ignored: the layer stack has its own layers");
    for (size_t i = 0; i < model->layers.size(); ++i) {
      geo::Layer l;
      l.index = static_cast<int>(i);
      l.z_bottom = model->layers[i].z_bottom;
      l.z_top = model->layers[i].z_top;
      l.loops = geo::to_rings(model->layers[i].polygons);
      out.layers.push_back(std::move(l));
    }
    out.facts.height = out.layers.empty() ? 0 : out.layers.back().z_top;
    out.facts.box = loops_box(out.layers);
    auto print = decide_print(cascade, out.facts);
    if (!print) return print.error();
    out.print = std::move(*print);
    return out;
  }
  const geo::Rings loops = geo::to_rings(model->layers[0].polygons);
  for (const auto& r : loops)
    for (const auto& p : r) out.facts.box.add(p);
  out.facts.height = o.svg_height_mm;
  auto print = decide_print(cascade, out.facts);
  if (!print) return print.error();
  out.print = std::move(*print);
  if (o.svg_height_mm <= 0) {
    auto top = height_of_layers(cascade, out.print, o.svg_layers > 0 ? o.svg_layers : 10);
    if (!top) return Error{o.model, top.error().to_string()};
    out.facts.height = *top;
  }
  auto planned = plan_heights(cascade, out.print, out.facts.height, o.model);
  if (!planned) return planned.error();
  out.print.ctx.set(schema::FieldId::PrintHeight, out.facts.height);
  out.layers = std::move(*planned);
  for (auto& l : out.layers) l.loops = loops;
  return out;
}

// The outputs of a run, open while the layers are written.
struct Outputs {
  std::unique_ptr<preview::PreviewEncoder> preview;
  std::unique_ptr<gcode::GcodeWriter> gcode;
  std::unique_ptr<exports::LayersSvg> svg;
  std::unique_ptr<exports::LayersJson> json;
  exports::Sheet sheet;
};

// The thumbnails the G-code carries (--thumbnails, else the `thumbnails` property), drawn from the
// sliced islands as they will sit on the bed: a top view, shaded by height.
Result<std::string> thumbnails(const SliceOptions& o, const setup::PrintSetup& setup,
                               const std::vector<geo::Layer>& resolved) {
  std::string specs = o.thumbnails;
  if (specs.empty()) {
    const auto t = static_cast<schema::Thumbnails>(static_cast<int>(setup.print_props[schema::PropId::Thumbnails]));
    if (t == schema::Thumbnails::Png) specs = "16x16/PNG, 220x124/PNG";
    if (t == schema::Thumbnails::Qoi) specs = "16x16/QOI, 313x173/QOI, 440x240/QOI";
  }
  if (specs.empty() || specs == "none") return std::string();
  auto parsed = preview::parse_thumbnail_specs(specs);
  if (!parsed) return Error{"--thumbnails", parsed.error().message};
  const double dx = geo::to_mm(setup.shift.X), dy = geo::to_mm(setup.shift.Y);
  preview::BoxMm box{1e30f, 1e30f, -1e30f, -1e30f};
  for (const auto& l : resolved)
    for (const auto& isl : l.islands)
      for (const auto& p : isl.shape.outer) {
        const auto x = static_cast<float>(geo::to_mm(p.X) + dx), y = static_cast<float>(geo::to_mm(p.Y) + dy);
        box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x), std::max(box.y1, y)};
      }
  if (box.empty()) return std::string();
  return preview::thumbnails_gcode(
      box, [&](preview::HeightCanvas& c) {
        for (const auto& l : resolved) c.add_layer(l, dx, dy);
      }, *parsed);
}

Result<Outputs> open_outputs(const SliceOptions& o, const setup::PrintSetup& setup, const ctx::Cascade& cascade,
                             const std::vector<geo::Layer>& resolved) {
  Outputs out;
  if (!o.output_gcode.empty()) {
    gcode::GcodeInfo info;
    auto pictures = thumbnails(o, setup, resolved);
    if (!pictures) return pictures.error();
    info.thumbnails = std::move(*pictures);
    info.model_name = o.model;
    info.max_bytes = o.max_gcode_mb << 20;
    info.sets = o.sets;
    if (o.profile)
      info.notes.push_back(fmt::format("profile: stdlib defaults, printer {}, material {}", o.printer, o.material));
    for (const auto& r : o.rules) info.notes.push_back("rules: " + r);
    auto g = gcode::GcodeWriter::open(o.output_gcode, setup, cascade.executors(), info);
    if (!g) return g.error();
    out.gcode = std::move(*g);
  }
  if (!o.export_svg.empty()) {
    out.sheet = exports::sheet_layout(resolved, true);
    auto s = exports::LayersSvg::open(o.export_svg, o.model, setup.layers.size(), out.sheet, true);
    if (!s) return s.error();
    out.svg = std::move(*s);
  }
  // The preview is written whole at the end: its file is checked now, before any output is.
  if (!o.export_preview.empty())
    if (Status s = RunFiles::claim_output(o.export_preview, "the preview"); !s) return s.error();
  if (!o.export_preview.empty())
    out.preview = std::make_unique<preview::PreviewEncoder>(static_cast<float>(setup.print_props[schema::PropId::BedSizeX]),
                                                            static_cast<float>(setup.print_props[schema::PropId::BedSizeY]),
                                                            o.model);
  if (!o.export_layers.empty()) {
    auto j = exports::LayersJson::open(o.export_layers, o.model, setup.layers.size(), true, o.exact_cells);
    if (!j) return j.error();
    out.json = std::move(*j);
  }
  return out;
}

// print_order = sequential: each object, lowest first, planned and written whole (its own print
// setup: its islands, its script angles), the head rising above what is printed between them.
Status print_sequential(SlicedPlate& in, const setup::PrintSetup& all, LayerOutputs lo, geo::FillAngleScript* script,
                        ctx::Cascade& cascade, const SliceOptions& options, Report& report) {
  if (!lo.gcode) return ok_status();
  auto passes = sequential_passes(in.layers, all.objects, in.print.props);
  if (!passes) return passes.error();
  lo.svg = nullptr, lo.json = nullptr, lo.preview = nullptr;
  double printed_top = 0;
  for (size_t k = 0; k < passes->size(); ++k) {
    ObjectPass& pass = (*passes)[k];
    auto one = setup::make_setup(pass.layers, in.facts, in.print.ctx, in.print.props, cascade, options.model, report);
    if (!one) return one.error();
    (*one)->provenance = all.provenance;
    (*one)->allow_off_bed = all.allow_off_bed;
    (*one)->object_texts = all.object_texts;
    (*one)->skirt_around = k == 0 ? all.skirt_around : geo::Rings{};  // one skirt, round every object
    std::unique_ptr<geo::ScriptAngles> angles;
    if (script) {
      auto a = geo::ScriptAngles::compute(*script, (*one)->layers, cascade, (*one)->print_ctx, in.print.props);
      if (!a) return a.error();
      angles = std::move(*a);
      cascade.set_middle(angles.get());
    }
    plan::SupportPassOptions so;
    so.strict = options.strict;
    so.warn = false;  // said once, for the whole plate
    if (Status s = plan::plan_support(**one, cascade, report, so); !s) return s;
    lo.object_change_z = k == 0 ? 0 : printed_top + 1;
    if (Status s = run_layers(**one, cascade, lo, report); !s) return s;
    printed_top = std::max(printed_top, pass.top_mm);
  }
  return ok_status();
}

// object.name of each object: its name's index among the rules' texts. A text the rules compare
// names with that no object has is most likely a typo: a warning lists the names there are.
void name_objects(setup::PrintSetup& setup, const setup::PrintFacts& facts, const vm::RuleSet* rules, Report& report) {
  for (const std::string& name : facts.names) setup.object_texts.push_back(rules ? rules->text_index(name) : -1);
  if (!rules) return;
  for (const auto& [text, where] : rules->compared_texts()) {
    if (std::find(facts.names.begin(), facts.names.end(), text) != facts.names.end()) continue;
    std::string names;
    for (size_t i = 0; i < facts.names.size() && i < 12; ++i)
      if (names.find(fmt::format("'{}'", facts.names[i])) == std::string::npos)
        names += fmt::format("{}'{}'", names.empty() ? "" : ", ", facts.names[i]);
    report.warn("object-name", where.empty() ? "rules" : where,
                fmt::format("the rules compare object.name with \"{}\", but no object has that name (the names: {})",
                            text, names));
  }
}

// What every layer reads besides the setup, computed once before them: the script's angles (one
// serial pass: Python calls never race and results never depend on scheduling; the cascade's
// middle layer, kept alive by `angles`), then the support and the brim (plan/support_pass).
Status before_layers(setup::PrintSetup& setup, const SlicedPlate& in, geo::FillAngleScript* script,
                     std::unique_ptr<geo::ScriptAngles>& angles, ctx::Cascade& cascade, const SliceOptions& options,
                     Progress& progress, Report& report) {
  if (script) {
    progress.start("fill angles");
    auto a = geo::ScriptAngles::compute(*script, setup.layers, cascade, setup.print_ctx, in.print.props);
    if (!a) return a.error();
    angles = std::move(*a);
    cascade.set_middle(angles.get());
    progress.finish();
  }
  progress.start("support");
  plan::SupportPassOptions so;
  so.strict = options.strict;
  if (Status s = plan::plan_support(setup, cascade, report, so); !s) return s;
  progress.finish();
  return ok_status();
}

// The stages after slicing, shared by STL and SVG input: islands, print setup, the script's
// angles, then every layer planned and written.
Result<SliceSummary> finish(SlicedPlate& in, SliceSummary summary, geo::FillAngleScript* script,
                            const SliceOptions& options, Progress& progress, ctx::Cascade& cascade,
                            const vm::RuleSet* rules, Report& report) {
  auto tick = [&](size_t done) { progress.update(done); };
  std::vector<geo::Layer>& layers = in.layers;
  if (std::all_of(layers.begin(), layers.end(), [](const geo::Layer& l) { return l.islands.empty(); }))
    return Error{options.model,
                 "nothing to print: no layer has any material (a surface without volume?); check that the "
                 "model is a closed solid"};

  const int raft = static_cast<int>(in.print.props[schema::PropId::RaftLayers]);
  if (raft > 0) {
    support::RaftSpec rs;
    rs.layers = raft;
    rs.first_height = layers.front().height();
    rs.height = layers.size() > 1 ? layers[1].height() : layers.front().height();
    rs.gap = in.print.props[schema::PropId::RaftZGap];
    support::lift_onto_raft(layers, rs);
  }
  auto setup = setup::make_setup(layers, in.facts, in.print.ctx, in.print.props, cascade, options.model, report);
  if (!setup) return setup.error();
  const bool sequential =
      in.print.props[schema::PropId::PrintOrder] == static_cast<double>(schema::PrintOrder::Sequential) &&
      (*setup)->objects.size() > 1;
  if (sequential && raft > 0)
    return Error{options.model,
                 "raft_layers and print_order = sequential: a raft lies under every object at once, so the objects "
                 "cannot be printed one after the other on it; set raft_layers = 0 or print_order = layers"};
  (*setup)->allow_off_bed = options.allow_off_bed;
  name_objects(**setup, in.facts, rules, report);
  std::unique_ptr<geo::ScriptAngles> angles;
  if (Status s = before_layers(**setup, in, script, angles, cascade, options, progress, report); !s) return s.error();
  if (!options.explain.empty()) {  // the one layer explained records provenance; the run only for a preview
    auto spec = parse_explain_spec(options.explain);
    if (!spec) return spec.error();
    (*setup)->provenance = true;
    auto text = explain_slice(**setup, cascade, rules, *spec);
    if (!text) return text.error();
    summary.explanation = std::move(*text);
    if (!writes_files(options)) {
      summary.layers = static_cast<int>(layers.size());
      return summary;
    }
  }
  (*setup)->provenance = !options.export_preview.empty();
  auto outputs = open_outputs(options, **setup, cascade, layers);
  if (!outputs) return outputs.error();
  LayerOutputs lo;
  lo.gcode = outputs->gcode.get();
  lo.svg = outputs->svg.get();
  lo.sheet = &outputs->sheet;
  lo.json = outputs->json.get();
  lo.resolved = layers;
  lo.exact_cells = options.exact_cells;
  lo.preview = outputs->preview.get();
  lo.rules = rules;
  progress.start("toolpaths", layers.size());
  if (!sequential) {
    if (Status s = run_layers(**setup, cascade, lo, report, tick); !s) return s.error();
  } else {
    if (Status s = print_sequential(in, **setup, lo, script, cascade, options, report); !s) return s.error();
    lo.gcode = nullptr;  // the exports and the preview still show the layers in z order
    if (lo.svg || lo.json || lo.preview)
      if (Status s = run_layers(**setup, cascade, lo, report, tick); !s) return s.error();
  }
  summary.layers = static_cast<int>(layers.size());
  std::string detail;
  if (outputs->gcode) {
    auto g = outputs->gcode->finish();
    if (!g) return g.error();
    detail = fmt::format("{} layers, {:.2f} m of filament, {}", g->layers, g->filament_mm / 1000,
                         gcode::format_duration(g->time_s));
    summary.written.push_back(options.output_gcode);
  }
  if (outputs->svg) {
    if (Status s = outputs->svg->finish(); !s) return s.error();
    summary.written.push_back(options.export_svg);
  }
  if (outputs->json) {
    if (Status s = outputs->json->finish(); !s) return s.error();
    summary.written.push_back(options.export_layers);
  }
  if (outputs->preview) {
    if (Status s = preview::write_preview_html(options.export_preview, *outputs->preview); !s) return s.error();
    summary.written.push_back(options.export_preview);
  }
  progress.finish(detail);
  return summary;
}

}  // namespace

Status check_options(const SliceOptions& options) {
  if (!writes_files(options) && options.explain.empty())
    return Error{"", "nothing to write: give -o FILE.gcode, --export-svg FILE, --export-layers FILE, "
                     "--export-preview FILE.html and/or --explain \"layer=N ...\""};
  if (!options.explain.empty())
    if (auto spec = parse_explain_spec(options.explain); !spec) return spec.error();
  return ok_status();
}

namespace {

Result<SliceSummary> run_slice_unguarded(const SliceOptions& options, const plate::Plate* plate,
                                         const vm::RuleSet* rs, Report& report) {
  // A --set of a property to a plain value (`0.2`, `20%`, `rear`) is an override, the last layer
  // of the cascade; the others (expressions, params) were compiled into `rs` by the caller.
  std::vector<std::pair<std::string, std::string>> plain;
  for (const auto& [k, v] : options.sets)
    if (ctx::is_plain_override(k, v)) plain.emplace_back(k, v);
  auto cascade = ctx::Cascade::create(plain, rs, rs, rs);  // a bad --set fails before any work
  if (!cascade) return cascade.error();
  warn_unapplied(options, plate == nullptr, report);
  Progress progress(!options.quiet);

  std::unique_ptr<geo::FillAngleScript> script;  // loaded first: a broken script fails before slicing
  if (!options.fill_angle_script.empty()) {
    auto s = geo::FillAngleScript::load(options.fill_angle_script, options.script_timeout_s);
    if (!s) return s.error();
    script = std::move(*s);
  }

  SliceSummary summary;
  // Islands (geometry/polygon): an SVG arrives with its overlap mode already applied; a plate's
  // objects are resolved each on its own.
  geo::ResolveOptions resolve;
  resolve.overlap = plate && options.overlap == OverlapMode::Boolean ? geo::OverlapMode::Boolean
                                                                     : geo::OverlapMode::Additive;
  resolve.strict = options.strict;
  if (!plate) {
    progress.start("load");
    auto loaded = load_svg(options, **cascade, report);
    if (!loaded) return loaded.error();
    progress.finish(fmt::format("{} layers", loaded->layers.size()));
    progress.start("islands", loaded->layers.size());
    if (auto st = geo::resolve_layers(loaded->layers, resolve, report, [&](size_t n) { progress.update(n); }); !st)
      return st.error();
    progress.finish();
    return finish(*loaded, summary, script.get(), options, progress, **cascade, rs, report);
  }
  auto sliced = slice_plate(*plate, **cascade, resolve, progress, report);
  if (!sliced) return sliced.error();
  summary.triangles = sliced->triangles;
  return finish(*sliced, summary, script.get(), options, progress, **cascade, rs, report);
}

}  // namespace

Result<SliceSummary> run_slice(const SliceOptions& options, const plate::Plate* plate, const vm::RuleSet* rs,
                               Report& report) {
  if (Status s = check_options(options); !s) return s.error();
  // Out of memory anywhere (slicing, islands, the print setup; the layer loop names its layer): an
  // error like any other. The outputs are not committed, so nothing is written.
  try {
    return run_slice_unguarded(options, plate, rs, report);
  } catch (const std::bad_alloc&) {
    return out_of_memory("", "slicing");
  } catch (const std::runtime_error& e) {
    // TBB starts its worker threads on demand; with the address space used up, it cannot.
    if (std::string_view(e.what()).find("pthread_create") == std::string_view::npos) throw;
    return out_of_memory("", "starting the slicing threads");
  }
}

}  // namespace tranche::pipeline
