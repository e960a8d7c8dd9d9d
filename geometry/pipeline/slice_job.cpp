#include "geometry/pipeline/slice_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "geometry/fillangle/fill_angle.h"
#include "geometry/gcode/print.h"
#include "geometry/io/layers_json.h"
#include "geometry/io/svg_export.h"
#include "geometry/io/svg_import.h"
#include "geometry/mesh/stl.h"
#include "geometry/pipeline/progress.h"
#include "geometry/polygon/decompose.h"
#include "geometry/polygon/layers.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"

namespace tranche::pipeline {
namespace {

bool ends_with_svg(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".svg";
}

// Options that later stages will honour; until then the user hears that they were ignored.
void warn_unapplied(const SliceOptions& o, bool svg, Report& report) {
  if (o.overlap == OverlapMode::Subtractive && !svg)
    report.warn("overlap-svg-only", "",
                "--overlap subtractive applies to SVG drawings only; overlapping shells are united "
                "(additive)");
}

// Moves the model so that its lowest point is at z = 0; errors for meshes with nothing to slice.
Status place(geo::Mesh& mesh, const std::string& file) {
  if (mesh.triangles.empty()) return Error{file, "the model has no triangles: nothing to slice"};
  const geo::BBox3 b = mesh.bbox();
  for (double v : {b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z})
    if (!std::isfinite(v))
      return Error{file, "the model has coordinates that are not finite numbers; repair it"};
  const double height = b.max.z - b.min.z;
  if (!(height > 0))
    return Error{file,
                 fmt::format("the model is flat (all its points at z = {} mm): nothing to slice; give it a "
                             "thickness, or slice a drawing as SVG",
                             b.min.z)};
  mesh.transform(1.0, {0, 0, -b.min.z});
  return ok_status();
}

void warn_topology(const geo::MeshTopology& t, const std::string& file, Report& report) {
  if (t.boundary_edges)
    report.warn(
        "mesh-open", file,
        fmt::format("the mesh is not closed: {} edges belong to a single triangle; each layer's outline is "
                    "closed across the gaps (see the open-loop warnings)",
                    t.boundary_edges));
  if (t.nonmanifold_edges)
    report.warn("mesh-nonmanifold", file,
                fmt::format("{} edges are shared by more than two triangles (shells touching along an edge)",
                            t.nonmanifold_edges));
  if (t.misoriented_edges)
    report.warn(
        "mesh-orientation", file,
        fmt::format("{} edges join triangles of opposite winding: some triangles are flipped; outlines may "
                    "break there — repair the model's winding",
                    t.misoriented_edges));
}

// SVG input: a layer stack keeps its own layers; a flat drawing is repeated on every layer of a
// prism --svg-height mm high, or of --svg-layers layers (10 by default).
Result<std::vector<geo::Layer>> svg_layers(const SliceOptions& o, Report& report) {
  geo::SvgImportOptions so;
  so.tolerance_mm = o.svg_tolerance_mm;
  so.overlap = o.overlap == OverlapMode::Boolean       ? geo::SvgOverlap::Boolean
               : o.overlap == OverlapMode::Subtractive ? geo::SvgOverlap::Subtractive
                                                       : geo::SvgOverlap::Additive;
  so.background = o.background;
  auto model = geo::load_svg(o.model, so, report);
  if (!model) return model.error();
  std::vector<geo::Layer> layers;
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
      layers.push_back(std::move(l));
    }
    return layers;
  }
  geo::LayerHeightParams params;
  const int n = o.svg_layers > 0 ? o.svg_layers : 10;
  const double height =
      o.svg_height_mm > 0 ? o.svg_height_mm : params.first_layer_height + (n - 1) * params.layer_height;
  auto planned = geo::plan_layer_heights(height, params);
  if (!planned) return Error{o.model, planned.error().to_string()};
  const geo::Rings loops = geo::to_rings(model->layers[0].polygons);
  for (auto& l : *planned) l.loops = loops;
  return planned;
}

// The stages after slicing, shared by STL and SVG input.
// What the G-code stage needs to know about the model besides its layers.
struct ModelInfo {
  double volume_mm3 = 0;
  geo::BBox2 box;  // XY extent (units); empty: the layers' extent
};

Result<SliceSummary> finish(std::vector<geo::Layer>& layers, SliceSummary summary,
                            geo::FillAngleScript* script, const SliceOptions& options, Progress& progress,
                            const ctx::Cascade& cascade, const ModelInfo& model, Report& report) {
  auto tick = [&](size_t done) { progress.update(done); };
  // Islands (geometry/polygon): SVG input arrives with its overlap mode already applied.
  geo::ResolveOptions resolve;
  const bool boolean = options.overlap == OverlapMode::Boolean && !ends_with_svg(options.model);
  resolve.overlap = boolean ? geo::OverlapMode::Boolean : geo::OverlapMode::Additive;
  resolve.strict = options.strict;
  progress.start("islands", layers.size());
  if (auto st = geo::resolve_layers(layers, resolve, report, tick); !st) return st.error();
  progress.finish();
  if (std::all_of(layers.begin(), layers.end(), [](const geo::Layer& l) { return l.islands.empty(); }))
    return Error{options.model,
                 "nothing to print: no layer has any material (a surface without volume?); check that the "
                 "model is a closed solid"};

  if (script) {  // one serial pass: Python calls never race and results never depend on scheduling
    progress.start("fill angles");
    if (auto st = geo::apply_fill_angle_script(*script, layers); !st) return st.error();
    progress.finish();
  }
  if (!options.export_svg.empty() || !options.export_layers.empty()) {
    // Monotone cells at each island's fill angle, for the exports. The G-code stage cuts each
    // island's fill region (inside its perimeters) at the angle the rules decide, on its own.
    progress.start("cells", layers.size());
    if (auto st = geo::decompose_layers(layers, nullptr, &report, tick); !st) return st.error();
    progress.finish();
  } else {
    for (auto& l : layers)
      for (auto& is : l.islands)
        if (std::isnan(is.fill_angle_deg)) is.fill_angle_deg = geo::default_fill_angle(l.index);
  }

  summary.layers = static_cast<int>(layers.size());
  if (!options.export_svg.empty()) {
    progress.start("svg", layers.size());
    if (auto st = geo::write_layers_svg(options.export_svg, layers, options.model, tick); !st)
      return st.error();
    progress.finish();
    summary.written.push_back(options.export_svg);
  }
  if (!options.export_layers.empty()) {
    progress.start("json", layers.size());
    if (auto st = geo::write_layers_json(options.export_layers, layers, options.model, tick); !st)
      return st.error();
    progress.finish();
    summary.written.push_back(options.export_layers);
  }
  if (!options.output_gcode.empty()) {
    progress.start("gcode", layers.size());
    gcode::GcodeJob job;
    job.output = options.output_gcode;
    job.layers = layers;
    job.rules = cascade.rules();
    job.model_name = options.model;
    job.model_volume_mm3 = model.volume_mm3;
    job.model_box = model.box;
    job.sets = options.sets;
    if (options.profile)
      job.notes.push_back(fmt::format("profile: stdlib defaults, printer {}, material {}", options.printer,
                                      options.material));
    for (const auto& r : options.rules) job.notes.push_back("rules: " + r);
    auto g = gcode::write_gcode(job, report);
    if (!g) return g.error();
    progress.finish(fmt::format("{} layers, {:.2f} m of filament, {}", g->layers, g->filament_mm / 1000,
                                gcode::format_duration(g->time_s)));
    summary.written.push_back(options.output_gcode);
  }
  return summary;
}

// Layer heights from the cascade (layer_height, first_layer_height, --set).
Result<geo::LayerHeightParams> layer_heights(const ctx::Cascade& cascade, const ctx::Context& print, Status& error) {
  auto props = cascade.print_props(print);
  if (!props) return props.error();
  geo::LayerHeightParams params;
  params.height = [&cascade, print, p = *props, &error](int index, double z_bottom) {
    auto h = cascade.layer_height(print, p, index, z_bottom);
    if (!h) {
      if (error) error = h.error();
      return 0.2;
    }
    return *h;
  };
  return params;
}

}  // namespace

Status check_options(const SliceOptions& options) {
  if (options.output_gcode.empty() && options.export_svg.empty() && options.export_layers.empty())
    return Error{"", "nothing to write: give -o FILE.gcode, --export-svg FILE and/or --export-layers FILE"};
  return ok_status();
}

Result<SliceSummary> run_slice(const SliceOptions& options, const vm::RuleSet* rs, Report& report) {
  if (Status s = check_options(options); !s) return s.error();
  // A --set of a property to a plain value (`0.2`, `20%`, `rear`) is an override, the last layer
  // of the cascade; the others (expressions, params) were compiled into `rs` by the caller.
  std::vector<std::pair<std::string, std::string>> plain;
  for (const auto& [k, v] : options.sets)
    if (ctx::is_plain_override(k, v)) plain.emplace_back(k, v);
  auto cascade = ctx::Cascade::create(plain, rs, rs, rs);  // a bad --set fails before any work
  if (!cascade) return cascade.error();
  const bool svg = ends_with_svg(options.model);
  warn_unapplied(options, svg, report);
  Progress progress(!options.quiet);

  std::unique_ptr<geo::FillAngleScript> script;  // loaded first: a broken script fails before slicing
  if (!options.fill_angle_script.empty()) {
    auto s = geo::FillAngleScript::load(options.fill_angle_script);
    if (!s) return s.error();
    script = std::move(*s);
  }

  SliceSummary summary;
  if (svg) {
    progress.start("load");
    auto layers = svg_layers(options, report);
    if (!layers) return layers.error();
    progress.finish(fmt::format("{} layers", layers->size()));
    return finish(*layers, summary, script.get(), options, progress, **cascade, ModelInfo{}, report);
  }

  progress.start("load");
  auto mesh = geo::load_stl(options.model, report);
  if (!mesh) return mesh.error();
  if (auto st = place(*mesh, options.model); !st) return st.error();
  const geo::MeshTopology topology = geo::build_topology(*mesh);
  warn_topology(topology, options.model, report);
  progress.finish(fmt::format("{} triangles", mesh->triangles.size()));

  const geo::BBox3 box = mesh->bbox();
  ModelInfo model{mesh->volume(), {}};
  model.box.add(geo::to_point(box.min.x, box.min.y));
  model.box.add(geo::to_point(box.max.x, box.max.y));
  ctx::Context print;
  print.set(schema::FieldId::PrintHeight, box.max.z);
  print.set(schema::FieldId::PrintSizeX, box.max.x - box.min.x);
  print.set(schema::FieldId::PrintSizeY, box.max.y - box.min.y);
  print.set(schema::FieldId::PrintVolume, model.volume_mm3);
  Status height_error = ok_status();
  auto heights = layer_heights(**cascade, print, height_error);
  if (!heights) return heights.error();
  auto layers = geo::plan_layer_heights(box.max.z, *heights);
  if (!height_error) return height_error.error();
  if (!layers) return Error{options.model, layers.error().to_string()};

  progress.start("slice", layers->size());
  geo::SliceParams params;
  params.progress = [&](size_t done) { progress.update(done); };
  auto stats = geo::slice_mesh(*mesh, topology, *layers, params, report);
  if (!stats) return Error{options.model + ": " + stats.error().where, stats.error().message};
  progress.finish(fmt::format("{} layers, {} loops", layers->size(), stats->loops));
  summary.triangles = mesh->triangles.size();
  return finish(*layers, summary, script.get(), options, progress, **cascade, model, report);
}

}  // namespace tranche::pipeline
