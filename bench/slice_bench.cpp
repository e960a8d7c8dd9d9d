// slice_bench: times the slicing stages on one model and prepares benchmark models.
//   slice_bench run MODEL.stl [--svg OUT.svg] [--json OUT.json] [--name NAME]
//       one table row: triangles, layers, seconds per stage (load, plan, slice, union, svg, json),
//       total, and peak memory (getrusage maxrss)
//   slice_bench header                         the table's header line
//   slice_bench write-demo OUT.stl             the demo model (examples/models/demo.stl)
//   slice_bench write-torus OUT.stl [M N]      a torus of 2 × M × N triangles (default 1280 × 320)
//   slice_bench prepare-bunny IN.stl OUT.stl   metres, Y up → mm, Z up: ×1000, (x, y, z) → (x, −z, y)
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "geometry/export/layers_json.h"
#include "geometry/export/layers_svg.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/simple_islands.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"

using namespace tranche;
using namespace tranche::geo;

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int fail(const std::string& msg) {
  std::fprintf(stderr, "slice_bench: %s\n", msg.c_str());
  return 1;
}

int write(const std::string& path, const Mesh& m) {
  auto st = write_stl_binary(path, m);
  if (!st) return fail(st.error().to_string());
  std::printf("wrote %s (%zu triangles)\n", path.c_str(), m.triangles.size());
  return 0;
}

int prepare_bunny(const std::string& in, const std::string& out) {
  Report report;
  auto mesh = load_stl(in, report);
  if (!mesh) return fail(mesh.error().to_string());
  // A rotation of +90° about x (determinant +1): the winding, and so the outside, is kept.
  for (auto& v : mesh->vertices) v = {v.x * 1000, -v.z * 1000, v.y * 1000};
  return write(out, *mesh);
}

void header() {
  fmt::print("{:<14} {:>9} {:>6} {:>6} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7} {:>8} {:>6}\n", "model",
             "triangles", "layers", "empty", "load s", "plan s", "slice s", "union s", "svg s", "json s",
             "total s", "maxrss", "open");
}

int run(int argc, char** argv) {
  std::string model, svg, json, name;
  for (int i = 2; i < argc; ++i) {
    std::string_view a = argv[i];
    if (a == "--svg" && i + 1 < argc)
      svg = argv[++i];
    else if (a == "--json" && i + 1 < argc)
      json = argv[++i];
    else if (a == "--name" && i + 1 < argc)
      name = argv[++i];
    else
      model = argv[i];
  }
  if (model.empty()) return fail("run needs a model");
  if (name.empty()) name = model;
  Report report;
  const auto t0 = Clock::now();
  auto t = Clock::now();
  auto mesh = load_stl(model, report);
  if (!mesh) return fail(mesh.error().to_string());
  const BBox3 b = mesh->bbox();
  mesh->transform(1.0, {0, 0, -b.min.z});
  const double t_load = since(t);

  t = Clock::now();
  auto layers = plan_layer_heights(b.max.z - b.min.z, {});
  if (!layers) return fail(layers.error().to_string());
  const double t_plan = since(t);

  t = Clock::now();
  const MeshTopology topo = build_topology(*mesh);
  auto stats = slice_mesh(*mesh, topo, *layers, {}, report);
  if (!stats) return fail(stats.error().to_string());
  const double t_slice = since(t);

  t = Clock::now();
  if (auto st = make_islands(*layers); !st) return fail(st.error().to_string());
  const double t_union = since(t);

  double t_svg = 0, t_json = 0;
  if (!svg.empty()) {
    t = Clock::now();
    if (auto st = exports::write_layers_svg(svg, *layers, model); !st) return fail(st.error().to_string());
    t_svg = since(t);
  }
  if (!json.empty()) {
    t = Clock::now();
    if (auto st = exports::write_layers_json(json, *layers, model); !st) return fail(st.error().to_string());
    t_json = since(t);
  }
  const double total = since(t0);
  size_t empty = 0;
  for (const auto& l : *layers) empty += l.islands.empty();
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  fmt::print(
      "{:<14} {:>9} {:>6} {:>6} {:>7.3f} {:>7.3f} {:>7.3f} {:>7.3f} {:>7.3f} {:>7.3f} {:>7.3f} {:>6}MB "
      "{:>6}\n",
      name, mesh->triangles.size(), layers->size(), empty, t_load, t_plan, t_slice, t_union, t_svg, t_json,
      total, ru.ru_maxrss / 1024, report.count("open-loop"));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string_view cmd = argc > 1 ? argv[1] : "";
  if (cmd == "run") return run(argc, argv);
  if (cmd == "header") return header(), 0;
  if (cmd == "write-demo" && argc == 3) return write(argv[2], demo_model());
  if (cmd == "write-torus" && (argc == 3 || argc == 5)) {
    int m = argc == 5 ? std::atoi(argv[3]) : 1280, n = argc == 5 ? std::atoi(argv[4]) : 320;
    if (m < 3 || n < 3) return fail("torus segments must be at least 3");
    return write(argv[2], torus(30, 10, m, n));
  }
  if (cmd == "prepare-bunny" && argc == 4) return prepare_bunny(argv[2], argv[3]);
  return fail(
      "usage: slice_bench run MODEL.stl [--svg F] [--json F] [--name N] | header | write-demo OUT.stl | "
      "write-torus OUT.stl [M N] | prepare-bunny IN.stl OUT.stl");
}
