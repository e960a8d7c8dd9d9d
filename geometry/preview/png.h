// PNG encoding (RGBA, 8 bits per channel) with zlib: the G-code thumbnails' format.
#pragma once

#include <string>

#include "base/result.h"
#include "geometry/preview/image.h"

namespace tranche::preview {

// The PNG file's bytes; an error for an empty image or when zlib fails.
Result<std::string> encode_png(const Image& image);

}  // namespace tranche::preview
