#include "geometry/io/svg_walk.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/io/svg_path.h"

namespace tranche::geo::svg {

namespace {

constexpr int kMaxDepth = 256;              // nested groups and use references
constexpr size_t kMaxElements = 1'000'000;  // elements rendered, counting each use expansion
constexpr size_t kMaxPoints = 20'000'000;   // flattened points over the whole drawing
constexpr double kMaxCoordMm = 2'000;       // beyond, the units are surely wrong (polygon work stops at 2147)

}  // namespace

std::string local_name(pugi::xml_node n) {
  std::string_view name = n.name();
  if (name.rfind("svg:", 0) == 0) name.remove_prefix(4);
  return std::string(name);
}

bool is_foreign(pugi::xml_node n) {
  return std::string_view(n.name()).find(':') != std::string_view::npos &&
         std::string_view(n.name()).rfind("svg:", 0) != 0;
}

void Walker::index_ids(pugi::xml_node root) {
  std::vector<pugi::xml_node> todo{root};
  while (!todo.empty()) {
    pugi::xml_node n = todo.back();
    todo.pop_back();
    if (pugi::xml_attribute id = n.attribute("id")) ids_.emplace(id.value(), n);
    for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling())
      if (c.type() == pugi::node_element) todo.push_back(c);
  }
}

// The element's own transform attribute (identity without one).
Result<Affine> Walker::transform_of(pugi::xml_node n) {
  pugi::xml_attribute a = n.attribute("transform");
  if (!a) return Affine{};
  size_t at = 0;
  auto t = parse_transform(a.value(), &at);
  if (!t) return Error{src_.at_attr(n, "transform", at), "transform: " + t.error().message};
  const Affine& m = *t;
  if (!std::isfinite(m.a) || !std::isfinite(m.b) || !std::isfinite(m.c) || !std::isfinite(m.d) ||
      !std::isfinite(m.e) || !std::isfinite(m.f))
    return error_at(n, "transform: the matrix is not finite");
  return t;
}

// A length attribute in user units (percentages of the viewport), `fallback` when absent.
Result<double> Walker::length(pugi::xml_node n, const char* attr, double fallback) {
  pugi::xml_attribute a = n.attribute(attr);
  if (!a) return fallback;
  std::string_view text = trim(a.value());
  if (!text.empty() && text.back() == '%' && viewport_.x > 0 && viewport_.y > 0) {
    // Percentages refer to the viewport: its width for x, its height for y, its normalised
    // diagonal for radii of circles.
    auto pct = parse_number(text.substr(0, text.size() - 1));
    if (pct) {
      std::string_view name = attr;
      double ref = name == "r" ? std::hypot(viewport_.x, viewport_.y) / std::sqrt(2.0)
                   : (name.find('y') != std::string_view::npos || name == "height") ? viewport_.y
                                                                                    : viewport_.x;
      return *pct / 100 * ref;
    }
  }
  auto v = parse_length_px(a.value());
  if (!v)
    return Error{src_.at_attr(n, attr, 0),
                 std::string(attr) + "=\"" + a.value() + "\": " + v.error().message};
  return v;
}

// The element's style: the parent's with its presentation attributes and style attribute applied.
Style Walker::style_of(pugi::xml_node n, const Style& parent, bool* display_none) {
  Style st = parent;
  *display_none = false;
  auto apply = [&](std::string_view prop, std::string_view value) {
    value = trim(value);
    if (value == "inherit") return;  // the parent's value, which st already holds
    if (prop == "fill") {
      if (auto p = parse_paint(value)) {
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
      if (auto c = parse_color(value)) st.color = *c;
    }
  };
  // Presentation attributes first; the style attribute overrides them.
  for (const char* prop : {"fill", "fill-rule", "visibility", "display", "stroke", "color"})
    if (pugi::xml_attribute a = n.attribute(prop)) apply(prop, a.value());
  if (pugi::xml_attribute a = n.attribute("style"))
    for (const auto& [prop, value] : parse_style(a.value())) apply(prop, value);
  return st;
}

// Draws the element children of n.
Status Walker::walk_children(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<Shape>& out,
                             int depth) {
  for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling()) {
    if (c.type() != pugi::node_element) continue;
    if (auto s = walk(c, ctm, st, out, depth + 1); !s) return s;
  }
  return ok_status();
}

// Draws element n (and what it contains or refers to) with the parent's style and transform.
Status Walker::walk(pugi::xml_node n, const Affine& ctm, const Style& parent, std::vector<Shape>& out,
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
    auto vp = viewport_of(n, src_, false);
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
    if (stack_ && !has_class(n, "island")) {
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

// Draws what a <use> refers to, moved by its x and y.
Status Walker::use(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<Shape>& out, int depth) {
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

// The outline of a shape element in user units, curves flattened within `tol`.
Result<std::vector<Subpath>> Walker::geometry(pugi::xml_node n, const std::string& name, double tol) {
  std::vector<Subpath> sp;
  auto len = [&](const char* attr) { return length(n, attr, 0); };
  auto negative = [&](const char* attr) {
    return Error{src_.at_attr(n, attr, 0), "<" + name + "> has a negative " + attr};
  };
  if (name == "path") {
    pugi::xml_attribute d = n.attribute("d");
    size_t at = 0;
    auto r = parse_path_data(d.value(), tol, &at, kMaxPoints - std::min(points_, kMaxPoints));
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
    Subpath s;
    s.closed = true;
    double x0 = *x, y0 = *y, x1 = *x + *w, y1 = *y + *h;
    if (rxv > 0 && ryv > 0) {  // the rounded corners are quarter ellipses, as SVG's rect path
      s.points.push_back({x0 + rxv, y0});
      s.points.push_back({x1 - rxv, y0});
      flatten_arc({x1 - rxv, y0}, rxv, ryv, 0, false, true, {x1, y0 + ryv}, tol, s.points);
      s.points.push_back({x1, y1 - ryv});
      flatten_arc({x1, y1 - ryv}, rxv, ryv, 0, false, true, {x1 - rxv, y1}, tol, s.points);
      s.points.push_back({x0 + rxv, y1});
      flatten_arc({x0 + rxv, y1}, rxv, ryv, 0, false, true, {x0, y1 - ryv}, tol, s.points);
      s.points.push_back({x0, y0 + ryv});
      flatten_arc({x0, y0 + ryv}, rxv, ryv, 0, false, true, {x0 + rxv, y0}, tol, s.points);
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
    if (*rx > 0 && *ry > 0) sp.push_back({ellipse_ring({*cx, *cy}, *rx, *ry, tol), true});
    return sp;
  }
  // polygon, polyline: both filled as closed
  bool odd = false;
  size_t at = 0;
  auto pts = parse_points(n.attribute("points").value(), &odd, &at);
  if (!pts) return Error{src_.at_attr(n, "points", at), "points: " + pts.error().message};
  if (odd) warn(n, "svg-points", "points has an odd count of numbers: the last one is ignored");
  sp.push_back({std::move(*pts), true});
  return sp;
}

// Subpaths placed on the bed (nm) by the transform, repeats dropped, rings under 3 points too.
Result<Rings> Walker::place(pugi::xml_node n, const std::vector<Subpath>& subpaths, const Affine& ctm) {
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

// A filled shape element as a Shape in `out` (nothing when hidden, unfilled or empty).
Status Walker::shape(pugi::xml_node n, const std::string& name, const Affine& ctm, const Style& st,
                     std::vector<Shape>& out) {
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
  Shape s;
  s.rings = std::move(*rings);
  s.evenodd = st.evenodd;
  s.fill = st.fill;
  if (s.fill.kind == Paint::Kind::CurrentColor) s.fill = Paint{Paint::Kind::Color, st.color};
  s.where = src_.at(n);
  out.push_back(std::move(s));
  return ok_status();
}

}  // namespace tranche::geo::svg
