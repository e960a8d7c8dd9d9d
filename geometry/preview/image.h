// An RGBA image (8 bits per channel, straight alpha, rows top to bottom), what the thumbnail
// rasterizer makes and the PNG and QOI encoders write.
#pragma once

#include <cstdint>
#include <vector>

namespace tranche::preview {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 0) {}
  uint8_t* at(int x, int y) {
    return &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
  }
  const uint8_t* at(int x, int y) const {
    return &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
  }
};

}  // namespace tranche::preview
