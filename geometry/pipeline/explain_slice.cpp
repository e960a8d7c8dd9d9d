#include "geometry/pipeline/explain_slice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <map>

#include "geometry/gcode/layer_text.h"
#include "geometry/pipeline/preview_adapter.h"
#include "geometry/plan/layer_loop.h"
#include "runtime/vm/trace_text.h"

namespace tranche::pipeline {
namespace {

using preview::ChainStep;
using preview::SourceKind;

// The slots every path has, in the order they are shown; others rank after them.
constexpr schema::PropId kPathSlotOrder[] = {schema::PropId::Speed, schema::PropId::Flow, schema::PropId::Width,
                                             schema::PropId::Fan, schema::PropId::FillAngle};
constexpr int kPathSlots = static_cast<int>(std::size(kPathSlotOrder));
int path_slot_rank(schema::PropId p) {
  for (int i = 0; i < kPathSlots; ++i)
    if (kPathSlotOrder[i] == p) return i;
  return kPathSlots;
}

Error spec_error(const std::string& message) { return Error{"--explain", message}; }

std::string kind_name(schema::PathKind k) {
  return std::string(schema::enum_value_name(schema::EnumType::PathKind, static_cast<int>(k)));
}

// "60 mm/s schema default", "15 mm/s rule \"bridges\" (my.rules:4)".
std::string step_text(schema::PropId prop, const ChainStep& s) {
  std::string who;
  switch (s.source) {
    case SourceKind::SchemaDefault: who = "schema default"; break;
    case SourceKind::BuiltinDefault: who = s.text.empty() ? "built-in default" : "built-in default (" + s.text + ")"; break;
    case SourceKind::Script: who = "--fill-angle-script"; break;
    case SourceKind::Set: who = "--set"; break;
    case SourceKind::Slicer: who = s.rule + (s.text.empty() ? "" : " (" + s.text + ")"); break;
    case SourceKind::Profile:
    case SourceKind::Rule:
      who = fmt::format("rule \"{}\" ({}:{}{})", s.rule, s.file, s.line, s.text.empty() ? "" : ", " + s.text);
      break;
  }
  return vm::value_text(prop, s.value) + " " + who;
}

std::string where(const std::string& rule, const std::string& file, int line) {
  return fmt::format("rule \"{}\" ({}:{})", rule, file, line);
}

Result<int> whole(const std::string& key, const std::string& value) {
  char* end = nullptr;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || v < 0 || v > 1000000)
    return spec_error(fmt::format("{}= needs a whole number from 0, not '{}'", key, value));
  return static_cast<int>(v);
}

Status set_key(ExplainSpec& s, const std::string& key, const std::string& value) {
  if (key == "path") {
    if (auto k = schema::find_enum_value(schema::EnumType::PathKind, value)) {
      s.kind = static_cast<schema::PathKind>(*k);
      return ok_status();
    }
    if (value.empty() || !std::isdigit(static_cast<unsigned char>(value[0])))
      return spec_error(fmt::format("path= is a path kind ({}) or the island's path number, not '{}'",
                                    "outer_perimeter, inner_perimeter, infill, solid_infill, top_solid, ...", value));
  }
  int* slot = key == "layer" ? &s.layer : key == "island" ? &s.island : key == "path" ? &s.path
              : key == "cell" ? &s.cell : key == "perimeter" ? &s.perimeter : nullptr;
  if (!slot)
    return spec_error(fmt::format("'{}' is not a key: write layer=N and any of island=N, path=KIND or path=N, "
                                  "cell=N, perimeter=N", key));
  auto v = whole(key, value);
  if (!v) return v.error();
  *slot = *v;
  return ok_status();
}

bool selected(const ExplainSpec& s, const preview::PreviewPath& p, int index_in_island) {
  return (s.island < 0 || p.island == s.island) && (!s.kind || p.kind == *s.kind) &&
         (s.path < 0 || index_in_island == s.path) && (s.cell < 0 || p.cell == s.cell) &&
         (s.perimeter < 0 || p.perimeter == s.perimeter);
}

// What the layer (or the island asked for) has, for the message when nothing matches.
std::string contents(const preview::PreviewLayer& l, int island) {
  std::map<std::string, int> kinds;
  for (const auto& p : l.paths)
    if (island < 0 || p.island == island) ++kinds[kind_name(p.kind)];
  std::string out;
  for (const auto& [k, n] : kinds) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", n, k);
  return out.empty() ? "no path" : out;
}

double length_mm(const preview::PreviewPath& p) {
  double len = 0;
  for (size_t i = 1; i < p.points.size(); ++i)
    len += std::hypot(p.points[i].x - p.points[i - 1].x, p.points[i].y - p.points[i - 1].y);
  return len;
}

// "layer 12 (z 2.60 mm), island 0, path 3: outer_perimeter, perimeter 0, 48 points, 62.4 mm".
std::string path_header(const preview::PreviewLayer& l, const preview::PreviewPath& p, int index) {
  std::string h = fmt::format("layer {} (z {:.2f} mm)", l.index, l.z);
  if (p.island >= 0) h += fmt::format(", island {}, path {}", p.island, index);
  else h += fmt::format(", path {} (outside the islands)", index);
  h += ": " + kind_name(p.kind);
  if (p.cell >= 0) h += fmt::format(", cell {}", p.cell);
  if (p.perimeter >= 0) h += fmt::format(", perimeter {}", p.perimeter);
  return h + fmt::format(", {} points, {:.1f} mm\n", p.points.size(), length_mm(p));
}

// The pieces decided otherwise than the path's first, grouped by what decided them:
// "pieces 3-7, 12, decided otherwise:" and their provenance.
std::string pieces_text(const preview::PreviewPath& p, const std::string& first) {
  std::vector<std::pair<std::string, std::vector<size_t>>> groups;  // text, pieces; in order of first piece
  for (size_t i = 0; i < p.piece_provenance.size(); ++i) {
    if (!p.piece_provenance[i]) continue;
    const std::string t = provenance_text(*p.piece_provenance[i], "    ");
    if (provenance_text(*p.piece_provenance[i], "  ") == first) continue;
    auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& x) { return x.first == t; });
    if (g == groups.end()) groups.push_back({t, {i}});
    else g->second.push_back(i);
  }
  std::string out;
  for (const auto& [t, pieces] : groups) {
    std::string list;
    for (size_t k = 0; k < pieces.size(); ++k) {
      size_t e = k;
      while (e + 1 < pieces.size() && pieces[e + 1] == pieces[e] + 1) ++e;
      list += (list.empty() ? "" : ", ") + (e == k ? fmt::format("{}", pieces[k]) : fmt::format("{}-{}", pieces[k], pieces[e]));
      k = e;
    }
    out += fmt::format("  piece{} {}, decided otherwise:\n{}", pieces.size() == 1 ? "" : "s", list, t);
  }
  return out;
}

}  // namespace

std::string provenance_text(const preview::Provenance& p, const std::string& indent) {
  // The slots of a path first (speed, flow, width, fan, fill_angle), then the others.
  std::vector<const preview::SlotChain*> slots;
  for (int rank = 0; rank <= kPathSlots; ++rank)
    for (const auto& slot : p.slots)
      if (path_slot_rank(slot.prop) == rank) slots.push_back(&slot);
  std::string out;
  for (const preview::SlotChain* s : slots) {
    const preview::SlotChain& slot = *s;
    if (slot.steps.empty()) continue;
    out += fmt::format("{}{} = {}: ", indent, schema::property(slot.prop).name,
                       vm::value_text(slot.prop, slot.steps.back().value));
    for (size_t i = 0; i < slot.steps.size(); ++i) out += (i ? " -> " : "") + step_text(slot.prop, slot.steps[i]);
    out += "\n";
  }
  for (const auto& e : p.executors) {
    std::string text = e.text;
    for (auto& c : text)
      if (c == '\n') c = ';';
    out += fmt::format("{}{} {}: {} wrote: {}\n", indent, e.after ? "after" : "before", schema::level_name(e.level),
                       where(e.rule, e.file, e.line), text);
  }
  if (p.replacer)
    out += fmt::format("{}generated by replacer {}{}\n", indent, where(p.replacer->rule, p.replacer->file, p.replacer->line),
                       p.replacer->emitted_default ? ", which also printed the default G-code" : "");
  else
    out += indent + "no replacer: the default G-code\n";
  return out;
}

Result<ExplainSpec> parse_explain_spec(const std::string& text) {
  ExplainSpec s;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == ',' || text[i] == '\t')) ++i;
    if (i >= text.size()) break;
    size_t e = i;
    while (e < text.size() && text[e] != ' ' && text[e] != ',' && text[e] != '\t') ++e;
    const std::string item = text.substr(i, e - i);
    i = e;
    const size_t eq = item.find('=');
    if (eq == std::string::npos)
      return spec_error(fmt::format("'{}' needs a value: write key=value, e.g. \"layer=12 island=0 "
                                    "path=outer_perimeter\"", item));
    if (Status st = set_key(s, item.substr(0, eq), item.substr(eq + 1)); !st) return st.error();
  }
  if (s.layer < 0) return spec_error("which layer? write layer=N, e.g. \"layer=12 island=0 path=outer_perimeter\"");
  return s;
}

Result<std::string> explain_slice(const setup::PrintSetup& setup, const ctx::Cascade& cascade,
                                  const vm::RuleSet* rules, const ExplainSpec& spec) {
  const int layers = static_cast<int>(setup.layers.size());
  if (spec.layer >= layers)
    return spec_error(fmt::format("layer {} is past the top: the print has {} layers (0 to {})", spec.layer, layers,
                                  layers - 1));
  if (!setup.provenance) return spec_error("the run does not record provenance (PrintSetup::provenance)");
  auto plan = plan::plan_layer(setup, cascade, spec.layer);
  if (!plan) return plan.error();
  auto text = gcode::format_layer(setup, cascade.executors(), *plan);
  if (!text) return text.error();
  const preview::PreviewLayer l = preview_layer(setup, *plan, &*text, rules);
  const int islands = static_cast<int>(plan->islands.size());
  if (spec.island >= islands)
    return spec_error(fmt::format("layer {} has {} island{}{}", spec.layer, islands, islands == 1 ? "" : "s",
                                  islands ? fmt::format(" (0 to {})", islands - 1) : ""));
  std::string out;
  std::map<std::string, std::string> seen;  // provenance text -> the path that showed it first
  std::map<int, int> counts;                // paths so far per island
  for (const auto& p : l.paths) {
    const int index = counts[p.island]++;
    if (!selected(spec, p, index)) continue;
    const std::string header = path_header(l, p, index);
    const std::string body = p.provenance ? provenance_text(*p.provenance, "  ") : "  (nothing recorded)\n";
    out += (out.empty() ? "" : "\n") + header;
    const std::string name = header.substr(0, header.find(':'));
    if (auto it = seen.find(body); it != seen.end()) out += "  decided as " + it->second + "\n";
    else out += body, seen.emplace(body, name);
    out += pieces_text(p, body);
  }
  if (out.empty())
    return spec_error(fmt::format("no path of layer {}{} matches; {} has {}", spec.layer,
                                  spec.island >= 0 ? fmt::format(" island {}", spec.island) : "",
                                  spec.island >= 0 ? "that island" : "the layer", contents(l, spec.island)));
  return out;
}

}  // namespace tranche::pipeline
