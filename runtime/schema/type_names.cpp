#include "runtime/schema/type_names.h"

namespace tranche::schema {

std::string_view gcode_type_name(PathKind k) {
  switch (k) {
    case PathKind::OuterPerimeter:
      return "External perimeter";
    case PathKind::InnerPerimeter:
      return "Perimeter";
    case PathKind::Infill:
      return "Internal infill";
    case PathKind::SolidInfill:
    case PathKind::BottomSolid:
      return "Solid infill";
    case PathKind::TopSolid:
      return "Top solid infill";
    case PathKind::Bridge:
      return "Bridge infill";
    case PathKind::Skirt:
    case PathKind::Brim:
      return "Skirt/Brim";
    case PathKind::Ironing:
      return "Ironing";
    case PathKind::Custom:
      return "Custom";
    case PathKind::Support:
      return "Support material";
    case PathKind::SupportInterface:
      return "Support material interface";
    case PathKind::GapFill:
      return "Gap fill";
  }
  return "Custom";
}

}  // namespace tranche::schema
