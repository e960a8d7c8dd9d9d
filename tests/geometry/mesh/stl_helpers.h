// Fixtures for the STL tests, generated in code: a cube, binary and ASCII STL bytes.
#pragma once

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/stl.h"

namespace tranche::test::stl {

using Tri = std::array<float, 9>;  // corners a, b, c

// The 12 triangles of the cube [x0, x0+s]³, counter-clockwise seen from outside.
inline std::vector<Tri> cube(float x0 = 0, float s = 1) {
  const float a = x0, b = x0 + s;
  const float v[8][3] = {{a, a, a}, {b, a, a}, {b, b, a}, {a, b, a},
                         {a, a, b}, {b, a, b}, {b, b, b}, {a, b, b}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::vector<Tri> out;
  for (const auto& t : f) {
    Tri tri;
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d) tri[3 * k + d] = v[t[k]][d];
    }
    out.push_back(tri);
  }
  return out;
}

inline std::array<float, 3> normal_of(const Tri& t) {
  const float u[3] = {t[3] - t[0], t[4] - t[1], t[5] - t[2]};
  const float w[3] = {t[6] - t[0], t[7] - t[1], t[8] - t[2]};
  return {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
}

inline void put_u32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}
inline void put_f32(std::string& s, float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  put_u32(s, u);
}

struct BinaryOptions {
  std::string header;      // padded with NULs to 80 bytes
  int64_t count = -1;      // -1: the number of triangles
  uint16_t attribute = 0;  // the per-triangle attribute word
  bool zero_normals = false;
  bool flip_normals = false;

  BinaryOptions& with_header(std::string h) { return header = std::move(h), *this; }
  BinaryOptions& with_count(int64_t n) { return count = n, *this; }
  BinaryOptions& with_attribute(uint16_t a) { return attribute = a, *this; }
  BinaryOptions& with_zero_normals() { return zero_normals = true, *this; }
  BinaryOptions& with_flipped_normals() { return flip_normals = true, *this; }
};

inline std::string binary_stl(const std::vector<Tri>& tris, const BinaryOptions& o = {}) {
  std::string s = o.header.substr(0, 80);
  s.resize(80, '\0');
  put_u32(s, static_cast<uint32_t>(o.count < 0 ? static_cast<int64_t>(tris.size()) : o.count));
  for (const auto& t : tris) {
    auto n = o.zero_normals ? std::array<float, 3>{0, 0, 0} : normal_of(t);
    for (float c : n) put_f32(s, o.flip_normals ? -c : c);
    for (float c : t) put_f32(s, c);
    s += static_cast<char>(o.attribute & 0xff);
    s += static_cast<char>(o.attribute >> 8);
  }
  return s;
}

// ASCII STL with the usual layout; `eol` lets tests write CRLF files.
inline std::string ascii_stl(const std::vector<Tri>& tris, const std::string& name = "cube",
                             const std::string& eol = "\n") {
  std::string s = "solid " + name + eol;
  for (const auto& t : tris) {
    const auto n = normal_of(t);
    s += "  facet normal " + std::to_string(n[0]) + " " + std::to_string(n[1]) + " " + std::to_string(n[2]) +
         eol;
    s += "    outer loop" + eol;
    for (int k = 0; k < 3; ++k) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "      vertex %.9g %.9g %.9g", t[3 * k], t[3 * k + 1], t[3 * k + 2]);
      s += buf + eol;
    }
    s += "    endloop" + eol + "  endfacet" + eol;
  }
  return s + "endsolid " + name + eol;
}

inline void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

inline Result<geo::Mesh> parse(const std::string& bytes, Report& report, const std::string& name = "t.stl") {
  return geo::parse_stl(bytes, name, report);
}

// The error text of a parse that must fail ("" and a failed check if it loaded).
inline std::string error_of(const std::string& bytes, const std::string& name = "t.stl") {
  Report report;
  auto r = geo::parse_stl(bytes, name, report);
  CHECK_MESSAGE(!r.ok(), "expected an error for ", name);
  return r.ok() ? std::string() : r.error().to_string();
}

}  // namespace tranche::test::stl
