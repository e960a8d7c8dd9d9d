#include "geometry/preview/png.h"

#include <zlib.h>

#include <cstdlib>

namespace tranche::preview {

namespace {

void put_u32(std::string& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xff));
}

void chunk(std::string& out, const char* type, const std::string& data) {
  put_u32(out, static_cast<uint32_t>(data.size()));
  const size_t start = out.size();
  out.append(type, 4);
  out += data;
  const uLong crc =
      ::crc32(0, reinterpret_cast<const Bytef*>(out.data() + start), static_cast<uInt>(out.size() - start));
  put_u32(out, static_cast<uint32_t>(crc));
}

// Each row with the filter (none, sub or up) that leaves the smallest residuals, as libpng's
// heuristic does: it is what makes flat backgrounds and shading compress well.
std::string filtered_rows(const Image& img) {
  const size_t stride = static_cast<size_t>(img.width) * 4;
  std::string out;
  out.reserve((stride + 1) * static_cast<size_t>(img.height));
  std::string cand[3];
  for (int y = 0; y < img.height; ++y) {
    const uint8_t* row = img.at(0, y);
    const uint8_t* up = y ? img.at(0, y - 1) : nullptr;
    long best_cost = -1;
    int best = 0;
    for (int f = 0; f < 3; ++f) {
      std::string& c = cand[f];
      c.assign(stride, '\0');
      long cost = 0;
      for (size_t i = 0; i < stride; ++i) {
        const int pred = f == 1 ? (i >= 4 ? row[i - 4] : 0) : f == 2 ? (up ? up[i] : 0) : 0;
        const auto v = static_cast<uint8_t>(row[i] - pred);
        c[i] = static_cast<char>(v);
        cost += std::abs(static_cast<int8_t>(v));
      }
      if (best_cost < 0 || cost < best_cost) best_cost = cost, best = f;
    }
    out.push_back(static_cast<char>(best));
    out += cand[best];
  }
  return out;
}

}  // namespace

Result<std::string> encode_png(const Image& img) {
  if (img.width <= 0 || img.height <= 0 || img.rgba.size() != static_cast<size_t>(img.width) * img.height * 4)
    return Error{"thumbnail", "cannot encode an empty image as PNG"};
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put_u32(ihdr, static_cast<uint32_t>(img.width));
  put_u32(ihdr, static_cast<uint32_t>(img.height));
  ihdr += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, adaptive filters, no interlace
  chunk(png, "IHDR", ihdr);
  const std::string raw = filtered_rows(img);
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string z(size, '\0');
  if (::compress2(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                  static_cast<uLong>(raw.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
    return Error{"thumbnail", "zlib could not compress the PNG (out of memory?)"};
  z.resize(size);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  return png;
}

}  // namespace tranche::preview
