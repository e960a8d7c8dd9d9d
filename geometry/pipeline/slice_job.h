// One `tranche slice` run: the options the command line gives, and the function that runs the
// whole pipeline (load → plan → slice → resolve → relate → decompose → toolpaths → G-code) with
// the rules already compiled (compiler/load_rules.h; apps/slice_command.h does both).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/plate/object.h"
#include "runtime/vm/vm.h"

namespace tranche::pipeline {

enum class OverlapMode { Additive, Boolean, Subtractive };

inline constexpr uint64_t kDefaultMaxGcodeMb = 2048;  // 2 GiB: docs/cli.md, "Files and safety"

struct SliceOptions {
  std::string model;                        // STL or SVG path
  std::string output_gcode;                 // -o; empty = no G-code
  std::vector<std::string> rules;           // --rules, in cascade order (compiled by the caller)
  std::string printer = "generic-marlin";   // --printer: stdlib/printers/NAME.rules or a file; "none"
  std::string material = "pla";             // --material: stdlib/materials/NAME.rules or a file; "none"
  bool profile = true;                      // false: no stdlib profile (library tests)
  std::string stdlib_dir;                   // --stdlib: where `use "printers/..."` looks first
  std::vector<std::pair<std::string, std::string>> sets;  // --set key=value, in order
  std::string export_svg;                   // --export-svg
  std::string export_layers;                // --export-layers (JSON)
  bool exact_cells = false;                 // --exact-cells: the exports also show the exact cells (analysis)
  std::string export_preview;               // --export-preview (HTML)
  std::string explain;                      // --explain "layer=12 island=0 path=outer_perimeter" (explain_slice.h)
  std::string thumbnails;                   // --thumbnails "16x16/QOI, 220x124/PNG": overrides the property
  OverlapMode overlap = OverlapMode::Additive;
  std::string fill_angle_script;            // --fill-angle-script (Python)
  int svg_layers = 0;                       // --svg-layers: flat SVG layer count (0: 10, or --svg-height)
  double svg_height_mm = 0;                 // --svg-height: flat SVG extrusion height, mm (0: by layers)
  double svg_tolerance_mm = 0.01;           // --svg-tolerance: largest curve-to-polyline gap, mm
  std::string background = "white";         // --background: the colour that erases (subtractive)
  bool strict = false;                      // --strict: coherence warnings become errors
  bool allow_off_bed = false;               // --allow-off-bed: a move off the bed is a warning, not an error
  bool quiet = false;                       // --quiet: no progress on stderr
  uint64_t max_gcode_mb = kDefaultMaxGcodeMb;  // --max-gcode-size: the largest G-code written (MiB; 0: none)
  double script_timeout_s = 5;              // --script-timeout: the longest a fill_angle(ctx) call may take
};

// What a finished run reports to the user.
struct SliceSummary {
  int layers = 0;
  size_t triangles = 0;
  std::vector<std::string> written;  // output files, in the order written
  std::string explanation;           // --explain: the paths explained (explain_slice.h)
};

// What can be refused before any work: a run that writes and explains nothing, an --explain
// that does not parse.
Status check_options(const SliceOptions& options);

// Slices `plate` (meshes: STL, 3MF, OBJ, placed by geometry/plate), or when it is null the SVG
// drawing `options.model`. `rules`: the profile, --rules files and --set expressions compiled and
// linked (null: none); the plain --set overrides of `options.sets` are applied above them.
Result<SliceSummary> run_slice(const SliceOptions& options, const plate::Plate* plate, const vm::RuleSet* rules,
                               Report& report);

}  // namespace tranche::pipeline
