// Slicing generated meshes with the stdlib profile (printer, material) and stdlib feature files,
// as `tranche slice --printer P --material M --rules stdlib/features/F.rules` would.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "apps/slice_command.h"
#include "tests/e2e/gcode_reader.h"
#include "tests/support/fixtures.h"

namespace tranche::test {

struct Profile {
  std::string printer_ = "generic-marlin";
  std::string material_ = "pla";
  std::vector<std::string> rule_files_;  // the user's own rule files, before the features
  std::vector<std::string> features_;  // names in stdlib/features, without .rules
  std::vector<std::pair<std::string, std::string>> sets_ = {{"skirt_loops", "0"}};

  Profile printer(std::string p) const { Profile c = *this; c.printer_ = std::move(p); return c; }
  Profile material(std::string m) const { Profile c = *this; c.material_ = std::move(m); return c; }
  Profile rules(std::string path) const { Profile c = *this; c.rule_files_.push_back(std::move(path)); return c; }
  Profile feature(std::string f) const { Profile c = *this; c.features_.push_back(std::move(f)); return c; }
  Profile set(std::string k, std::string v) const { Profile c = *this; c.sets_.emplace_back(std::move(k), std::move(v)); return c; }
};

inline std::filesystem::path stdlib_path() { return source_dir() / "stdlib"; }

inline Gcode slice_with(const TempDir& dir, const std::string& name, const geo::Mesh& mesh, const Profile& p) {
  pipeline::SliceOptions o;
  o.quiet = true;
  o.model = (dir / (name + ".stl")).string();
  REQUIRE(geo::write_stl_binary(o.model, mesh).ok());
  o.output_gcode = (dir / (name + ".gcode")).string();
  o.printer = p.printer_;
  o.material = p.material_;
  o.stdlib_dir = stdlib_path().string();
  o.rules = p.rule_files_;
  for (const auto& f : p.features_) o.rules.push_back((stdlib_path() / "features" / (f + ".rules")).string());
  o.sets = p.sets_;
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  for (const auto& w : report.warnings()) CHECK_MESSAGE(w.code != "rules", w.where << ": " << w.message);
  return read_gcode(o.output_gcode);
}

inline bool extrudes(const Move& m) { return m.has_xy && m.de > 0; }

inline double length(const Move& m) { return std::hypot(m.x - m.x0, m.y - m.y0); }

// Direction of a segment as an undirected line, in [0, 180) degrees.
inline double line_angle(const Move& m) {
  double a = std::atan2(m.y - m.y0, m.x - m.x0) * 180 / std::numbers::pi;
  return std::fmod(a + 360, 180);
}

// Smallest difference between two undirected line angles, in degrees.
inline double angle_diff(double a, double b) {
  double d = std::abs(std::fmod(a - b + 360 * 4, 180.0));
  return std::min(d, 180 - d);
}

// The direction of the longest sparse-infill line of each layer.
inline std::map<int, double> infill_angles(const Gcode& g) {
  std::map<int, std::pair<double, double>> longest;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.type != "Internal infill") continue;
    auto& l = longest[m.layer];
    if (length(m) > l.first) l = {length(m), line_angle(m)};
  }
  std::map<int, double> out;
  for (const auto& [layer, l] : longest) out[layer] = l.second;
  return out;
}

// Filament per mm of travel of the extruding moves of one type (optionally on one layer).
inline double e_per_mm(const Gcode& g, const std::string& type, int layer = -1) {
  double e = 0, len = 0;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == type && (layer < 0 || m.layer == layer) && length(m) > 0.5) {
      e += m.de;
      len += length(m);
    }
  return len > 0 ? e / len : 0;
}

inline size_t count_lines(const Gcode& g, const std::string& prefix) {
  size_t n = 0;
  for (const auto& l : g.lines) n += l.rfind(prefix, 0) == 0;
  return n;
}

// The layer (;LAYER:n) a line index is in, -1 before the first.
inline int layer_of_line(const Gcode& g, size_t line) {
  int layer = -1;
  for (size_t i = 0; i <= line && i < g.lines.size(); ++i)
    if (g.lines[i].rfind(";LAYER:", 0) == 0) layer = std::stoi(g.lines[i].substr(7));
  return layer;
}

inline std::vector<size_t> lines_starting(const Gcode& g, const std::string& prefix) {
  std::vector<size_t> out;
  for (size_t i = 0; i < g.lines.size(); ++i)
    if (g.lines[i].rfind(prefix, 0) == 0) out.push_back(i);
  return out;
}

}  // namespace tranche::test
