#include "geometry/preview/preview.h"

#include <numbers>

namespace tranche::preview {

const char* source_kind_name(SourceKind k) {
  switch (k) {
    case SourceKind::SchemaDefault:
      return "schema default";
    case SourceKind::BuiltinDefault:
      return "built-in default";
    case SourceKind::Profile:
      return "profile";
    case SourceKind::Script:
      return "fill-angle script";
    case SourceKind::Rule:
      return "rule";
    case SourceKind::Set:
      return "--set";
    case SourceKind::Slicer:
      return "slicer";
  }
  return "unknown";
}

// The formula of toolpath/flow.h, which this folder sits below and cannot include.
double bead_area_mm2(double width_mm, double height_mm) {
  if (width_mm <= height_mm) return std::numbers::pi * width_mm * width_mm / 4;  // a round bead
  return (width_mm - height_mm) * height_mm + std::numbers::pi * height_mm * height_mm / 4;
}

double volumetric_rate_mm3_s(double width_mm, double height_mm, double speed_mm_s, double flow) {
  return bead_area_mm2(width_mm, height_mm) * speed_mm_s * flow;
}

}  // namespace tranche::preview
