#include "runtime/context/context.h"

#include <atomic>
#include <vector>

namespace tranche::ctx {

PropertyValues PropertyValues::schema_defaults() {
  PropertyValues p;
  for (const auto& info : schema::properties()) p[info.id] = info.default_value;
  return p;
}

namespace {
const PropertyValues& static_defaults() {
  static const PropertyValues p = PropertyValues::schema_defaults();
  return p;
}
}  // namespace

LayerTable::LayerTable(size_t layer_count) : rows_(layer_count) {
  for (auto& r : rows_) r.fill(0.0);
}

int LayerTable::column(FieldId field) {
  switch (field) {
    case FieldId::LayerIndex:
      return 0;
    case FieldId::LayerZBottom:
      return 1;
    case FieldId::LayerZ:
      return 2;
    case FieldId::LayerHeight:
      return 3;
    case FieldId::LayerArea:
      return 4;
    case FieldId::LayerIslands:
      return 5;
    case FieldId::LayerTime:
      return 6;
    case FieldId::LayerMaxSlope:
      return 7;
    default:
      return -1;
  }
}

bool LayerTable::holds(FieldId field) { return column(field) >= 0; }

double LayerTable::get(long index, FieldId field) const {
  int c = column(field);
  if (c < 0 || index < 0 || static_cast<size_t>(index) >= rows_.size()) return 0.0;
  return rows_[static_cast<size_t>(index)][static_cast<size_t>(c)];
}

void LayerTable::set(size_t index, FieldId field, double value) {
  int c = column(field);
  if (c >= 0 && index < rows_.size()) rows_[index][static_cast<size_t>(c)] = value;
}

Context::Context() : props_(&static_defaults()) {}

namespace {
// Generations: a per-thread counter under a per-thread prefix, so no two contexts on any
// threads ever share one, without a shared atomic on every element.
// Reserves `n` consecutive generations and returns the first.
uint64_t next_generations(uint64_t n) {
  static std::atomic<uint64_t> threads{0};
  thread_local uint64_t prefix = (threads.fetch_add(1) + 1) << 40;
  thread_local uint64_t counter = 0;
  uint64_t first = counter + 1;
  counter += n;
  return prefix | (first & ((uint64_t(1) << 40) - 1));
}
}  // namespace

namespace {
// Per level, the slots of the fields of that level and deeper (computed once from the schema).
struct Slots {
  std::array<std::vector<uint16_t>, schema::kLevelCount> from;
  Slots() {
    for (int l = 0; l < schema::kLevelCount; ++l)
      for (const auto& f : schema::fields())
        if (static_cast<int>(f.level) >= l) from[static_cast<size_t>(l)].push_back(static_cast<uint16_t>(f.id));
  }
};
const Slots& slots() {
  static const Slots s;
  return s;
}
}  // namespace

void Context::clear_from(schema::Level level) {
  const auto l0 = static_cast<size_t>(level);
  uint64_t g = next_generations(static_cast<size_t>(schema::kLevelCount) - l0);
  for (size_t l = l0; l < static_cast<size_t>(schema::kLevelCount); ++l) gen_[l] = g++;
  for (uint16_t i : slots().from[l0]) values_[i] = 0.0;
  if (static_cast<int>(level) <= static_cast<int>(schema::Level::Path)) {
    points_ = {};
    pieces_ = {};
  }
  if (static_cast<int>(level) <= static_cast<int>(schema::Level::Layer)) islands_ = {};
}

}  // namespace tranche::ctx
