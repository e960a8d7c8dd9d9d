#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "geometry/preview/preview_data.h"
#include "tests/geometry/preview/decode_util.h"
#include "tests/geometry/preview/fixture_print.h"

using namespace tranche;
using namespace tranche::preview;
using tranche::preview::test::VarintReader;

namespace {

PreviewPath line_path(std::vector<PointMm> pts) {
  PreviewPath p;
  p.kind = schema::PathKind::OuterPerimeter;
  p.points = std::move(pts);
  p.width = {0.45f};
  p.speed = {25};
  p.flow = {1};
  return p;
}

std::string blob_of(const std::string& json) {
  const std::string b64 = test::json_value(json, "blob");
  const size_t size = std::stoul(test::json_value(json, "blobBytes"));
  return test::inflate(test::base64_decode(b64), size);
}

}  // namespace

TEST_CASE(
    "preview data: the blob holds each path's header, values and delta-coded points as docs/preview.md "
    "says") {
  PreviewPrint print;
  PreviewLayer layer;
  layer.z = 0.2f;
  layer.height = 0.2f;
  PreviewPath p = line_path({{10, 20}, {10.5f, 20}, {10.5f, 21.25f}});
  p.kind = schema::PathKind::Bridge;
  p.speed = {25, 12.5f};  // per piece
  p.fan = 0.5f;
  p.nozzle_temp = 215;
  p.island = 2;
  layer.paths.push_back(p);
  layer.travels.push_back({{10.5f, 21.25f}, {0, 0}, {{5, 5}}, true});
  print.layers.push_back(layer);

  auto json = encode_preview_json(print);
  REQUIRE(json.ok());
  CHECK(json->find('<') == std::string::npos);
  CHECK(test::json_value(*json, "format") == "tranche-preview");
  CHECK(test::json_value(*json, "version") == "1");
  CHECK(json->find("\"counts\":{\"paths\":1,\"points\":3,\"travels\":1,\"travelPoints\":3}") !=
        std::string::npos);

  const std::string blob = blob_of(*json);
  VarintReader r{blob};
  CHECK(r.u() == static_cast<uint64_t>(schema::PathKind::Bridge));
  CHECK(r.u() == 3);      // points
  CHECK(r.u() == 2);      // flags: speed per piece
  CHECK(r.u() == 0);      // no provenance
  CHECK(r.s() == 2);      // island
  CHECK(r.s() == -1);     // cell
  CHECK(r.s() == -1);     // perimeter
  CHECK(r.s() == 500);    // fan, 1/1000
  CHECK(r.s() == 2150);   // nozzle, 0.1 °C
  CHECK(r.s() == 450);    // width, µm
  CHECK(r.s() == 2500);   // speed, 0.01 mm/s, piece 1
  CHECK(r.s() == 1250);   // piece 2
  CHECK(r.s() == 10000);  // flow, 1/10000
  CHECK(r.s() == 1000);   // x 10 mm in 10 µm
  CHECK(r.s() == 2000);
  CHECK(r.s() == 50);  // +0.5 mm
  CHECK(r.s() == 0);
  CHECK(r.s() == 0);
  CHECK(r.s() == 125);  // +1.25 mm
  CHECK(r.u() == 1);    // travel: retracted
  CHECK(r.u() == 1);    // one via point
  CHECK(r.s() == 0);    // from = where the path ended
  CHECK(r.s() == 0);
  CHECK(r.s() == -550);  // via (5, 5)
  CHECK(r.s() == -1625);
  CHECK(r.s() == -500);  // to (0, 0)
  CHECK(r.s() == -500);
  CHECK(r.at == r.buf.size());
}

TEST_CASE("preview data: equal provenance records are stored once, whoever owns them") {
  PreviewPrint print = fixture::vase_print(12);
  auto json = encode_preview_json(print);
  REQUIRE(json.ok());
  // The fixture has 6 distinct records (outer, slow outer, overhang, inner, infill, top) shared by 36 paths.
  const size_t from = json->find("\"provenance\":["), to = json->find("],\"layers\"");
  const std::string table = json->substr(from, to - from);
  size_t records = 0;
  for (size_t at = table.find("{\"s\":"); at != std::string::npos; at = table.find("{\"s\":", at + 1))
    ++records;
  CHECK(records == 6);
  // A copy of a record under another pointer is still the same record.
  auto copy = std::make_shared<Provenance>(*print.layers[0].paths[0].provenance);
  print.layers[1].paths[0].provenance = copy;
  auto again = encode_preview_json(print);
  REQUIRE(again.ok());
  CHECK(again->find("\"provenance\":[") != std::string::npos);
  CHECK(again->substr(again->find("\"provenance\":["),
                      again->find("],\"layers\"") - again->find("\"provenance\":[")) == table);
  // Strings (rule names, files, G-code) are interned and escaped for a <script> element.
  CHECK(json->find("\"slow walls\"") != std::string::npos);
  CHECK(json->find("\"speed = speed * 50%\"") != std::string::npos);
}

TEST_CASE("preview data: bad paths are refused with the layer and path named") {
  PreviewPrint print;
  print.layers.emplace_back();
  print.layers[0].paths.push_back(line_path({{1, 1}}));
  auto r = encode_preview_json(print);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().to_string() == "preview: layer 0, path 0: 1 point(s); a path needs at least 2");

  print.layers[0].paths[0] = line_path({{1, 1}, {2, 2}, {3, 3}});
  print.layers[0].paths[0].width = {0.4f, 0.4f, 0.4f};
  r = encode_preview_json(print);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().to_string() ==
        "preview: layer 0, path 0: 3 width value(s) for 2 piece(s); give 1 or one per piece");

  print.layers[0].paths[0] = line_path({{1, 1}, {std::numeric_limits<float>::quiet_NaN(), 2}});
  r = encode_preview_json(print);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("not a finite bed coordinate") != std::string::npos);

  print.layers[0].paths[0] = line_path({{1, 1}, {2, 2}});
  print.layers[0].paths[0].piece_provenance.resize(3);
  r = encode_preview_json(print);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message == "3 piece provenance(s) for 1 piece(s)");

  print.layers[0].paths.clear();
  print.bed_x = 0;
  CHECK_FALSE(encode_preview_json(print).ok());
}

TEST_CASE("preview data: strings cannot close the page's <script> element") {
  PreviewPrint print;
  print.title = "</script><b>model</b>";
  print.layers.emplace_back();
  PreviewPath p = line_path({{0, 0}, {1, 0}});
  auto prov = std::make_shared<Provenance>();
  prov->executors.push_back(
      {false, schema::Level::Path, "x</script>", "a&b.rules", 3, "M117 <hi>\n\"quoted\""});
  p.provenance = prov;
  print.layers[0].paths.push_back(p);
  auto json = encode_preview_json(print);
  REQUIRE(json.ok());
  CHECK(json->find('<') == std::string::npos);
  CHECK(json->find('>') == std::string::npos);
  CHECK(json->find("x\\u003c/script\\u003e") != std::string::npos);
  CHECK(json->find("M117 \\u003chi\\u003e\\u000a\\\"quoted\\\"") != std::string::npos);
}

TEST_CASE("preview data: enum and bool properties carry their value names, numbers their unit only") {
  PreviewPrint print;
  auto json = encode_preview_json(print);
  REQUIRE(json.ok());
  CHECK(json->find("[\"seam\",\"\",[\"aligned\",\"nearest\",\"rear\",\"random\",\"sharpest_corner\",\"point\"]]") != std::string::npos);
  CHECK(json->find("[\"outer_first\",\"\",[\"false\",\"true\"]]") != std::string::npos);
  CHECK(json->find("[\"speed\",\"mm/s\"]") != std::string::npos);
}

TEST_CASE("preview data: the volumetric rate is the bead's area times speed and flow") {
  CHECK(bead_area_mm2(0.45, 0.2) == doctest::Approx(0.25 * 0.2 + M_PI * 0.01));
  CHECK(volumetric_rate_mm3_s(0.45, 0.2, 50, 0.9) == doctest::Approx((0.25 * 0.2 + M_PI * 0.01) * 50 * 0.9));
  CHECK(bead_area_mm2(0.1, 0.2) == doctest::Approx(M_PI * 0.01 / 4));  // narrower than high: round
}

TEST_CASE("preview data: layer by layer, the encoder writes what the whole print gives, and keeps an error") {
  const PreviewPrint print = fixture::vase_print(8);
  PreviewEncoder enc(print.bed_x, print.bed_y, print.title);
  for (const PreviewLayer& l : print.layers) REQUIRE(enc.add_layer(l).ok());
  auto streamed = enc.finish();
  REQUIRE(streamed.ok());
  CHECK(*streamed == *encode_preview_json(print));
  CHECK(enc.title() == "fixture vase");

  PreviewEncoder bad(200, 200, "");
  REQUIRE(bad.add_layer(print.layers[0]).ok());
  PreviewLayer broken = print.layers[1];
  broken.paths[1].points.resize(1);
  auto st = bad.add_layer(broken);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().to_string() == "preview: layer 1, path 1: 1 point(s); a path needs at least 2");
  CHECK_FALSE(bad.add_layer(print.layers[2]).ok());  // the data is incomplete from there on
  auto fin = bad.finish();
  REQUIRE_FALSE(fin.ok());
  CHECK(fin.error().to_string() == st.error().to_string());
}
