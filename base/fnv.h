// FNV-1a, 64-bit (Fowler, Noll, Vo: http://www.isthe.com/chongo/tech/comp/fnv/): the hash the
// bundle checksum and the schema hash use. Offset basis and prime as the reference gives them;
// tests/base/fnv_test.cpp checks the reference's test vectors.
#pragma once

#include <cstdint>
#include <string_view>

namespace tranche {

inline constexpr uint64_t kFnv1a64Basis = 14695981039346656037ull;
inline constexpr uint64_t kFnv1a64Prime = 1099511628211ull;

// Continues a hash `h` over `bytes` (start with kFnv1a64Basis).
constexpr uint64_t fnv1a64(std::string_view bytes, uint64_t h = kFnv1a64Basis) {
  for (char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * kFnv1a64Prime;
  return h;
}

}  // namespace tranche
