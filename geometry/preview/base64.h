// Base64 (RFC 4648, with padding), for the preview's data and the G-code thumbnails.
#pragma once

#include <string>
#include <string_view>

namespace tranche::preview {

std::string base64_encode(std::string_view bytes);

}  // namespace tranche::preview
