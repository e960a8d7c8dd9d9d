// Writes the browser test's page: the fixture vase (fixture_print.h) as a preview, and a JSON of
// probes (bed points with the colour and the decider the page must show there); beside them,
// empty.html, the preview of a print with no layers.
//   preview_fixture OUT.html OUT.json [LAYERS]
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "geometry/preview/colours.h"
#include "geometry/preview/preview_html.h"
#include "tests/geometry/preview/fixture_print.h"

using namespace tranche::preview;
namespace schema = tranche::schema;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: preview_fixture OUT.html OUT.json [LAYERS]\n");
    return 2;
  }
  const int layers = argc > 3 ? std::stoi(argv[3]) : 60;
  const PreviewPrint print = fixture::vase_print(layers);
  if (auto st = write_preview_html(argv[1], print); !st) {
    std::fprintf(stderr, "preview_fixture: %s\n", st.error().to_string().c_str());
    return 1;
  }
  // An empty print (nothing to slice, or every layer empty) must open too.
  const std::string empty = (std::filesystem::path(argv[1]).parent_path() / "empty.html").string();
  if (auto st = write_preview_html(empty, PreviewPrint{}); !st) {
    std::fprintf(stderr, "preview_fixture: %s\n", st.error().to_string().c_str());
    return 1;
  }
  using schema::PathKind;
  const int mid = fixture::kSlowFrom + 2, top = layers - 1;
  auto front = [](int li) { return fixture::kCy - fixture::outer_radius(li); };  // bottom of the outer circle
  const float d = 0.7071068f;  // a point on the 45°/135° infill line through the centre
  std::string j = "{\"layers\":" + std::to_string(layers) + ",\"probes\":[";
  auto probe = [&](const char* name, int li, float x, float y, PathKind kind, const char* rule,
                   const char* where) {
    j += fmt::format(
        "{}{{\"name\":\"{}\",\"layer\":{},\"x\":{},\"y\":{},\"kind\":\"{}\",\"colour\":\"{}\",\"rule\":\"{}"
        "\",\"where\":\"{}\"}}",
        j.back() == '[' ? "" : ",", name, li, x, y,
        schema::enum_value_name(schema::EnumType::PathKind, static_cast<int>(kind)),
        to_hex(kind_colour(kind)), rule, where);
  };
  probe("outer wall, slow", mid, fixture::kCx, front(mid), PathKind::OuterPerimeter, "slow walls",
        "fixture.rules:4");
  probe("outer wall, top", top, fixture::kCx, front(top), PathKind::OuterPerimeter, "slow walls",
        "fixture.rules:4");
  probe("outer wall, default", 2, fixture::kCx, front(2), PathKind::OuterPerimeter, "outer perimeter speed",
        "stdlib/defaults.rules:14");
  probe("overhang piece", fixture::kOverhangLayer, fixture::kCx,
        fixture::kCy + fixture::outer_radius(fixture::kOverhangLayer), PathKind::OuterPerimeter, "overhangs",
        "fixture.rules:20");
  probe("infill", 4, fixture::kCx + 3 * d, fixture::kCy + 3 * d, PathKind::Infill, "fast infill",
        "fixture.rules:7");
  probe("top solid", top, fixture::kCx + 3 * d, fixture::kCy - 3 * d, PathKind::TopSolid, "top speed",
        "stdlib/defaults.rules:18");
  j += "]}\n";
  std::ofstream(argv[2]) << j;
  return 0;
}
