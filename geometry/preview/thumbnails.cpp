#include "geometry/preview/thumbnails.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>

#include "geometry/preview/base64.h"
#include "geometry/preview/png.h"
#include "geometry/preview/qoi.h"

namespace tranche::preview {

namespace {

constexpr size_t kLineChars = 78;  // base64 characters per comment line, as PrusaSlicer writes

bool parse_int(std::string_view s, int& v) {
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && p == s.data() + s.size();
}

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

}  // namespace

Result<std::vector<ThumbnailSpec>> parse_thumbnail_specs(std::string_view text) {
  std::vector<ThumbnailSpec> specs;
  size_t at = 0;
  while (at < text.size()) {
    const size_t end = text.find_first_of(", \t", at);
    const std::string_view entry =
        text.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at);
    at = end == std::string_view::npos ? text.size() : end + 1;
    if (entry.empty()) continue;
    const auto bad = [&](std::string why) {
      return Error{"thumbnails",
                   fmt::format("'{}': {}; write WxH or WxH/PNG or WxH/QOI, e.g. \"16x16/QOI, 300x300/PNG\"",
                               entry, why)};
    };
    ThumbnailSpec s;
    std::string_view size = entry;
    if (const size_t slash = entry.find('/'); slash != std::string_view::npos) {
      size = entry.substr(0, slash);
      const std::string f = upper(entry.substr(slash + 1));
      if (f == "PNG")
        s.format = ThumbnailFormat::Png;
      else if (f == "QOI")
        s.format = ThumbnailFormat::Qoi;
      else
        return bad(fmt::format("format '{}' is not PNG or QOI", entry.substr(slash + 1)));
    }
    const size_t x = size.find_first_of("xX");
    if (x == std::string_view::npos || !parse_int(size.substr(0, x), s.width) ||
        !parse_int(size.substr(x + 1), s.height))
      return bad("not a size");
    if (s.width < 1 || s.height < 1 || s.width > kMaxThumbnailSide || s.height > kMaxThumbnailSide)
      return bad(fmt::format("each side must be 1 to {} px", kMaxThumbnailSide));
    specs.push_back(s);
  }
  return specs;
}

std::string thumbnail_block(std::string_view encoded, const ThumbnailSpec& spec) {
  const std::string b64 = base64_encode(encoded);
  const char* tag = spec.format == ThumbnailFormat::Qoi ? "thumbnail_QOI" : "thumbnail";
  std::string out = fmt::format(";\n; {} begin {}x{} {}\n", tag, spec.width, spec.height, b64.size());
  for (size_t i = 0; i < b64.size(); i += kLineChars) {
    out += "; ";
    out.append(b64, i, kLineChars);
    out.push_back('\n');
  }
  return out + fmt::format("; {} end\n;\n", tag);
}

Result<std::string> thumbnail_block(const Image& image, const ThumbnailSpec& spec) {
  auto bytes = spec.format == ThumbnailFormat::Qoi ? encode_qoi(image) : encode_png(image);
  if (!bytes) return bytes.error();
  return thumbnail_block(*bytes, spec);
}

Result<std::string> thumbnails_gcode(BoxMm box, const DrawThumbnail& draw,
                                     std::span<const ThumbnailSpec> specs, const ShadeStyle& style) {
  std::string out;
  for (const ThumbnailSpec& s : specs) {
    HeightCanvas canvas(s.width, s.height, box);
    draw(canvas);
    auto block = thumbnail_block(canvas.shade(style), s);
    if (!block) return block.error();
    out += *block;
  }
  return out;
}

Result<std::string> thumbnails_gcode(const PreviewPrint& print, std::span<const ThumbnailSpec> specs,
                                     const ShadeStyle& style) {
  std::string out;
  for (const ThumbnailSpec& s : specs) {
    auto block = thumbnail_block(render_thumbnail(print, s.width, s.height, style), s);
    if (!block) return block.error();
    out += *block;
  }
  return out;
}

}  // namespace tranche::preview
