// make_cells on fill regions that broke it: every region is cut into monotone cells that tile it,
// without the fallback (a region filled with travel moves between lines).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/toolpath/cells.h"
#include "geometry/toolpath/clip.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {
// tests/data/fill-regions/*.txt: "# angle A" then "loop" and one "x y" (nm) per line.
struct Region {
  double angle = 45;
  geo::Rings rings;
};
Region read_region(const fs::path& p) {
  Region r;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# angle ", 0) == 0) r.angle = std::stod(line.substr(8));
    if (line.empty() || line[0] == '#') continue;
    if (line == "loop") {
      r.rings.emplace_back();
      continue;
    }
    std::istringstream ss(line);
    long long x, y;
    ss >> x >> y;
    r.rings.back().push_back(geo::Point(x, y));
  }
  return r;
}
}  // namespace

TEST_CASE("cells: fill regions whose plain union decompose() refused are cut through strict islands") {
  int files = 0;
  for (const auto& e : fs::directory_iterator(test::source_dir() / "tests" / "data" / "fill-regions")) {
    if (e.path().extension() != ".txt") continue;
    ++files;
    INFO(e.path().filename().string());
    Region r = read_region(e.path());
    REQUIRE_FALSE(r.rings.empty());
    toolpath::EdgeGrid border(r.rings);
    Report report;
    auto cells = toolpath::make_cells(r.rings, r.angle, border, report, "test");
    CHECK(report.count("decompose") == 0);
    CHECK(report.count("cell-not-monotone") == 0);
    double area = 0;
    for (const auto& c : cells) {
      CHECK(c.monotone);
      area += c.area_mm2;
    }
    double want = 0;
    for (const auto& ring : r.rings) want += geo::area_mm2(ring);
    CHECK(area == doctest::Approx(std::abs(want)).epsilon(1e-6));
  }
  CHECK(files >= 3);
}
