#include "geometry/plate/model_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <new>
#include <optional>
#include <string_view>

#include "geometry/mesh/file_bytes.h"
#include "geometry/mesh/stl.h"
#include "geometry/plate/detect.h"
#include "geometry/plate/obj.h"
#include "geometry/plate/threemf.h"

namespace tranche::plate {
namespace {

// What the first bytes of a file look like, for a message: "text starting with '...'" or "bytes 00 1f ...".
std::string first_bytes(std::string_view bytes) {
  const std::string_view head = bytes.substr(0, 24);
  bool text = true;
  for (unsigned char c : head) text = text && (c >= 0x20 || c == '\n' || c == '\r' || c == '\t') && c < 0x7f;
  if (text) {
    std::string shown(head.substr(0, head.find_first_of("\r\n")));
    return fmt::format("text starting with '{}'", shown);
  }
  std::string hex;
  for (unsigned char c : head.substr(0, 8)) hex += fmt::format("{}{:02x}", hex.empty() ? "" : " ", c);
  return "bytes " + hex;
}

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Result<std::vector<Object>> parse(std::string_view bytes, const std::string& path, Report& report) {
  const Detected d = detect_format(bytes);
  switch (d.format) {
    case Format::ThreeMf: return parse_3mf(bytes, path, report);
    case Format::Obj: return parse_obj(bytes, path, report);
    case Format::Svg:
      return Error{path, "this is an SVG drawing, not a mesh: slice it on its own, from a file named .svg"};
    case Format::Other: return Error{path, "this is " + d.what};
    case Format::Stl: break;
  }
  // Bytes no format claims, in a file named for one we read: say so in that format's words.
  if (!d.sure && extension(path) == ".3mf")
    return Error{path, fmt::format("not a 3MF file: a 3MF file is a ZIP archive, and this is {}; export the model "
                                   "again, or give the file it was meant to be",
                                   first_bytes(bytes))};
  auto mesh = geo::parse_stl(bytes, path, report);
  if (!mesh) return mesh.error();
  Object o;
  o.file = path;
  o.name = std::filesystem::path(path).stem().string();
  o.mesh = std::move(*mesh);
  std::vector<Object> out;
  out.push_back(std::move(o));
  return out;
}

}  // namespace

Result<std::vector<Object>> parse_model_file(std::string_view bytes, const std::string& path, Report& report) {
  try {
    return parse(bytes, path, report);
  } catch (const std::bad_alloc&) {
    return Error{path, "not enough memory to load the model; close other programs or simplify the model"};
  }
}

Result<std::vector<Object>> load_model_file(const std::string& path, Report& report) {
  // An STL refused from its header (a triangle count its size cannot hold) is never read whole. A
  // 3MF (a ZIP archive) is kept in huge pages (geo::FileMemory): it is read once, its model part
  // inflated from it, and a fresh process would fault its pages in one by one.
  Format format = Format::Other;
  auto bytes = geo::read_file_bytes(
      path,
      [&](std::string_view head, std::optional<uint64_t> size) {
        const Detected d = detect_format(head, size.value_or(head.size()));
        format = d.format;
        // Not an STL, or unsure bytes named .3mf (parse() says what they are in 3MF words): read whole.
        if (d.format != Format::Stl || (!d.sure && extension(path) == ".3mf"))
          return Result<uint64_t>(UINT64_MAX);
        return geo::check_stl_head(head, size, path, report);
      },
      [&] { return format == Format::ThreeMf ? geo::FileMemory::kHugePages : geo::FileMemory::kHeap; });
  if (!bytes) return bytes.error();
  if (bytes->size == 0)
    return Error{path, "the file is empty (0 bytes); export the model again or check that it was copied completely"};
  return parse_model_file(bytes->view(), path, report);
}

}  // namespace tranche::plate
