#include "geometry/preview/preview_data.h"

#include <fmt/format.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>

#include "geometry/preview/base64.h"
#include "geometry/preview/colours.h"

namespace tranche::preview {

namespace {

// Quanta of the per-path and per-piece values in the blob (the viewer divides by the same).
constexpr double kWidthQuantum = 0.001;  // mm
constexpr double kSpeedQuantum = 0.01;   // mm/s
constexpr double kFlowQuantum = 0.0001;  // ratio
constexpr double kFanQuantum = 0.001;    // ratio
constexpr double kTempQuantum = 0.1;     // °C

enum PathFlags : uint32_t { kWidthPerPiece = 1, kSpeedPerPiece = 2, kFlowPerPiece = 4, kPieceProvenance = 8 };

void put_varint(std::string& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<char>((v & 0x7f) | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<char>(v));
}
void put_signed(std::string& out, int64_t v) {
  put_varint(out, (static_cast<uint64_t>(v) << 1) ^ static_cast<uint64_t>(v >> 63));  // zigzag
}
int64_t quantize(double v, double quantum) { return std::llround(v / quantum); }

void append_json_string(std::string& out, std::string_view s) {
  out.push_back('"');
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out.push_back('\\');
      out.push_back(static_cast<char>(c));
    } else if (c < 0x20 || c == '<' || c == '>' || c == '&') {
      out += fmt::format("\\u{:04x}", c);  // no '<': the JSON may sit in a <script> element
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  out.push_back('"');
}
std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.7g}", v) : "null"; }

std::string compress(const std::string& raw);

}  // namespace

class PreviewEncoder::Impl {
 public:
  Impl(float bed_x, float bed_y, std::string title)
      : bed_x_(bed_x), bed_y_(bed_y), title_(std::move(title)) {}
  Status layer(const PreviewLayer& layer, size_t li);
  Result<std::string> json();
  size_t layers = 0;
  std::optional<Error> failed;
  const std::string& title() const {
    return title_;
  }  // the first error: the data is incomplete from there on

 private:
  Status path(const PreviewPath& p, const std::string& where);
  Status point(PointMm p, const std::string& where);
  int string_id(const std::string& s);
  int provenance_id(const std::shared_ptr<const Provenance>& p);
  std::string provenance_json(const Provenance& p);

  std::string blob_;
  int64_t qx_ = 0, qy_ = 0;  // the last point written, in quanta
  std::unordered_map<std::string, int> string_ids_;
  std::vector<std::string> strings_;
  std::unordered_map<const Provenance*, int> prov_by_ptr_;
  std::unordered_map<std::string, int> prov_by_json_;
  std::vector<std::string> provs_;
  std::vector<std::shared_ptr<const Provenance>> keep_;  // keeps prov_by_ptr_'s keys alive
  std::string layers_json_;
  size_t paths_ = 0, points_ = 0, travels_ = 0, travel_points_ = 0;
  float bed_x_, bed_y_;
  std::string title_;
};

Status PreviewEncoder::Impl::point(PointMm p, const std::string& where) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::fabs(p.x) > 1e6 || std::fabs(p.y) > 1e6)
    return Error{where, fmt::format("point ({}, {}) mm is not a finite bed coordinate", p.x, p.y)};
  const int64_t x = quantize(p.x, kCoordQuantumMm), y = quantize(p.y, kCoordQuantumMm);
  put_signed(blob_, x - qx_);
  put_signed(blob_, y - qy_);
  qx_ = x;
  qy_ = y;
  return ok_status();
}

Status PreviewEncoder::Impl::path(const PreviewPath& p, const std::string& where) {
  const size_t pieces = p.piece_count();
  if (pieces == 0) return Error{where, fmt::format("{} point(s); a path needs at least 2", p.points.size())};
  auto per_piece = [&](const std::vector<float>& v, const char* name, double quantum, uint32_t flag,
                       uint32_t& flags) -> Status {
    if (v.size() != 1 && v.size() != pieces)
      return Error{where, fmt::format("{} {} value(s) for {} piece(s); give 1 or one per piece", v.size(),
                                      name, pieces)};
    for (float x : v)
      if (!std::isfinite(x) || std::fabs(x / quantum) > 1e15)
        return Error{where, fmt::format("{} {} is not finite", name, x)};
    if (v.size() > 1) flags |= flag;
    return ok_status();
  };
  uint32_t flags = 0;
  if (Status s = per_piece(p.width, "width", kWidthQuantum, kWidthPerPiece, flags); !s) return s;
  if (Status s = per_piece(p.speed, "speed", kSpeedQuantum, kSpeedPerPiece, flags); !s) return s;
  if (Status s = per_piece(p.flow, "flow", kFlowQuantum, kFlowPerPiece, flags); !s) return s;
  if (!p.piece_provenance.empty()) {
    if (p.piece_provenance.size() != pieces)
      return Error{where,
                   fmt::format("{} piece provenance(s) for {} piece(s)", p.piece_provenance.size(), pieces)};
    flags |= kPieceProvenance;
  }
  if (!std::isfinite(p.fan) || !std::isfinite(p.nozzle_temp))
    return Error{where, "fan or nozzle temperature is not finite"};
  put_varint(blob_, static_cast<uint64_t>(p.kind));
  put_varint(blob_, p.points.size());
  put_varint(blob_, flags);
  put_varint(blob_, static_cast<uint64_t>(provenance_id(p.provenance) + 1));
  put_signed(blob_, p.island);
  put_signed(blob_, p.cell);
  put_signed(blob_, p.perimeter);
  put_signed(blob_, quantize(p.fan, kFanQuantum));
  put_signed(blob_, quantize(p.nozzle_temp, kTempQuantum));
  for (float w : p.width) put_signed(blob_, quantize(w, kWidthQuantum));
  for (float s : p.speed) put_signed(blob_, quantize(s, kSpeedQuantum));
  for (float f : p.flow) put_signed(blob_, quantize(f, kFlowQuantum));
  for (const auto& pp : p.piece_provenance) put_varint(blob_, static_cast<uint64_t>(provenance_id(pp) + 1));
  for (PointMm pt : p.points)
    if (Status s = point(pt, where); !s) return s;
  points_ += p.points.size();
  return ok_status();
}

Status PreviewEncoder::Impl::layer(const PreviewLayer& layer, size_t li) {
  qx_ = qy_ = 0;  // each layer decodes on its own
  for (size_t i = 0; i < layer.paths.size(); ++i)
    if (Status s = path(layer.paths[i], fmt::format("preview: layer {}, path {}", li, i)); !s) return s;
  for (size_t i = 0; i < layer.travels.size(); ++i) {
    const PreviewTravel& t = layer.travels[i];
    const std::string where = fmt::format("preview: layer {}, travel {}", li, i);
    put_varint(blob_, (t.retracted ? 1u : 0u));
    put_varint(blob_, t.via.size());
    if (Status s = point(t.from, where); !s) return s;
    for (PointMm v : t.via)
      if (Status s = point(v, where); !s) return s;
    if (Status s = point(t.to, where); !s) return s;
    travel_points_ += t.via.size() + 2;
  }
  if (!std::isfinite(layer.z) || !std::isfinite(layer.height))
    return Error{fmt::format("preview: layer {}", li), "z or height is not finite"};
  if (!layers_json_.empty()) layers_json_.push_back(',');
  layers_json_ += fmt::format("[{},{},{},{},{}]", layer.index, num(layer.z), num(layer.height),
                              layer.paths.size(), layer.travels.size());
  paths_ += layer.paths.size();
  travels_ += layer.travels.size();
  return ok_status();
}

int PreviewEncoder::Impl::string_id(const std::string& s) {
  auto [it, fresh] = string_ids_.try_emplace(s, static_cast<int>(strings_.size()));
  if (fresh) strings_.push_back(s);
  return it->second;
}

std::string PreviewEncoder::Impl::provenance_json(const Provenance& p) {
  std::string j = "{\"s\":[";
  for (size_t i = 0; i < p.slots.size(); ++i) {
    const SlotChain& c = p.slots[i];
    j += fmt::format("{}[{},[", i ? "," : "", static_cast<int>(c.prop));
    for (size_t k = 0; k < c.steps.size(); ++k) {
      const ChainStep& s = c.steps[k];
      j += fmt::format("{}[{},{},{},{},{},{}]", k ? "," : "", num(s.value), static_cast<int>(s.source),
                       string_id(s.rule), string_id(s.file), s.line, string_id(s.text));
    }
    j += "]]";
  }
  j += "],\"e\":[";
  for (size_t i = 0; i < p.executors.size(); ++i) {
    const ExecutorNote& e = p.executors[i];
    j += fmt::format("{}[{},{},{},{},{},{}]", i ? "," : "", e.after ? 1 : 0, static_cast<int>(e.level),
                     string_id(e.rule), string_id(e.file), e.line, string_id(e.text));
  }
  j += "],\"r\":";
  if (const ReplacerNote* r = p.replacer.get())
    j += fmt::format("[{},{},{},{}]", string_id(r->rule), string_id(r->file), r->line,
                     r->emitted_default ? 1 : 0);
  else
    j += "null";
  return j + "}";
}

int PreviewEncoder::Impl::provenance_id(const std::shared_ptr<const Provenance>& p) {
  if (!p) return -1;
  if (auto it = prov_by_ptr_.find(p.get()); it != prov_by_ptr_.end()) return it->second;
  std::string j = provenance_json(*p);
  auto [it, fresh] = prov_by_json_.try_emplace(j, static_cast<int>(provs_.size()));
  if (fresh) provs_.push_back(std::move(j));
  prov_by_ptr_.emplace(p.get(), it->second);
  keep_.push_back(p);
  return it->second;
}

namespace {

// Level 1: the varints leave zlib little to find (level 6 makes the bunny's page 2% smaller, in
// twice the time, all of it on the writer's thread after the layers).
std::string compress(const std::string& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string out(size, '\0');
  if (::compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                  static_cast<uLong>(raw.size()), 1) != Z_OK)
    return {};
  out.resize(size);
  return out;
}

}  // namespace

Result<std::string> PreviewEncoder::Impl::json() {
  std::string j =
      fmt::format("{{\"format\":\"tranche-preview\",\"version\":{},\"title\":", kPreviewFormatVersion);
  append_json_string(j, title_);
  j += fmt::format(
      ",\"bed\":[{},{}],\"quantum\":{{\"xy\":{},\"width\":{},\"speed\":{},\"flow\":{},\"fan\":{},\"temp\":{}}"
      "}",
      num(bed_x_), num(bed_y_), kCoordQuantumMm, kWidthQuantum, kSpeedQuantum, kFlowQuantum, kFanQuantum,
      kTempQuantum);
  j += ",\"kinds\":[";
  for (int k = 0; k < kPathKindCount; ++k) {
    const auto kind = static_cast<schema::PathKind>(k);
    j += fmt::format("{}[\"{}\",\"{}\",\"{}\"]", k ? "," : "",
                     schema::enum_value_name(schema::EnumType::PathKind, k), kind_label(kind),
                     to_hex(kind_colour(kind)));
  }
  j += "],\"ranges\":[";
  for (int i = 0; i < kRangeColourCount; ++i)
    j += fmt::format("{}\"{}\"", i ? "," : "", to_hex(range_colours()[i]));
  j += "],\"categories\":[";
  for (int i = 0; i < kCategoryColourCount; ++i)
    j += fmt::format("{}\"{}\"", i ? "," : "", to_hex(category_colour(i)));
  j += "],\"props\":[";
  for (int i = 0; i < schema::kPropCount; ++i) {
    const auto& info = schema::property(static_cast<schema::PropId>(i));
    j += fmt::format("{}[\"{}\",", i ? "," : "", info.name);
    append_json_string(j, schema::unit_name(info.unit));
    // The names of an enum's or a bool's values, for the panel ("aligned", not 0).
    if (info.type == schema::Type::Bool) j += ",[\"false\",\"true\"]";
    if (info.type == schema::Type::Enum) {
      j += ",[";
      const auto values = schema::enum_info(info.enum_type).values;
      for (size_t v = 0; v < values.size(); ++v) j += fmt::format("{}\"{}\"", v ? "," : "", values[v]);
      j += "]";
    }
    j += "]";
  }
  j += "],\"levels\":[";
  for (int i = 0; i < schema::kLevelCount; ++i)
    j += fmt::format("{}\"{}\"", i ? "," : "", schema::level_name(static_cast<schema::Level>(i)));
  j += "],\"sources\":[";
  for (int i = 0; i < kSourceKindCount; ++i)
    j += fmt::format("{}\"{}\"", i ? "," : "", source_kind_name(static_cast<SourceKind>(i)));
  j += "],\"strings\":[";
  for (size_t i = 0; i < strings_.size(); ++i) {
    if (i) j.push_back(',');
    append_json_string(j, strings_[i]);
  }
  j += "],\"provenance\":[";
  for (size_t i = 0; i < provs_.size(); ++i) {
    if (i) j.push_back(',');
    j += provs_[i];
  }
  j += fmt::format(
      "],\"layers\":[{}],\"counts\":{{\"paths\":{},\"points\":{},\"travels\":{},\"travelPoints\":{}}}",
      layers_json_, paths_, points_, travels_, travel_points_);
  const std::string packed = compress(blob_);
  if (packed.empty()) return Error{"preview", "zlib could not compress the preview's data (out of memory?)"};
  j += fmt::format(",\"blobBytes\":{},\"blob\":\"", blob_.size());
  j += base64_encode(packed);
  return j + "\"}";
}

PreviewEncoder::PreviewEncoder(float bed_x, float bed_y, std::string title)
    : impl_(std::make_unique<Impl>(bed_x, bed_y, std::move(title))) {}
PreviewEncoder::~PreviewEncoder() = default;
PreviewEncoder::PreviewEncoder(PreviewEncoder&&) noexcept = default;
PreviewEncoder& PreviewEncoder::operator=(PreviewEncoder&&) noexcept = default;

Status PreviewEncoder::add_layer(const PreviewLayer& layer) {
  if (impl_->failed) return *impl_->failed;
  if (Status s = impl_->layer(layer, impl_->layers++); !s) {
    impl_->failed = s.error();
    return s;
  }
  return ok_status();
}

const std::string& PreviewEncoder::title() const { return impl_->title(); }

Result<std::string> PreviewEncoder::finish() {
  if (impl_->failed) return *impl_->failed;
  return impl_->json();
}

Result<std::string> encode_preview_json(const PreviewPrint& print) {
  if (!std::isfinite(print.bed_x) || !std::isfinite(print.bed_y) || print.bed_x <= 0 || print.bed_y <= 0)
    return Error{"preview", fmt::format("bed size {} x {} mm is not positive", print.bed_x, print.bed_y)};
  PreviewEncoder e(print.bed_x, print.bed_y, print.title);
  for (const PreviewLayer& layer : print.layers)
    if (Status s = e.add_layer(layer); !s) return s.error();
  return e.finish();
}

}  // namespace tranche::preview
