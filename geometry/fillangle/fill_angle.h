// The fill angle of each island before the rules decide: the default 45°/135° alternation, or a
// Python script given with --fill-angle-script (docs/fill-angle-script.md). Precedence, lowest
// first: default < script < rules; rules see the script's value as the angle they override.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/core/layer.h"
#include "base/result.h"

namespace tranche::geo {

// The default fill angle, deg: 45 on even layers, 135 on odd ones (perpendicular layer to layer).
double default_fill_angle_deg(int layer_index);

// What a script sees about one island. Lengths mm, areas mm², angles deg.
struct FillAngleContext {
  int layer_index = 0, layer_count = 0;
  double z = 0, z_bottom = 0;  // top and bottom of the layer
  int island_index = 0, island_count = 0;
  double area = 0;
  const Polygon* shape = nullptr;  // the island: outer CCW, holes CW (units, see geom.h)
};

// A loaded script. Calls are thread-safe (each takes the interpreter lock), but the pipeline
// makes them all in one serial pass (apply_fill_angle_script) so results never depend on
// scheduling.
class FillAngleScript {
 public:
  // Runs the script once (its top level) and checks it defines fill_angle(ctx). Errors name the
  // file: unreadable, a syntax error (file:line:col), an exception at load (with the traceback),
  // no callable fill_angle, or a build without Python.
  static Result<std::unique_ptr<FillAngleScript>> load(const std::string& path);
  // True when this build embeds Python (CMake option TRANCHE_PYTHON with pybind11 found).
  static bool available();

  ~FillAngleScript();
  FillAngleScript(const FillAngleScript&) = delete;
  FillAngleScript& operator=(const FillAngleScript&) = delete;

  // Calls fill_angle(ctx): a finite int or float, in degrees. Errors carry the Python traceback;
  // a wrong return type (str, bool, None...), NaN or infinity is an error naming the island.
  Result<double> angle(const FillAngleContext& ctx);

  const std::string& path() const { return path_; }

 private:
  struct Impl;
  FillAngleScript(std::string path, std::unique_ptr<Impl> impl);
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

// Sets Island::fill_angle_deg of every island of every layer (bottom to top) from the script,
// in one serial pass, before decomposition. The first error stops the pass.
Status apply_fill_angle_script(FillAngleScript& script, std::vector<Layer>& layers);

}  // namespace tranche::geo
