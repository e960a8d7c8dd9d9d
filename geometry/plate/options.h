// What the command line asks of the plate: the files, the transforms of each object, copies,
// arrangement and the bed check; and the parsers of the option values ("2", "1,1,2", "lid=45").
//
// A transform applies to every object, or to those a selector names: `NAME=VALUE` picks the
// objects called NAME (a 3MF object's name, else the file's stem), `N=VALUE` the N-th object
// loaded (from 1, in the order of the files and of a 3MF's build items).
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "geometry/plate/hull.h"

namespace tranche::plate {

template <class T>
struct PerObject {
  std::string selector;  // empty: every object (for --move and --center: the plate as a whole)
  T value;
};

enum class ArrangeMode {
  Auto,    // arrange objects without a place when there are several, or some with a place
  Always,  // --arrange: every object not placed by --move or --center, 3MF positions too
  Never,   // --no-arrange: objects keep their files' coordinates, the group centred on the bed
};

struct PlateOptions {
  std::vector<std::string> files;
  std::vector<PerObject<int>> copies;                 // --copies: instances of each object (>= 1)
  bool lay_flat = false;                              // --lay-flat
  std::vector<PerObject<double>> rotate_x, rotate_y;  // --rotate-x, --rotate-y, deg
  std::vector<PerObject<double>> rotate;              // --rotate (about z), deg
  std::vector<PerObject<Eigen::Vector3d>> scale;      // --scale: factors x, y, z
  bool scale_to_fit = false;                          // --scale-to-fit: as large as the bed allows
  std::vector<PerObject<Vec2>> move;                  // --move X,Y: mm
  std::vector<PerObject<Vec2>> center;                // --center X,Y: mm, bed coordinates
  ArrangeMode arrange = ArrangeMode::Auto;
  double spacing_mm = 6;        // --spacing: between arranged objects (PrusaSlicer's default)
  bool allow_off_bed = false;   // --allow-off-bed
};

// Parsers for option values; errors are the usage messages ("--scale needs ...").
Result<PerObject<Eigen::Vector3d>> parse_scale(const std::string& value);
Result<PerObject<double>> parse_angle(const std::string& option, const std::string& value);
Result<PerObject<Vec2>> parse_xy(const std::string& option, const std::string& value);
Result<PerObject<int>> parse_copies(const std::string& value);
Result<double> parse_spacing(const std::string& value);

}  // namespace tranche::plate
