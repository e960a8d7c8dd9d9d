// libFuzzer target: a whole slice. A small mesh made from the input's bytes goes through the
// pipeline — slicing, islands, the print setup, the layer loop with rules (properties, hooks,
// replacers), toolpaths — into the G-code writer and the layer export, as `tranche slice` runs
// it. Every run must give files or an Error, never crash or hang.
//
// The input: byte 0 picks the layer height and which rules apply; byte 1 the shape: a closed
// solid (a cube's 8 corners moved by the next 24 bytes) or a triangle soup (vertices and
// triangles from the bytes, open or self-crossing as they come). Seeds: fuzz/corpus/slice/.
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "compiler/load_rules.h"
#include "geometry/pipeline/slice_job.h"
#include "geometry/plate/object.h"

namespace {

namespace fs = std::filesystem;
using tranche::geo::Mesh;

constexpr const char* kRules = R"(rule "fast" when layer.index > 1 { speed = speed * 120% }
rule "hooks" { before layer { gcode "M117 L{layer.index}" } }
on layer.start when layer.index == 2 { gcode "M600" }
rule "shrink" when island.area < 30 mm2 { replace island { offset -0.1 mm; default } }
rule "angle" { fill_angle = 30 deg * layer.index }
)";

struct Setup {
  fs::path dir;
  std::shared_ptr<const tranche::vm::RuleSet> with_rules, profile_only;
};

const Setup& setup() {
  static const Setup s = [] {
    Setup out;
    out.dir = fs::temp_directory_path() / ("fuzz-slice-" + std::to_string(::getpid()));
    fs::create_directories(out.dir);
    std::atexit([] {  // libFuzzer ends with exit(): the scratch folder goes with it
      std::error_code ec;
      fs::remove_all(fs::temp_directory_path() / ("fuzz-slice-" + std::to_string(::getpid())), ec);
    });
    const fs::path rules = out.dir / "fuzz.rules";
    std::ofstream(rules) << kRules;
    tranche::Report report;
    tranche::compiler::RulesInput in;
    in.files = {rules.string()};
    auto a = tranche::compiler::load_rules(in, report);
    in.files.clear();
    auto b = tranche::compiler::load_rules(in, report);
    if (!a || !b) std::abort();  // the fixed rules must compile
    out.with_rules = *a;
    out.profile_only = *b;
    return out;
  }();
  return s;
}

// A cube whose corners the bytes move by up to ±2.5 mm: closed, maybe folded.
Mesh moved_cube(const uint8_t* d, size_t n) {
  Mesh m;
  for (int i = 0; i < 8; ++i) {
    auto off = [&](int k) { return static_cast<size_t>(3 * i + k) < n ? (d[3 * i + k] - 128) / 51.2 : 0.0; };
    m.vertices.push_back({(i & 1) * 8.0 + off(0), (i >> 1 & 1) * 8.0 + off(1), (i >> 2 & 1) * 6.0 + off(2)});
  }
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Up to 16 vertices on a 0.5 mm grid in a 10 mm box, then triangles of their indices.
Mesh soup(const uint8_t* d, size_t n) {
  Mesh m;
  const size_t nv = n < 1 ? 0 : std::min<size_t>(d[0] % 16 + 3, (n - 1) / 3);
  for (size_t i = 0; i < nv; ++i)
    m.vertices.push_back({d[1 + 3 * i] % 21 * 0.5, d[2 + 3 * i] % 21 * 0.5, d[3 + 3 * i] % 13 * 0.5});
  for (size_t at = 1 + 3 * nv; at + 2 < n && m.triangles.size() < 32 && nv > 0; at += 3) {
    const uint32_t a = d[at] % nv, b = d[at + 1] % nv, c = d[at + 2] % nv;
    if (a != b && b != c && a != c) m.triangles.push_back({a, b, c});
  }
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const Setup& s = setup();
  tranche::plate::Object o;
  o.name = "fuzz";
  o.mesh = data[1] & 1 ? soup(data + 2, size - 2) : moved_cube(data + 2, size - 2);
  if (o.mesh.triangles.empty()) return 0;
  double low = o.mesh.vertices[0].z;
  for (const auto& v : o.mesh.vertices) low = std::min(low, v.z);
  o.transform = Eigen::Affine3d(Eigen::Translation3d(100, 100, -low));  // on the bed, as the plate puts it
  tranche::plate::Plate plate;
  plate.objects.push_back(std::move(o));

  tranche::pipeline::SliceOptions options;
  options.model = "fuzz";
  options.quiet = true;
  options.output_gcode = (s.dir / "out.gcode").string();
  if (data[0] & 0x10) options.export_layers = (s.dir / "out.json").string();
  const double heights[] = {0.1, 0.2, 0.3, 0.45};
  options.sets = {{"layer_height", std::to_string(heights[data[0] & 3])}};
  if (data[0] & 0x20) options.sets.push_back({"perimeters", std::to_string(data[0] >> 6)});
  options.max_gcode_mb = 64;
  tranche::Report report;
  const tranche::vm::RuleSet* rules = (data[0] & 4 ? s.with_rules : s.profile_only).get();
  auto r = tranche::pipeline::run_slice(options, &plate, rules, report);
  if (!r && r.error().message.empty()) std::abort();
  return 0;
}
