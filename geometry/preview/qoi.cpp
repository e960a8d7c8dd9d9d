#include "geometry/preview/qoi.h"

#include <array>
#include <cstring>

namespace tranche::preview {

namespace {

enum : uint8_t {
  kOpIndex = 0x00,
  kOpDiff = 0x40,
  kOpLuma = 0x80,
  kOpRun = 0xc0,
  kOpRgb = 0xfe,
  kOpRgba = 0xff
};

struct Px {
  uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Px&) const = default;
};
int hash(Px p) { return (p.r * 3 + p.g * 5 + p.b * 7 + p.a * 11) % 64; }

void put_u32(std::string& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xff));
}

}  // namespace

Result<std::string> encode_qoi(const Image& img) {
  const size_t count = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  if (img.width <= 0 || img.height <= 0 || img.rgba.size() != count * 4)
    return Error{"thumbnail", "cannot encode an empty image as QOI"};
  std::string out = "qoif";
  put_u32(out, static_cast<uint32_t>(img.width));
  put_u32(out, static_cast<uint32_t>(img.height));
  out.push_back(4);  // channels: RGBA
  out.push_back(0);  // colour space: sRGB with linear alpha
  std::array<Px, 64> seen{};
  for (Px& p : seen) p = Px{0, 0, 0, 0};
  Px prev;
  int run = 0;
  auto c = [&](int v) { out.push_back(static_cast<char>(static_cast<uint8_t>(v))); };
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* q = &img.rgba[i * 4];
    const Px px{q[0], q[1], q[2], q[3]};
    if (px == prev) {
      if (++run == 62 || i + 1 == count) c(kOpRun | (run - 1)), run = 0;
      continue;
    }
    if (run) c(kOpRun | (run - 1)), run = 0;
    const int h = hash(px);
    if (seen[h] == px) {
      c(kOpIndex | h);
    } else {
      seen[h] = px;
      if (px.a == prev.a) {
        const auto dr = static_cast<int8_t>(px.r - prev.r), dg = static_cast<int8_t>(px.g - prev.g),
                   db = static_cast<int8_t>(px.b - prev.b);
        const int dr_dg = dr - dg, db_dg = db - dg;
        if (dr >= -2 && dr <= 1 && dg >= -2 && dg <= 1 && db >= -2 && db <= 1) {
          c(kOpDiff | (dr + 2) << 4 | (dg + 2) << 2 | (db + 2));
        } else if (dg >= -32 && dg <= 31 && dr_dg >= -8 && dr_dg <= 7 && db_dg >= -8 && db_dg <= 7) {
          c(kOpLuma | (dg + 32));
          c((dr_dg + 8) << 4 | (db_dg + 8));
        } else {
          c(kOpRgb), c(px.r), c(px.g), c(px.b);
        }
      } else {
        c(kOpRgba), c(px.r), c(px.g), c(px.b), c(px.a);
      }
    }
    prev = px;
  }
  out.append("\0\0\0\0\0\0\0\x01", 8);  // the end marker
  return out;
}

}  // namespace tranche::preview
