#include "apps/slice_command.h"

#include <sys/stat.h>

#include <filesystem>
#include <new>
#include <system_error>

#include "base/input_file.h"
#include "base/memory.h"
#include "base/run_files.h"
#include "compiler/frontend.h"
#include "compiler/load_rules.h"
#include "geometry/pipeline/load_plate.h"
#include "geometry/plate/detect.h"
#include "geometry/plate/plate.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"

namespace tranche::app {
namespace {

// A drawing for the SVG path: named .svg (as the pipeline decides) and not a mesh inside, since
// the content decides (a 3MF named .svg is a plate).
bool is_svg(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".svg") return false;
  // Peeked at only when it is a regular file: a FIFO's bytes are read once, by the loader.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return true;
  auto in = InputFile::open(path, kSvgInput);
  if (!in) return true;  // the loader says why
  std::string head(4096, '\0');
  auto got = in->read_at(head.data(), head.size(), 0);
  head.resize(got ? *got : 0);
  const plate::Detected d = plate::detect_format(head, in->size());
  const bool mesh = d.sure && (d.format == plate::Format::ThreeMf || d.format == plate::Format::Obj ||
                               d.format == plate::Format::Stl);
  return !mesh;
}

// Options of the plate other than the files, for the SVG check.
bool transforms_given(const plate::PlateOptions& p) {
  return !p.copies.empty() || p.lay_flat || !p.rotate.empty() || !p.rotate_x.empty() || !p.rotate_y.empty() ||
         !p.scale.empty() || p.scale_to_fit || !p.move.empty() || !p.center.empty() ||
         p.arrange != plate::ArrangeMode::Auto;
}

Result<std::shared_ptr<const vm::RuleSet>> compile(const pipeline::SliceOptions& options, Report& report) {
  compiler::RulesInput in;
  in.profile = options.profile;
  in.printer = options.printer;
  in.material = options.material;
  in.stdlib_dir = options.stdlib_dir;
  in.files = options.rules;
  // A --set key that is not a plain property value may be an expression or a `param` of the
  // rules: the compiler knows (and says "did you mean" when it is neither).
  for (const auto& [k, v] : options.sets)
    if (!ctx::is_plain_override(k, v)) in.expressions.emplace_back(k, v);
  return compiler::load_rules(in, report);
}

// The bed the printer profile describes (bed_shape, bed_size_x/y, bed_origin_x/y,
// max_print_height), from the compiled rules and the plain --set overrides. It is decided before
// the plate exists, since placing the objects needs it: pipeline::decide_bed says why, and the
// pipeline's print stage checks that it gives the same bed.
Result<plate::Bed> bed_from_profile(const pipeline::SliceOptions& options, const vm::RuleSet* rules) {
  std::vector<std::pair<std::string, std::string>> plain;
  for (const auto& [k, v] : options.sets)
    if (ctx::is_plain_override(k, v)) plain.emplace_back(k, v);
  auto cascade = ctx::Cascade::create(plain, rules, rules, rules);
  if (!cascade) return cascade.error();
  return pipeline::decide_bed(**cascade);
}

// The files named on the command line, noted as inputs of the run before anything is read, and
// the outputs checked against them and each other: `-o model.stl` is refused before any work.
Status check_files(const pipeline::SliceOptions& o, const plate::PlateOptions& plate) {
  for (const auto& f : plate.files) RunFiles::note_input_path(f, "a model");
  for (const auto& r : o.rules) RunFiles::note_input_path(r, "a --rules file");
  if (o.profile && compiler::profile_is_path(o.printer)) RunFiles::note_input_path(o.printer, "the printer profile");
  if (o.profile && compiler::profile_is_path(o.material)) RunFiles::note_input_path(o.material, "the material profile");
  if (!o.fill_angle_script.empty()) RunFiles::note_input_path(o.fill_angle_script, "the fill-angle script");
  const std::pair<const std::string*, const char*> outputs[] = {{&o.output_gcode, "the G-code"},
                                                                {&o.export_svg, "the SVG export"},
                                                                {&o.export_layers, "the layer export"},
                                                                {&o.export_preview, "the preview"}};
  for (const auto& [path, what] : outputs)
    if (!path->empty())
      if (Status s = RunFiles::claim_output(*path, what); !s) return s;
  return ok_status();
}

Result<pipeline::SliceSummary> slice_run(const pipeline::SliceOptions& options, const plate::PlateOptions& plate,
                                         Report& report) {
  if (plate.files.empty()) return Error{"", "no model given"};
  if (Status s = check_files(options, plate); !s) return s.error();
  bool svg = false;
  for (const auto& f : plate.files) svg |= is_svg(f);
  if (svg && plate.files.size() > 1)
    return Error{"", "an SVG drawing is sliced on its own: give it as the only model"};
  if (svg && transforms_given(plate))
    return Error{plate.files[0],
                 "--copies, --scale, --rotate, --lay-flat, --move, --center and --arrange apply to meshes (STL, 3MF, "
                 "OBJ), not to an SVG drawing"};
  auto rules = compile(options, report);
  if (!rules) return rules.error();
  pipeline::SliceOptions o = options;
  o.model = plate.files[0];
  o.allow_off_bed = plate.allow_off_bed;
  for (size_t i = 1; i < plate.files.size() && !svg; ++i) o.model += " + " + plate.files[i];
  if (svg) return pipeline::run_slice(o, nullptr, rules->get(), report);
  auto bed = bed_from_profile(options, rules->get());
  if (!bed) return bed.error();
  auto p = plate::build_plate(plate, *bed, report);
  if (!p) return p.error();
  return pipeline::run_slice(o, &*p, rules->get(), report);
}

}  // namespace

Result<pipeline::SliceSummary> slice(const pipeline::SliceOptions& options, Report& report) {
  plate::PlateOptions plate;
  plate.files = {options.model};
  return slice(options, plate, report);
}

Result<pipeline::SliceSummary> slice(const pipeline::SliceOptions& options, const plate::PlateOptions& plate,
                                     Report& report) {
  if (Status s = pipeline::check_options(options); !s) return s.error();
  RunFiles run;  // every file read from here on is an input that no output may replace
  try {
    return slice_run(options, plate, report);
  } catch (const std::bad_alloc&) {  // compiling the rules, loading and placing the models
    return out_of_memory("", "loading the models and rules");
  } catch (const std::system_error& e) {
    // A thread of our own (the script's watchdog, a 3MF read-ahead) that cannot start: with the
    // address space used up there is no room for its stack.
    if (e.code() != std::errc::resource_unavailable_try_again) throw;
    return out_of_memory("", "starting a thread");
  }
}

}  // namespace tranche::app
