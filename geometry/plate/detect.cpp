#include "geometry/plate/detect.h"

#include <array>
#include <cstdint>

#include "geometry/plate/zip.h"

namespace tranche::plate {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view skip_space(std::string_view s) {
  if (s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  return s;
}

bool starts_with_word_ci(std::string_view s, std::string_view word) {
  if (s.size() < word.size()) return false;
  for (size_t i = 0; i < word.size(); ++i)
    if ((s[i] | 0x20) != word[i]) return false;
  return s.size() == word.size() || is_space(s[word.size()]);
}

// Binary files have NUL bytes or control characters in their first kilobyte; text has neither.
bool looks_like_text(std::string_view s) {
  for (char ch : s.substr(0, 1024)) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == 0 || (c < 0x20 && !is_space(ch))) return false;
  }
  return true;
}

// The first word of the first line that is neither blank nor a comment (`#` or `;`).
std::string_view first_word(std::string_view s) {
  s = s.substr(0, 64 * 1024);
  while (!s.empty()) {
    s = skip_space(s);
    if (s.empty()) break;
    if (s.front() == '#') {
      const size_t nl = s.find('\n');
      if (nl == std::string_view::npos) break;
      s.remove_prefix(nl + 1);
      continue;
    }
    size_t n = 0;
    while (n < s.size() && !is_space(s[n])) ++n;
    return s.substr(0, n);
  }
  return {};
}

bool is_obj_keyword(std::string_view w) {
  static constexpr std::array<std::string_view, 12> kWords = {"v",  "vt", "vn", "vp",     "f",      "o",
                                                              "g",  "s",  "l",  "mtllib", "usemtl", "p"};
  for (auto k : kWords)
    if (w == k) return true;
  return false;
}

bool is_gcode_word(std::string_view w) {
  if (w.empty()) return false;
  if (w.front() == ';') return true;
  if (w.size() < 2 || (w[0] != 'G' && w[0] != 'M' && w[0] != 'T')) return false;
  for (char c : w.substr(1))
    if (c < '0' || c > '9') return false;
  return true;
}

Detected xml_kind(std::string_view s) {
  const std::string_view head = s.substr(0, 4096);
  if (head.find("<svg") != std::string_view::npos) return {Format::Svg, "an SVG drawing"};
  if (head.find("<amf") != std::string_view::npos)
    return {Format::Other, "an AMF file; export the model as 3MF or STL"};
  if (head.find("<model") != std::string_view::npos)
    return {Format::Other, "the model part of a 3MF package, not a whole 3MF file; open the .3mf itself"};
  return {Format::Other, "an XML file, not a model"};
}

}  // namespace

Detected detect_format(std::string_view b) { return detect_format(b, b.size()); }

Detected detect_format(std::string_view b, uint64_t size) {
  if (looks_like_zip(b)) return {Format::ThreeMf, "a ZIP archive (3MF?)"};
  if (b.size() >= 84) {
    uint64_t count = 0;
    for (int i = 3; i >= 0; --i) count = count << 8 | static_cast<unsigned char>(b[80 + i]);
    if (84 + 50 * count == size) return {Format::Stl, "a binary STL file"};
  }
  struct Magic {
    std::string_view bytes, what;
  };
  static constexpr std::array<Magic, 9> kMagic = {{
      {"\x89PNG", "a PNG image, not a model"},
      {"\xFF\xD8\xFF", "a JPEG image, not a model"},
      {"GIF8", "a GIF image, not a model"},
      {"%PDF", "a PDF document, not a model"},
      {"\x1F\x8B", "a gzip-compressed file; decompress it first"},
      {"7z\xBC\xAF", "a 7-Zip archive; extract the model first"},
      {"Rar!", "a RAR archive; extract the model first"},
      {"\x7F" "ELF", "a program, not a model"},
      {"ISO-10303-21", "a STEP file (CAD); export the model as STL or 3MF"},
  }};
  for (const auto& m : kMagic)
    if (b.starts_with(m.bytes)) return {Format::Other, std::string(m.what)};
  if (!looks_like_text(b)) return {Format::Stl, "a binary file", false};
  const std::string_view s = skip_space(b);
  if (starts_with_word_ci(s, "solid")) return {Format::Stl, "an ASCII STL file"};
  if (starts_with_word_ci(s, "ply")) return {Format::Other, "a PLY mesh; export the model as STL, 3MF or OBJ"};
  if (s.starts_with("<")) return xml_kind(s);
  const std::string_view w = first_word(b);
  if (is_obj_keyword(w)) return {Format::Obj, "an OBJ file"};
  if (is_gcode_word(w)) return {Format::Other, "a G-code file: it is already sliced"};
  return {Format::Stl, "a text file", false};
}

}  // namespace tranche::plate
