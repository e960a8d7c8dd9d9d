// Bundles: a compiled rule set in a file (`rulec build`), read by `tranche slice --rules`.
// All integers little-endian; sections 8-byte aligned; identical programs give identical bytes.
//
//   offset  size   field
//   0       8      magic "TRNCHRUL"
//   8       4      format version (kBundleVersion)
//   12      4      flags: bit 0 = a debug section is present
//   16      8      schema hash (runtime/schema): a bundle built for other fields is refused
//   24      8      checksum: FNV-1a 64 of every byte from offset 32 to the end
//   32      4      number of sections n
//   36      4      file size in bytes
//   40      16·n   section table: id u32, 0 u32, offset u32, size u32
//   ...            sections, each starting on a multiple of 8
//
//   section  id  contents
//   strings   1  u32 n, then n × (u32 length, bytes)
//   consts    2  u32 n, then n × f64
//   code      3  u32 n, then n × u64 (program.h draws the instruction layout)
//   chunks    4  u32 n, then n × (u32 start, u32 size, u16 registers, u8 kind, u8 0)
//   rules     5  u32 n, n × conjunct (u32 chunk, u8 level, 3 × u8 0); u32 m, m × rule (u32 first, u32 count)
//   slots     6  for each property (schema order), each level's before and after hook, each
//                level's replacement: u32 n, then n × (u32 rule, u32 chunk, u8 append, 3 × u8 0)
//   order     7  u32 n, then n × u16 property id
//   debug     8  files (u32 n, strings), locations (u32 n, n × 3 × u32), per instruction (u32 n,
//                n × u32), rule names (u32 n, strings), rule locations (u32 n, n × u32),
//                conjunct texts (u32 n, strings), conjunct locations (u32 n, n × u32)
//
// Reading never trusts a count: every length is checked against the bytes left before anything
// is allocated, and the program is verified (verify.h) before it is returned.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.h"
#include "runtime/vm/program.h"

namespace tranche::vm {

inline constexpr char kBundleMagic[8] = {'T', 'R', 'N', 'C', 'H', 'R', 'U', 'L'};
// Version 2: the checksum is FNV-1a 64 with the reference offset basis (version 1 used a basis
// missing its last digit), and the schema hash changed with it.
inline constexpr uint32_t kBundleVersion = 2;
inline constexpr size_t kMaxBundleBytes = 256u << 20;

// The bundle's bytes. `with_debug` false drops the debug section.
std::string write_bundle(const Program& program, bool with_debug = true);

// Parses and verifies; `name` (the file) is used in messages.
Result<Program> read_bundle(std::string_view bytes, const std::string& name);

// Whether the bytes start with the bundle magic (to tell a bundle from a .rules file).
bool looks_like_bundle(std::string_view bytes);

// The checksum a bundle's header holds: FNV-1a 64 of every byte from offset 32 on (tools and
// tests that build or alter bundles use it to keep them readable).
uint64_t bundle_checksum(std::string_view bundle);

}  // namespace tranche::vm
