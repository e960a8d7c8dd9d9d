#include "geometry/io/svg_import.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>
#include <unordered_set>

#include "base/input_file.h"
#include "geometry/io/svg_source.h"
#include "geometry/io/svg_stack.h"
#include "geometry/io/svg_walk.h"
#include "geometry/polygon/resolve.h"

namespace tranche::geo {

namespace {

using svg::Affine;
using svg::local_name;
using svg::Style;

constexpr double kMaxSizeMm = 2'000;  // the largest bed the schema allows

// Reads a document: its page, then a layer stack's layer groups or the whole drawing (walked by
// svg::Walker), then the checks and islands of the material.
class Reader {
 public:
  Reader(const svg::SourceMap& src, const SvgImportOptions& opt, svg::Rgb background, Report& report)
      : src_(src), opt_(opt), background_(background), report_(report), walker_(src, opt, report) {}

  Result<SvgModel> read(const pugi::xml_document& doc);

 private:
  Result<Affine> page(pugi::xml_node root, SvgModel& model);
  Status draw_stack(pugi::xml_node root, const svg::Stack& stack, SvgModel& model);
  Status draw_page(pugi::xml_node root, const Affine& to_mm, const Style& st, bool display_none,
                   SvgModel& model);
  Result<BBox2> material_box(const SvgModel& model) const;
  static void to_bottom(SvgModel& model, coord_t min_y);
  Status split_islands(SvgModel& model, const svg::Stack& stack) const;
  void warn_outside_layers(pugi::xml_node root, const svg::Stack& stack);
  static Result<Polygons> strict(const Polygons& resolved);
  void warn(pugi::xml_node n, const char* code, std::string msg) {
    report_.warn(code, src_.at(n), std::move(msg));
  }

  const svg::SourceMap& src_;
  const SvgImportOptions& opt_;
  svg::Rgb background_;
  Report& report_;
  svg::Walker walker_;
};

// Material split into strictly connected islands by the polygon stage (regions touching at a
// point become separate polygons).
Result<Polygons> Reader::strict(const Polygons& resolved) {
  auto islands = strict_islands(to_rings(resolved), OverlapMode::Additive);
  if (!islands) return islands.error();
  Polygons out;
  out.reserve(islands->size());
  for (Island& i : *islands) out.push_back(std::move(i.shape));
  return out;
}

// Warns of shapes outside the layer groups of a stack (they are not read).
void Reader::warn_outside_layers(pugi::xml_node root, const svg::Stack& stack) {
  std::unordered_set<const void*> layers;
  for (const auto& l : stack.layers) layers.insert(l.node.internal_object());
  std::vector<pugi::xml_node> todo{root};
  while (!todo.empty()) {
    pugi::xml_node n = todo.back();
    todo.pop_back();
    std::string name = local_name(n);
    if (layers.count(n.internal_object()) || name == "defs" || name == "symbol" ||
        svg::has_class(n, "legend"))
      continue;  // layers are read; definitions and the export's legend are not material
    if (name == "path" || name == "rect" || name == "circle" || name == "ellipse" || name == "polygon" ||
        name == "polyline")
      warn(n, "svg-stack-outside",
           "<" + name +
               "> outside the layer groups of a layer stack: ignored (move it "
               "into a layer group and give it class=\"island\")");
    for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling())
      if (c.type() == pugi::node_element) todo.push_back(c);
  }
}

// The page size in mm and the transform from the root's user units to mm (y up); sets the
// walker's viewport.
Result<Affine> Reader::page(pugi::xml_node root, SvgModel& model) {
  auto vp = svg::viewport_of(root, src_, true);
  if (!vp) return vp.error();
  model.page_width_mm = vp->width_px * svg::kMmPerPx;
  model.page_height_mm = vp->height_px * svg::kMmPerPx;
  walker_.set_viewport({vp->user_width, vp->user_height});
  // User units -> px -> mm, with y flipped about the page height: (x, y) -> (x, H - y).
  Affine to_mm = Affine{svg::kMmPerPx, 0, 0, -svg::kMmPerPx, 0, model.page_height_mm} * vp->user_to_px;
  auto t = walker_.transform_of(root);  // SVG 2 allows a transform on the root
  if (!t) return t.error();
  to_mm = to_mm * *t;
  return to_mm;
}

// One layer per layer group of a stack, each group's shapes resolved by the overlap mode.
Status Reader::draw_stack(pugi::xml_node root, const svg::Stack& stack, SvgModel& model) {
  warn_outside_layers(root, stack);
  // Inside a layer group a point (X, Y) is the model point (X, -Y) in mm; the group's own
  // transform only places the layer on the sheet, and the page size means nothing.
  model.page_width_mm = model.page_height_mm = 0;
  for (const svg::StackLayer& g : stack.layers) {
    std::vector<svg::Shape> shapes;
    if (auto s = walker_.walk_children(g.node, Affine{1, 0, 0, -1, 0, 0}, Style{}, shapes, 1); !s) return s;
    model.layers.push_back({g.z_bottom, g.z_top, svg::resolve_shapes(shapes, opt_.overlap, background_)});
  }
  return ok_status();
}

// The one layer of a flat drawing: the page's shapes resolved by the overlap mode.
Status Reader::draw_page(pugi::xml_node root, const Affine& to_mm, const Style& st, bool display_none,
                         SvgModel& model) {
  std::vector<svg::Shape> shapes;
  if (!display_none)
    if (auto s = walker_.walk_children(root, to_mm, st, shapes, 0); !s) return s;
  model.layers.push_back({0, 0, svg::resolve_shapes(shapes, opt_.overlap, background_)});
  return ok_status();
}

// The box around the material of every layer; errors when there are no shapes, no material, or
// the drawing is larger than any bed.
Result<BBox2> Reader::material_box(const SvgModel& model) const {
  if (walker_.shape_elements() == 0)
    return Error{src_.name(),
                 "no shapes to fill: the file has no path, rect, circle, ellipse, polygon or "
                 "polyline (convert text and strokes to paths in your editor)"};
  BBox2 box;
  for (const auto& l : model.layers)
    for (const auto& p : l.polygons) {
      BBox2 b = bbox(p);
      if (!b.empty()) box.add({b.min_x, b.min_y}), box.add({b.max_x, b.max_y});
    }
  if (box.empty())
    return Error{src_.name(), "the shapes enclose no material: " + std::to_string(walker_.shape_elements()) +
                                  " shapes, all unfilled, hidden, of zero area or erased"};
  double w = geo::to_mm(box.max_x - box.min_x), h = geo::to_mm(box.max_y - box.min_y);
  if (w > kMaxSizeMm || h > kMaxSizeMm) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "the drawing is %.0f x %.0f mm, larger than %.0f mm: check the units of width, "
                  "height and viewBox",
                  w, h, kMaxSizeMm);
    return Error{src_.name(), buf};
  }
  return box;
}

// No page size: the drawing's lowest point goes to y = 0 (it was flipped about y = 0).
void Reader::to_bottom(SvgModel& model, coord_t min_y) {
  for (auto& l : model.layers)
    for (auto& p : l.polygons) {
      for (auto& pt : p.outer) pt.Y -= min_y;
      for (auto& hole : p.holes)
        for (auto& pt : hole) pt.Y -= min_y;
    }
}

// Every layer's material as strictly connected islands; errors name the layer group.
Status Reader::split_islands(SvgModel& model, const svg::Stack& stack) const {
  for (size_t i = 0; i < model.layers.size(); ++i) {
    auto polys = strict(model.layers[i].polygons);
    if (!polys)
      return Error{model.layer_stack ? src_.at(stack.layers[i].node) : src_.name(), polys.error().message};
    model.layers[i].polygons = std::move(*polys);
  }
  return ok_status();
}

// The page, the root's style, the stack or drawing, then the checks and islands.
Result<SvgModel> Reader::read(const pugi::xml_document& doc) {
  pugi::xml_node root = doc.document_element();
  if (!root || local_name(root) != "svg")
    return Error{root ? src_.at(root) : src_.name(),
                 std::string("not an SVG document: the root element is <") + (root ? root.name() : "") +
                     ">, not <svg>"};
  walker_.index_ids(root);
  SvgModel model;
  auto to_mm = page(root, model);
  if (!to_mm) return to_mm.error();
  bool display_none = false;
  Style st = walker_.style_of(root, Style{}, &display_none);

  auto stack = svg::read_stack(root, src_, report_);
  if (!stack) return stack.error();
  model.layer_stack = stack->is_stack;
  walker_.set_stack(model.layer_stack);
  Status drawn =
      model.layer_stack ? draw_stack(root, *stack, model) : draw_page(root, *to_mm, st, display_none, model);
  if (!drawn) return drawn.error();
  auto box = material_box(model);
  if (!box) return box.error();
  if (model.page_height_mm <= 0 && !model.layer_stack) to_bottom(model, box->min_y);
  if (Status s = split_islands(model, *stack); !s) return s.error();
  return model;
}

}  // namespace

bool looks_like_svg(std::string_view head) {
  size_t p = head.find_first_not_of(" \t\r\n\xef\xbb\xbf");
  if (p == std::string_view::npos || head[p] != '<') return false;
  return head.find("<svg") != std::string_view::npos || head.find(":svg") != std::string_view::npos;
}

Result<SvgModel> parse_svg(std::string_view text, const std::string& name, const SvgImportOptions& options,
                           Report& report) {
  svg::SourceMap src(text, name);
  if (!(options.tolerance_mm > 0) || options.tolerance_mm > 10)
    return Error{
        name, "the curve tolerance must be between 0 and 10 mm, got " + std::to_string(options.tolerance_mm)};
  auto background = svg::parse_color(options.background);
  if (!background)
    return Error{"--background",
                 "\"" + options.background + "\" is not a colour (use a name, #rrggbb or rgb(r, g, b))"};
  pugi::xml_document doc;
  pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_auto);
  if (!parsed)
    return Error{src.at(static_cast<size_t>(parsed.offset)),
                 std::string("not valid XML: ") + parsed.description()};
  Reader reader(src, options, *background, report);
  return reader.read(doc);
}

Result<SvgModel> load_svg(const std::string& path, const SvgImportOptions& options, Report& report) {
  auto text = read_input(path, kSvgInput);
  if (!text) return text.error();
  return parse_svg(*text, path, options, report);
}

}  // namespace tranche::geo
