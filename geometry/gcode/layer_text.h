// Writes one layer plan as G-code text, in parallel with other layers. The text is
// self-contained: it starts with `G92 E0` and the layer-change retraction, so it does not depend
// on the previous layer's E or position. Commands that depend on the state the previous layer
// left (fan, temperatures) are marks, resolved in order by the print writer, which emits them
// only when the value changes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/plan/plan.h"
#include "geometry/setup/print_setup.h"
#include "geometry/toolpath/comb.h"
#include "runtime/context/hooks.h"

namespace tranche::gcode {

struct LayerText {
  struct Mark {
    // LayerRetract/LayerUnretract: the layer change's retraction, written only when the travel
    // from the previous layer is longer than retract_before_travel.
    // LayerTravel: where the travel from the previous layer may go around holes (combing).
    enum class Kind : uint8_t { Fan, NozzleTemp, BedTemp, LayerRetract, LayerTravel, LayerUnretract };
    size_t offset;  // insert before text[offset]
    Kind kind;
    double value;  // ratio for the fan, °C for temperatures
  };
  std::string text;
  std::vector<Mark> marks;
  double e_mm = 0;  // filament fed, mm (retractions excluded)
  bool any_move = false;
  geo::Point first, last;  // model units: where the layer's first travel goes, where it ends
  bool ends_retracted = false;  // a retraction (a replacer's) that no extrusion of the layer undid
  int travels = 0, retractions = 0;
  // The move that goes farthest off the bed (PrintSetup::bed): by how much (mm, 0 when none) and
  // where (G-code mm).
  double off_bed_mm = 0, off_bed_x = 0, off_bed_y = 0;
  std::shared_ptr<const toolpath::Comber> comber;  // the layer's material, to comb the layer change
  // Provenance (PrintSetup::provenance): the G-code each executor added, and where.
  struct HookNote {
    const plan::PathPlan* path = nullptr;  // the path it ran around (null: a layer or island hook)
    int island = -1;                       // the island's index, for island and path hooks
    schema::Level level = schema::Level::Path;
    bool after = false;
    uint32_t rule = 0;
    std::string text;
  };
  std::vector<HookNote> hooks;
};

// G-code words for the flavour's fan command (ratio 0..1): "M106 S255", "M107", "M106 P0 S0.5".
std::string fan_command(schema::Flavor flavor, double ratio);

// The layer's text; `executors` (may be null) add the hooks' G-code around its elements.
Result<LayerText> format_layer(const setup::PrintSetup& setup, const ctx::Executors* executors,
                               const plan::LayerPlan& plan);

}  // namespace tranche::gcode
