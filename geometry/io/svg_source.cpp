#include "geometry/io/svg_source.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tranche::geo::svg {

SourceMap::SourceMap(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {
  line_starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts_.push_back(i + 1);
}

std::string SourceMap::at(size_t offset) const {
  offset = std::min(offset, text_.size());
  auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  size_t line = static_cast<size_t>(it - line_starts_.begin());
  size_t col = offset - line_starts_[line - 1] + 1;
  return name_ + ":" + std::to_string(line) + ":" + std::to_string(col);
}

std::string SourceMap::at(pugi::xml_node n) const {
  ptrdiff_t off = n.offset_debug();  // the element name, just after '<'
  if (off < 0) return name_;
  size_t o = static_cast<size_t>(off);
  if (o > 0 && o <= text_.size() && text_[o - 1] == '<') --o;
  return at(o);
}

std::string SourceMap::at_attr(pugi::xml_node n, std::string_view attr, size_t index) const {
  ptrdiff_t off = n.offset_debug();
  if (off < 0) return name_;
  size_t tag_end = text_.find('>', static_cast<size_t>(off));
  if (tag_end == std::string_view::npos) tag_end = text_.size();
  std::string_view tag = text_.substr(static_cast<size_t>(off), tag_end - static_cast<size_t>(off));
  // The attribute name preceded by whitespace, then '=' and a quote (values may hold '>' in
  // principle, which only makes us fall back to the element's location).
  for (size_t p = tag.find(attr); p != std::string_view::npos; p = tag.find(attr, p + 1)) {
    if (p == 0 || !std::isspace(static_cast<unsigned char>(tag[p - 1]))) continue;
    size_t q = p + attr.size();
    while (q < tag.size() && std::isspace(static_cast<unsigned char>(tag[q]))) ++q;
    if (q >= tag.size() || tag[q] != '=') continue;
    ++q;
    while (q < tag.size() && std::isspace(static_cast<unsigned char>(tag[q]))) ++q;
    if (q >= tag.size() || (tag[q] != '"' && tag[q] != '\'')) continue;
    size_t value_start = static_cast<size_t>(off) + q + 1;
    std::string_view raw = text_.substr(value_start, std::min(index, text_.size() - value_start));
    if (raw.find('&') != std::string_view::npos || raw.find('\r') != std::string_view::npos) break;
    return at(value_start + index);
  }
  return at(n);
}

namespace {

Result<double> length_attr(pugi::xml_node n, const SourceMap& src, const char* attr, bool* given,
                           bool* percent) {
  *given = false;
  if (percent) *percent = false;
  pugi::xml_attribute a = n.attribute(attr);
  if (!a) return 0.0;
  std::string_view v = trim(a.value());
  if (percent && !v.empty() && v.back() == '%') {
    *percent = true;
    return 0.0;
  }
  auto px = parse_length_px(v);
  if (!px)
    return Error{src.at_attr(n, attr, 0),
                 std::string(attr) + "=\"" + a.value() + "\": " + px.error().message};
  *given = true;
  return px;
}

}  // namespace

Result<Viewport> viewport_of(pugi::xml_node el, const SourceMap& src, bool root) {
  Viewport vp;
  bool has_w = false, has_h = false, pct_w = false, pct_h = false;
  auto w = length_attr(el, src, "width", &has_w, &pct_w);
  if (!w) return w.error();
  auto h = length_attr(el, src, "height", &has_h, &pct_h);
  if (!h) return h.error();
  constexpr double kMaxPx = 1e5 / kMmPerPx;  // 100 m
  auto check = [&](bool given, double v, const char* name) -> Status {
    if (given && !(v > 0 && v < kMaxPx))
      return Error{src.at_attr(el, name, 0),
                   std::string(name) + "=\"" + el.attribute(name).value() +
                       "\" is not a usable page size (it must be above 0 and below 100 m)"};
    return ok_status();
  };
  if (auto s = check(has_w, *w, "width"); !s) return s.error();
  if (auto s = check(has_h, *h, "height"); !s) return s.error();

  bool has_vb = false;
  double vb[4] = {0, 0, 0, 0};
  if (pugi::xml_attribute a = el.attribute("viewBox")) {
    std::string_view s = a.value();
    size_t p = 0;
    int count = 0;
    while (true) {
      while (p < s.size() && (std::isspace(static_cast<unsigned char>(s[p])) || s[p] == ',')) ++p;
      if (p >= s.size()) break;
      auto v = scan_number(s, &p);
      if (!v || count == 4)
        return Error{src.at_attr(el, "viewBox", p), "viewBox must be four numbers: min-x min-y width height"};
      vb[count++] = *v;
    }
    if (count != 4)
      return Error{src.at_attr(el, "viewBox", 0), "viewBox must be four numbers: min-x min-y width height"};
    if (!(vb[2] > 0 && vb[3] > 0))
      return Error{src.at_attr(el, "viewBox", 0), "viewBox width and height must be positive"};
    has_vb = true;
  }

  // A missing size defaults to the viewBox size (in px), or follows the other side's ratio.
  double vw = has_w ? *w : 0, vh = has_h ? *h : 0;
  if (has_vb) {
    if (!has_w && !has_h)
      vw = vb[2], vh = vb[3];
    else if (!has_w)
      vw = vh * vb[2] / vb[3];
    else if (!has_h)
      vh = vw * vb[3] / vb[2];
  }
  vp.width_px = vw;
  vp.height_px = vh;
  vp.user_width = has_vb ? vb[2] : vw;
  vp.user_height = has_vb ? vb[3] : vh;

  if (has_vb && vw > 0 && vh > 0) {
    std::string par = el.attribute("preserveAspectRatio").value();
    double sx = vw / vb[2], sy = vh / vb[3];
    double tx = -vb[0] * sx, ty = -vb[1] * sy;
    if (par.find("none") == std::string::npos) {
      bool slice = par.find("slice") != std::string::npos;
      double s = slice ? std::max(sx, sy) : std::min(sx, sy);
      // Alignment: xMin/xMid/xMax and YMin/YMid/YMax; xMidYMid by default.
      double ax = par.find("xMin") != std::string::npos ? 0 : par.find("xMax") != std::string::npos ? 1 : 0.5;
      double ay = par.find("YMin") != std::string::npos ? 0 : par.find("YMax") != std::string::npos ? 1 : 0.5;
      sx = sy = s;
      tx = -vb[0] * s + ax * (vw - vb[2] * s);
      ty = -vb[1] * s + ay * (vh - vb[3] * s);
    }
    vp.user_to_px = Affine{sx, 0, 0, sy, tx, ty};
  }
  if (!root) {  // a nested viewport sits at its x, y in the parent's user space
    bool gx = false, gy = false;
    auto x = length_attr(el, src, "x", &gx, nullptr);
    if (!x) return x.error();
    auto y = length_attr(el, src, "y", &gy, nullptr);
    if (!y) return y.error();
    vp.user_to_px = Affine::translate(*x, *y) * vp.user_to_px;
  }
  return vp;
}

}  // namespace tranche::geo::svg
