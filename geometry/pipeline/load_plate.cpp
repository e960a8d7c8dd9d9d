#include "geometry/pipeline/load_plate.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/polygon/layers.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"

namespace tranche::pipeline {
namespace {

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

// The object's mesh turned, scaled or mirrored as the plate says, not yet moved: sliced in its
// own frame, its islands then moved by whole nanometres (a model that is only moved is sliced
// from its file's coordinates, so its slices do not depend on where it lands).
geo::Mesh linear_mesh(const plate::Object& o) {
  plate::Object lin = o;
  lin.transform.translation().setZero();
  return plate::world_mesh(lin);
}

// The plate was placed on `placed` (decide_bed); the print stage must give the same bed.
Status same_bed(const plate::Bed& placed, const ctx::PropertyValues& print) {
  const plate::Bed now = bed_of(print);
  const std::pair<const char*, std::pair<double, double>> all[] = {
      {"bed_shape", {static_cast<double>(placed.shape), static_cast<double>(now.shape)}},
      {"bed_size_x", {placed.size_x_mm, now.size_x_mm}},
      {"bed_size_y", {placed.size_y_mm, now.size_y_mm}},
      {"bed_origin_x", {placed.origin_x_mm, now.origin_x_mm}},
      {"bed_origin_y", {placed.origin_y_mm, now.origin_y_mm}},
      {"max_print_height", {placed.max_height_mm, now.max_height_mm}}};
  for (const auto& [name, v] : all)
    if (v.first != v.second)
      return Error{"rules", fmt::format("{} is {:g} for an empty plate but {:g} for this one: a rule makes the bed "
                                        "depend on the plate (print.height, print.size_x/y, print.volume or "
                                        "object.count), but the plate is placed on the bed before those are "
                                        "measured; decide the bed without reading them",
                                        name, v.first, v.second)};
  return ok_status();
}

void move_island(geo::Island& island, const geo::Point& by) {
  auto move = [&](geo::Ring& r) {
    for (auto& p : r) p = geo::Point(p.X + by.X, p.Y + by.Y);
  };
  move(island.shape.outer);
  for (auto& h : island.shape.holes) move(h);
}

}  // namespace

Result<PrintStage> decide_print(const ctx::Cascade& cascade, const setup::PrintFacts& facts) {
  PrintStage p;
  p.ctx = setup::print_context(facts);
  auto props = cascade.print_props(p.ctx);
  if (!props) return props.error();
  p.props = std::move(*props);
  return p;
}

plate::Bed bed_of(const ctx::PropertyValues& P) {
  plate::Bed bed;
  bed.shape = P[schema::PropId::BedShape] == static_cast<double>(schema::BedShape::Circular) ? plate::Bed::Shape::Circle
                                                                                            : plate::Bed::Shape::Rectangle;
  bed.size_x_mm = P[schema::PropId::BedSizeX];
  bed.size_y_mm = bed.shape == plate::Bed::Shape::Circle ? bed.size_x_mm : P[schema::PropId::BedSizeY];
  bed.origin_x_mm = P[schema::PropId::BedOriginX];
  bed.origin_y_mm = P[schema::PropId::BedOriginY];
  bed.max_height_mm = P[schema::PropId::MaxPrintHeight];
  // The skirt's reach round the objects: its distance and loops (a loop at most 1.5 nozzles wide).
  if (P[schema::PropId::SkirtLoops] > 0)
    bed.margin_mm = P[schema::PropId::SkirtDistance] + P[schema::PropId::SkirtLoops] * 1.5 * P[schema::PropId::NozzleDiameter];
  return bed;
}

Result<plate::Bed> decide_bed(const ctx::Cascade& cascade) {
  auto print = decide_print(cascade, setup::PrintFacts{});
  if (!print) return print.error();
  return bed_of(print->props);
}

// Layer heights from the cascade (layer_height, first_layer_height, --set) up to `top` mm.
Result<std::vector<geo::Layer>> plan_heights(const ctx::Cascade& cascade, const PrintStage& print, double top,
                                             const std::string& model, const geo::SurfaceSlopes* slopes,
                                             Report* report) {
  const ctx::PropertyValues& P = print.props;
  const bool adaptive = P[schema::PropId::AdaptiveLayers] != 0;
  geo::AdaptiveParams ap;
  ap.min_height = P[schema::PropId::MinLayerHeight];
  ap.max_height = P[schema::PropId::MaxLayerHeight];
  ap.quality = P[schema::PropId::AdaptiveQuality];
  ap.smoothing = static_cast<int>(P[schema::PropId::AdaptiveSmoothing]);
  if (adaptive)
    if (Status s = geo::check_adaptive(ap); !s) return s.error();
  // The smoothing's cap on the planner's heights (none without adaptive layers or smoothing).
  const geo::SmoothHeights smooth = adaptive && slopes ? geo::SmoothHeights(*slopes, ap) : geo::SmoothHeights();
  // layer.max_slope looks max_layer_height ahead (at least 1 µm, for bounds adaptive_layers
  // does not check when it is off).
  const double ahead = std::isfinite(ap.max_height) ? std::max(0.001, ap.max_height) : 0.3;
  const bool slope = slopes && !slopes->empty() && (adaptive || cascade.reads(schema::FieldId::LayerMaxSlope));
  auto max_slope = [&](double z) { return slope ? slopes->max_slope_deg(z, z + ahead) : 0.0; };
  Status error = ok_status();
  size_t planned_layers = 0, overridden = 0;  // layers after the first, and those a rule decided
  geo::LayerHeightParams params;
  params.height = [&](int index, double z_bottom) {
    const double planned = adaptive ? (slopes ? slopes->adaptive_height(z_bottom, ap, smooth.cap(z_bottom)) : ap.max_height) : 0.0;
    auto h = cascade.layer_height(print.ctx, P, index, z_bottom, max_slope(z_bottom), planned);
    if (!h) {
      if (error) error = h.error();
      return 0.2;
    }
    if (index > 0) {
      ++planned_layers;
      // Decided by a rule or --set when it differs from the planner's height, or, when it
      // matches it (a layer planned where a fixed height would put it too), when it does not
      // follow the planner's height moved a little.
      bool decided = *h != planned;
      if (!decided && adaptive) {
        auto again = cascade.layer_height(print.ctx, P, index, z_bottom, max_slope(z_bottom), planned * (1 + 1e-6));
        decided = again && *again == *h;
      }
      overridden += decided;
    }
    return *h;
  };
  auto layers = geo::plan_layer_heights(top, params);
  if (!error) return error.error();
  if (!layers) return Error{model, layers.error().to_string()};
  for (auto& l : *layers) l.max_slope = max_slope(l.z_bottom);
  if (adaptive && report && planned_layers > 1 && overridden == planned_layers)
    report->warn("adaptive-overridden", model,
                 "adaptive_layers is on, but a rule or --set decides layer_height on every layer, so the planner's "
                 "heights are not used: drop --set layer_height, or limit the rule to the layers it is meant for");
  return layers;
}

Result<SlicedPlate> slice_plate(const plate::Plate& plate, const ctx::Cascade& cascade,
                                const geo::ResolveOptions& resolve, Progress& progress, Report& report) {
  SlicedPlate out;
  if (plate.objects.empty()) return Error{"", "no model given"};
  // Each object in its own frame, lifted onto the bed; where its centre goes on the bed.
  struct Part {
    geo::Mesh mesh;
    geo::MeshTopology topology;
    geo::Point shift;  // units: the object's frame + shift = bed coordinates
  };
  std::vector<Part> parts;
  progress.start("load");
  for (const plate::Object& o : plate.objects) {
    Part part;
    part.mesh = linear_mesh(o);
    const std::string name = o.file.empty() ? plate::display_name(o) : o.file;
    if (Status s = place(part.mesh, name); !s) return s.error();
    part.topology = geo::build_topology(part.mesh);
    warn_topology(part.topology, name, report);
    const geo::BBox3 lin = part.mesh.bbox(), world = plate::world_bbox(o);
    const geo::Point lo = geo::to_point(lin.min.x, lin.min.y), hi = geo::to_point(lin.max.x, lin.max.y);
    part.shift = geo::Point(geo::to_units(0.5 * (world.min.x + world.max.x)) - (lo.X + hi.X) / 2,
                            geo::to_units(0.5 * (world.min.y + world.max.y)) - (lo.Y + hi.Y) / 2);
    out.facts.height = std::max(out.facts.height, lin.max.z);
    out.facts.volume += part.mesh.volume();
    out.facts.box.add(geo::Point(lo.X + part.shift.X, lo.Y + part.shift.Y));  // bed coordinates
    out.facts.box.add(geo::Point(hi.X + part.shift.X, hi.Y + part.shift.Y));
    out.triangles += part.mesh.triangles.size();
    parts.push_back(std::move(part));
  }
  out.facts.placed = true;
  out.facts.shift = parts[0].shift;
  for (const plate::Object& o : plate.objects) {
    out.facts.objects.push_back(plate::display_name(o));
    out.facts.names.push_back(o.name);
  }
  progress.finish(fmt::format("{} triangles", out.triangles));
  auto print = decide_print(cascade, out.facts);
  if (!print) return print.error();
  out.print = std::move(*print);
  if (plate.bed)
    if (Status s = same_bed(*plate.bed, out.print.props); !s) return s.error();
  geo::SurfaceSlopes slopes;  // only when something reads it: it costs a pass over the triangles
  if (out.print.props[schema::PropId::AdaptiveLayers] != 0 || cascade.reads(schema::FieldId::LayerMaxSlope))
    for (const Part& part : parts) slopes.add(part.mesh);
  auto planned = plan_heights(cascade, out.print, out.facts.height,
                              plate.objects.size() == 1 ? plate.objects[0].file : std::string("the plate"), &slopes,
                              &report);
  if (!planned) return planned.error();
  out.layers = std::move(*planned);
  for (size_t k = 0; k < parts.size(); ++k) {
    Part& part = parts[k];
    const std::string name = plate.objects[k].file.empty() ? plate::display_name(plate.objects[k]) : plate.objects[k].file;
    std::vector<geo::Layer> layers = out.layers;
    progress.start(parts.size() == 1 ? "slice" : fmt::format("slice {}", plate::display_name(plate.objects[k])),
                   layers.size());
    geo::SliceParams params;
    params.progress = [&](size_t done) { progress.update(done); };
    auto stats = geo::slice_mesh(part.mesh, part.topology, layers, params, report);
    if (!stats) return Error{name + ": " + stats.error().where, stats.error().message};
    progress.finish(fmt::format("{} layers, {} loops", layers.size(), stats->loops));
    progress.start("islands", layers.size());
    if (auto st = geo::resolve_layers(layers, resolve, report, [&](size_t done) { progress.update(done); }); !st)
      return st.error();
    progress.finish();
    // The print's frame is the first object's: the others move by the difference, and the
    // writer adds the first one's shift (one model sliced alone is where it always was).
    const geo::Point by(part.shift.X - parts[0].shift.X, part.shift.Y - parts[0].shift.Y);
    for (size_t i = 0; i < layers.size(); ++i) {
      for (geo::Island& island : layers[i].islands) {
        if (by != geo::Point(0, 0)) move_island(island, by);
        island.object = static_cast<int>(k);
        out.layers[i].islands.push_back(std::move(island));
      }
      if (parts.size() == 1) out.layers[i].loops = std::move(layers[i].loops);
    }
  }
  return out;
}

}  // namespace tranche::pipeline
