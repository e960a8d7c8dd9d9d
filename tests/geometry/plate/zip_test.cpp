// The ZIP reading under the 3MF loader: round trips, and damage that must be refused, not believed.
#include <doctest/doctest.h>

#include "geometry/plate/zip.h"
#include "tests/geometry/plate/plate_fixtures.h"

using namespace tranche;
using namespace tranche::plate;

namespace {
bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST_CASE("zip: stored and deflated entries read back; names are found case-insensitively") {
  const std::string big(100000, 'x');
  for (const std::string& bytes : {write_stored_zip({{"a.txt", "alpha"}, {"dir/B.xml", big}}),
                                   test::plate::deflated_zip({{"a.txt", "alpha"}, {"dir/B.xml", big}})}) {
    auto zip = ZipArchive::open(bytes, "t.zip");
    REQUIRE_MESSAGE(zip.ok(), zip.error().to_string());
    REQUIRE(zip->entries().size() == 2);
    REQUIRE(zip->find("/DIR/b.xml"));
    auto b = zip->read(*zip->find("dir/b.xml"));
    REQUIRE_MESSAGE(b.ok(), b.error().to_string());
    CHECK(*b == big);
    CHECK(*zip->read(*zip->find("a.txt")) == "alpha");
    CHECK(zip->find("c.txt") == nullptr);
  }
  CHECK(looks_like_zip(write_stored_zip({})));
  CHECK(ZipArchive::open(write_stored_zip({}), "empty.zip")->entries().empty());
}

TEST_CASE("zip: damage is named, and sizes are not believed") {
  const std::string good = test::plate::deflated_zip({{"model.xml", std::string(5000, 'm')}});
  CHECK(has(ZipArchive::open(good.substr(0, good.size() - 30), "t.zip").error().message, "damaged or truncated"));
  CHECK(has(ZipArchive::open("PK\x03\x04 not really a ZIP archive, only its first bytes", "t.zip").error().message, "no end-of-archive record"));

  std::string crc = good;
  crc[40] ^= 0x55;  // inside the deflated data
  auto z = ZipArchive::open(crc, "t.zip");
  REQUIRE(z.ok());
  auto r = z->read(z->entries()[0]);
  REQUIRE_FALSE(r.ok());
  CHECK(has(r.error().to_string(), "t.zip, model.xml"));

  // The central directory claims 2 GiB for a few bytes of deflate: refused before allocating.
  std::string claim = good;
  const size_t cd = claim.find("PK\x01\x02");
  REQUIRE(cd != std::string::npos);
  for (int i = 0; i < 4; ++i) claim[cd + 24 + i] = i == 3 ? '\x7f' : '\xff';
  auto zc = ZipArchive::open(claim, "t.zip");
  REQUIRE(zc.ok());
  CHECK(has(zc->read(zc->entries()[0]).error().message, "impossible"));
}
