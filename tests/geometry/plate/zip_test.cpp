// The ZIP reading under the 3MF loader: round trips, and damage that must be refused, not believed.
#include <doctest/doctest.h>

#include <algorithm>

#include "geometry/plate/zip.h"
#include "tests/geometry/plate/plate_fixtures.h"

using namespace tranche;
using namespace tranche::plate;

namespace {
bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// An entry read through ZipArchive::stream in pieces of `piece` bytes.
Result<std::string> streamed(const ZipArchive& zip, const ZipEntry& e, size_t piece) {
  auto in = zip.stream(e);
  if (!in) return in.error();
  std::string out;
  std::vector<char> buf(piece);
  size_t longest = 0;
  for (;;) {
    auto got = in->read(buf.data(), buf.size());
    if (!got) return got.error();
    if (*got == 0) break;
    longest = std::max(longest, *got);
    out.append(buf.data(), *got);
  }
  CHECK(longest <= piece);
  auto after = in->read(buf.data(), buf.size());  // ended: stays ended
  REQUIRE(after.ok());
  CHECK(*after == 0);
  return out;
}

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
    for (size_t piece : {size_t{1}, size_t{4096}, size_t{1} << 20}) {  // in pieces, as long as they come
      CAPTURE(piece);
      CHECK(*streamed(*zip, *zip->find("dir/b.xml"), piece) == big);
      CHECK(*streamed(*zip, *zip->find("a.txt"), piece) == "alpha");
    }
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

namespace {

// A ZIP archive of one deflated entry whose data and directory sizes are given as they are,
// damage included.
std::string one_entry(const std::string& packed, uint64_t size, uint32_t crc) {
  std::string out, dir;
  const std::string name = "model.xml";
  for (bool central : {false, true}) {
    std::string& to = central ? dir : out;
    test::plate::put(to, central ? 0x02014b50 : 0x04034b50, 4);
    if (central) test::plate::put(to, 20, 2);
    for (uint64_t v : {20, 0, 8, 0, 0x21}) test::plate::put(to, v, 2);
    test::plate::put(to, crc, 4);
    test::plate::put(to, packed.size(), 4);
    test::plate::put(to, size, 4);
    test::plate::put(to, name.size(), 2);
    test::plate::put(to, 0, 2);
    if (central) {
      for (int i = 0; i < 3; ++i) test::plate::put(to, 0, 2);
      test::plate::put(to, 0, 4);
      test::plate::put(to, 0, 4);
    }
    to += name;
    if (!central) to += packed;
  }
  const uint64_t cd = out.size();
  out += dir;
  test::plate::put(out, 0x06054b50, 4);
  test::plate::put(out, 0, 4);
  test::plate::put(out, 1, 2);
  test::plate::put(out, 1, 2);
  test::plate::put(out, dir.size(), 4);
  test::plate::put(out, cd, 4);
  test::plate::put(out, 0, 2);
  return out;
}

// The deflate data of the entry of a deflated_zip() of `content` alone.
std::string packed_of(const std::string& content) {
  const std::string zip = test::plate::deflated_zip({{"model.xml", content}});
  const size_t packed = test::plate::le32(zip, 18), name = 9;
  return zip.substr(30 + name, packed);
}

std::string read_error(const std::string& zip_bytes) {
  auto zip = ZipArchive::open(zip_bytes, "t.3mf");
  REQUIRE(zip.ok());
  auto r = zip->read(zip->entries()[0]);
  REQUIRE_FALSE(r.ok());
  auto b = zip->read_bytes(zip->entries()[0]);
  REQUIRE_FALSE(b.ok());
  CHECK(b.error().to_string() == r.error().to_string());  // every way, the same message
  for (size_t piece : {size_t{1} << 20, size_t{777}}) {
    auto s = streamed(*zip, zip->entries()[0], piece);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().to_string() == r.error().to_string());
  }
  return r.error().to_string();
}

}  // namespace

TEST_CASE("zip: damaged deflate data says how it is damaged") {
  std::string content;
  for (int i = 0; i < 20000; ++i) content += fmt::format("<vertex x=\"{}\" y=\"{}\" z=\"0\"/>\n", i * 0.37, i % 101);
  const std::string packed = packed_of(content);
  const uint32_t crc = test::plate::crc_of(content);
  REQUIRE(packed.size() > 1000);
  {
    const std::string good = one_entry(packed, content.size(), crc);  // outlives the archive
    auto zip = ZipArchive::open(good, "t.3mf");
    REQUIRE(zip.ok());
    CHECK(*zip->read(zip->entries()[0]) == content);
  }
  SUBCASE("a truncated stream") {
    const std::string e = read_error(one_entry(packed.substr(0, packed.size() / 2), content.size(), crc));
    CHECK(has(e, "t.3mf, model.xml"));
    CHECK(has(e, "the data ends early"));
  }
  SUBCASE("bytes that are no deflate data") {
    CHECK(has(read_error(one_entry(std::string(400, '\xff'), 1000, crc)), "bad deflate data"));
  }
  SUBCASE("more data than the directory says") {
    CHECK(has(read_error(one_entry(packed, content.size() - 100, crc)), "the data is longer than the directory says"));
  }
  SUBCASE("less data than the directory says") {
    CHECK(has(read_error(one_entry(packed, content.size() + 100, crc)), "its size disagrees with the directory"));
  }
  SUBCASE("a wrong CRC") {
    CHECK(has(read_error(one_entry(packed, content.size(), crc ^ 1)), "CRC mismatch"));
  }
}

TEST_CASE("zip: a large entry read into memory of its own reads back whole") {
  // Past ZipBytes' threshold for mapped memory (4 MiB), and past the size from which a second
  // thread makes the pages ready while the entry is inflated into them (32 MiB): deflated and
  // stored, every byte must come back.
  std::string big;
  for (int i = 0; big.size() < (size_t{40} << 20); ++i) big += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>", i, i + 1, i + 2);
  for (const std::string& bytes : {test::plate::deflated_zip({{"3D/3dmodel.model", big}}),
                                   write_stored_zip({{"3D/3dmodel.model", big}})}) {
    auto zip = ZipArchive::open(bytes, "big.3mf");
    REQUIRE(zip.ok());
    auto b = zip->read_bytes(zip->entries()[0]);
    REQUIRE_MESSAGE(b.ok(), b.error().to_string());
    CHECK(b->size() == big.size());
    CHECK(*streamed(*zip, zip->entries()[0], size_t{1} << 20) == big);
    CHECK(b->view() == big);
    ZipBytes moved = std::move(*b);  // the memory changes hands, once
    CHECK(moved.view() == big);
    CHECK(b->size() == 0);
  }
  // Cut short: refused, however far the second thread had made pages ready.
  const std::string packed = packed_of(big);
  const std::string cut = one_entry(packed.substr(0, packed.size() / 3), big.size(), test::plate::crc_of(big));
  CHECK(has(read_error(cut), "the data ends early"));
  // A small one, in ordinary memory; and an empty one.
  const std::string small = write_stored_zip({{"a", "alpha"}, {"e", ""}});  // outlives the archive
  auto zip = ZipArchive::open(small, "s.zip");
  REQUIRE(zip.ok());
  CHECK(zip->read_bytes(*zip->find("a"))->view() == "alpha");
  CHECK(zip->read_bytes(*zip->find("e"))->view().empty());
}
