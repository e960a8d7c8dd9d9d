#include "base/fnv.h"

#include <doctest/doctest.h>

#include <string>

using tranche::fnv1a64;

// Test vectors of the FNV reference (test_fnv.c of the reference implementation, FNV-1a 64).
TEST_CASE("fnv1a64: the reference's test vectors") {
  CHECK(fnv1a64("") == 0xcbf29ce484222325ull);
  CHECK(fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  CHECK(fnv1a64("b") == 0xaf63df4c8601f1a5ull);
  CHECK(fnv1a64("foobar") == 0x85944171f73967e8ull);
  CHECK(fnv1a64(std::string("\0", 1)) == 0xaf63bd4c8601b7dfull);
  static_assert(fnv1a64("") == tranche::kFnv1a64Basis);
}

TEST_CASE("fnv1a64: hashing in pieces equals hashing the whole") {
  CHECK(fnv1a64("bar", fnv1a64("foo")) == fnv1a64("foobar"));
}
