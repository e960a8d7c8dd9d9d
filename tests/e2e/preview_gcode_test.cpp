// End to end: what a person looks at besides the G-code, from a real slice: the thumbnails in
// the G-code (decoded with libpng), the --export-preview page (self-contained, its layers and a
// known rule's file:line in a value chain) and `tranche slice --explain` (the library call and
// the executable).
#include <doctest/doctest.h>
#include <fmt/format.h>
#include <png.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "apps/slice_command.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "tests/geometry/preview/decode_util.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

// Line 2 halves the outer wall's speed; line 3 adds G-code before it.
const char* kWallRules =
    "# walls\n"
    "rule \"slow walls\" when path.kind == outer_perimeter { speed = speed * 50% }\n"
    "rule \"pa\" when path.kind == outer_perimeter { before path { gcode \"M900 K0.045\" } }\n";

struct Job {
  test::TempDir dir{"preview-e2e"};
  pipeline::SliceOptions o;
  std::string rules;
  Job() {
    o.quiet = true;
    o.model = (dir / "cube.stl").string();
    REQUIRE(geo::write_stl_binary(o.model, geo::box({20, 10, 5})).ok());
    rules = (dir / "walls.rules").string();
    std::ofstream(rules) << kWallRules;
    o.rules = {rules};
  }
  Result<pipeline::SliceSummary> run() {
    Report report;
    return app::slice(o, report);
  }
};

struct Picture {
  unsigned width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// libpng's decoder, independent of ours.
Picture decode_png(const std::string& bytes) {
  png_image pi{};
  pi.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_memory(&pi, bytes.data(), bytes.size()));
  pi.format = PNG_FORMAT_RGBA;
  Picture p;
  p.width = pi.width, p.height = pi.height;
  p.rgba.resize(PNG_IMAGE_SIZE(pi));
  REQUIRE(png_image_finish_read(&pi, nullptr, p.rgba.data(), 0, nullptr));
  return p;
}

// The base64 text of the thumbnail block of `size` ("220x124"), checked for PrusaSlicer's layout.
std::string thumbnail_base64(const std::string& g, const std::string& size) {
  const size_t at = g.find("; thumbnail begin " + size + " ");
  REQUIRE(at != std::string::npos);
  CHECK(at < g.find(";LAYER:0"));
  const size_t end = g.find("; thumbnail end", at);
  REQUIRE(end != std::string::npos);
  std::string data;  // lines of at most 78 base64 characters after "; "
  size_t line = g.find('\n', at) + 1;
  for (size_t next; line < end; line = next + 1) {
    next = g.find('\n', line);
    CHECK(next - line <= 80);
    data += g.substr(line + 2, next - line - 2);
  }
  CHECK(data.size() == std::stoul(g.substr(g.find(' ', at + 18) + 1)));  // the declared length
  return data;
}

struct Run {
  int status = -1;
  std::string out;
};

Run tranche_exe(const std::string& args) {
  std::string cmd = "'";  // appended, not added: GCC 12 warns (-Wrestrict) wrongly on "'" + string
  cmd.append((test::binary_dir() / "apps" / "tranche").string()).append("' ").append(args).append(" 2>&1");
  Run r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int raw = pclose(p);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// The top-level elements of the JSON array after "key":[ (counted by bracket depth).
size_t array_length(const std::string& json, const std::string& key) {
  size_t i = json.find("\"" + key + "\":[");
  REQUIRE(i != std::string::npos);
  i += key.size() + 4;
  size_t n = 0;
  int depth = 0;
  bool any = false;
  for (; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '"') {
      i = json.find('"', i + 1);  // strings hold no bracket that counts (escaped quotes aside)
      continue;
    }
    if (depth == 0 && c == ']') break;
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (depth == 0 && c == ',') ++n;
    any = true;
  }
  return any ? n + 1 : 0;
}

// Index of `s` in the preview's "strings" (-1: absent); strings hold no escaped quote here.
int string_index(const std::string& json, const std::string& s) {
  const size_t start = json.find("\"strings\":[") + 11, end = json.find("],\"provenance\"");
  int index = 0;
  for (size_t i = start; i < end; ++index) {
    const size_t close = json.find('"', i + 1);
    if (json.substr(i + 1, close - i - 1) == s) return index;
    i = close + 2;
  }
  return -1;
}

}  // namespace

TEST_CASE("thumbnails: PNG pictures of the print in PrusaSlicer's format, decoded: the declared size, not blank") {
  Job j;
  j.o.output_gcode = (j.dir / "cube.gcode").string();
  j.o.thumbnails = "16x16/PNG, 220x124/PNG";
  auto r = j.run();
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const std::string g = test::read_file(j.o.output_gcode);
  for (auto [w, h] : {std::pair{16u, 16u}, {220u, 124u}}) {
    const std::string data = thumbnail_base64(g, fmt::format("{}x{}", w, h));
    const Picture pic = decode_png(preview::test::base64_decode(data));
    CHECK(pic.width == w);
    CHECK(pic.height == h);
    // Not blank: the print covers part of the picture (opaque pixels, not every one), in more
    // than one shade (it is shaded by height and slope).
    size_t opaque = 0;
    std::set<uint32_t> colours;
    for (size_t i = 0; i + 3 < pic.rgba.size(); i += 4)
      if (pic.rgba[i + 3] > 0) {
        ++opaque;
        colours.insert(uint32_t(pic.rgba[i]) << 16 | uint32_t(pic.rgba[i + 1]) << 8 | pic.rgba[i + 2]);
      }
    const size_t all = size_t(w) * h;
    CHECK(opaque > all / 20);
    CHECK(opaque < all);
    CHECK(colours.size() > 1);
  }
  // The printer profile decides without the option; "none" removes them.
  j.o.thumbnails = "none";
  REQUIRE(j.run().ok());
  CHECK(test::read_file(j.o.output_gcode).find("thumbnail begin") == std::string::npos);
  j.o.thumbnails.clear();
  j.o.printer = "prusa-mk3s";
  REQUIRE(j.run().ok());
  const Picture mk3s = decode_png(preview::test::base64_decode(thumbnail_base64(test::read_file(j.o.output_gcode), "220x124")));
  CHECK(mk3s.width == 220);
  j.o.thumbnails = "16x16/JPG";
  auto bad = j.run();
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().where == "--thumbnails");
}

TEST_CASE("--export-preview: one self-contained page with every layer and the chain of a known rule with file:line") {
  Job j;
  j.o.output_gcode = (j.dir / "cube.gcode").string();
  j.o.export_preview = (j.dir / "cube.html").string();
  auto r = j.run();
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  CHECK(r->written.back() == j.o.export_preview);
  const std::string html = test::read_file(j.o.export_preview);
  REQUIRE(html.rfind("<!DOCTYPE html>", 0) == 0);
  // Self-contained: no file, script, style or font is fetched.
  for (const char* outside : {"http://", "https://", "<script src", "<link", "@import", "url("})
    CHECK_MESSAGE(html.find(outside) == std::string::npos, outside);
  const std::string open = "<script type=\"application/json\" id=\"tranche-data\">";
  const size_t a = html.find(open), b = html.find("</script>", a);
  REQUIRE(a != std::string::npos);
  const std::string json = html.substr(a + open.size(), b - a - open.size());
  CHECK(preview::test::json_value(json, "format") == "tranche-preview");
  CHECK(array_length(json, "layers") == static_cast<size_t>(r->layers));
  CHECK(r->layers == 25);  // 5 mm at 0.2 mm
  // The geometry inflates to the size the page declares.
  const std::string blob = preview::test::base64_decode(preview::test::json_value(json, "blob"));
  CHECK(preview::test::inflate(blob, std::stoul(preview::test::json_value(json, "blobBytes"))).size() > 1000);
  // The outer walls' speed chain: the rule "slow walls" of walls.rules, line 2; the executor "pa", line 3.
  const int rule = string_index(json, "slow walls"), file = string_index(json, j.rules);
  const int pa = string_index(json, "pa"), gcode = string_index(json, "M900 K0.045");
  REQUIRE(rule >= 0);
  REQUIRE(file >= 0);
  CHECK(json.find(fmt::format(",{},{},2,", rule, file)) != std::string::npos);
  CHECK(json.find(fmt::format("[0,{},{},{},3,{}]", static_cast<int>(schema::Level::Path), pa, file, gcode)) !=
        std::string::npos);
  // The same G-code as without the preview: recording changes nothing that is printed.
  const std::string with = test::read_file(j.o.output_gcode);
  j.o.export_preview.clear();
  REQUIRE(j.run().ok());
  CHECK(test::read_file(j.o.output_gcode) == with);
}

TEST_CASE("tranche slice --explain: the decided values of a real layer's paths, their chains, executors, replacer") {
  Job j;
  j.o.explain = "layer=3 island=0 path=outer_perimeter";
  auto r = j.run();
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const std::string& e = r->explanation;
  INFO(e);
  CHECK(e.rfind("layer 3 (z 0.80 mm), island 0, path ", 0) == 0);
  CHECK(e.find(": outer_perimeter, perimeter 0, ") != std::string::npos);
  CHECK(e.find("  speed = ") != std::string::npos);
  CHECK(e.find("60 mm/s schema default -> ") != std::string::npos);
  CHECK(e.find(fmt::format(" rule \"slow walls\" ({}:2)", j.rules)) != std::string::npos);
  CHECK(e.find("  flow = ") != std::string::npos);
  CHECK(e.find(fmt::format("  before path: rule \"pa\" ({}:3) wrote: M900 K0.045", j.rules)) != std::string::npos);
  CHECK(e.find("  no replacer: the default G-code") != std::string::npos);
  CHECK(r->written.empty());  // alone, --explain writes nothing
  // Every path of the layer; paths decided alike (two copies of the block) are explained once.
  j.o.explain = "layer=3";
  plate::PlateOptions two;
  two.files = {j.o.model};
  two.copies = {*plate::parse_copies("2")};
  Report report;
  auto all = app::slice(j.o, two, report);
  REQUIRE_MESSAGE(all.ok(), all.error().to_string());
  INFO(all->explanation);
  CHECK(all->explanation.find(": infill, cell 0") != std::string::npos);
  for (const char* island : {"island 0, path 2: outer_perimeter", "island 1, path 2: outer_perimeter"})
    CHECK(all->explanation.find(island) != std::string::npos);
  // The island printed second repeats nothing: each of its paths is "decided as" the first's.
  size_t alike = 0;
  for (size_t at = 0; (at = all->explanation.find("\n  decided as layer 3 (z 0.80 mm), island ", at)) != std::string::npos; ++at)
    ++alike;
  CHECK(alike == 3);
  // Specs that do not parse or match nothing are refused, saying what to write or what there is.
  for (auto [spec, says] : {std::pair{"layer=99", "past the top: the print has 25 layers (0 to 24)"},
                            {"layer=3 island=4", "layer 3 has 1 island (0 to 0)"},
                            {"layer=3 path=bridge", "no path of layer 3 matches; the layer has "},
                            {"layr=3", "'layr' is not a key"},
                            {"island=0", "which layer? write layer=N"},
                            {"layer=three", "layer= needs a whole number"},
                            {"layer=3 path=wall", "path= is a path kind"}}) {
    j.o.explain = spec;
    auto bad = j.run();
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().where == "--explain");
    CHECK_MESSAGE(bad.error().message.find(says) != std::string::npos, bad.error().message);
  }
}

TEST_CASE("tranche slice --explain, the executable: the explanation on stdout, exit 1 and a message for a bad spec") {
  Job j;
  const std::string common = "slice '" + j.o.model + "' --rules '" + j.rules + "' --quiet";
  const Run ok = tranche_exe(common + " --explain 'layer=2 path=outer_perimeter'");
  INFO(ok.out);
  CHECK(ok.status == 0);
  CHECK(ok.out.find("layer 2 (z 0.60 mm), island 0, path ") != std::string::npos);
  CHECK(ok.out.find("rule \"slow walls\" (" + j.rules + ":2)") != std::string::npos);
  CHECK(ok.out.find("wrote ") == std::string::npos);
  const Run bad = tranche_exe(common + " --explain 'layer=2 path=bridge'");
  CHECK(bad.status == 1);
  CHECK(bad.out.find("error: --explain: no path of layer 2 matches; the layer has ") != std::string::npos);
  const Run missing = tranche_exe(common + " --explain");
  CHECK(missing.status == 2);
  CHECK(missing.out.find("--explain needs which paths") != std::string::npos);
}
