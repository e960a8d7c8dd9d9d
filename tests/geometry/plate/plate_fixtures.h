// Fixtures for the plate tests, generated in code: 3MF packages written by hand (model XML, our
// ZIP writer, optionally deflated as slicers write them) for the cases lib3mf would never
// write, and OBJ text.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "geometry/plate/zip.h"

namespace tranche::test::plate {

inline const char* kNs =
    "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" "
    "xmlns:p=\"http://schemas.microsoft.com/3dmanufacturing/production/2015/06\"";

// The <mesh> of the box [x0, x0+sx] × [0, sy] × [0, sz], mm, counter-clockwise from outside.
inline std::string box_mesh(double sx, double sy, double sz, double x0 = 0) {
  std::string v;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) v += fmt::format("<vertex x=\"{}\" y=\"{}\" z=\"{}\"/>", x0 + x * sx, y * sy, z * sz);
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  std::string t;
  for (const auto& tri : f) t += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>", tri[0], tri[1], tri[2]);
  return "<mesh><vertices>" + v + "</vertices><triangles>" + t + "</triangles></mesh>";
}

// Two boxes in one mesh: triangles 0-11 the first, 12-23 the second (x from 20).
inline std::string two_box_mesh() {
  std::string a = box_mesh(10, 10, 10), b = box_mesh(5, 5, 5, 20);
  // Renumber the second box's vertices after the first's 8.
  std::string verts = a.substr(a.find("<vertices>") + 10, a.find("</vertices>") - a.find("<vertices>") - 10) +
                      b.substr(b.find("<vertices>") + 10, b.find("</vertices>") - b.find("<vertices>") - 10);
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  std::string t;
  for (int off : {0, 8})
    for (const auto& tri : f)
      t += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>", tri[0] + off, tri[1] + off, tri[2] + off);
  return "<mesh><vertices>" + verts + "</vertices><triangles>" + t + "</triangles></mesh>";
}

inline std::string model(const std::string& resources, const std::string& build,
                         const std::string& unit = "millimeter") {
  return fmt::format("<?xml version=\"1.0\" encoding=\"UTF-8\"?><model unit=\"{}\" {}><resources>{}</resources>"
                     "<build>{}</build></model>",
                     unit, kNs, resources, build);
}

inline const char* kContentTypes =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Types "
    "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default Extension=\"rels\" "
    "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default Extension=\"model\" "
    "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/><Default Extension=\"config\" "
    "ContentType=\"text/xml\"/></Types>";
inline const char* kRels =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Relationships "
    "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
    "Target=\"/3D/3dmodel.model\" Id=\"rel0\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>"
    "</Relationships>";

inline void put(std::string& out, uint64_t v, int n) {
  for (int i = 0; i < n; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

inline uint64_t le32(const std::string& b, size_t at) {
  uint64_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + i]);
  return v;
}

inline uint32_t crc_of(const std::string& content) {
  return static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(content.data()), static_cast<uInt>(content.size())));
}

// A ZIP archive whose entries are deflated (method 8), as PrusaSlicer and Python write them.
inline std::string deflated_zip(const std::vector<std::pair<std::string, std::string>>& files) {
  std::string out, dir;
  for (const auto& [name, content] : files) {
    z_stream zs{};
    deflateInit2(&zs, 6, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
    std::string packed(deflateBound(&zs, content.size()), '\0');
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(content.data()));
    zs.avail_in = static_cast<uInt>(content.size());
    zs.next_out = reinterpret_cast<Bytef*>(packed.data());
    zs.avail_out = static_cast<uInt>(packed.size());
    deflate(&zs, Z_FINISH);
    packed.resize(zs.total_out);
    deflateEnd(&zs);
    const uint32_t crc = static_cast<uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(content.data()), static_cast<uInt>(content.size())));
    const uint64_t offset = out.size();
    for (bool central : {false, true}) {
      std::string& to = central ? dir : out;
      put(to, central ? 0x02014b50 : 0x04034b50, 4);
      if (central) put(to, 20, 2);
      for (uint64_t v : {20, 0, 8, 0, 0x21}) put(to, v, 2);
      put(to, crc, 4);
      put(to, packed.size(), 4);
      put(to, content.size(), 4);
      put(to, name.size(), 2);
      put(to, 0, 2);
      if (central) {
        for (int i = 0; i < 3; ++i) put(to, 0, 2);
        put(to, 0, 4);
        put(to, offset, 4);
      }
      to += name;
      if (!central) to += packed;
    }
  }
  const uint64_t cd = out.size();
  out += dir;
  put(out, 0x06054b50, 4);
  put(out, 0, 4);
  put(out, files.size(), 2);
  put(out, files.size(), 2);
  put(out, dir.size(), 4);
  put(out, cd, 4);
  put(out, 0, 2);
  return out;
}

// A 3MF package of one model part and `extra` entries; deflated unless `stored`.
inline std::string package(const std::string& model_xml,
                           std::vector<std::pair<std::string, std::string>> extra = {}, bool stored = false) {
  std::vector<std::pair<std::string, std::string>> files = {
      {"[Content_Types].xml", kContentTypes}, {"_rels/.rels", kRels}, {"3D/3dmodel.model", model_xml}};
  for (auto& e : extra) files.push_back(std::move(e));
  return stored ? tranche::plate::write_stored_zip(files) : deflated_zip(files);
}

// The 6 quads of the unit cube scaled by `s` as OBJ text (1-based indices).
inline std::string cube_obj(double s = 10) {
  std::string t = "# a cube of quads\no cube\n";
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) t += fmt::format("v {} {} {}\n", x * s, y * s, z * s);
  // vertex (x, y, z) is 1 + x + 2y + 4z
  t += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return t;
}

}  // namespace tranche::test::plate
