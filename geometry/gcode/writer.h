// The G-code file: the header (estimates filled in at the end, the settings, the start G-code:
// the `before print` executors, i.e. the printer profile's), each layer's text in order with its
// marks resolved (fan and temperatures only when they change, the layer change's travel and
// retraction), then the end G-code (`after print`) and the footer. The file appears only when
// complete (base/output_file.h). Layers are planned and formatted elsewhere, in parallel
// (geometry/pipeline/driver.h); this class only writes, in order.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/output_file.h"
#include "base/result.h"
#include "geometry/gcode/layer_text.h"
#include "geometry/plan/travel.h"
#include "geometry/setup/print_setup.h"

namespace tranche::gcode {

struct GcodeInfo {
  std::string model_name;
  std::vector<std::pair<std::string, std::string>> sets;  // --set as given, for the header
  std::vector<std::string> notes;                         // more header lines (profile, rules files)
  std::string thumbnails;  // the thumbnail comment blocks (geometry/preview/thumbnails.h), or empty
  uint64_t max_bytes = 0;  // the largest G-code written (--max-gcode-size); 0: no limit
};

struct GcodeSummary {
  int layers = 0;
  double filament_mm = 0, filament_cm3 = 0, filament_g = 0;
  double time_s = 0;
  int travels = 0, retractions = 0;
};

// Filament density used for the weight estimate, g/cm³ (PLA).
inline constexpr double kFilamentDensity = 1.24;

// "1d 2h 3m 4s" / "27m 8s" / "8s", as PrusaSlicer writes it.
std::string format_duration(double seconds);

class GcodeWriter {
 public:
  // Creates the file and writes the header and the start G-code. `setup` and `executors` (may
  // be null) must outlive the writer.
  static Result<std::unique_ptr<GcodeWriter>> open(const std::string& path, const setup::PrintSetup& setup,
                                                   const ctx::Executors* executors, const GcodeInfo& info);
  // The next layer: its text (format_layer), its estimated time (s) and height (mm).
  Status layer(const LayerText& text, double time_s, double height_mm);
  // Between two objects printed one after the other: retract, rise to `safe_z_mm` (above what is
  // printed), cross to `to` (the next object's first point, model units); the next layer's change
  // then starts there, retracted.
  Status object_change(const geo::Point& to, double safe_z_mm);
  // The end G-code and the footer; fills in the header's estimates and moves the file into place.
  Result<GcodeSummary> finish();

 private:
  struct Slot {  // a header value known only at the end: written padded, patched in place
    uint64_t offset = 0;
    size_t width = 0;
  };
  GcodeWriter(OutputFile file, const setup::PrintSetup& setup, const ctx::Executors* executors)
      : file_(std::move(file)), S(setup), exec_(executors), travel_(plan::TravelPolicy::of(setup.print_props)) {}
  Status header(const GcodeInfo& info);
  Status slot(std::string_view prefix, size_t width, Slot& s);
  Status fill(const Slot& s, const std::string& v);
  // Runs a print hook; its text goes to `into` when given, else to the file.
  Status executors(ctx::When when, std::string* into = nullptr);
  // Whether the layer change into `t` retracts, and its combing route.
  void layer_change(const LayerText& t, bool& retract, geo::Ring& via) const;
  std::string resolve_marks(const LayerText& t, bool already, bool retract, const geo::Ring& via);

  OutputFile file_;
  const setup::PrintSetup& S;
  const ctx::Executors* exec_;
  plan::TravelPolicy travel_;
  Slot time_slot_, mm_slot_, cm3_slot_, g_slot_, cura_time_slot_, cura_fil_slot_;
  double fan_ = -1, nozzle_ = -1, bed_ = -1;
  bool has_last_ = false;
  geo::Point last_;              // where the last layer ended (model units)
  bool ends_retracted_ = false;  // the last layer written ended retracted (LayerText::ends_retracted)
  GcodeSummary summary_;
};

}  // namespace tranche::gcode
