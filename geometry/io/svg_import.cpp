#include "geometry/io/svg_import.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "geometry/io/svg_source.h"
#include "geometry/io/svg_stack.h"
#include "geometry/polygon/resolve.h"

namespace tranche::geo {

namespace {

using svg::Affine;
using svg::Paint;
using svg::Vec2;

constexpr int kMaxDepth = 256;              // nested groups and use references
constexpr size_t kMaxElements = 1'000'000;  // elements rendered, counting each use expansion
constexpr size_t kMaxPoints = 20'000'000;   // flattened points over the whole drawing
constexpr double kMaxCoordMm = 2'000;       // beyond, the units are surely wrong (polygon work stops at 2147)
constexpr double kMaxSizeMm = 2'000;        // the largest bed the schema allows

// Inherited presentation properties, as computed for one element.
struct Style {
  Paint fill;            // initial: black
  bool evenodd = false;  // fill-rule
  bool visible = true;   // visibility
  bool stroked = false;  // stroke is not none (for the stroke-only warning)
  svg::Rgb color = 0;    // for currentColor
};

std::string local_name(pugi::xml_node n) {
  std::string_view name = n.name();
  if (name.rfind("svg:", 0) == 0) name.remove_prefix(4);
  return std::string(name);
}

bool is_foreign(pugi::xml_node n) {
  return std::string_view(n.name()).find(':') != std::string_view::npos &&
         std::string_view(n.name()).rfind("svg:", 0) != 0;
}

class Reader {
 public:
  Reader(const svg::SourceMap& src, const SvgImportOptions& opt, svg::Rgb background, Report& report)
      : src_(src), opt_(opt), background_(background), report_(report) {}

  Result<SvgModel> read(const pugi::xml_document& doc);

 private:
  Status walk(pugi::xml_node n, const Affine& ctm, const Style& parent, std::vector<svg::Shape>& out,
              int depth);
  Status walk_children(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<svg::Shape>& out,
                       int depth);
  Status use(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<svg::Shape>& out, int depth);
  Status shape(pugi::xml_node n, const std::string& name, const Affine& ctm, const Style& st,
               std::vector<svg::Shape>& out);
  Style style_of(pugi::xml_node n, const Style& parent, bool* display_none);
  Result<Affine> transform_of(pugi::xml_node n);
  Result<double> length(pugi::xml_node n, const char* attr, double fallback);
  Result<std::vector<svg::Subpath>> geometry(pugi::xml_node n, const std::string& name, double tol);
  Result<Rings> place(pugi::xml_node n, const std::vector<svg::Subpath>& subpaths, const Affine& ctm);
  void warn_outside_layers(pugi::xml_node root, const svg::Stack& stack);
  static Result<Polygons> strict(const Polygons& resolved);
  Error error_at(pugi::xml_node n, std::string msg) const { return Error{src_.at(n), std::move(msg)}; }
  void warn(pugi::xml_node n, const char* code, std::string msg) {
    report_.warn(code, src_.at(n), std::move(msg));
  }

  const svg::SourceMap& src_;
  const SvgImportOptions& opt_;
  svg::Rgb background_;
  Report& report_;
  std::unordered_map<std::string, pugi::xml_node> ids_;
  std::unordered_set<const void*> active_uses_;  // referenced elements being expanded (cycles)
  size_t elements_ = 0, points_ = 0, shape_elements_ = 0;
  bool warned_css_ = false;
  bool stack_ = false;  // reading the layer groups of a layer stack
  Vec2 viewport_;       // the nearest viewport's size in user units, for percentages (0: unknown)
};

Result<Affine> Reader::transform_of(pugi::xml_node n) {
  pugi::xml_attribute a = n.attribute("transform");
  if (!a) return Affine{};
  size_t at = 0;
  auto t = svg::parse_transform(a.value(), &at);
  if (!t) return Error{src_.at_attr(n, "transform", at), "transform: " + t.error().message};
  const Affine& m = *t;
  if (!std::isfinite(m.a) || !std::isfinite(m.b) || !std::isfinite(m.c) || !std::isfinite(m.d) ||
      !std::isfinite(m.e) || !std::isfinite(m.f))
    return error_at(n, "transform: the matrix is not finite");
  return t;
}

Result<double> Reader::length(pugi::xml_node n, const char* attr, double fallback) {
  pugi::xml_attribute a = n.attribute(attr);
  if (!a) return fallback;
  std::string_view text = svg::trim(a.value());
  if (!text.empty() && text.back() == '%' && viewport_.x > 0 && viewport_.y > 0) {
    // Percentages refer to the viewport: its width for x, its height for y, its normalised
    // diagonal for radii of circles.
    auto pct = svg::parse_number(text.substr(0, text.size() - 1));
    if (pct) {
      std::string_view name = attr;
      double ref = name == "r" ? std::hypot(viewport_.x, viewport_.y) / std::sqrt(2.0)
                   : (name.find('y') != std::string_view::npos || name == "height") ? viewport_.y
                                                                                    : viewport_.x;
      return *pct / 100 * ref;
    }
  }
  auto v = svg::parse_length_px(a.value());
  if (!v)
    return Error{src_.at_attr(n, attr, 0),
                 std::string(attr) + "=\"" + a.value() + "\": " + v.error().message};
  return v;
}

Style Reader::style_of(pugi::xml_node n, const Style& parent, bool* display_none) {
  Style st = parent;
  *display_none = false;
  auto apply = [&](std::string_view prop, std::string_view value) {
    value = svg::trim(value);
    if (value == "inherit") return;  // the parent's value, which st already holds
    if (prop == "fill") {
      if (auto p = svg::parse_paint(value)) {
        st.fill = *p;
        if (p->kind == Paint::Kind::Url)
          warn(n, "svg-paint",
               "fill \"" + std::string(value) + "\" is a gradient or pattern: the shape is material" +
                   (opt_.overlap == SvgOverlap::Subtractive ? " and never erases" : ""));
      } else {
        warn(n, "svg-paint",
             "fill \"" + std::string(value) + "\" is not a colour: the inherited fill is used");
      }
    } else if (prop == "fill-rule") {
      if (value == "evenodd")
        st.evenodd = true;
      else if (value == "nonzero")
        st.evenodd = false;
      else
        warn(n, "svg-style", "fill-rule \"" + std::string(value) + "\" is not nonzero or evenodd: ignored");
    } else if (prop == "visibility") {
      st.visible = value == "visible";
    } else if (prop == "display") {
      *display_none = value == "none";
    } else if (prop == "stroke") {
      st.stroked = value != "none";
    } else if (prop == "color") {
      if (auto c = svg::parse_color(value)) st.color = *c;
    }
  };
  // Presentation attributes first; the style attribute overrides them.
  for (const char* prop : {"fill", "fill-rule", "visibility", "display", "stroke", "color"})
    if (pugi::xml_attribute a = n.attribute(prop)) apply(prop, a.value());
  if (pugi::xml_attribute a = n.attribute("style"))
    for (const auto& [prop, value] : svg::parse_style(a.value())) apply(prop, value);
  return st;
}

Status Reader::walk_children(pugi::xml_node n, const Affine& ctm, const Style& st,
                             std::vector<svg::Shape>& out, int depth) {
  for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling()) {
    if (c.type() != pugi::node_element) continue;
    if (auto s = walk(c, ctm, st, out, depth + 1); !s) return s;
  }
  return ok_status();
}

Status Reader::walk(pugi::xml_node n, const Affine& ctm, const Style& parent, std::vector<svg::Shape>& out,
                    int depth) {
  if (depth > kMaxDepth) return error_at(n, "elements nested deeper than " + std::to_string(kMaxDepth));
  if (++elements_ > kMaxElements)
    return error_at(
        n, "more than " + std::to_string(kMaxElements) + " elements to draw (counting <use> copies)");
  if (is_foreign(n)) return ok_status();  // editor metadata (inkscape:, sodipodi:...)
  std::string name = local_name(n);
  static const std::unordered_set<std::string> kNotRendered = {
      "defs",           "symbol",         "clipPath", "mask",  "marker",   "pattern",
      "linearGradient", "radialGradient", "filter",   "title", "desc",     "metadata",
      "script",         "view",           "cursor",   "font",  "font-face"};
  if (kNotRendered.count(name)) return ok_status();
  if (stack_ && (name == "style" || name == "text"))
    return ok_status();  // the sheet's own styling and captions
  if (name == "style") {
    if (!warned_css_)
      warn(n, "svg-css",
           "<style> stylesheets are not applied: use fill/fill-rule attributes or style=\"...\"");
    warned_css_ = true;
    return ok_status();
  }
  static const std::unordered_set<std::string> kIgnored = {"text",  "image",  "foreignObject", "video",
                                                           "audio", "iframe", "canvas"};
  if (kIgnored.count(name)) {
    warn(n, "svg-ignored",
         "<" + name + "> is not material: ignored" +
             (name == "text" ? " (convert text to paths in your editor)" : ""));
    return ok_status();
  }
  bool display_none = false;
  Style st = style_of(n, parent, &display_none);
  if (display_none) return ok_status();
  auto t = transform_of(n);
  if (!t) return t.error();
  Affine m = ctm * *t;
  if (n.attribute("clip-path") || n.attribute("mask"))
    warn(n, "svg-clip", "clip-path and mask are not applied: the whole shape is used");

  if (name == "g" || name == "a") return walk_children(n, m, st, out, depth);
  if (name == "switch") {  // the first child element is the one SVG renders when features are met
    for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling())
      if (c.type() == pugi::node_element && !is_foreign(c)) return walk(c, m, st, out, depth + 1);
    return ok_status();
  }
  if (name == "svg") {  // nested viewport: its x, y, and viewBox mapping
    auto vp = svg::viewport_of(n, src_, false);
    if (!vp) return vp.error();
    Vec2 outer = viewport_;
    if (vp->user_width > 0 && vp->user_height > 0) viewport_ = {vp->user_width, vp->user_height};
    Status s = walk_children(n, m * vp->user_to_px, st, out, depth);
    viewport_ = outer;
    return s;
  }
  if (name == "use") return use(n, m, st, out, depth);
  if (name == "line") {
    warn(n, "svg-line", "<line> encloses no area: ignored (draw a thin rectangle or a closed path instead)");
    return ok_status();
  }
  static const std::unordered_set<std::string> kShapes = {"path",    "rect",    "circle",
                                                          "ellipse", "polygon", "polyline"};
  if (kShapes.count(name)) {
    if (stack_ && !svg::has_class(n, "island")) {
      // Frames, and whatever later format versions add (cells, edges), are not material.
      if (!n.attribute("class"))
        warn(n, "svg-stack-unclassed",
             "<" + name +
                 "> in a layer group has no class=\"island\": not material "
                 "(add class=\"island\" to make it part of the layer)");
      return ok_status();
    }
    ++shape_elements_;
    return shape(n, name, m, st, out);
  }
  return ok_status();  // unknown elements draw nothing, as in browsers
}

Status Reader::use(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<svg::Shape>& out,
                   int depth) {
  std::string_view href = n.attribute("href").value();
  if (href.empty()) href = n.attribute("xlink:href").value();
  if (href.empty() || href[0] != '#') {
    warn(n, "svg-use", "<use> without a local reference (href=\"#id\"): ignored");
    return ok_status();
  }
  auto it = ids_.find(std::string(href.substr(1)));
  if (it == ids_.end()) {
    warn(n, "svg-use", "<use> refers to \"" + std::string(href) + "\", which is not in the file: ignored");
    return ok_status();
  }
  pugi::xml_node target = it->second;
  if (active_uses_.count(target.internal_object()) || target == n)
    return error_at(n, "<use> refers to \"" + std::string(href) + "\", which contains this <use>: a cycle");
  auto x = length(n, "x", 0);
  if (!x) return x.error();
  auto y = length(n, "y", 0);
  if (!y) return y.error();
  Affine m = ctm * Affine::translate(*x, *y);
  active_uses_.insert(target.internal_object());
  Status s = ok_status();
  if (local_name(target) == "symbol") {  // a symbol draws its children, like a group
    bool display_none = false;
    Style sym = style_of(target, st, &display_none);
    if (!display_none) s = walk_children(target, m, sym, out, depth + 1);
  } else {
    s = walk(target, m, st, out, depth + 1);
  }
  active_uses_.erase(target.internal_object());
  return s;
}

Result<std::vector<svg::Subpath>> Reader::geometry(pugi::xml_node n, const std::string& name, double tol) {
  std::vector<svg::Subpath> sp;
  auto len = [&](const char* attr) { return length(n, attr, 0); };
  auto negative = [&](const char* attr) {
    return Error{src_.at_attr(n, attr, 0), "<" + name + "> has a negative " + attr};
  };
  if (name == "path") {
    pugi::xml_attribute d = n.attribute("d");
    size_t at = 0;
    auto r = svg::parse_path_data(d.value(), tol, &at, kMaxPoints - std::min(points_, kMaxPoints));
    if (!r) {
      std::string_view v = d.value();
      size_t from = at > 12 ? at - 12 : 0;
      std::string snippet(v.substr(from, std::min<size_t>(24, v.size() - from)));
      return Error{src_.at_attr(n, "d", at), "path data: " + r.error().message + " at character " +
                                                 std::to_string(at + 1) + " of d (near \"" + snippet + "\")"};
    }
    return r;
  }
  if (name == "rect") {
    auto x = len("x"), y = len("y"), w = len("width"), h = len("height");
    for (auto* r : {&x, &y, &w, &h})
      if (!*r) return r->error();
    if (*w < 0) return negative("width");
    if (*h < 0) return negative("height");
    auto rx = length(n, "rx", -1), ry = length(n, "ry", -1);
    if (!rx) return rx.error();
    if (!ry) return ry.error();
    double rxv = *rx, ryv = *ry;
    if (rxv < 0 && ryv < 0)
      rxv = ryv = 0;  // neither given (or both negative, an error SVG ignores)
    else if (rxv < 0)
      rxv = ryv;
    else if (ryv < 0)
      ryv = rxv;
    rxv = std::min(rxv, *w / 2), ryv = std::min(ryv, *h / 2);
    svg::Subpath s;
    s.closed = true;
    double x0 = *x, y0 = *y, x1 = *x + *w, y1 = *y + *h;
    if (rxv > 0 && ryv > 0) {  // the rounded corners are quarter ellipses, as SVG's rect path
      s.points.push_back({x0 + rxv, y0});
      s.points.push_back({x1 - rxv, y0});
      svg::flatten_arc({x1 - rxv, y0}, rxv, ryv, 0, false, true, {x1, y0 + ryv}, tol, s.points);
      s.points.push_back({x1, y1 - ryv});
      svg::flatten_arc({x1, y1 - ryv}, rxv, ryv, 0, false, true, {x1 - rxv, y1}, tol, s.points);
      s.points.push_back({x0 + rxv, y1});
      svg::flatten_arc({x0 + rxv, y1}, rxv, ryv, 0, false, true, {x0, y1 - ryv}, tol, s.points);
      s.points.push_back({x0, y0 + ryv});
      svg::flatten_arc({x0, y0 + ryv}, rxv, ryv, 0, false, true, {x0 + rxv, y0}, tol, s.points);
    } else {
      s.points = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    }
    sp.push_back(std::move(s));
    return sp;
  }
  if (name == "circle" || name == "ellipse") {
    auto cx = len("cx"), cy = len("cy");
    if (!cx) return cx.error();
    if (!cy) return cy.error();
    Result<double> rx = name == "circle" ? len("r") : len("rx");
    Result<double> ry = name == "circle" ? len("r") : len("ry");
    if (!rx) return rx.error();
    if (!ry) return ry.error();
    if (*rx < 0) return negative(name == "circle" ? "r" : "rx");
    if (*ry < 0) return negative(name == "circle" ? "r" : "ry");
    if (*rx > 0 && *ry > 0) sp.push_back({svg::ellipse_ring({*cx, *cy}, *rx, *ry, tol), true});
    return sp;
  }
  // polygon, polyline: both filled as closed
  bool odd = false;
  size_t at = 0;
  auto pts = svg::parse_points(n.attribute("points").value(), &odd, &at);
  if (!pts) return Error{src_.at_attr(n, "points", at), "points: " + pts.error().message};
  if (odd) warn(n, "svg-points", "points has an odd count of numbers: the last one is ignored");
  sp.push_back({std::move(*pts), true});
  return sp;
}

Result<Rings> Reader::place(pugi::xml_node n, const std::vector<svg::Subpath>& subpaths, const Affine& ctm) {
  Rings rings;
  for (const auto& s : subpaths) {
    Ring r;
    r.reserve(s.points.size());
    for (const Vec2& p : s.points) {
      Vec2 q = ctm.apply(p);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || std::abs(q.x) > kMaxCoordMm ||
          std::abs(q.y) > kMaxCoordMm)
        return error_at(n, "a point lies " +
                               (std::isfinite(q.x) && std::isfinite(q.y)
                                    ? "at (" + std::to_string(q.x) + ", " + std::to_string(q.y) + ") mm"
                                    : std::string("at infinity")) +
                               ", more than 2 m from the page origin: check the units and transforms");
      Point pt = to_point(q.x, q.y);
      if (r.empty() || r.back() != pt) r.push_back(pt);
    }
    while (r.size() > 1 && r.front() == r.back()) r.pop_back();
    points_ += r.size();
    if (points_ > kMaxPoints)
      return error_at(n, "the drawing flattens to more than " + std::to_string(kMaxPoints) +
                             " points: raise the curve tolerance (--svg-tolerance)");
    if (r.size() >= 3) rings.push_back(std::move(r));
  }
  return rings;
}

Status Reader::shape(pugi::xml_node n, const std::string& name, const Affine& ctm, const Style& st,
                     std::vector<svg::Shape>& out) {
  // Flatten in user units with the tolerance that becomes opt_.tolerance_mm after the transform.
  double scale = ctm.max_scale();
  if (!(scale > 0)) return ok_status();  // a degenerate transform squashes the shape to nothing
  auto geom = geometry(n, name, opt_.tolerance_mm / scale);
  if (!geom) return geom.error();
  if (!st.visible) return ok_status();
  if (st.fill.kind == Paint::Kind::None) {
    if (st.stroked)
      warn(n, "svg-stroke", "<" + name + "> has a stroke but no fill: strokes are not material, ignored");
    return ok_status();
  }
  auto rings = place(n, *geom, ctm);
  if (!rings) return rings.error();
  if (rings->empty()) {
    warn(n, "svg-zero-area", "<" + name + "> encloses no area: ignored");
    return ok_status();
  }
  svg::Shape s;
  s.rings = std::move(*rings);
  s.evenodd = st.evenodd;
  s.fill = st.fill;
  if (s.fill.kind == Paint::Kind::CurrentColor) s.fill = Paint{Paint::Kind::Color, st.color};
  s.where = src_.at(n);
  out.push_back(std::move(s));
  return ok_status();
}

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

void Reader::warn_outside_layers(pugi::xml_node root, const svg::Stack& stack) {
  std::unordered_set<const void*> layers;
  for (const auto& l : stack.layers) layers.insert(l.node.internal_object());
  std::vector<pugi::xml_node> todo{root};
  while (!todo.empty()) {
    pugi::xml_node n = todo.back();
    todo.pop_back();
    std::string name = local_name(n);
    if (layers.count(n.internal_object()) || name == "defs" || name == "symbol" || svg::has_class(n, "legend"))
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

Result<SvgModel> Reader::read(const pugi::xml_document& doc) {
  pugi::xml_node root = doc.document_element();
  if (!root || local_name(root) != "svg")
    return Error{root ? src_.at(root) : src_.name(),
                 std::string("not an SVG document: the root element is <") + (root ? root.name() : "") +
                     ">, not <svg>"};
  // Ids for <use>; the first element with an id wins, as in browsers.
  std::vector<pugi::xml_node> todo{root};
  while (!todo.empty()) {
    pugi::xml_node n = todo.back();
    todo.pop_back();
    if (pugi::xml_attribute id = n.attribute("id")) ids_.emplace(id.value(), n);
    for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling())
      if (c.type() == pugi::node_element) todo.push_back(c);
  }

  auto vp = svg::viewport_of(root, src_, true);
  if (!vp) return vp.error();
  SvgModel model;
  model.page_width_mm = vp->width_px * svg::kMmPerPx;
  model.page_height_mm = vp->height_px * svg::kMmPerPx;
  viewport_ = {vp->user_width, vp->user_height};
  // User units -> px -> mm, with y flipped about the page height: (x, y) -> (x, H - y).
  Affine to_mm = Affine{svg::kMmPerPx, 0, 0, -svg::kMmPerPx, 0, model.page_height_mm} * vp->user_to_px;
  auto t = transform_of(root);  // SVG 2 allows a transform on the root
  if (!t) return t.error();
  to_mm = to_mm * *t;
  bool display_none = false;
  Style st = style_of(root, Style{}, &display_none);

  auto stack = svg::read_stack(root, src_, report_);
  if (!stack) return stack.error();
  model.layer_stack = stack_ = stack->is_stack;
  if (stack_) {
    warn_outside_layers(root, *stack);
    // Inside a layer group a point (X, Y) is the model point (X, -Y) in mm; the group's own
    // transform only places the layer on the sheet, and the page size means nothing.
    model.page_width_mm = model.page_height_mm = 0;
    for (const svg::StackLayer& g : stack->layers) {
      std::vector<svg::Shape> shapes;
      if (auto s = walk_children(g.node, Affine{1, 0, 0, -1, 0, 0}, Style{}, shapes, 1); !s) return s.error();
      model.layers.push_back({g.z_bottom, g.z_top, svg::resolve_shapes(shapes, opt_.overlap, background_)});
    }
  } else {
    std::vector<svg::Shape> shapes;
    if (!display_none)
      if (auto s = walk_children(root, to_mm, st, shapes, 0); !s) return s.error();
    model.layers.push_back({0, 0, svg::resolve_shapes(shapes, opt_.overlap, background_)});
  }

  if (shape_elements_ == 0)
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
    return Error{src_.name(), "the shapes enclose no material: " + std::to_string(shape_elements_) +
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
  if (model.page_height_mm <= 0 && !stack_) {
    // No page size: the drawing's lowest point goes to y = 0 (it was flipped about y = 0).
    for (auto& l : model.layers)
      for (auto& p : l.polygons) {
        for (auto& pt : p.outer) pt.Y -= box.min_y;
        for (auto& hole : p.holes)
          for (auto& pt : hole) pt.Y -= box.min_y;
      }
  }
  for (size_t i = 0; i < model.layers.size(); ++i) {
    auto polys = strict(model.layers[i].polygons);
    if (!polys) return Error{stack_ ? src_.at(stack->layers[i].node) : src_.name(), polys.error().message};
    model.layers[i].polygons = std::move(*polys);
  }
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
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, "cannot open the file"};
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return Error{path, "cannot read the file"};
  return parse_svg(ss.str(), path, options, report);
}

}  // namespace tranche::geo
