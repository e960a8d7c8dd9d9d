// Inputs for bench_preview.sh: previews of a made-up bunny-sized print or of a G-code file's
// toolpaths (until the slicer writes previews itself), and the thumbnails' cost.
//   preview_bench synthetic OUT.html [LAYERS PATHS POINTS]   default 800 layers, 5000 paths, 1000000 points
//   preview_bench gcode IN.gcode OUT.html                    the extrusions and travels of a Tranche G-code
//   file
// Prints one line: layers paths points bytes encode_seconds thumbnail_seconds (16x16/QOI + 300x300/PNG
// from the toolpaths) outline_thumbnail_seconds (the same from the outer perimeters taken as
// island outlines, as the slicer could before planning any toolpath).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include "geometry/preview/preview_html.h"
#include "geometry/preview/thumbnails.h"

using namespace tranche;
using namespace tranche::preview;
using schema::PathKind;

namespace {

// A few provenance records like the ones the slicer shares between paths: one per kind.
std::shared_ptr<const Provenance> provenance_for(PathKind kind) {
  static std::map<PathKind, std::shared_ptr<const Provenance>> by_kind;
  auto& p = by_kind[kind];
  if (!p) {
    auto r = std::make_shared<Provenance>();
    const double speed = kind == PathKind::OuterPerimeter ? 25 : kind == PathKind::Infill ? 80 : 40;
    r->slots.push_back(
        {schema::PropId::Speed,
         {{60, SourceKind::SchemaDefault, "", "", 0, ""},
          {speed, SourceKind::BuiltinDefault, "speed by kind", "stdlib/defaults.rules", 12,
           "speed = 40 mm/s"},
          {speed / 2, SourceKind::Rule, "small islands", "my.rules", 9, "speed = speed * 50%"}}});
    r->slots.push_back({schema::PropId::Flow, {{1, SourceKind::SchemaDefault, "", "", 0, ""}}});
    r->slots.push_back({schema::PropId::Width, {{0.45, SourceKind::SchemaDefault, "", "", 0, ""}}});
    r->slots.push_back({schema::PropId::Fan, {{1, SourceKind::SchemaDefault, "", "", 0, ""}}});
    p = r;
  }
  return p;
}

PreviewPrint synthetic(int layers, int paths, long points) {
  PreviewPrint print;
  print.title = "synthetic bunny-sized print";
  const int per_layer = std::max(1, paths / layers);
  const int per_path = static_cast<int>(std::max<long>(2, points / std::max(1, paths)));
  uint32_t seed = 12345;
  auto jitter = [&]() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>((seed >> 8) & 0xffff) / 65536.0f - 0.5f;
  };
  for (int li = 0; li < layers; ++li) {
    PreviewLayer L;
    L.index = li;
    L.height = 0.2f;
    L.z = 0.2f * static_cast<float>(li + 1);
    const float r0 = 20 + 10 * std::sin(static_cast<float>(li) * 0.01f);
    for (int k = 0; k < per_layer; ++k) {
      PreviewPath p;
      const bool infill = k >= 2;
      p.kind = k == 0 ? PathKind::OuterPerimeter : k == 1 ? PathKind::InnerPerimeter : PathKind::Infill;
      const float r = r0 - 0.45f * static_cast<float>(k);
      for (int i = 0; i < per_path; ++i) {
        const float t = static_cast<float>(i) / static_cast<float>(per_path - 1);
        if (infill) {  // zig-zag lines across the disc, 2 points a line
          const float y = -r + 2 * r * t, half = std::sqrt(std::max(0.0f, r * r - y * y));
          p.points.push_back({100 + ((i / 2) % 2 == i % 2 ? -half : half), 100 + y});
        } else {
          const double a = 2 * std::numbers::pi * t;
          p.points.push_back({100 + static_cast<float>(r * std::cos(a)) + 0.02f * jitter(),
                              100 + static_cast<float>(r * std::sin(a)) + 0.02f * jitter()});
        }
      }
      p.width = {0.45f};
      p.speed = {p.kind == PathKind::OuterPerimeter ? 25.0f : p.kind == PathKind::Infill ? 80.0f : 40.0f};
      p.flow = {1};
      p.fan = 1;
      p.nozzle_temp = 210;
      p.island = 0;
      p.provenance = provenance_for(p.kind);
      L.paths.push_back(std::move(p));
    }
    L.travels.push_back({{100, 100 - r0}, L.paths[0].points[0], {}, li % 3 == 0});
    print.layers.push_back(std::move(L));
  }
  return print;
}

PathKind kind_of(const std::string& type) {
  static const std::map<std::string, PathKind> k = {{"External perimeter", PathKind::OuterPerimeter},
                                                    {"Perimeter", PathKind::InnerPerimeter},
                                                    {"Internal infill", PathKind::Infill},
                                                    {"Solid infill", PathKind::SolidInfill},
                                                    {"Top solid infill", PathKind::TopSolid},
                                                    {"Bridge infill", PathKind::Bridge},
                                                    {"Skirt/Brim", PathKind::Skirt},
                                                    {"Ironing", PathKind::Ironing}};
  auto it = k.find(type);
  return it == k.end() ? PathKind::Custom : it->second;
}

double word(const std::string& line, char w, double fallback) {
  for (size_t i = line.find(' '); i != std::string::npos && i + 1 < line.size(); i = line.find(' ', i + 1))
    if (line[i + 1] == w) return std::atof(line.c_str() + i + 2);
  return fallback;
}

// The extrusion runs and travels of a G-code file as Tranche writes it (docs/gcode.md).
PreviewPrint from_gcode(const std::string& path) {
  PreviewPrint print;
  print.title = std::filesystem::path(path).filename().string();
  std::ifstream in(path);
  std::string line;
  double x = 0, y = 0, e = 0, f = 0, width = 0.45, fan = 0, temp = 0;
  bool relative = false, retracted = false, extruding = false;
  PathKind kind = PathKind::Custom;
  PreviewLayer* layer = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind(";LAYER_CHANGE", 0) == 0) {
      print.layers.emplace_back().index = static_cast<int>(print.layers.size()) - 1;
      layer = &print.layers.back();
      extruding = false;
    } else if (line.rfind(";Z:", 0) == 0 && layer) {
      layer->z = std::stof(line.substr(3));
    } else if (line.rfind(";HEIGHT:", 0) == 0 && layer) {
      layer->height = std::stof(line.substr(8));
    } else if (line.rfind(";TYPE:", 0) == 0) {
      kind = kind_of(line.substr(6));
      extruding = false;
    } else if (line.rfind(";WIDTH:", 0) == 0) {
      width = std::stod(line.substr(7));
    } else if (line.rfind("M83", 0) == 0) {
      relative = true;
    } else if (line.rfind("M106", 0) == 0) {
      fan = word(line, 'S', 255) / 255;
    } else if (line.rfind("M107", 0) == 0) {
      fan = 0;
    } else if (line.rfind("M104", 0) == 0 || line.rfind("M109", 0) == 0) {
      temp = word(line, 'S', temp);
    } else if (line.rfind("G92", 0) == 0) {
      e = word(line, 'E', e);
    } else if (line.rfind("G1 ", 0) == 0 || line.rfind("G0 ", 0) == 0) {
      const double nx = word(line, 'X', x), ny = word(line, 'Y', y), ne = word(line, 'E', relative ? 0 : e);
      f = word(line, 'F', f);
      const double de = relative ? ne : ne - e;
      e = relative ? e + de : ne;
      const bool moves = nx != x || ny != y;
      if (!moves) {
        if (de < 0) retracted = true;
        if (de > 0) retracted = false;
      } else if (layer && de > 0) {
        if (!extruding) {
          PreviewPath p;
          p.kind = kind;
          p.points.push_back({static_cast<float>(x), static_cast<float>(y)});
          p.width = {static_cast<float>(width)};
          p.flow = {1};
          p.fan = static_cast<float>(fan);
          p.nozzle_temp = static_cast<float>(temp);
          p.provenance = provenance_for(kind);
          layer->paths.push_back(std::move(p));
          extruding = true;
        }
        PreviewPath& p = layer->paths.back();
        p.points.push_back({static_cast<float>(nx), static_cast<float>(ny)});
        p.speed.push_back(static_cast<float>(f / 60));
      } else if (layer) {
        if (extruding || layer->travels.empty())
          layer->travels.push_back({{static_cast<float>(x), static_cast<float>(y)}, {}, {}, retracted});
        else
          layer->travels.back().via.push_back(layer->travels.back().to);
        layer->travels.back().to = {static_cast<float>(nx), static_cast<float>(ny)};
        extruding = false;
      }
      x = nx;
      y = ny;
    }
  }
  for (PreviewLayer& l : print.layers)
    for (PreviewPath& p : l.paths)  // one speed for the path when its pieces agree, as the planner stores it
      if (std::all_of(p.speed.begin(), p.speed.end(), [&](float s) { return s == p.speed[0]; }))
        p.speed.resize(1);
  return print;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  PreviewPrint print;
  std::string out;
  if (cmd == "synthetic" && (argc == 3 || argc == 6)) {
    out = argv[2];
    print = argc == 6 ? synthetic(std::stoi(argv[3]), std::stoi(argv[4]), std::stol(argv[5]))
                      : synthetic(800, 5000, 1000000);
  } else if (cmd == "gcode" && argc == 4) {
    print = from_gcode(argv[2]);
    out = argv[3];
  } else {
    std::fprintf(stderr,
                 "usage: preview_bench synthetic OUT.html [LAYERS PATHS POINTS] | gcode IN.gcode OUT.html\n");
    return 2;
  }
  size_t paths = 0, points = 0;
  for (const PreviewLayer& l : print.layers)
    for (const PreviewPath& p : l.paths) ++paths, points += p.points.size();
  auto t0 = std::chrono::steady_clock::now();
  if (auto st = write_preview_html(out, print); !st) {
    std::fprintf(stderr, "preview_bench: %s\n", st.error().to_string().c_str());
    return 1;
  }
  const double encode = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const std::vector<ThumbnailSpec> specs = {{16, 16, ThumbnailFormat::Qoi}, {300, 300, ThumbnailFormat::Png}};
  auto thumbs = thumbnails_gcode(print, specs);
  const double thumb = seconds_since(t0);
  if (!thumbs) return 1;
  // The outer perimeters as islands (one polygon each, no holes), drawn at each layer's z.
  std::vector<std::vector<std::pair<geo::Polygon, float>>> outlines(print.layers.size());
  for (size_t i = 0; i < print.layers.size(); ++i)
    for (const PreviewPath& p : print.layers[i].paths)
      if (p.kind == PathKind::OuterPerimeter) {
        geo::Polygon poly;
        for (PointMm q : p.points) poly.outer.push_back(geo::to_point(q.x, q.y));
        outlines[i].push_back({std::move(poly), print.layers[i].z});
      }
  t0 = std::chrono::steady_clock::now();
  auto from_outlines = thumbnails_gcode(
      print_box(print),
      [&](HeightCanvas& c) {
        for (const auto& layer : outlines)
          for (const auto& [poly, z] : layer) c.add_polygon(poly, 0, 0, z);
      },
      specs);
  const double outline = seconds_since(t0);
  if (!from_outlines) return 1;
  std::printf("%zu %zu %zu %ju %.3f %.3f %.3f\n", print.layers.size(), paths, points,
              static_cast<uintmax_t>(std::filesystem::file_size(out)), encode, thumb, outline);
  return 0;
}
