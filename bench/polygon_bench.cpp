// polygon_bench: times the polygon stage (overlap resolution, monotone decomposition) against
// slicing on one model, and prints cells per island.
//   polygon_bench header                              the table's header line
//   polygon_bench run MODEL.stl [--name N] [--y-up-metres] [--runs N]
//       one row: layers, islands, cells per island (mean, max), slicing time, resolution and
//       decomposition time per layer, and the polygon stage as a fraction of slicing
//       (--y-up-metres: ×1000 and Y up → Z up, for the Stanford bunny of stl-models)
//   polygon_bench write-plate OUT.stl                 a 100 × 80 mm plate with 48 holes
#include <chrono>
#include <cstdio>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/polygon/layers.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"

using namespace tranche;
using namespace tranche::geo;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int fail(const std::string& msg) {
  std::fprintf(stderr, "polygon_bench: %s\n", msg.c_str());
  return 1;
}

void header() {
  fmt::print("{:<22} {:>7} {:>8} {:>6} {:>5} {:>9} {:>11} {:>11} {:>8}\n", "model", "layers", "islands",
             "cells", "max", "slice ms", "resolve ms", "decomp ms", "share");
  fmt::print("{:<22} {:>7} {:>8} {:>6} {:>5} {:>9} {:>11} {:>11} {:>8}\n", "", "", "", "/isl.", "/isl.",
             "total", "per layer", "per layer", "of slice");
}

int run(int argc, char** argv) {
  std::string model, name;
  bool y_up = false;
  int runs = 1;
  for (int i = 2; i < argc; ++i) {
    std::string_view a = argv[i];
    if (a == "--name" && i + 1 < argc) {
      name = argv[++i];
    } else if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--y-up-metres") {
      y_up = true;
    } else {
      model = argv[i];
    }
  }
  if (model.empty()) return fail("run needs a model");
  if (name.empty()) name = model.substr(model.find_last_of('/') + 1);
  Report report;
  auto mesh = load_stl(model, report);
  if (!mesh) return fail(mesh.error().to_string());
  if (y_up) {
    for (auto& v : mesh->vertices) v = {v.x * 1000, -v.z * 1000, v.y * 1000};
  }
  mesh->transform(1.0, {0, 0, -mesh->bbox().min.z});
  const MeshTopology topology = build_topology(*mesh);

  // Best of `runs` for each stage: the machine is shared.
  double slice_s = 1e300, resolve_s = 1e300, decompose_s = 1e300;
  std::vector<Layer> layers;
  std::vector<LayerCells> cells_of;
  for (int r = 0; r < runs; ++r) {
    auto planned = plan_layer_heights(mesh->bbox().max.z, {});
    if (!planned) return fail(planned.error().to_string());
    layers = std::move(*planned);
    Report rep;
    auto t = Clock::now();
    auto st = slice_mesh(*mesh, topology, layers, {}, rep);
    if (!st) return fail(st.error().to_string());
    slice_s = std::min(slice_s, since(t));
    t = Clock::now();
    if (auto s = resolve_layers(layers, {}, rep); !s) return fail(s.error().to_string());
    resolve_s = std::min(resolve_s, since(t));
    t = Clock::now();
    auto decomposed = decompose_layers(layers, [](const Layer& l, size_t) { return l.index % 2 ? 135.0 : 45.0; });
    if (!decomposed) return fail(decomposed.error().to_string());
    decompose_s = std::min(decompose_s, since(t));
    cells_of = std::move(*decomposed);
  }
  size_t islands = 0, cells = 0, max_cells = 0;
  for (const LayerCells& l : cells_of) {
    for (const auto& is : l) {
      ++islands;
      cells += is.size();
      max_cells = std::max(max_cells, is.size());
    }
  }
  const double n = static_cast<double>(std::max<size_t>(1, layers.size()));
  fmt::print(
      "{:<22} {:>7} {:>8} {:>6.2f} {:>5} {:>9.1f} {:>11.3f} {:>11.3f} {:>7.0f}%\n", name, layers.size(),
      islands, islands ? static_cast<double>(cells) / static_cast<double>(islands) : 0.0, max_cells,
      slice_s * 1e3, resolve_s * 1e3 / n, decompose_s * 1e3 / n, 100 * (resolve_s + decompose_s) / slice_s);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string_view cmd = argc > 1 ? argv[1] : "";
  if (cmd == "header") {
    header();
    return 0;
  }
  if (cmd == "run") return run(argc, argv);
  if (cmd == "write-plate" && argc == 3) {
    const Mesh m = plate_with_holes(100, 80, 5, 8, 6, 4, 48);
    if (auto st = write_stl_binary(argv[2], m); !st) return fail(st.error().to_string());
    return 0;
  }
  return fail(
      "usage: polygon_bench header | run MODEL.stl [--name N] [--y-up-metres] [--runs N] | write-plate "
      "OUT.stl");
}
