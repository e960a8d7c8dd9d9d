// tranche: the slicer's command line. Parses flags into SliceOptions and runs the pipeline.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "apps/slice_command.h"

namespace {

constexpr const char* kUsage = R"(usage: tranche slice MODEL [options]

Slices MODEL (.stl, binary or ASCII, or .svg) into G-code and/or layer exports.

options:
  -o, --output FILE            write G-code to FILE
  --rules FILE                 apply a .rules file or compiled bundle (repeatable; later wins)
  --printer NAME               printer profile: stdlib/printers/NAME.rules or a .rules file
                               (default generic-marlin; `none` for the defaults only)
  --material NAME              material profile: stdlib/materials/NAME.rules or a .rules file
                               (default pla; `none` for none)
  --stdlib DIR                 where stdlib rules (`use "printers/..."`) are looked for first
  --set KEY=VALUE              override a property, e.g. --set layer_height=0.15 (repeatable)
  --export-svg FILE            write every layer as SVG: its islands and the paths printed on them
  --export-layers FILE         write every layer as JSON: its islands and the paths printed on them
  --export-preview FILE        write the toolpaths as one HTML page: layers, colours by kind, speed,
                               flow, width, fan or deciding rule, and why each path is as it is
  --exact-cells                the exports also show each island's exact monotone cells (the
                               seed's decomposition: an analysis view, not what is printed)
  --overlap MODE               additive (default), boolean, or subtractive (SVG only)
  --fill-angle-script FILE     Python script defining fill_angle(ctx) -> degrees (trusted code)
  --svg-layers N               layers a flat SVG drawing is extruded to (default 10)
  --svg-height MM              height a flat SVG drawing is extruded to (instead of --svg-layers)
  --svg-tolerance MM           largest distance between an SVG curve and its polyline (default 0.01)
  --background COLOR           the colour that erases with --overlap subtractive (default white)
  --strict                     treat geometry coherence warnings as errors
  -q, --quiet                  no progress output
  -h, --help                   this text
)";

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "tranche: %s\n\n%s", msg.c_str(), kUsage);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using tranche::pipeline::OverlapMode;
  if (argc < 2) return usage_error("missing command");
  std::string_view cmd = argv[1];
  if (cmd == "-h" || cmd == "--help" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd != "slice") return usage_error("unknown command '" + std::string(cmd) + "'");

  tranche::pipeline::SliceOptions opt;
  opt.quiet = !isatty(STDERR_FILENO);
  for (int i = 2; i < argc; ++i) {
    std::string_view a = argv[i];
    auto value = [&](std::string& out) -> bool {
      if (i + 1 >= argc) return false;
      out = argv[++i];
      return true;
    };
    std::string v;
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "-o" || a == "--output") {
      if (!value(opt.output_gcode)) return usage_error("-o needs a file name");
    } else if (a == "--rules") {
      if (!value(v)) return usage_error("--rules needs a file name");
      opt.rules.push_back(v);
    } else if (a == "--printer") {
      if (!value(opt.printer) || opt.printer.empty()) return usage_error("--printer needs a name or a file");
    } else if (a == "--material") {
      if (!value(opt.material) || opt.material.empty()) return usage_error("--material needs a name or a file");
    } else if (a == "--stdlib") {
      if (!value(opt.stdlib_dir)) return usage_error("--stdlib needs a directory");
    } else if (a == "--set") {
      if (!value(v)) return usage_error("--set needs KEY=VALUE");
      auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0) return usage_error("--set needs KEY=VALUE, got '" + v + "'");
      opt.sets.emplace_back(v.substr(0, eq), v.substr(eq + 1));
    } else if (a == "--export-svg") {
      if (!value(opt.export_svg)) return usage_error("--export-svg needs a file name");
    } else if (a == "--export-layers") {
      if (!value(opt.export_layers)) return usage_error("--export-layers needs a file name");
    } else if (a == "--export-preview") {
      if (!value(opt.export_preview)) return usage_error("--export-preview needs a file name");
    } else if (a == "--exact-cells") {
      opt.exact_cells = true;
    } else if (a == "--overlap") {
      if (!value(v)) return usage_error("--overlap needs additive, boolean or subtractive");
      if (v == "additive") opt.overlap = OverlapMode::Additive;
      else if (v == "boolean") opt.overlap = OverlapMode::Boolean;
      else if (v == "subtractive") opt.overlap = OverlapMode::Subtractive;
      else return usage_error("--overlap must be additive, boolean or subtractive, not '" + v + "'");
    } else if (a == "--fill-angle-script") {
      if (!value(opt.fill_angle_script)) return usage_error("--fill-angle-script needs a file name");
    } else if (a == "--svg-layers" || a == "--svg-height" || a == "--svg-tolerance") {
      if (!value(v)) return usage_error(std::string(a) + " needs a number");
      char* end = nullptr;
      double x = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(x > 0) || x > 1e5)
        return usage_error(std::string(a) + " needs a positive number, not '" + v + "'");
      if (a == "--svg-layers") {
        if (x != std::floor(x))
          return usage_error("--svg-layers needs a whole number of layers, not '" + v + "'");
        opt.svg_layers = static_cast<int>(x);
      } else if (a == "--svg-height") {
        opt.svg_height_mm = x;
      } else {
        opt.svg_tolerance_mm = x;
      }
    } else if (a == "--background") {
      if (!value(opt.background)) return usage_error("--background needs a colour");
    } else if (a == "--strict") {
      opt.strict = true;
    } else if (a == "-q" || a == "--quiet") {
      opt.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + std::string(a) + "'");
    } else if (opt.model.empty()) {
      opt.model = a;
    } else {
      return usage_error("more than one model given ('" + opt.model + "' and '" + std::string(a) + "')");
    }
  }
  if (opt.model.empty()) return usage_error("missing MODEL");

  tranche::Report report;
  auto result = tranche::app::slice(opt, report);
  for (const auto& w : report.warnings())
    std::fprintf(stderr, "warning: %s%s%s\n", w.where.c_str(), w.where.empty() ? "" : ": ", w.message.c_str());
  if (!result) {
    std::fprintf(stderr, "error: %s\n", result.error().to_string().c_str());
    return 1;
  }
  for (const auto& f : result->written) std::printf("wrote %s\n", f.c_str());
  return 0;
}
