// QOI encoding ("The Quite OK Image Format", qoiformat.org, specification 1.0): the thumbnail
// format Prusa's printers (MK4, XL, MINI) read fastest. RGBA, sRGB.
#pragma once

#include <string>

#include "base/result.h"
#include "geometry/preview/image.h"

namespace tranche::preview {

Result<std::string> encode_qoi(const Image& image);

}  // namespace tranche::preview
