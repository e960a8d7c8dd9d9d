// The polygon corpus format (tests/data/polygons/*.txt): loops of integer points that once broke
// resolution or decomposition, replayed by the tests. Line oriented, `#` starts a comment:
//
//   mode boolean           overlap mode, additive (default) or boolean
//   angles 0 45 90         fill angles to replay, degrees (default: 0 30 45 90 135)
//   expect islands 2       optional checks after resolution
//   expect holes 1         (total number of holes over all islands)
//   expect cells 90 1      cells over all islands when decomposed at that angle
//   loop                   starts a loop; then one point per line: "x y", integers in nm
//   0 0
//   1000000 0
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "geometry/polygon/resolve.h"
#include "base/result.h"

namespace tranche::geo {

struct PolygonCase {
  std::string name;
  OverlapMode mode = OverlapMode::Additive;
  std::vector<double> angles{0, 30, 45, 90, 135};
  int expect_islands = -1;  // -1: not checked
  int expect_holes = -1;
  std::vector<std::pair<double, int>> expect_cells;  // (angle in degrees, total cells)
  Rings loops;
};

// Errors name `name` and the line.
Result<PolygonCase> parse_polygon_case(std::string_view text, const std::string& name);
Result<PolygonCase> load_polygon_case(const std::string& path);
std::string format_polygon_case(const PolygonCase& c);

}  // namespace tranche::geo
