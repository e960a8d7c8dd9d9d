// A small constructed print for the preview's tests: a vase of `layers` layers (0.2 mm) centred
// at (100, 100) on a 200 mm bed, with an outer and an inner perimeter (circles), infill lines
// at 45°/135° through the centre and, on the top 3 layers, top solid instead, all with known
// provenance (fixture.rules, stdlib/defaults.rules, --set). Probes name bed points whose path
// and decider the tests know.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/preview/preview.h"

namespace tranche::preview::fixture {

inline constexpr float kCx = 100, kCy = 100;

inline float outer_radius(int layer) { return 15.0f + 4.0f * std::sin(static_cast<float>(layer) * 0.15f); }

inline ChainStep step(double v, SourceKind k, std::string rule = {}, std::string file = {}, int line = 0,
                      std::string text = {}) {
  return ChainStep{v, k, std::move(rule), std::move(file), line, std::move(text)};
}

inline std::vector<PointMm> circle(float r, int n = 96) {
  std::vector<PointMm> pts;
  for (int i = 0; i <= n; ++i) {  // starts and ends at angle -90° (the bottom of the circle)
    const double a = -std::numbers::pi / 2 + 2 * std::numbers::pi * i / n;
    pts.push_back({kCx + static_cast<float>(r * std::cos(a)), kCy + static_cast<float>(r * std::sin(a))});
  }
  return pts;
}

// Lines at 45° (even layers) or 135° through the centre, 2 mm apart, clipped to radius r, zig-zag.
inline std::vector<PointMm> infill(float r, bool odd) {
  std::vector<PointMm> pts;
  const float dx = std::numbers::sqrt2_v<float> / 2, dy = odd ? -dx : dx;  // line direction
  const float nx = -dy, ny = dx;                                           // across the lines
  const int n = static_cast<int>((r - 0.5f) / 2);  // lines at offsets 2k mm: one through the centre
  for (int k = -n; k <= n; ++k) {
    const float off = 2.0f * static_cast<float>(k);
    const float half = std::sqrt(r * r - off * off);
    const float sx = kCx + nx * off, sy = kCy + ny * off;
    PointMm a{sx - dx * half, sy - dy * half}, b{sx + dx * half, sy + dy * half};
    if ((k + n) % 2) std::swap(a, b);
    pts.push_back(a);
    pts.push_back(b);
  }
  return pts;
}

struct Provenances {
  std::shared_ptr<const Provenance> outer, outer_slow, inner, infill, top, overhang;
};

inline Provenances provenances() {
  const SlotChain flow{
      schema::PropId::Flow,
      {step(1, SourceKind::SchemaDefault), step(0.95, SourceKind::Set, {}, {}, 0, "flow=0.95")}};
  const SlotChain width{schema::PropId::Width, {step(0.45, SourceKind::SchemaDefault)}};
  const SlotChain fan{schema::PropId::Fan, {step(1, SourceKind::SchemaDefault)}};
  const ChainStep outer_default = step(25, SourceKind::BuiltinDefault, "outer perimeter speed",
                                       "stdlib/defaults.rules", 14, "speed = 25 mm/s");
  Provenances p;
  p.outer = std::make_shared<Provenance>(Provenance{
      {{schema::PropId::Speed, {step(60, SourceKind::SchemaDefault), outer_default}}, flow, width, fan},
      {},
      nullptr});
  p.outer_slow = std::make_shared<Provenance>(
      Provenance{{{schema::PropId::Speed,
                   {step(60, SourceKind::SchemaDefault), outer_default,
                    step(12.5, SourceKind::Rule, "slow walls", "fixture.rules", 4, "speed = speed * 50%")}},
                  flow,
                  width,
                  fan},
                 {},
                 nullptr});
  p.overhang = std::make_shared<Provenance>(
      Provenance{{{schema::PropId::Speed,
                   {step(60, SourceKind::SchemaDefault), outer_default,
                    step(10, SourceKind::Rule, "overhangs", "fixture.rules", 20, "speed = 10 mm/s")}},
                  flow,
                  width,
                  fan},
                 {},
                 nullptr});
  p.inner = std::make_shared<Provenance>(Provenance{
      {{schema::PropId::Speed,
        {step(60, SourceKind::SchemaDefault), step(40, SourceKind::BuiltinDefault, "inner perimeter speed",
                                                   "stdlib/defaults.rules", 15, "speed = 40 mm/s")}},
       flow,
       width,
       fan},
      {ExecutorNote{false, schema::Level::Path, "pressure advance", "fixture.rules", 10, "M900 K0.045"}},
      nullptr});
  p.infill = std::make_shared<Provenance>(Provenance{
      {{schema::PropId::Speed,
        {step(60, SourceKind::SchemaDefault),
         step(80, SourceKind::Rule, "fast infill", "fixture.rules", 7, "speed = 80 mm/s")}},
       flow,
       width,
       fan,
       {schema::PropId::FillAngle,
        {step(45, SourceKind::SchemaDefault), step(135, SourceKind::BuiltinDefault, "alternate fill angle",
                                                   "stdlib/defaults.rules", 30, "fill_angle = 135°")}}},
      {},
      nullptr});
  p.top = std::make_shared<Provenance>(Provenance{
      {{schema::PropId::Speed,
        {step(60, SourceKind::SchemaDefault),
         step(30, SourceKind::BuiltinDefault, "top speed", "stdlib/defaults.rules", 18, "speed = 30 mm/s")}},
       flow,
       width,
       fan},
      {},
      std::make_shared<ReplacerNote>(ReplacerNote{"ironing pass", "fixture.rules", 14, true})});
  return p;
}

inline constexpr int kSlowFrom = 10;      // layers from here print the outer wall at 12.5 mm/s
inline constexpr int kOverhangLayer = 6;  // this layer's outer wall is at 10 mm/s where y > kCy

inline PreviewPrint vase_print(int layers = 24) {
  const Provenances P = provenances();
  PreviewPrint print;
  print.title = "fixture vase";
  for (int li = 0; li < layers; ++li) {
    PreviewLayer L;
    L.index = li;
    L.height = 0.2f;
    L.z = 0.2f * static_cast<float>(li + 1);
    const float r = outer_radius(li);
    const bool top = li >= layers - 3;
    auto path = [&](schema::PathKind kind, std::vector<PointMm> pts, float speed,
                    std::shared_ptr<const Provenance> prov) {
      PreviewPath p;
      p.kind = kind;
      p.points = std::move(pts);
      p.width = {0.45f};
      p.speed = {speed};
      p.flow = {0.95f};
      p.fan = li == 0 ? 0.0f : 1.0f;
      p.nozzle_temp = li == 0 ? 215.0f : 210.0f;
      p.island = 0;
      p.provenance = std::move(prov);
      return p;
    };
    PreviewPath fill = path(top ? schema::PathKind::TopSolid : schema::PathKind::Infill,
                            infill(r - 1.0f, li % 2 == 1), top ? 30.0f : 80.0f, top ? P.top : P.infill);
    fill.cell = 0;
    L.paths.push_back(std::move(fill));
    PreviewPath inner = path(schema::PathKind::InnerPerimeter, circle(r - 0.45f), 40, P.inner);
    inner.perimeter = 1;
    L.paths.push_back(std::move(inner));
    PreviewPath outer = path(schema::PathKind::OuterPerimeter, circle(r), li >= kSlowFrom ? 12.5f : 25.0f,
                             li >= kSlowFrom ? P.outer_slow : P.outer);
    outer.perimeter = 0;
    if (li == kOverhangLayer) {  // per-piece decisions: the back half is an overhang
      outer.speed.clear();
      for (size_t i = 0; i + 1 < outer.points.size(); ++i) {
        const bool back = outer.points[i].y + outer.points[i + 1].y > 2 * kCy;
        outer.speed.push_back(back ? 10.0f : 25.0f);
        outer.piece_provenance.push_back(back ? P.overhang : P.outer);
      }
    }
    const PointMm fill_start = L.paths[0].points.front(), fill_end = L.paths[0].points.back();
    L.travels.push_back({{kCx + 5, kCy - 10}, fill_start, {}, true});  // the layer change, retracted
    L.travels.push_back({fill_end, L.paths[1].points.front(), {{kCx + r * 0.5f, kCy - r * 0.5f}}, false});
    L.paths.push_back(std::move(outer));
    print.layers.push_back(std::move(L));
  }
  return print;
}

}  // namespace tranche::preview::fixture
