#include "geometry/pipeline/slice_job.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "geometry/io/layers_json.h"
#include "geometry/io/svg_export.h"
#include "geometry/mesh/stl.h"
#include "geometry/pipeline/progress.h"
#include "geometry/slice/layer_plan.h"
#include "geometry/slice/simple_islands.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"

namespace tranche::pipeline {
namespace {

bool ends_with_svg(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".svg";
}

// Options that later stages will honour; until then the user hears that they were ignored.
void warn_unapplied(const SliceOptions& o, Report& report) {
  if (!o.rules.empty() || !o.sets.empty())
    report.warn("not-implemented", "",
                "--rules and --set are not applied yet: layers are 0.2 mm, first layer 0.2 mm");
  if (o.overlap != OverlapMode::Additive)
    report.warn("not-implemented", "",
                "--overlap is not applied yet: overlapping shells are united (additive)");
  if (!o.fill_angle_script.empty())
    report.warn("not-implemented", "", "--fill-angle-script is not applied yet");
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

}  // namespace

Result<SliceSummary> run_slice(const SliceOptions& options, Report& report) {
  if (!options.output_gcode.empty())
    return Error{options.output_gcode,
                 "G-code output is not implemented yet; use --export-svg/--export-layers"};
  if (options.export_svg.empty() && options.export_layers.empty())
    return Error{"", "nothing to write: give --export-svg FILE and/or --export-layers FILE"};
  if (ends_with_svg(options.model))
    return Error{options.model, "SVG input is not wired into `tranche slice` yet"};
  warn_unapplied(options, report);
  Progress progress(!options.quiet);

  progress.start("load");
  auto mesh = geo::load_stl(options.model, report);
  if (!mesh) return mesh.error();
  if (auto st = place(*mesh, options.model); !st) return st.error();
  const geo::MeshTopology topology = geo::build_topology(*mesh);
  warn_topology(topology, options.model, report);
  progress.finish(fmt::format("{} triangles", mesh->triangles.size()));

  auto layers = geo::plan_layers(mesh->bbox().max.z, {});
  if (!layers) return Error{options.model, layers.error().to_string()};

  progress.start("slice", layers->size());
  geo::SliceParams params;
  params.progress = [&](size_t done) { progress.update(done); };
  auto stats = geo::slice_mesh(*mesh, topology, *layers, params, report);
  if (!stats) return Error{options.model + ": " + stats.error().where, stats.error().message};
  progress.finish(fmt::format("{} layers, {} loops", layers->size(), stats->loops));

  progress.start("union");
  if (auto st = geo::make_islands(*layers); !st) return st.error();
  progress.finish();

  SliceSummary summary;
  summary.layers = static_cast<int>(layers->size());
  summary.triangles = mesh->triangles.size();
  if (!options.export_svg.empty()) {
    progress.start("svg");
    if (auto st = geo::write_layers_svg(options.export_svg, *layers, options.model); !st) return st.error();
    progress.finish();
    summary.written.push_back(options.export_svg);
  }
  if (!options.export_layers.empty()) {
    progress.start("json");
    if (auto st = geo::write_layers_json(options.export_layers, *layers, options.model); !st)
      return st.error();
    progress.finish();
    summary.written.push_back(options.export_layers);
  }
  return summary;
}

}  // namespace tranche::pipeline
