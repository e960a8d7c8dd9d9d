// The extension points the rule VM implements: a Decider sets properties at each stage,
// Executors add G-code before/after elements, Replacers produce an element's output instead of
// the default. The cascade (cascade.h) orders the deciders; the slicing loop reaches all three
// through it, with the context of the element at hand.
//
// Threading: layers are planned in parallel, so every method may be called concurrently from
// several threads with different contexts; implementations keep no mutable shared state.
#pragma once

#include <bitset>
#include <optional>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "runtime/context/context.h"

namespace tranche::ctx {

// Decides the properties of one stage for one element (the cascade: last matching rule wins).
class Decider {
 public:
  virtual ~Decider() = default;
  // Sets the properties decided at `stage` in `props`. On entry `props` holds, for those
  // properties, the value the lower cascade layers give (schema default, then built-in
  // defaults, the fill-angle script...) and, for earlier stages, their final values.
  virtual Status decide(schema::Stage stage, const Context& ctx, PropertyValues& props) const = 0;
  // The deepest level whose fields the decisions of `stage` read. The loop calls decide(stage)
  // once per element of that level and reuses the result below it (hoisting): Level::Path for
  // Stage::Piece means speed and flow do not vary along a path, so there is no per-piece call.
  virtual schema::Level varies_at(schema::Stage stage) const = 0;
  // Whether any decision reads `field`. Fields nobody reads and that are costly to compute
  // (island.supported, island.covered, piece.overhang) are then left at 0.
  virtual bool reads(schema::FieldId) const { return true; }

  // What the decisions of `stage` depend on for the element `ctx` describes, which is the element
  // just outside the stage's level (a path, for Stage::Piece): `level` is the deepest level they
  // read for this element (below the stage's level: one decision holds for every element inside),
  // `fields` the fields of that level or deeper they read, directly or through a collection
  // (path.pieces). Rules whose conditions on outer fields fail for this element count for
  // nothing. The default is varies_at(stage), with every field when that reaches the stage's level.
  struct Dependence {
    schema::Level level = schema::Level::Print;
    std::bitset<schema::kFieldCount> fields;
  };
  virtual Result<Dependence> depends(schema::Stage stage, const Context& ctx) const;
  // Whether anything other than the decisions of `stage` reads `field` (a field only those read
  // need computing only for the elements depends() names it for). Default: reads(field).
  virtual bool reads_beyond(schema::Stage, schema::FieldId field) const { return reads(field); }
};

// Where executor and replacer output goes: G-code text lines, without the newline.
class LineSink {
 public:
  virtual ~LineSink() = default;
  virtual void line(std::string_view text) = 0;
};

enum class When : uint8_t { Before, After };

// `before LEVEL { ... }` / `after LEVEL { ... }` and `on LEVEL.start|end`.
class Executors {
 public:
  virtual ~Executors() = default;
  // Whether any executor is attached to this hook: the loop skips preparing the context (path
  // points, pieces) for hooks nobody uses.
  virtual bool has(schema::Level level, When when) const = 0;
  // Whether any executor reads `field` (see Decider::reads).
  virtual bool reads(schema::FieldId) const { return true; }
  // Emits the hook's G-code for the element `ctx` describes (nothing when no filter matches).
  virtual Status run(schema::Level level, When when, const Context& ctx, LineSink& out) const = 0;
};

// Options of `move to (X, Y) [travel] [with speed = S, flow = F, width = W]`; unset values take
// the element's decided speed, flow and width.
struct MoveOptions {
  bool travel = false;
  std::optional<double> speed;  // mm/s
  std::optional<double> flow;   // ratio
  std::optional<double> width;  // mm
};

// What the statements of a replacer can do to the element being replaced.
class ReplaceApi {
 public:
  virtual ~ReplaceApi() = default;
  // `move to (x, y)`: x, y in bed coordinates (mm).
  virtual void move_to(double x_mm, double y_mm, const MoveOptions& options) = 0;
  virtual void gcode(std::string_view line) = 0;    // `gcode "..."`, one line (already rendered)
  virtual void comment(std::string_view text) = 0;  // `comment "..."` -> "; text"
  // `default`: the element's normal output, after any alteration made so far.
  virtual Status emit_default() = 0;
  // `offset D` (mm): an island grows (D > 0) or shrinks before its perimeters and infill are
  // made; a path's points move sideways, positive to the left of travel.
  virtual Status offset(double mm) = 0;
  // `reverse`: paths only.
  virtual Status reverse() = 0;
  // `retract`: pull the filament back now (retract_length, and retract_lift); the next extruding
  // move, of the replacer or after it, unretracts first.
  virtual void retract() = 0;
};

// `replace island { ... }` and `replace path { ... }`.
class Replacers {
 public:
  virtual ~Replacers() = default;
  // Whether any replacer exists for the level (Island or Path).
  virtual bool has(schema::Level level) const = 0;
  // Whether any replacer reads `field` (see Decider::reads).
  virtual bool reads(schema::FieldId) const { return true; }
  // Runs the replacer that matches the element, if any, and returns whether one did (false:
  // the default output is used). An altered element is not offered to replacers again.
  virtual Result<bool> replace(schema::Level level, const Context& ctx, ReplaceApi& api) const = 0;
};

}  // namespace tranche::ctx
