#include "geometry/plate/obj.h"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <charconv>
#include <filesystem>

#include "geometry/mesh/weld.h"

namespace tranche::plate {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Each `f` line: at least 3 vertices, each a vertex number that exists (1-based, or negative:
// counted back from the last `v` so far). tinyobjloader only warns about these and goes on.
Status check_faces(std::string_view text, const std::string& file) {
  uint64_t vertices = 0, line = 0;
  while (!text.empty()) {
    ++line;
    const size_t nl = text.find('\n');
    std::string_view s = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    if (s.size() >= 2 && s[0] == 'v' && is_blank(s[1])) {
      ++vertices;
      continue;
    }
    if (s.size() < 2 || s[0] != 'f' || !is_blank(s[1])) continue;
    s.remove_prefix(2);
    int corners = 0;
    while (true) {
      while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
      if (s.empty() || s.front() == '#') break;
      size_t n = 0;
      while (n < s.size() && !is_blank(s[n])) ++n;
      const std::string_view token = s.substr(0, n);
      s.remove_prefix(n);
      ++corners;
      const std::string_view index = token.substr(0, token.find('/'));
      int64_t v = 0;
      const auto [end, ec] = std::from_chars(index.data(), index.data() + index.size(), v);
      const std::string where = fmt::format("{}:{}", file, line);
      if (ec != std::errc() || end != index.data() + index.size())
        return Error{where, fmt::format("'{}' is not a vertex number", token)};
      const int64_t resolved = v < 0 ? static_cast<int64_t>(vertices) + v + 1 : v;
      if (v == 0) return Error{where, "vertex number 0: OBJ numbers vertices from 1"};
      if (resolved < 1) return Error{where, fmt::format("the face refers to vertex {}, before the first vertex", v)};
    }
    if (corners < 3)
      return Error{fmt::format("{}:{}", file, line),
                   fmt::format("a face with {} vert{}: a face needs at least 3", corners, corners == 1 ? "ex" : "ices")};
  }
  return ok_status();
}

// Positive vertex numbers beyond the file's vertices, with the line of the first.
Status check_range(std::string_view text, const std::string& file, uint64_t vertices) {
  uint64_t line = 0;
  while (!text.empty()) {
    ++line;
    const size_t nl = text.find('\n');
    std::string_view s = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    if (s.size() < 2 || s[0] != 'f' || !is_blank(s[1])) continue;
    s.remove_prefix(2);
    while (!s.empty()) {
      while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
      size_t n = 0;
      while (n < s.size() && !is_blank(s[n])) ++n;
      const std::string_view index = s.substr(0, std::min(n, s.substr(0, n).find('/')));
      s.remove_prefix(n);
      int64_t v = 0;
      std::from_chars(index.data(), index.data() + index.size(), v);
      if (v > 0 && static_cast<uint64_t>(v) > vertices)
        return Error{fmt::format("{}:{}", file, line),
                     fmt::format("the face refers to vertex {}, but the file has {} vertices", v, vertices)};
    }
  }
  return ok_status();
}

}  // namespace

Result<std::vector<Object>> parse_obj(std::string_view bytes, const std::string& file, Report& report) {
  if (Status s = check_faces(bytes, file); !s) return s.error();
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(std::string(bytes), "", config))
    return Error{file, fmt::format("the OBJ file cannot be read (tinyobjloader: {})", reader.Error())};
  const auto& attrib = reader.GetAttrib();
  const uint64_t nv = attrib.vertices.size() / 3;
  if (Status s = check_range(bytes, file, nv); !s) return s.error();
  std::vector<float> corners;
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (size_t i = 0; i + 2 < idx.size(); i += 3) {
      for (int k = 0; k < 3; ++k) {
        const int v = idx[i + k].vertex_index;
        if (v < 0 || static_cast<uint64_t>(v) >= nv)
          return Error{file, fmt::format("a face refers to vertex {}, but the file has {} vertices", v + 1, nv)};
        for (int d = 0; d < 3; ++d) corners.push_back(attrib.vertices[3 * v + d]);
      }
    }
  }
  if (corners.empty())
    return Error{file, fmt::format("the OBJ file has no faces ({} vertices): nothing to print; export the model "
                                   "as a mesh",
                                   nv)};
  auto mesh = geo::weld_corners(corners, file, report);
  if (!mesh) return mesh.error();
  Object o;
  o.file = file;
  o.name = std::filesystem::path(file).stem().string();
  o.mesh = std::move(*mesh);
  o.mesh.name = o.name;
  std::vector<Object> out;
  out.push_back(std::move(o));
  return out;
}

}  // namespace tranche::plate
