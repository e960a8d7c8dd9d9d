#include <doctest/doctest.h>

#include <filesystem>

#include "geometry/preview/preview_html.h"
#include "tests/geometry/preview/fixture_print.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::preview;

TEST_CASE("preview html: one self-contained page, every viewer part embedded, nothing fetched") {
  auto html = preview_html(fixture::vase_print(6));
  REQUIRE(html.ok());
  const std::string& h = *html;
  CHECK(h.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK(h.find("/*@") == std::string::npos);  // every marker filled
  CHECK(h.find("<title>fixture vase — Tranche preview</title>") != std::string::npos);
  CHECK(h.find("id=\"tranche-data\">{\"format\":\"tranche-preview\"") != std::string::npos);
  CHECK(h.find("TP.decode = function") != std::string::npos);   // decode.js
  CHECK(h.find("TP.View = class") != std::string::npos);        // draw.js
  CHECK(h.find("window.tranchePreview") != std::string::npos);  // ui.js
  CHECK(h.find("#layer-bar") != std::string::npos);             // viewer.css
  // No network: no external script, style, font or image.
  for (const char* s : {"src=\"http", "href=\"http", "url(http", "@import", "<link"})
    CHECK(h.find(s) == std::string::npos);
  // Four <script> elements (data, decode, draw, ui), each closed once: no embedded text closes one early.
  size_t opens = 0, closes = 0;
  for (size_t at = h.find("<script"); at != std::string::npos; at = h.find("<script", at + 1)) ++opens;
  for (size_t at = h.find("</script"); at != std::string::npos; at = h.find("</script", at + 1)) ++closes;
  CHECK(opens == 4);
  CHECK(closes == 4);
}

TEST_CASE("preview html: the title is escaped, and a file is written whole or not at all") {
  PreviewPrint print = fixture::vase_print(2);
  print.title = "a<b>&\"c\"";
  auto html = preview_html(print);
  REQUIRE(html.ok());
  CHECK(html->find("<title>a&lt;b&gt;&amp;&quot;c&quot; — Tranche preview</title>") != std::string::npos);

  tranche::test::TempDir dir("preview-html");
  const auto out = dir.path() / "p.html";
  REQUIRE(write_preview_html(out.string(), print).ok());
  CHECK(tranche::test::read_file(out) == *html);

  print.layers[0].paths[0].points.resize(1);  // refused: the old file stays as it was
  auto st = write_preview_html(out.string(), print);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().to_string().find("layer 0, path 0") != std::string::npos);
  CHECK(tranche::test::read_file(out) == *html);
  auto bad_dir = write_preview_html((dir.path() / "missing" / "p.html").string(), fixture::vase_print(1));
  CHECK_FALSE(bad_dir.ok());
}

TEST_CASE("preview html: the streaming form writes the same page") {
  const PreviewPrint print = fixture::vase_print(5);
  PreviewEncoder enc(print.bed_x, print.bed_y, print.title);
  for (const PreviewLayer& l : print.layers) REQUIRE(enc.add_layer(l).ok());
  tranche::test::TempDir dir("preview-stream");
  const auto out = dir.path() / "s.html";
  REQUIRE(write_preview_html(out.string(), enc).ok());
  CHECK(tranche::test::read_file(out) == *preview_html(print));
}
