// The plate: every object of the model files, transformed, arranged on the bed and checked, in
// bed coordinates (mm; the bed's front-left corner at its origin, z = 0 on its surface).
//
// The steps, in order (each a function of its own for callers that need one):
//   load_plate         each file's objects as the file gives them (3MF positions kept)
//   apply_transforms   --lay-flat, --rotate-x, --rotate-y, --rotate, --scale, --scale-to-fit
//                      (each about the object's centre), onto the bed, --copies, then the
//                      --move and --center that name one object
//   place_objects      arrangement of the objects without a place (or centring, or keeping the
//                      files' layout with --no-arrange), then a plate-wide --move or --center
//   check_plate        every object on the bed and below its height (an error unless
//                      --allow-off-bed, then a warning); placed objects that overlap are a warning
// build_plate runs them all.
#pragma once

#include <string>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/plate/bed.h"
#include "geometry/plate/object.h"
#include "geometry/plate/options.h"

namespace tranche::plate {

Result<Plate> load_plate(const std::vector<std::string>& files, Report& report);
Status apply_transforms(Plate& plate, const PlateOptions& options, const Bed& bed, Report& report);
Status place_objects(Plate& plate, const PlateOptions& options, const Bed& bed);
Status check_plate(const Plate& plate, const Bed& bed, bool allow_off_bed, Report& report);

Result<Plate> build_plate(const PlateOptions& options, const Bed& bed, Report& report);

// Each object's outline on the bed and height, for the bed check.
std::vector<Footprint> footprints(const Plate& plate);

// Every object as one mesh in bed coordinates, each a shell of its own (for a pipeline that
// slices one mesh).
geo::Mesh merged_mesh(const Plate& plate);

}  // namespace tranche::plate
