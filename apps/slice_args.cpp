#include "apps/slice_args.h"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <span>
#include <string_view>

namespace tranche::app {
namespace {

struct Spec {
  const char* names;  // CLI11 names: "-o,--output"
  const char* value;  // what follows it in --help ("FILE"); null: a flag
  const char* need;   // "-o needs ..." when the value is missing
  const char* help;   // lines of --help, '\n' between them
};

constexpr Spec kOptions[] = {
    {"-o,--output", "FILE", "a file name", "write G-code to FILE"},
    {"--rules", "FILE", "a file name", "apply a .rules file or compiled bundle (repeatable; later wins)"},
    {"--printer", "NAME", "a name or a file",
     "printer profile: stdlib/printers/NAME.rules or a .rules file\n(default generic-marlin; `none` for the defaults only)"},
    {"--material", "NAME", "a name or a file",
     "material profile: stdlib/materials/NAME.rules or a .rules file\n(default pla; `none` for none)"},
    {"--stdlib", "DIR", "a directory", "where stdlib rules (`use \"printers/...\"`) are looked for first"},
    {"--set", "KEY=VALUE", "KEY=VALUE", "override a property, e.g. --set layer_height=0.15 (repeatable)"},
    {"--export-svg", "FILE", "a file name", "write every layer as SVG: its islands and the paths printed on them"},
    {"--export-layers", "FILE", "a file name", "write every layer as JSON: its islands and the paths printed on them"},
    {"--export-preview", "FILE", "a file name",
     "write the toolpaths as one HTML page: layers, colours by kind, speed,\nflow, width, fan or deciding rule, and why each path is as it is"},
    {"--explain", "SPEC", "which paths, e.g. \"layer=12 island=0 path=outer_perimeter\"",
     "explain the paths SPEC selects (layer=N, and island=N, path=KIND or N,\ncell=N, perimeter=N): each slot's value chain with the deciding rules'\nfile:line, the executors, the replacer; alone, nothing else is written"},
    {"--thumbnails", "SIZES", "sizes like 16x16/QOI,220x124/PNG",
     "pictures of the print in the G-code for the printer's screen, e.g.\n16x16/QOI,220x124/PNG (overrides the thumbnails property; none: none)"},
    {"--exact-cells", nullptr, nullptr,
     "the exports also show each island's exact monotone cells (the\nseed's decomposition: an analysis view, not what is printed)"},
    {"--overlap", "MODE", "additive, boolean or subtractive", "additive (default), boolean, or subtractive (SVG only)"},
    {"--fill-angle-script", "FILE", "a file name", "Python script defining fill_angle(ctx) -> degrees (trusted code)"},
    {"--svg-layers", "N", "a number", "layers a flat SVG drawing is extruded to (default 10)"},
    {"--svg-height", "MM", "a number", "height a flat SVG drawing is extruded to (instead of --svg-layers)"},
    {"--svg-tolerance", "MM", "a number", "largest distance between an SVG curve and its polyline (default 0.01)"},
    {"--background", "COLOR", "a colour", "the colour that erases with --overlap subtractive (default white)"},
    {"--strict", nullptr, nullptr, "treat geometry coherence warnings as errors"},
    {"--script-timeout", "SECONDS", "a number of seconds",
     "the longest one fill_angle(ctx) call may take (default 5)"},
    {"--max-memory", "MB", "a number of megabytes",
     "the most memory (address space) the run may use; beyond it the run\nstops with an error and writes nothing"},
    {"--max-gcode-size", "MB", "a number of megabytes", "the largest G-code written (default 2048; 0: no limit)"},
    {"-q,--quiet", nullptr, nullptr, "no progress output"},
    {"-h,--help", nullptr, nullptr, "this text"},
};

// The plate: several models, transforms, arrangement, the bed.
constexpr Spec kPlateOptions[] = {
    {"--copies", "N", "a number", "print N of each object (NAME=N: of one object)"},
    {"--scale", "F", "a factor", "scale by F (2, 50%) or by X,Y,Z factors (1,1,2); NAME=F: one object"},
    {"--scale-to-fit", nullptr, nullptr, "scale each object to the largest size the bed allows"},
    {"--rotate", "DEG", "an angle", "turn about z, counter-clockwise seen from above (NAME=DEG: one object)"},
    {"--rotate-x", "DEG", "an angle", "turn about x (NAME=DEG: one object)"},
    {"--rotate-y", "DEG", "an angle", "turn about y (NAME=DEG: one object)"},
    {"--lay-flat", nullptr, nullptr, "put each object's largest flat face on the bed"},
    {"--move", "X,Y", "X,Y", "move the plate by X,Y mm (NAME=X,Y: one object, from its file's place)"},
    {"--center", "X,Y", "X,Y", "centre the plate at X,Y mm on the bed (NAME=X,Y: one object)"},
    {"--arrange", nullptr, nullptr, "arrange every object not placed by --move or --center (3MF places too)"},
    {"--no-arrange", nullptr, nullptr, "keep the layout of the files' coordinates, centred on the bed"},
    {"--spacing", "MM", "a distance", "between arranged objects (default 6)"},
    {"--allow-off-bed", nullptr, nullptr, "slice objects off the bed or too tall (a warning, not an error)"},
};

// "  -o, --output FILE            write G-code to FILE": descriptions from column 31.
std::string option_lines(std::span<const Spec> specs) {
  std::string out;
  for (const Spec& s : specs) {
    std::string line = "  ";
    for (const char* c = s.names; *c; ++c) {
      line.push_back(*c);
      if (*c == ',') line.push_back(' ');
    }
    if (s.value) {
      line.push_back(' ');
      line.append(s.value);
    }
    line.resize(std::max<size_t>(line.size() + 1, 31), ' ');
    std::string_view help = s.help;
    for (size_t nl = 0; nl != std::string_view::npos; line.assign(31, ' ')) {
      nl = help.find('\n');
      out.append(line).append(help.substr(0, nl)).push_back('\n');
      if (nl != std::string_view::npos) help.remove_prefix(nl + 1);
    }
  }
  return out;
}

// The long name of a spec ("--output"), as CLI11 names the option in its errors.
std::string long_name(const Spec& s) {
  const std::string n = s.names;
  const size_t comma = n.find(',');
  return comma == std::string::npos ? n : n.substr(comma + 1);
}

constexpr std::span<const Spec> kTables[] = {kOptions, kPlateOptions};

// CLI11's "--output: 1 required FILE missing", in our words.
std::string missing_value(const std::string& what) {
  for (auto table : kTables)
    for (const Spec& s : table)
      if (s.need && what.rfind(long_name(s) + ":", 0) == 0) return long_name(s) + " needs " + s.need;
  return what;
}

Error usage(const std::string& message) { return Error{"", message}; }

// --svg-layers, --svg-height, --svg-tolerance: a positive number (whole, for layers), at most 100000.
Status svg_number(const std::string& option, const std::string& v, pipeline::SliceOptions& o) {
  constexpr double kMax = 1e5;
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0' || !(x > 0)) return usage(option + " needs a positive number, not '" + v + "'");
  const char* unit = option == "--svg-layers" ? "layers" : "mm";
  if (!(x <= kMax)) return usage(option + " takes at most 100000 " + unit + ", not '" + v + "'");
  if (option == "--svg-layers") {
    if (x != std::floor(x)) return usage("--svg-layers needs a whole number of layers, not '" + v + "'");
    o.svg_layers = static_cast<int>(x);
  } else if (option == "--svg-height") {
    o.svg_height_mm = x;
  } else {
    o.svg_tolerance_mm = x;
  }
  return ok_status();
}

// A whole number from `min` to `max` (the limits the message names).
Result<uint64_t> whole_number(const std::string& option, const std::string& v, uint64_t min, uint64_t max,
                              const char* unit) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long x = std::strtoull(v.c_str(), &end, 10);
  if (v.empty() || v[0] == '-' || end == v.c_str() || *end != '\0' || errno == ERANGE)
    return usage(option + " needs a whole number of " + unit + ", not '" + v + "'");
  if (x < min || x > max)
    return usage(option + " takes " + std::to_string(min) + " to " + std::to_string(max) + " " + unit + ", not '" + v +
                 "'");
  return static_cast<uint64_t>(x);
}

// --script-timeout SECONDS, --max-gcode-size MB (--max-memory is read by parse_slice_args).
Status limit_values(const std::map<std::string, std::vector<std::string>>& values, pipeline::SliceOptions& o) {
  if (auto it = values.find("--script-timeout"); it != values.end() && !it->second.empty()) {
    const std::string& v = it->second.back();
    char* end = nullptr;
    const double s = std::strtod(v.c_str(), &end);
    if (end == v.c_str() || *end != '\0' || !(s > 0) || !(s <= 86400))
      return usage("--script-timeout needs a number of seconds from 0.001 to 86400, not '" + v + "'");
    o.script_timeout_s = s;
  }
  if (auto it = values.find("--max-gcode-size"); it != values.end() && !it->second.empty()) {
    auto mb = whole_number("--max-gcode-size", it->second.back(), 0, uint64_t{1} << 30, "MB");
    if (!mb) return mb.error();
    o.max_gcode_mb = *mb;
  }
  return ok_status();
}

class Values {
 public:
  explicit Values(std::map<std::string, std::vector<std::string>>& v) : v_(v) {}
  const std::vector<std::string>& all(const std::string& name) const { return v_[name]; }
  bool given(const std::string& name) const { return !v_[name].empty(); }
  const std::string& last(const std::string& name) const { return v_[name].back(); }

 private:
  std::map<std::string, std::vector<std::string>>& v_;
};

Status slice_values(const Values& v, pipeline::SliceOptions& o) {
  using pipeline::OverlapMode;
  if (v.given("--output")) o.output_gcode = v.last("--output");
  o.rules = v.all("--rules");
  for (const char* name : {"--printer", "--material"})
    if (v.given(name) && v.last(name).empty()) return usage(std::string(name) + " needs a name or a file");
  if (v.given("--printer")) o.printer = v.last("--printer");
  if (v.given("--material")) o.material = v.last("--material");
  if (v.given("--stdlib")) o.stdlib_dir = v.last("--stdlib");
  for (const auto& s : v.all("--set")) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0) return usage("--set needs KEY=VALUE, got '" + s + "'");
    o.sets.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  if (v.given("--export-svg")) o.export_svg = v.last("--export-svg");
  if (v.given("--export-layers")) o.export_layers = v.last("--export-layers");
  if (v.given("--export-preview")) o.export_preview = v.last("--export-preview");
  if (v.given("--explain")) o.explain = v.last("--explain");
  if (v.given("--thumbnails")) o.thumbnails = v.last("--thumbnails");
  if (v.given("--overlap")) {
    const std::string& m = v.last("--overlap");
    if (m == "additive") o.overlap = OverlapMode::Additive;
    else if (m == "boolean") o.overlap = OverlapMode::Boolean;
    else if (m == "subtractive") o.overlap = OverlapMode::Subtractive;
    else return usage("--overlap must be additive, boolean or subtractive, not '" + m + "'");
  }
  if (v.given("--fill-angle-script")) o.fill_angle_script = v.last("--fill-angle-script");
  for (const char* name : {"--svg-layers", "--svg-height", "--svg-tolerance"})
    for (const auto& x : v.all(name))
      if (Status s = svg_number(name, x, o); !s) return s;
  if (v.given("--background")) o.background = v.last("--background");
  return ok_status();
}

template <class T, class Parse>
Status each(const Values& v, const std::string& name, std::vector<T>& out, Parse parse) {
  for (const auto& x : v.all(name)) {
    auto r = parse(x);
    if (!r) return r.error();
    out.push_back(*r);
  }
  return ok_status();
}

Status plate_values(const Values& v, plate::PlateOptions& p) {
  if (Status s = each(v, "--copies", p.copies, plate::parse_copies); !s) return s;
  if (Status s = each(v, "--scale", p.scale, plate::parse_scale); !s) return s;
  for (const auto& turn : {std::pair{"--rotate", &p.rotate}, {"--rotate-x", &p.rotate_x}, {"--rotate-y", &p.rotate_y}}) {
    const std::string name = turn.first;
    if (Status s = each(v, name, *turn.second, [&](const std::string& x) { return plate::parse_angle(name, x); }); !s)
      return s;
  }
  for (const auto& place : {std::pair{"--move", &p.move}, {"--center", &p.center}}) {
    const std::string name = place.first;
    if (Status s = each(v, name, *place.second, [&](const std::string& x) { return plate::parse_xy(name, x); }); !s)
      return s;
  }
  if (v.given("--spacing")) {
    auto d = plate::parse_spacing(v.last("--spacing"));
    if (!d) return d.error();
    p.spacing_mm = *d;
  }
  return ok_status();
}

}  // namespace

std::string slice_usage() {
  return "usage: tranche slice MODEL... [options]\n\n"
         "Slices MODEL (.stl, binary or ASCII; .3mf; .obj; or one .svg drawing) into G-code and/or layer\n"
         "exports, or explains why the paths of a layer are printed as they are (--explain). Several models\n"
         "make one plate: objects without a place are arranged on the bed.\n\n"
         "options:\n" +
         option_lines(kOptions) + "\nplate:\n" + option_lines(kPlateOptions);
}

Result<SliceArgs> parse_slice_args(const std::vector<std::string>& args, bool quiet) {
  CLI::App app;
  app.set_help_flag();
  app.allow_extras();
  std::map<std::string, std::vector<std::string>> values;
  std::map<std::string, int> flags;
  for (auto table : kTables)
    for (const Spec& s : table) {
      if (s.value)
        app.add_option(s.names, values[long_name(s)])
            ->expected(1)
            ->allow_extra_args(false)
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
      else
        app.add_flag(s.names, flags[long_name(s)]);
    }
  std::vector<std::string> models;
  app.add_option("MODEL", models);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 parses from the back
  try {
    app.parse(reversed);
  } catch (const CLI::ArgumentMismatch& e) {
    return usage(missing_value(e.what()));
  } catch (const CLI::ParseError& e) {
    return usage(e.what());
  }
  SliceArgs out;
  if (flags["--help"]) {
    out.help = true;
    return out;
  }
  for (const auto& extra : app.remaining())
    if (!extra.empty() && extra[0] == '-') return usage("unknown option '" + extra + "'");
  if (Status s = limit_values(values, out.slice); !s) return s.error();
  if (!values["--max-memory"].empty()) {
    auto mb = whole_number("--max-memory", values["--max-memory"].back(), 64, uint64_t{1} << 30, "MB");
    if (!mb) return mb.error();
    out.max_memory_mb = *mb;
  }
  const Values v(values);
  if (Status s = slice_values(v, out.slice); !s) return s.error();
  if (Status s = plate_values(v, out.plate); !s) return s.error();
  out.slice.strict = flags["--strict"] > 0;
  out.slice.exact_cells = flags["--exact-cells"] > 0;
  out.slice.quiet = quiet || flags["--quiet"] > 0;
  out.plate.lay_flat = flags["--lay-flat"] > 0;
  out.plate.scale_to_fit = flags["--scale-to-fit"] > 0;
  out.plate.allow_off_bed = flags["--allow-off-bed"] > 0;
  if (flags["--arrange"] && flags["--no-arrange"]) return usage("--arrange and --no-arrange contradict each other");
  if (flags["--arrange"]) out.plate.arrange = plate::ArrangeMode::Always;
  if (flags["--no-arrange"]) out.plate.arrange = plate::ArrangeMode::Never;
  if (models.empty()) return usage("missing MODEL");
  out.plate.files = models;
  out.slice.model = models.front();
  return out;
}

}  // namespace tranche::app
