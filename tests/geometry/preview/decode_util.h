// Test-side readers of what the preview writes, written from the format's description
// (docs/preview.md), not from the writer's code: base64, zlib and the varint blob.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tranche::preview::test {

inline std::string base64_decode(std::string_view s) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    if (c == '=') break;
    const int v = val(c);
    if (v < 0) throw std::runtime_error("bad base64 character");
    acc = acc << 6 | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

inline std::string inflate(std::string_view z, size_t size) {
  std::string out(size, '\0');
  uLongf n = static_cast<uLongf>(size);
  if (::uncompress(reinterpret_cast<Bytef*>(out.data()), &n, reinterpret_cast<const Bytef*>(z.data()),
                   static_cast<uLong>(z.size())) != Z_OK ||
      n != size)
    throw std::runtime_error("zlib stream does not inflate to the declared size");
  return out;
}

// The value of "key": in a flat JSON text (first occurrence), up to the next ',' '}' or ']'.
inline std::string json_value(const std::string& json, const std::string& key) {
  const size_t k = json.find("\"" + key + "\":");
  if (k == std::string::npos) return {};
  size_t b = k + key.size() + 3, e = b;
  if (json[b] == '"') {
    e = json.find('"', b + 1);
    return json.substr(b + 1, e - b - 1);
  }
  while (e < json.size() && json[e] != ',' && json[e] != '}' && json[e] != ']') ++e;
  return json.substr(b, e - b);
}

struct VarintReader {
  std::string_view buf;
  size_t at = 0;
  uint64_t u() {
    uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
      if (at >= buf.size()) throw std::runtime_error("blob ends early");
      const auto b = static_cast<uint8_t>(buf[at++]);
      v |= static_cast<uint64_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) return v;
    }
  }
  int64_t s() {
    const uint64_t v = u();
    return static_cast<int64_t>(v >> 1) ^ -static_cast<int64_t>(v & 1);
  }
};

}  // namespace tranche::preview::test
