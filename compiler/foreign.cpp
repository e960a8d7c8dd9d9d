// What users carry over from other slicers: their placeholders, setting names and feature names,
// and what each is called here (compiler/names.h).
#include <array>
#include <utility>

#include "compiler/names.h"

namespace tranche::compiler {

namespace {

struct Entry {
  std::string_view theirs, ours, whose;
};

constexpr std::string_view kPrusa = "PrusaSlicer's";
constexpr std::string_view kCura = "Cura's";
constexpr std::string_view kOrca = "OrcaSlicer's";
constexpr std::string_view kKlipper = "Klipper's";

constexpr Entry kValues[] = {
    {"layer_z", "layer.z", kPrusa},
    {"layer_num", "layer.index", kPrusa},
    {"layer_nr", "layer.index", kCura},
    {"layer_number", "layer.index", kCura},
    {"current_layer", "layer.index", kOrca},
    {"initial_layer", "layer.index == 0", kOrca},
    {"max_layer_z", "print.height", kPrusa},
    {"total_layer_count", "print.layers", kPrusa},
    {"total_layers", "print.layers", kOrca},
    {"layer_count", "print.layers", kCura},
    {"print_time", "layer.time", kCura},
    {"first_layer_temperature", "nozzle_temp", kPrusa},
    {"temperature", "nozzle_temp", kPrusa},
    {"nozzle_temperature", "nozzle_temp", kOrca},
    {"nozzle_temperature_initial_layer", "nozzle_temp", kOrca},
    {"material_print_temperature", "nozzle_temp", kCura},
    {"material_print_temperature_layer_0", "nozzle_temp", kCura},
    {"print_temperature", "nozzle_temp", kCura},
    {"first_layer_bed_temperature", "bed_temp", kPrusa},
    {"bed_temperature", "bed_temp", kPrusa},
    {"bed_temperature_initial_layer", "bed_temp", kOrca},
    {"hot_plate_temp", "bed_temp", kOrca},
    {"material_bed_temperature", "bed_temp", kCura},
    {"material_bed_temperature_layer_0", "bed_temp", kCura},
    {"bed_temp_initial_layer", "bed_temp", kOrca},
    {"extruder_temperature", "nozzle_temp", kKlipper},
    {"fan_speed", "fan", kPrusa},
    {"machine_nozzle_size", "nozzle_diameter", kCura},
    {"material_diameter", "filament_diameter", kCura},
    {"layer_height_0", "first_layer_height", kCura},
    {"first_layer_print_height", "first_layer_height", kPrusa},
    {"z_offset", "layer.z", kPrusa},
};

constexpr Entry kProperties[] = {
    {"temperature", "nozzle_temp", kPrusa},
    {"temp", "nozzle_temp", ""},
    {"first_layer_temperature", "nozzle_temp", kPrusa},
    {"nozzle_temperature", "nozzle_temp", kOrca},
    {"material_print_temperature", "nozzle_temp", kCura},
    {"hotend_temp", "nozzle_temp", ""},
    {"extruder_temp", "nozzle_temp", ""},
    {"bed_temperature", "bed_temp", kPrusa},
    {"first_layer_bed_temperature", "bed_temp", kPrusa},
    {"hot_plate_temp", "bed_temp", kOrca},
    {"material_bed_temperature", "bed_temp", kCura},
    {"fan_speed", "fan", kPrusa},
    {"cool_fan_speed", "fan", kCura},
    {"fan_percent", "fan", ""},
    {"cooling", "fan", kPrusa},
    {"infill_angle", "fill_angle", kPrusa},
    {"fill_direction", "fill_angle", ""},
    {"infill_direction", "fill_angle", kOrca},
    {"infill_angles", "fill_angle", kCura},
    {"perimeter_count", "perimeters", ""},
    {"wall_count", "perimeters", ""},
    {"wall_line_count", "perimeters", kCura},
    {"wall_loops", "perimeters", kOrca},
    {"walls", "perimeters", ""},
    {"extrusion_width", "width", kPrusa},
    {"line_width", "width", kCura},
    {"extrusion_multiplier", "flow", kPrusa},
    {"flow_rate", "flow", ""},
    {"flow_ratio", "flow", kOrca},
    {"material_flow", "flow", kCura},
    {"print_speed", "speed", ""},
    {"speed_print", "speed", kCura},
    {"feedrate", "speed", ""},
    {"feed_rate", "speed", ""},
    {"fill_density", "infill_density", kPrusa},
    {"sparse_infill_density", "infill_density", kOrca},
    {"infill_sparse_density", "infill_density", kCura},
    {"infill", "infill_density", ""},
    {"retraction_length", "retract_length", ""},
    {"retraction_amount", "retract_length", kCura},
    {"retraction_speed", "retract_speed", ""},
    {"z_hop", "retract_lift", ""},
    {"retraction_hop", "retract_lift", kCura},
    {"top_solid_layers", "top_layers", kPrusa},
    {"top_shell_layers", "top_layers", kOrca},
    {"bottom_solid_layers", "bottom_layers", kPrusa},
    {"bottom_shell_layers", "bottom_layers", kOrca},
    {"seam_position", "seam", kPrusa},
    {"skirts", "skirt_loops", kPrusa},
    {"slowdown_below_layer_time", "min_layer_time", kPrusa},
    {"cool_min_layer_time", "min_layer_time", kCura},
    {"layer_height_0", "first_layer_height", kCura},
    {"nozzle_size", "nozzle_diameter", ""},
    {"travel_speed_mm", "travel_speed", ""},
};

constexpr std::array<std::array<std::string_view, 3>, 18> kFields = {{
    {"path", "type", "path.kind"},
    {"path", "role", "path.kind"},
    {"path", "feature", "path.kind"},
    {"path", "extrusion_role", "path.kind"},
    {"path", "feature_type", "path.kind"},
    {"layer", "number", "layer.index"},
    {"layer", "num", "layer.index"},
    {"layer", "nr", "layer.index"},
    {"layer", "id", "layer.index"},
    {"layer", "z_top", "layer.z"},
    {"layer", "top", "layer.z"},
    {"layer", "bottom", "layer.z_bottom"},
    {"layer", "thickness", "layer.height"},
    {"layer", "duration", "layer.time"},
    {"island", "size", "island.area"},
    {"island", "support", "island.supported"},
    {"print", "layer_count", "print.layers"},
    {"piece", "overhang_ratio", "piece.overhang"},
}};

constexpr std::array<std::array<std::string_view, 3>, 26> kEnumValues = {{
    {"path_kind", "perimeter", "outer_perimeter"},
    {"path_kind", "external_perimeter", "outer_perimeter"},
    {"path_kind", "outer_wall", "outer_perimeter"},
    {"path_kind", "wall_outer", "outer_perimeter"},
    {"path_kind", "wall", "outer_perimeter"},
    {"path_kind", "inner_wall", "inner_perimeter"},
    {"path_kind", "wall_inner", "inner_perimeter"},
    {"path_kind", "internal_perimeter", "inner_perimeter"},
    {"path_kind", "sparse_infill", "infill"},
    {"path_kind", "internal_infill", "infill"},
    {"path_kind", "solid", "solid_infill"},
    {"path_kind", "internal_solid_infill", "solid_infill"},
    {"path_kind", "top", "top_solid"},
    {"path_kind", "top_surface", "top_solid"},
    {"path_kind", "top_solid_infill", "top_solid"},
    {"path_kind", "skin", "top_solid"},
    {"path_kind", "bottom", "bottom_solid"},
    {"path_kind", "bottom_surface", "bottom_solid"},
    {"path_kind", "overhang", "bridge"},
    {"path_kind", "bridge_infill", "bridge"},
    {"path_kind", "brim", "skirt"},
    {"seam", "back", "rear"},
    {"seam", "random", "nearest"},
    {"seam", "shortest", "nearest"},
    {"gcode_flavor", "reprap", "reprapfirmware"},
    {"gcode_flavor", "rrf", "reprapfirmware"},
}};

// `first_layer_temperature_0` → `first_layer_temperature`.
std::string_view without_index(std::string_view name) {
  size_t k = name.size();
  while (k > 0 && name[k - 1] >= '0' && name[k - 1] <= '9') --k;
  if (k < name.size() && k > 1 && name[k - 1] == '_') return name.substr(0, k - 1);
  return name;
}

}  // namespace

std::optional<Foreign> foreign_value(std::string_view name) {
  for (std::string_view n : {name, without_index(name)})
    for (const auto& e : kValues)
      if (e.theirs == n) return Foreign{e.ours, e.whose};
  return std::nullopt;
}

std::optional<Foreign> foreign_property(std::string_view name) {
  for (const auto& e : kProperties)
    if (e.theirs == name) return Foreign{e.ours, e.whose};
  return std::nullopt;
}

std::optional<std::string_view> field_synonym(std::string_view level, std::string_view member) {
  for (const auto& e : kFields)
    if (e[0] == level && e[1] == member) return e[2];
  return std::nullopt;
}

std::optional<std::string_view> enum_synonym(std::string_view enum_name, std::string_view value) {
  for (const auto& e : kEnumValues)
    if (e[0] == enum_name && e[1] == value) return e[2];
  return std::nullopt;
}

}  // namespace tranche::compiler
