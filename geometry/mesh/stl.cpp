#include "geometry/mesh/stl.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>

#include "base/output_file.h"
#include "geometry/mesh/file_bytes.h"
#include "geometry/mesh/stl_parse.h"
#include "geometry/mesh/weld.h"

namespace tranche::geo {
namespace stl {

std::string at_line(const std::string& file, uint64_t line) { return fmt::format("{}:{}", file, line); }
std::string at_triangle(const std::string& file, uint64_t index0) {
  return fmt::format("{}, triangle {}", file, index0 + 1);
}

}  // namespace stl

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// The first word is `solid` (any case), after an optional byte order mark and whitespace.
bool starts_with_solid_word(std::string_view s) {
  if (s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  if (s.size() < 5) return false;
  for (size_t i = 0; i < 5; ++i) {
    if ((s[i] | 0x20) != "solid"[i]) return false;
  }
  return s.size() == 5 || is_space(s[5]);
}

// Text files have no NUL and few control bytes; binary STL data (floats, a padded header) has NULs.
bool looks_like_text(std::string_view s) {
  s = s.substr(0, 1024);
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == 0 || (c < 0x20 && !is_space(ch))) return false;
  }
  return true;
}

std::string excerpt(std::string_view s) {
  std::string out;
  for (size_t i = 0; i < s.size() && out.size() < 24; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c == '\n' || c == '\r') break;
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  return out;
}

// Normals are only checked, never used: the corner order defines the outside.
bool normal_disagrees(const stl::Facet& f) {
  const double n[3] = {f.normal[0], f.normal[1], f.normal[2]};
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (nn == 0 || !std::isfinite(nn)) return false;
  const double u[3] = {double{f.v[3]} - f.v[0], double{f.v[4]} - f.v[1], double{f.v[5]} - f.v[2]};
  const double w[3] = {double{f.v[6]} - f.v[0], double{f.v[7]} - f.v[1], double{f.v[8]} - f.v[2]};
  const double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  const double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  if (cc == 0 || !std::isfinite(cc)) return false;
  // More than 60° apart: beyond any exporter's rounding, so the normal or the winding is wrong.
  return n[0] * c[0] + n[1] * c[1] + n[2] * c[2] < 0.5 * std::sqrt(nn * cc);
}

Result<Mesh> weld(stl::RawStl raw, const std::string& file, Report& report) {
  const auto where = [&](uint64_t i) {
    return raw.lines.empty() ? stl::at_triangle(file, i) : stl::at_line(file, raw.lines[i]);
  };
  const size_t n = raw.size();
  Welder welder(n);
  // Chunks small enough to stay in cache between decoding, checking and welding.
  constexpr size_t kChunk = 2048;
  std::vector<float> corners(9 * kChunk);
  std::vector<uint8_t> dropped(kChunk);
  uint64_t wrong_normals = 0, first_wrong = 0, degenerate = 0, first_degenerate = 0;
  stl::Facet decoded;
  for (size_t base = 0; base < n; base += kChunk) {
    const size_t m = std::min(kChunk, n - base);
    for (size_t k = 0; k < m; ++k) {
      const size_t i = base + k;
      const stl::Facet* f = &decoded;
      if (raw.records.empty()) {
        f = &raw.facets[i];
      } else {
        stl::decode_record(raw.records.data() + i * stl::RawStl::kRecordBytes, decoded);
      }
      for (int c = 0; c < 9; ++c) {
        if (!std::isfinite(f->v[c])) {
          return Error{where(i),
                       fmt::format("corner {} has a coordinate that is not a finite number ({}); the "
                                   "file is corrupt — repair or re-export the model",
                                   c / 3 + 1, f->v[c])};
        }
      }
      if (normal_disagrees(*f) && wrong_normals++ == 0) first_wrong = i;
      std::memcpy(&corners[9 * k], f->v, sizeof f->v);
    }
    welder.add(corners.data(), m, dropped.data());
    for (size_t k = 0; k < m; ++k) {
      if (dropped[k] && degenerate++ == 0) first_degenerate = base + k;
    }
  }
  if (degenerate == n) {
    return Error{file,
                 fmt::format("all {} triangles are degenerate (two or three corners at the same point); "
                             "the model has no surface — check its export settings",
                             n)};
  }
  if (degenerate > 0) {
    report.warn(
        "stl-degenerate", where(first_degenerate),
        fmt::format("dropped {} degenerate triangle{} of {} (two corners at the same point; first here)",
                    degenerate, degenerate == 1 ? "" : "s", n));
  }
  if (wrong_normals > 0) {
    report.warn(
        "stl-normal", where(first_wrong),
        fmt::format("{} of {} facets have a normal that disagrees with their vertex order (first here); "
                    "the vertex order (counter-clockwise seen from outside) is used — if the print "
                    "comes out inside out, repair the model's winding",
                    wrong_normals, n));
  }
  Mesh mesh;
  welder.finish(mesh);
  mesh.name = raw.name.empty() ? std::filesystem::path(file).stem().string() : std::move(raw.name);
  return mesh;
}

// Which parser a file goes to, from its first bytes (a kilobyte is enough) and its size.
enum class Kind { Binary, Ascii, OtherText };

Kind classify(std::string_view head, uint64_t size) {
  // Binary when the header's count agrees with the size, even after "solid".
  if (size >= 84 && head.size() >= 84 && 84 + 50 * uint64_t{stl::binary_count(head)} == size) return Kind::Binary;
  // "solid" with NULs or control bytes is a binary header, unless the file is too short for one.
  if (starts_with_solid_word(head) && (looks_like_text(head) || size < 84)) return Kind::Ascii;
  if (looks_like_text(head)) return Kind::OtherText;
  return Kind::Binary;
}

Error not_stl_text(std::string_view bytes, const std::string& name) {
  return Error{name, fmt::format("not an STL file: it is text but does not start with 'solid' (it starts "
                                 "with '{}'); export the model as STL",
                                 excerpt(bytes))};
}

Result<Mesh> parse_bytes(std::string_view bytes, const std::string& name, Report& report) {
  if (bytes.empty()) {
    return Error{name,
                 "the file is empty (0 bytes); export the model again or check that it was copied "
                 "completely"};
  }
  switch (classify(bytes, bytes.size())) {
    case Kind::Ascii: {
      Result<stl::RawStl> raw = stl::parse_ascii(bytes, name, report);
      if (!raw) return raw.error();
      return weld(std::move(raw.value()), name, report);
    }
    case Kind::OtherText: return not_stl_text(bytes, name);
    case Kind::Binary: break;
  }
  Result<stl::RawStl> raw = stl::parse_binary(bytes, name, report);
  if (!raw) return raw.error();
  return weld(std::move(raw.value()), name, report);
}

void put_u32(char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<char>((v >> (8 * i)) & 0xff);
}
void put_float(char* p, double v) { put_u32(p, std::bit_cast<uint32_t>(static_cast<float>(v))); }

}  // namespace

Result<Mesh> parse_stl(std::string_view bytes, const std::string& name, Report& report) {
  try {
    return parse_bytes(bytes, name, report);
  } catch (const std::bad_alloc&) {
    return Error{name,
                 fmt::format("not enough memory to load the model ({} MB of STL); close other programs or "
                             "simplify the model",
                             bytes.size() >> 20)};
  }
}

Result<uint64_t> check_stl_head(std::string_view head, std::optional<uint64_t> size, const std::string& name,
                                Report& report) {
  constexpr uint64_t kAll = UINT64_MAX;
  if (head.empty()) return size.value_or(kAll);  // the parser says "empty"
  const uint64_t count = stl::binary_count(head);
  const uint64_t needed = 84 + 50 * count;
  if (size) {
    switch (classify(head, *size)) {
      case Kind::Ascii: return *size;
      case Kind::OtherText: return not_stl_text(head, name);
      case Kind::Binary: break;
    }
    if (Status s = stl::check_binary_count(count, *size, name); !s) return s.error();
    if (needed < *size) stl::warn_extra_data(count, *size, name, report);  // and those bytes are not read
    return needed;
  }
  // A stream: its size is unknown, but a binary header is believed: no triangles is an error at
  // once, and no more than its triangles are read (an endless stream of zeros is not read at all).
  if (head.size() < 84 || starts_with_solid_word(head) || looks_like_text(head)) return kAll;
  if (count == 0 || count > Welder::kMaxTriangles) {
    if (Status s = stl::check_binary_count(count, needed, name); !s) return s.error();
  }
  return needed;
}

Result<Mesh> load_stl(const std::string& path, Report& report) {
  Result<FileBytes> bytes = read_file_bytes(path, [&](std::string_view head, std::optional<uint64_t> size) {
    return check_stl_head(head, size, path, report);
  });
  if (!bytes) return bytes.error();
  return parse_stl(bytes->view(), path, report);
}

Status write_stl_binary(const std::string& path, const Mesh& mesh) {
  if (mesh.triangles.size() > UINT32_MAX) {
    return Error{path, fmt::format("{} triangles do not fit a binary STL (at most {})", mesh.triangles.size(),
                                   UINT32_MAX)};
  }
  std::string out(84 + 50 * mesh.triangles.size(), '\0');
  // Never start the header with "solid": older readers would take the file for ASCII.
  std::string header = mesh.name;
  std::string lower = header.substr(0, 5);
  for (char& ch : lower) ch = static_cast<char>(ch | 0x20);
  if (lower == "solid") header = "model " + header;
  std::memcpy(out.data(), header.data(), std::min<size_t>(header.size(), 80));
  put_u32(out.data() + 80, static_cast<uint32_t>(mesh.triangles.size()));
  char* p = out.data() + 84;
  for (size_t i = 0; i < mesh.triangles.size(); ++i, p += 50) {
    const auto& t = mesh.triangles[i];
    for (uint32_t id : t) {
      if (id >= mesh.vertices.size()) {
        return Error{stl::at_triangle(path, i),
                     fmt::format("vertex id {} is out of range ({} vertices); nothing was written", id,
                                 mesh.vertices.size())};
      }
    }
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    for (const Vec3* v : {&a, &b, &c}) {
      for (double x : {v->x, v->y, v->z}) {
        if (!(std::fabs(x) <= std::numeric_limits<float>::max())) {
          return Error{stl::at_triangle(path, i),
                       fmt::format("coordinate {} mm does not fit a 32-bit float; nothing was written", x)};
        }
      }
    }
    const Vec3 u{b.x - a.x, b.y - a.y, b.z - a.z}, w{c.x - a.x, c.y - a.y, c.z - a.z};
    Vec3 nrm{u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
    const double len = std::sqrt(nrm.x * nrm.x + nrm.y * nrm.y + nrm.z * nrm.z);
    if (len > 0 && std::isfinite(len)) {
      nrm = {nrm.x / len, nrm.y / len, nrm.z / len};
    } else {
      nrm = {};
    }
    const double vals[12] = {nrm.x, nrm.y, nrm.z, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z};
    for (int k = 0; k < 12; ++k) put_float(p + 4 * k, vals[k]);
  }
  auto file = OutputFile::create(path, "the STL file");
  if (!file) return file.error();
  if (Status s = file->write(out); !s) return s;
  return file->commit();
}

}  // namespace tranche::geo
