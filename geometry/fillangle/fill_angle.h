// --fill-angle-script (docs/fill-angle-script.md): a Python function that gives each island's
// fill angle, as one layer of the cascade between the built-in defaults (the 45°/135°
// alternation, which the script sees as ctx.default_angle) and the rules, which see the script's
// value as the angle they override.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/result.h"
#include "geometry/core/layer.h"
#include "runtime/context/cascade.h"

namespace tranche::geo {

// What a script sees about one island. Lengths mm, areas mm², angles deg.
struct FillAngleContext {
  int layer_index = 0, layer_count = 0;
  double z = 0, z_bottom = 0;  // top and bottom of the layer
  int island_index = 0, island_count = 0;
  double area = 0;
  const Polygon* shape = nullptr;  // the island: outer CCW, holes CW (units, see geom.h)
  double default_angle = 45;       // what the cascade gives below the script (deg)
};

// A loaded script. Calls are thread-safe (each takes the interpreter lock), but the pipeline
// makes them all in one serial pass (apply_fill_angle_script) so results never depend on
// scheduling.
class FillAngleScript {
 public:
  // Runs the script once (its top level) and checks it defines fill_angle(ctx). Errors name the
  // file: unreadable, a syntax error (file:line:col), an exception at load (with the traceback),
  // no callable fill_angle, or a build without Python. `timeout_s` bounds the top level's run and
  // each call of fill_angle (--script-timeout; CallWatch in call_watch.h).
  static Result<std::unique_ptr<FillAngleScript>> load(const std::string& path, double timeout_s = 5);
  // True when this build embeds Python (CMake option TRANCHE_PYTHON with pybind11 found).
  static bool available();

  ~FillAngleScript();
  FillAngleScript(const FillAngleScript&) = delete;
  FillAngleScript& operator=(const FillAngleScript&) = delete;

  // Calls fill_angle(ctx): a finite int or float, in degrees. Errors carry the Python traceback;
  // a wrong return type (str, bool, None...), NaN or infinity is an error naming the island, and
  // so is a call that takes longer than the timeout (stopped with a TimeoutError in the script).
  Result<double> angle(const FillAngleContext& ctx);

  const std::string& path() const { return path_; }

 private:
  struct Impl;
  FillAngleScript(std::string path, std::unique_ptr<Impl> impl);
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

// The script's angle of every island, as a layer of the cascade (Cascade::set_middle): computed
// in one serial pass over the layers, bottom to top, so Python calls never race and results
// never depend on scheduling; then read by layer.index and island.index at the island stage.
class ScriptAngles final : public ctx::Decider {
 public:
  // `layers`: the islands as the loop will see them (print setup's); `print_ctx` and
  // `print_props`: the print stage. The first error of the script stops the pass.
  static Result<std::unique_ptr<ScriptAngles>> compute(FillAngleScript& script, std::span<const Layer> layers,
                                                       const ctx::Cascade& cascade, const ctx::Context& print_ctx,
                                                       const ctx::PropertyValues& print_props);
  double angle(size_t layer, size_t island) const { return angles_[layer][island]; }

  Status decide(schema::Stage stage, const ctx::Context& ctx, ctx::PropertyValues& props) const override;
  schema::Level varies_at(schema::Stage stage) const override;
  bool reads(schema::FieldId field) const override;

 private:
  std::vector<std::vector<double>> angles_;  // [layer][island], deg
};

}  // namespace tranche::geo
