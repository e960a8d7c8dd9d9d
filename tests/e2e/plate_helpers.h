// Helpers of the plate's end-to-end tests: the parts of a layer's extrusions (one per object),
// slice options writing plate.gcode in a test folder, objects for a 3MF.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/plate/object.h"
#include "tests/support/fixtures.h"

namespace tranche::test::plate_e2e {

inline bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct Box {
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  void add(double x, double y) {
    min_x = std::min(min_x, x), max_x = std::max(max_x, x), min_y = std::min(min_y, y), max_y = std::max(max_y, y);
  }
  double w() const { return max_x - min_x; }
  double h() const { return max_y - min_y; }
};

// The extrusions of one layer (skirt left out), grouped into the parts that lie more than
// `gap` mm apart: one part per object.
inline std::vector<Box> parts(const test::Gcode& g, int layer, double gap = 2) {
  std::vector<std::pair<double, double>> p;
  for (const auto& m : g.moves)
    if (m.layer == layer && m.has_xy && m.de > 0 && m.type != "Skirt/Brim") {
      const int n = 1 + static_cast<int>(std::hypot(m.x - m.x0, m.y - m.y0));  // a point every mm or less
      for (int k = 0; k <= n; ++k) p.emplace_back(m.x0 + (m.x - m.x0) * k / n, m.y0 + (m.y - m.y0) * k / n);
    }
  std::vector<int> group(p.size(), -1);
  int groups = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    if (group[i] >= 0) continue;
    std::vector<size_t> stack = {i};
    group[i] = groups;
    while (!stack.empty()) {
      const size_t a = stack.back();
      stack.pop_back();
      for (size_t b = 0; b < p.size(); ++b)
        if (group[b] < 0 && std::hypot(p[a].first - p[b].first, p[a].second - p[b].second) <= gap) {
          group[b] = groups;
          stack.push_back(b);
        }
    }
    ++groups;
  }
  std::vector<Box> out(groups);
  for (size_t i = 0; i < p.size(); ++i) out[group[i]].add(p[i].first, p[i].second);
  std::sort(out.begin(), out.end(), [](const Box& a, const Box& b) { return a.min_x < b.min_x; });
  return out;
}

inline pipeline::SliceOptions options(const test::TempDir& dir) {
  pipeline::SliceOptions o;
  o.quiet = true;
  o.output_gcode = (dir / "plate.gcode").string();
  return o;
}

inline plate::Object object(const std::string& name, geo::Mesh mesh, const Eigen::Affine3d& t) {
  plate::Object o;
  o.name = name;
  o.mesh = std::move(mesh);
  o.transform = t;
  return o;
}

}  // namespace tranche::test::plate_e2e
