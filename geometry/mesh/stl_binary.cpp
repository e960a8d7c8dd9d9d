// Binary STL: an 80-byte header, a little-endian uint32 triangle count, then 50 bytes per
// triangle (normal and three corners as 12 little-endian float32, then a uint16 attribute).
#include <fmt/format.h>

#include <bit>
#include <cstring>

#include "geometry/mesh/stl_parse.h"
#include "geometry/mesh/weld.h"

namespace tranche::geo::stl {
namespace {

constexpr size_t kHeader = 84;
constexpr size_t kRecord = RawStl::kRecordBytes;

uint32_t read_u32(const char* p) {
  const auto* u = reinterpret_cast<const unsigned char*>(p);
  return uint32_t{u[0]} | uint32_t{u[1]} << 8 | uint32_t{u[2]} << 16 | uint32_t{u[3]} << 24;
}

void read_floats(const char* p, float* out, size_t n) {
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(out, p, n * sizeof(float));
  } else {
    for (size_t i = 0; i < n; ++i) out[i] = std::bit_cast<float>(read_u32(p + 4 * i));
  }
}

bool starts_with_solid(std::string_view s) {
  if (s.size() < 5) return false;
  for (size_t i = 0; i < 5; ++i) {
    if ((s[i] | 0x20) != "solid"[i]) return false;
  }
  return true;
}

// Header text up to the first NUL, trimmed, without a leading "solid"; empty unless printable ASCII.
std::string header_name(std::string_view header) {
  header = header.substr(0, std::min(header.find('\0'), header.size()));
  if (starts_with_solid(header)) header.remove_prefix(5);
  while (!header.empty() && (header.front() == ' ' || header.front() == '\t')) header.remove_prefix(1);
  while (!header.empty() && (header.back() == ' ' || header.back() == '\t')) header.remove_suffix(1);
  for (char c : header) {
    if (c < 0x20 || c > 0x7e) return {};
  }
  return std::string(header);
}

}  // namespace

Status check_binary_count(uint64_t count, uint64_t size, const std::string& file) {
  if (size < kHeader) {
    return Error{file, fmt::format("file is {} bytes: too short for a binary STL (84-byte header and count) "
                                   "and it does not start with 'solid', so it is not an ASCII STL either; "
                                   "check that this is the model file and that it was copied completely",
                                   size)};
  }
  const uint64_t complete = (size - kHeader) / kRecord;
  const uint64_t needed = kHeader + kRecord * count;
  if (count == 0) {
    return Error{file,
                 fmt::format("header says 0 triangles{}; the model is empty — export it again with "
                             "its geometry selected",
                             size > kHeader ? fmt::format(" ({} bytes follow it)", size - kHeader) : "")};
  }
  if (needed > size) {
    return Error{at_triangle(file, complete),
                 fmt::format("header says {} triangles, file holds {} complete ones ({} bytes; {} triangles "
                             "need {}); the file is truncated or its triangle count is wrong — re-export "
                             "the model or copy it again",
                             count, complete, size, count, needed)};
  }
  if (count > Welder::kMaxTriangles) {
    return Error{file, fmt::format("header says {} triangles; at most {} are supported — simplify the model",
                                   count, Welder::kMaxTriangles)};
  }
  return ok_status();
}

void warn_extra_data(uint64_t count, uint64_t size, const std::string& file, Report& report) {
  const uint64_t needed = kHeader + kRecord * count;
  const uint64_t more = (size - kHeader) / kRecord - count;
  report.warn("stl-extra-data", file,
              fmt::format("{} bytes after the last of the header's {} triangles are ignored{}; if parts of "
                          "the model are missing, its triangle count is wrong — re-export it",
                          size - needed, count, more > 0 ? fmt::format(" (room for {} more)", more) : std::string()));
}

uint32_t binary_count(std::string_view bytes) { return bytes.size() < kHeader ? 0 : read_u32(bytes.data() + 80); }

Result<RawStl> parse_binary(std::string_view bytes, const std::string& file, Report& report) {
  const uint64_t size = bytes.size();
  const uint64_t count = binary_count(bytes);
  if (Status s = check_binary_count(count, size, file); !s) return s.error();
  const uint64_t needed = kHeader + kRecord * count;
  if (needed < size) warn_extra_data(count, size, file, report);

  RawStl raw;
  raw.name = header_name(bytes.substr(0, 80));
  raw.records = bytes.substr(kHeader, kRecord * count);
  return raw;
}

void decode_record(const char* record, Facet& out) {
  read_floats(record, out.normal, 3);
  read_floats(record + 12, out.v, 9);
}

}  // namespace tranche::geo::stl
