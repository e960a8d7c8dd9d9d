// Helper of the end-to-end tests that slice one constructed mesh: the mesh written as NAME.stl in
// a test folder, rules (if any) as NAME.rules, sliced to NAME.gcode with no skirt and `sets`.
#pragma once

#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/mesh/stl.h"
#include "tests/support/fixtures.h"

namespace tranche::test {

using Sets = std::vector<std::pair<std::string, std::string>>;

struct MeshRun {
  Result<pipeline::SliceSummary> result = Error{"", "not run"};
  std::vector<Warning> warnings;
  Gcode g;  // read when the slice succeeded
};

inline MeshRun slice_mesh(const TempDir& dir, const std::string& name, const geo::Mesh& mesh, const Sets& sets,
                          const std::string& rules = "", bool strict = false) {
  pipeline::SliceOptions o;
  o.quiet = true;
  o.strict = strict;
  o.model = (dir / (name + ".stl")).string();
  REQUIRE(geo::write_stl_binary(o.model, mesh).ok());
  o.output_gcode = (dir / (name + ".gcode")).string();
  if (!rules.empty()) {
    o.rules = {(dir / (name + ".rules")).string()};
    std::ofstream(o.rules[0], std::ios::binary) << rules;
  }
  o.sets = {{"skirt_loops", "0"}};
  o.sets.insert(o.sets.end(), sets.begin(), sets.end());
  Report report;
  MeshRun r;
  r.result = app::slice(o, report);
  r.warnings = report.warnings();
  if (r.result.ok()) r.g = read_gcode(o.output_gcode);
  return r;
}

}  // namespace tranche::test
