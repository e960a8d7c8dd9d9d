#include <doctest/doctest.h>
#include <png.h>

#include <array>
#include <sstream>

#include "geometry/preview/png.h"
#include "geometry/preview/qoi.h"
#include "geometry/preview/raster.h"
#include "geometry/preview/thumbnails.h"
#include "tests/geometry/preview/decode_util.h"
#include "tests/geometry/preview/fixture_print.h"

using namespace tranche;
using namespace tranche::preview;

namespace {

// libpng's decoder, independent of our encoder.
Image decode_png(const std::string& bytes) {
  png_image pi{};
  pi.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_memory(&pi, bytes.data(), bytes.size()));
  pi.format = PNG_FORMAT_RGBA;
  Image img(static_cast<int>(pi.width), static_cast<int>(pi.height));
  REQUIRE(png_image_finish_read(&pi, nullptr, img.rgba.data(), 0, nullptr));
  return img;
}

// A QOI decoder written from the specification (qoiformat.org/qoi-specification.pdf).
Image decode_qoi(const std::string& s) {
  REQUIRE(s.size() >= 22);
  REQUIRE(s.substr(0, 4) == "qoif");
  auto u32 = [&](size_t at) {
    return static_cast<uint32_t>(static_cast<uint8_t>(s[at])) << 24 |
           static_cast<uint32_t>(static_cast<uint8_t>(s[at + 1])) << 16 |
           static_cast<uint32_t>(static_cast<uint8_t>(s[at + 2])) << 8 |
           static_cast<uint32_t>(static_cast<uint8_t>(s[at + 3]));
  };
  Image img(static_cast<int>(u32(4)), static_cast<int>(u32(8)));
  std::array<std::array<uint8_t, 4>, 64> index{};
  std::array<uint8_t, 4> px{0, 0, 0, 255};
  size_t p = 14;
  auto byte = [&]() { return static_cast<uint8_t>(s.at(p++)); };
  int run = 0;
  for (size_t i = 0; i < img.rgba.size(); i += 4) {
    if (run > 0) {
      --run;
    } else {
      const uint8_t b = byte();
      if (b == 0xfe) {
        px[0] = byte(), px[1] = byte(), px[2] = byte();
      } else if (b == 0xff) {
        px[0] = byte(), px[1] = byte(), px[2] = byte(), px[3] = byte();
      } else if ((b & 0xc0) == 0x00) {
        px = index[b];
      } else if ((b & 0xc0) == 0x40) {
        px[0] = static_cast<uint8_t>(px[0] + ((b >> 4) & 3) - 2);
        px[1] = static_cast<uint8_t>(px[1] + ((b >> 2) & 3) - 2);
        px[2] = static_cast<uint8_t>(px[2] + (b & 3) - 2);
      } else if ((b & 0xc0) == 0x80) {
        const uint8_t b2 = byte();
        const int vg = (b & 0x3f) - 32;
        px[0] = static_cast<uint8_t>(px[0] + vg - 8 + (b2 >> 4));
        px[1] = static_cast<uint8_t>(px[1] + vg);
        px[2] = static_cast<uint8_t>(px[2] + vg - 8 + (b2 & 0x0f));
      } else {
        run = b & 0x3f;
      }
      index[(px[0] * 3 + px[1] * 5 + px[2] * 7 + px[3] * 11) % 64] = px;
    }
    std::copy(px.begin(), px.end(), img.rgba.begin() + static_cast<std::ptrdiff_t>(i));
  }
  CHECK(s.substr(p) == std::string("\0\0\0\0\0\0\0\x01", 8));
  return img;
}

int opaque_pixels(const Image& img) {
  int n = 0;
  for (size_t i = 3; i < img.rgba.size(); i += 4) n += img.rgba[i] > 0;
  return n;
}

}  // namespace

TEST_CASE("thumbnails: the vase renders as a shaded, anti-aliased disc on a transparent background") {
  const Image img = render_thumbnail(fixture::vase_print(30), 64, 48);
  REQUIRE(img.width == 64);
  REQUIRE(img.height == 48);
  CHECK(img.at(0, 0)[3] == 0);     // corners: background
  CHECK(img.at(32, 24)[3] > 0);    // centre: the part (its top fill has gaps)
  CHECK(img.at(32, 5)[3] == 255);  // the wall's rim
  const int covered = opaque_pixels(img);
  CHECK(covered > 64 * 48 / 4);  // a disc filling most of the height
  CHECK(covered < 64 * 48 * 3 / 4);
  int partial = 0, lo = 255, hi = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const uint8_t* p = img.at(x, y);
      partial += p[3] > 0 && p[3] < 255;
      if (p[3] == 255) lo = std::min<int>(lo, p[0]), hi = std::max<int>(hi, p[0]);
    }
  CHECK(partial > 20);  // edges are blended
  CHECK(hi - lo > 30);  // shading varies over the surface
  const Image empty = render_thumbnail(PreviewPrint{}, 8, 8);
  CHECK(opaque_pixels(empty) == 0);
}

TEST_CASE("thumbnails: islands render before any toolpath, holes left open") {
  geo::Polygon ring;
  ring.outer = {geo::to_point(-10, -10), geo::to_point(10, -10), geo::to_point(10, 10),
                geo::to_point(-10, 10)};
  ring.holes = {{geo::to_point(-5, -5), geo::to_point(-5, 5), geo::to_point(5, 5), geo::to_point(5, -5)}};
  HeightCanvas canvas(40, 40, BoxMm{90, 90, 110, 110});
  canvas.add_polygon(ring, 100, 100, 5);
  const Image img = canvas.shade();
  CHECK(img.at(20, 20)[3] == 0);    // the hole
  CHECK(img.at(4, 20)[3] == 255);   // the frame, left
  CHECK(img.at(20, 35)[3] == 255);  // and bottom
  CHECK(img.at(0, 0)[3] == 0);      // the margin
}

TEST_CASE("thumbnails: PNG decodes (libpng) to the very pixels rendered") {
  const Image img = render_thumbnail(fixture::vase_print(20), 100, 80);
  auto png = encode_png(img);
  REQUIRE(png.ok());
  const Image back = decode_png(*png);
  CHECK(back.width == 100);
  CHECK(back.height == 80);
  CHECK(back.rgba == img.rgba);
  CHECK_FALSE(encode_png(Image{}).ok());
}

TEST_CASE("thumbnails: QOI follows the specification") {
  // Hand-encoded from the specification: a run of the initial pixel, an RGB op, a diff, a luma
  // op, an index hit and an RGBA op.
  Image tiny(6, 1);
  const uint8_t px[6][4] = {{0, 0, 0, 255},    {10, 20, 30, 255}, {11, 19, 30, 255},
                            {31, 39, 50, 255}, {10, 20, 30, 255}, {1, 2, 3, 4}};
  for (int i = 0; i < 6; ++i) std::copy(px[i], px[i] + 4, tiny.at(i, 0));
  auto q = encode_qoi(tiny);
  REQUIRE(q.ok());
  const std::string body = q->substr(14, q->size() - 14 - 8);
  const uint8_t want[] = {0xc0,  // run of 1: (0,0,0,255) is the initial pixel
                          0xfe,
                          10,
                          20,
                          30,                          // RGB
                          0x40 | 3 << 4 | 1 << 2 | 2,  // diff +1 -1 0
                          0x80 | (20 + 32),
                          (0 + 8) << 4 | (0 + 8),  // luma: dg 20, dr-dg 0, db-dg 0
                          static_cast<uint8_t>((10 * 3 + 20 * 5 + 30 * 7 + 255 * 11) % 64),  // index
                          0xff,
                          1,
                          2,
                          3,
                          4};  // RGBA
  CHECK(body == std::string(reinterpret_cast<const char*>(want), sizeof want));
  CHECK(q->substr(0, 14) == std::string("qoif\0\0\0\x06\0\0\0\x01\x04\x00", 14));

  const Image img = render_thumbnail(fixture::vase_print(20), 120, 90);
  auto qoi = encode_qoi(img);
  REQUIRE(qoi.ok());
  CHECK(decode_qoi(*qoi).rgba == img.rgba);
  Image runs(100, 1);  // a run longer than 62 is split
  for (int x = 0; x < 100; ++x) runs.at(x, 0)[3] = 255;
  CHECK(decode_qoi(*encode_qoi(runs)).rgba == runs.rgba);
}

TEST_CASE("thumbnails: PrusaSlicer's G-code comment block") {
  auto specs = parse_thumbnail_specs("16x16/QOI, 300x200/png 48x48");
  REQUIRE(specs.ok());
  REQUIRE(specs->size() == 3);
  CHECK((*specs)[0].format == ThumbnailFormat::Qoi);
  CHECK((*specs)[1].width == 300);
  CHECK((*specs)[1].height == 200);
  CHECK((*specs)[1].format == ThumbnailFormat::Png);
  CHECK((*specs)[2].format == ThumbnailFormat::Png);

  auto gcode = thumbnails_gcode(fixture::vase_print(10), *specs);
  REQUIRE(gcode.ok());
  std::istringstream in(*gcode);
  std::string line;
  int blocks = 0;
  while (std::getline(in, line)) {
    if (line.find("begin") == std::string::npos) continue;
    std::string tag, begin, size;
    size_t len = 0;
    std::istringstream head(line.substr(2));
    head >> tag >> begin >> size >> len;
    const auto& spec = (*specs)[static_cast<size_t>(blocks)];
    CHECK(tag == (spec.format == ThumbnailFormat::Qoi ? "thumbnail_QOI" : "thumbnail"));
    CHECK(size == std::to_string(spec.width) + "x" + std::to_string(spec.height));
    std::string b64;
    while (std::getline(in, line) && line.rfind("; " + tag + " end", 0) != 0) {
      REQUIRE(line.rfind("; ", 0) == 0);
      CHECK(line.size() <= 80);  // "; " and at most 78 characters
      b64 += line.substr(2);
    }
    CHECK(line == "; " + tag + " end");
    CHECK(b64.size() == len);
    const std::string bytes = test::base64_decode(b64);
    const Image img = spec.format == ThumbnailFormat::Qoi ? decode_qoi(bytes) : decode_png(bytes);
    CHECK(img.width == spec.width);
    CHECK(img.height == spec.height);
    CHECK(opaque_pixels(img) > spec.width * spec.height / 10);  // not blank
    ++blocks;
  }
  CHECK(blocks == 3);
  CHECK(gcode->rfind(";\n; thumbnail_QOI begin 16x16 ", 0) == 0);
  CHECK(gcode->substr(gcode->size() - 18) == "; thumbnail end\n;\n");
}

TEST_CASE("thumbnails: a bad size list says which entry and what to write") {
  auto r = parse_thumbnail_specs("16x16/QOI, 300x/PNG");
  REQUIRE_FALSE(r.ok());
  CHECK(
      r.error().to_string() ==
      "thumbnails: '300x/PNG': not a size; write WxH or WxH/PNG or WxH/QOI, e.g. \"16x16/QOI, 300x300/PNG\"");
  r = parse_thumbnail_specs("220x124/JPG");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("format 'JPG' is not PNG or QOI") != std::string::npos);
  r = parse_thumbnail_specs("0x10");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("each side must be 1 to 1024 px") != std::string::npos);
  CHECK(parse_thumbnail_specs("")->empty());
}

TEST_CASE("thumbnails: the rasterizer covers the area it is given") {
  // 100 px for a 50 mm box, less the 4 % margins: 1.84 px/mm. Coverage (alpha) counts pixels.
  const double px_per_mm = 0.92 * 100 / 50;
  auto coverage = [](const Image& img) {
    double a = 0;
    for (size_t i = 3; i < img.rgba.size(); i += 4) a += img.rgba[i] / 255.0;
    return a;
  };
  geo::Polygon tri;
  tri.outer = {geo::to_point(0, 0), geo::to_point(40, 0), geo::to_point(10, 30)};
  HeightCanvas a(100, 100, BoxMm{0, 0, 50, 50});
  a.add_polygon(tri, 5, 5, 1);
  CHECK(coverage(a.shade()) == doctest::Approx(600 * px_per_mm * px_per_mm).epsilon(0.02));
  HeightCanvas b(100, 100, BoxMm{0, 0, 50, 50});
  b.add_segment({5, 5}, {45, 35}, 4, 1);  // a 50 mm bead, 4 mm wide: 50·4 + π·2²
  CHECK(coverage(b.shade()) == doctest::Approx((200 + M_PI * 4) * px_per_mm * px_per_mm).epsilon(0.02));
}
