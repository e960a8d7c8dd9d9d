// The context of the slicing loop print ⊃ layer ⊃ island ⊃ cell ⊃ path ⊃ piece: one value per
// schema field slot for the element being processed (and its enclosing elements), the table of
// every layer's layer-level fields (`layers[i].area`, `below.z`), the collections replacers and
// executors iterate (`path.points`, `path.pieces`, `layer.islands`), and the properties decided
// so far. Rules read it by slot number, never by name. The loop owns and fills it; everything
// else receives it as `const Context&`.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "runtime/context/trace.h"
#include "runtime/schema/schema.h"

namespace tranche::ctx {

using schema::FieldId;
using schema::PropId;

inline constexpr size_t slot(FieldId id) { return static_cast<size_t>(id); }
inline constexpr size_t slot(PropId id) { return static_cast<size_t>(id); }

// One value per property slot, in the property's unit (mm, mm/s, deg, °C, s, ratio 0..1;
// ints, bools and enum values as exact doubles).
struct PropertyValues {
  std::array<double, schema::kPropCount> values{};
  // Per property, the value the cascade gives it below the compiled rules (schema default,
  // built-in defaults, the fill-angle script), recorded by the rules when they decide it: a
  // rule that sets `speed` reads `speed` as the value of the rules before it, from there.
  std::array<double, schema::kPropCount> base{};

  double operator[](PropId id) const { return values[slot(id)]; }
  double& operator[](PropId id) { return values[slot(id)]; }
  // Every property at its schema default (properties.def).
  static PropertyValues schema_defaults();
};

// A finite sequence of context elements (pieces of a path, islands of a layer) whose fields a
// `for` loop reads by slot. Reading a field the element kind does not have gives 0.
class Collection {
 public:
  using Getter = double (*)(const void* data, size_t index, FieldId field);
  Collection() = default;
  Collection(const void* data, size_t size, Getter getter) : data_(data), size_(size), get_(getter) {}
  size_t size() const { return size_; }
  double get(size_t index, FieldId field) const {
    return index < size_ && get_ ? get_(data_, index, field) : 0.0;
  }

 private:
  const void* data_ = nullptr;
  size_t size_ = 0;
  Getter get_ = nullptr;
};

// A point of `path.points`, in bed coordinates (mm).
struct PointMm {
  double x = 0, y = 0;
};

// Every layer's layer-level fields (index, z_bottom, z, height, area, islands, time), so that a
// rule reads `layers[i].area` or `below.z` with one indexed load. Layers outside the print read
// as an empty layer: every field 0.
class LayerTable {
 public:
  LayerTable() = default;
  explicit LayerTable(size_t layer_count);
  size_t size() const { return rows_.size(); }
  // Value of a layer-level field of layer `index` (0 when out of range or not a layer field).
  double get(long index, FieldId field) const;
  void set(size_t index, FieldId field, double value);
  // True when `field` is a layer-level field (the only ones the table holds).
  static bool holds(FieldId field);

 private:
  static constexpr size_t kColumns = 8;
  static int column(FieldId field);
  std::vector<std::array<double, kColumns>> rows_;
};

// The read-only context of one element of the loop. Fields of the current element and of every
// enclosing element are set; fields of deeper levels read 0.
class Context {
 public:
  Context();

  double get(FieldId id) const { return values_[slot(id)]; }
  const std::array<double, schema::kFieldCount>& values() const { return values_; }
  // Layer-level field of another layer (`layers[index].field`), 0 outside the print.
  double layer(long index, FieldId id) const { return layers_ ? layers_->get(index, id) : 0.0; }
  // `below.field` / `above.field`.
  double below(FieldId id) const { return layer(static_cast<long>(get(FieldId::LayerIndex)) - 1, id); }
  double above(FieldId id) const { return layer(static_cast<long>(get(FieldId::LayerIndex)) + 1, id); }
  const LayerTable* layers() const { return layers_; }

  std::span<const PointMm> points() const { return points_; }  // path.points
  const Collection& pieces() const { return pieces_; }         // path.pieces
  const Collection& islands() const { return islands_; }       // layer.islands

  // Properties decided so far for this element (its stage and every earlier one).
  const PropertyValues& props() const { return *props_; }
  double prop(PropId id) const { return (*props_)[id]; }
  // Where decisions are recorded (provenance), or null: nothing is recorded.
  Trace* trace() const { return trace_; }

  // Writers, used by the loop that owns the context.
  void set(FieldId id, double v) { values_[slot(id)] = v; }
  // Sets every field of `level` and of the levels nested in it to 0 (entering a new element),
  // and gives those levels a new generation.
  void clear_from(schema::Level level);
  // A number that identifies the element of `level` this context describes: it changes at
  // every clear_from of that level or an outer one, and is unique across contexts and threads,
  // so that a result computed from the fields of that level (and outer ones) can be kept while
  // it stays the same. 0 means "never entered by clear_from": nothing may be kept.
  uint64_t generation(schema::Level level) const { return gen_[static_cast<size_t>(level)]; }
  void set_layers(const LayerTable* table) { layers_ = table; }
  void set_points(std::span<const PointMm> pts) { points_ = pts; }
  void set_pieces(Collection c) { pieces_ = c; }
  void set_islands(Collection c) { islands_ = c; }
  void set_props(const PropertyValues* p) { props_ = p; }
  void set_trace(Trace* t) { trace_ = t; }

 private:
  std::array<double, schema::kFieldCount> values_{};
  std::array<uint64_t, schema::kLevelCount> gen_{};
  const LayerTable* layers_ = nullptr;
  std::span<const PointMm> points_;
  Collection pieces_, islands_;
  const PropertyValues* props_;
  Trace* trace_ = nullptr;
};

}  // namespace tranche::ctx
