#include "geometry/io/svg_style.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

namespace tranche::geo::svg {

namespace {

bool is_wsp(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// The CSS Color Module Level 4 named colours.
struct NamedColor {
  std::string_view name;
  Rgb rgb;
};
constexpr NamedColor kNamedColors[] = {
    {"aliceblue", 0xf0f8ff},
    {"antiquewhite", 0xfaebd7},
    {"aqua", 0x00ffff},
    {"aquamarine", 0x7fffd4},
    {"azure", 0xf0ffff},
    {"beige", 0xf5f5dc},
    {"bisque", 0xffe4c4},
    {"black", 0x000000},
    {"blanchedalmond", 0xffebcd},
    {"blue", 0x0000ff},
    {"blueviolet", 0x8a2be2},
    {"brown", 0xa52a2a},
    {"burlywood", 0xdeb887},
    {"cadetblue", 0x5f9ea0},
    {"chartreuse", 0x7fff00},
    {"chocolate", 0xd2691e},
    {"coral", 0xff7f50},
    {"cornflowerblue", 0x6495ed},
    {"cornsilk", 0xfff8dc},
    {"crimson", 0xdc143c},
    {"cyan", 0x00ffff},
    {"darkblue", 0x00008b},
    {"darkcyan", 0x008b8b},
    {"darkgoldenrod", 0xb8860b},
    {"darkgray", 0xa9a9a9},
    {"darkgreen", 0x006400},
    {"darkgrey", 0xa9a9a9},
    {"darkkhaki", 0xbdb76b},
    {"darkmagenta", 0x8b008b},
    {"darkolivegreen", 0x556b2f},
    {"darkorange", 0xff8c00},
    {"darkorchid", 0x9932cc},
    {"darkred", 0x8b0000},
    {"darksalmon", 0xe9967a},
    {"darkseagreen", 0x8fbc8f},
    {"darkslateblue", 0x483d8b},
    {"darkslategray", 0x2f4f4f},
    {"darkslategrey", 0x2f4f4f},
    {"darkturquoise", 0x00ced1},
    {"darkviolet", 0x9400d3},
    {"deeppink", 0xff1493},
    {"deepskyblue", 0x00bfff},
    {"dimgray", 0x696969},
    {"dimgrey", 0x696969},
    {"dodgerblue", 0x1e90ff},
    {"firebrick", 0xb22222},
    {"floralwhite", 0xfffaf0},
    {"forestgreen", 0x228b22},
    {"fuchsia", 0xff00ff},
    {"gainsboro", 0xdcdcdc},
    {"ghostwhite", 0xf8f8ff},
    {"gold", 0xffd700},
    {"goldenrod", 0xdaa520},
    {"gray", 0x808080},
    {"green", 0x008000},
    {"greenyellow", 0xadff2f},
    {"grey", 0x808080},
    {"honeydew", 0xf0fff0},
    {"hotpink", 0xff69b4},
    {"indianred", 0xcd5c5c},
    {"indigo", 0x4b0082},
    {"ivory", 0xfffff0},
    {"khaki", 0xf0e68c},
    {"lavender", 0xe6e6fa},
    {"lavenderblush", 0xfff0f5},
    {"lawngreen", 0x7cfc00},
    {"lemonchiffon", 0xfffacd},
    {"lightblue", 0xadd8e6},
    {"lightcoral", 0xf08080},
    {"lightcyan", 0xe0ffff},
    {"lightgoldenrodyellow", 0xfafad2},
    {"lightgray", 0xd3d3d3},
    {"lightgreen", 0x90ee90},
    {"lightgrey", 0xd3d3d3},
    {"lightpink", 0xffb6c1},
    {"lightsalmon", 0xffa07a},
    {"lightseagreen", 0x20b2aa},
    {"lightskyblue", 0x87cefa},
    {"lightslategray", 0x778899},
    {"lightslategrey", 0x778899},
    {"lightsteelblue", 0xb0c4de},
    {"lightyellow", 0xffffe0},
    {"lime", 0x00ff00},
    {"limegreen", 0x32cd32},
    {"linen", 0xfaf0e6},
    {"magenta", 0xff00ff},
    {"maroon", 0x800000},
    {"mediumaquamarine", 0x66cdaa},
    {"mediumblue", 0x0000cd},
    {"mediumorchid", 0xba55d3},
    {"mediumpurple", 0x9370db},
    {"mediumseagreen", 0x3cb371},
    {"mediumslateblue", 0x7b68ee},
    {"mediumspringgreen", 0x00fa9a},
    {"mediumturquoise", 0x48d1cc},
    {"mediumvioletred", 0xc71585},
    {"midnightblue", 0x191970},
    {"mintcream", 0xf5fffa},
    {"mistyrose", 0xffe4e1},
    {"moccasin", 0xffe4b5},
    {"navajowhite", 0xffdead},
    {"navy", 0x000080},
    {"oldlace", 0xfdf5e6},
    {"olive", 0x808000},
    {"olivedrab", 0x6b8e23},
    {"orange", 0xffa500},
    {"orangered", 0xff4500},
    {"orchid", 0xda70d6},
    {"palegoldenrod", 0xeee8aa},
    {"palegreen", 0x98fb98},
    {"paleturquoise", 0xafeeee},
    {"palevioletred", 0xdb7093},
    {"papayawhip", 0xffefd5},
    {"peachpuff", 0xffdab9},
    {"peru", 0xcd853f},
    {"pink", 0xffc0cb},
    {"plum", 0xdda0dd},
    {"powderblue", 0xb0e0e6},
    {"purple", 0x800080},
    {"rebeccapurple", 0x663399},
    {"red", 0xff0000},
    {"rosybrown", 0xbc8f8f},
    {"royalblue", 0x4169e1},
    {"saddlebrown", 0x8b4513},
    {"salmon", 0xfa8072},
    {"sandybrown", 0xf4a460},
    {"seagreen", 0x2e8b57},
    {"seashell", 0xfff5ee},
    {"sienna", 0xa0522d},
    {"silver", 0xc0c0c0},
    {"skyblue", 0x87ceeb},
    {"slateblue", 0x6a5acd},
    {"slategray", 0x708090},
    {"slategrey", 0x708090},
    {"snow", 0xfffafa},
    {"springgreen", 0x00ff7f},
    {"steelblue", 0x4682b4},
    {"tan", 0xd2b48c},
    {"teal", 0x008080},
    {"thistle", 0xd8bfd8},
    {"tomato", 0xff6347},
    {"turquoise", 0x40e0d0},
    {"violet", 0xee82ee},
    {"wheat", 0xf5deb3},
    {"white", 0xffffff},
    {"whitesmoke", 0xf5f5f5},
    {"yellow", 0xffff00},
    {"yellowgreen", 0x9acd32},
};

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Splits "name(args)" into the lower-case name and the argument text; nullopt if not that shape.
std::optional<std::pair<std::string, std::string_view>> function_call(std::string_view s) {
  auto open = s.find('(');
  if (open == std::string_view::npos || s.empty() || s.back() != ')') return std::nullopt;
  return std::make_pair(lower(trim(s.substr(0, open))), s.substr(open + 1, s.size() - open - 2));
}

// One rgb() channel: 0..255, or a percentage of 255; clamped as CSS says.
std::optional<int> channel(std::string_view s) {
  s = trim(s);
  bool pct = !s.empty() && s.back() == '%';
  if (pct) s.remove_suffix(1);
  auto v = parse_number(s);
  if (!v) return std::nullopt;
  double x = pct ? *v * 255 / 100 : *v;
  return static_cast<int>(std::lround(std::clamp(x, 0.0, 255.0)));
}

}  // namespace

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_wsp(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_wsp(s.back())) s.remove_suffix(1);
  return s;
}

Affine Affine::operator*(const Affine& t) const {
  return {a * t.a + c * t.b, b * t.a + d * t.b,     a * t.c + c * t.d,
          b * t.c + d * t.d, a * t.e + c * t.f + e, b * t.e + d * t.f + f};
}

double Affine::max_scale() const {
  double s = a * a + b * b + c * c + d * d;
  double det = a * d - b * c;
  return std::sqrt((s + std::sqrt(std::max(0.0, s * s - 4 * det * det))) / 2);
}

Affine Affine::rotate_deg(double deg) {
  double r = deg * std::numbers::pi / 180;
  double cs = std::cos(r), sn = std::sin(r);
  return {cs, sn, -sn, cs, 0, 0};
}

Result<Affine> parse_transform(std::string_view s, size_t* error_offset) {
  Affine m;
  size_t p = 0;
  auto fail = [&](size_t at, std::string msg) -> Error {
    if (error_offset) *error_offset = at;
    return Error{"", std::move(msg)};
  };
  auto skip = [&] {
    while (p < s.size() && (is_wsp(s[p]) || s[p] == ',')) ++p;
  };
  skip();
  while (p < s.size()) {
    size_t name_at = p;
    while (p < s.size() && std::isalpha(static_cast<unsigned char>(s[p]))) ++p;
    std::string name(s.substr(name_at, p - name_at));
    while (p < s.size() && is_wsp(s[p])) ++p;
    if (name.empty() || p >= s.size() || s[p] != '(')
      return fail(name_at, "expected a transform (matrix, translate, scale, rotate, skewX or skewY)");
    size_t close = s.find(')', p);
    if (close == std::string_view::npos) return fail(p, "missing ')' in transform");
    std::vector<double> args;
    std::string_view body = s.substr(p + 1, close - p - 1);
    size_t q = 0;
    while (true) {
      while (q < body.size() && (is_wsp(body[q]) || body[q] == ',')) ++q;
      if (q >= body.size()) break;
      auto v = scan_number(body, &q);  // numbers may run together: "1-2" is 1 and -2
      if (!v) return fail(p + 1 + q, "expected a number in " + name + "()");
      args.push_back(*v);
    }
    size_t n = args.size();
    auto bad_count = [&](const char* expected) {
      return fail(name_at, name + "() takes " + expected + " numbers, got " + std::to_string(n));
    };
    Affine t;
    if (name == "matrix") {
      if (n != 6) return bad_count("6");
      t = {args[0], args[1], args[2], args[3], args[4], args[5]};
    } else if (name == "translate") {
      if (n != 1 && n != 2) return bad_count("1 or 2");
      t = Affine::translate(args[0], n == 2 ? args[1] : 0);
    } else if (name == "scale") {
      if (n != 1 && n != 2) return bad_count("1 or 2");
      t = Affine::scale(args[0], n == 2 ? args[1] : args[0]);
    } else if (name == "rotate") {
      if (n != 1 && n != 3) return bad_count("1 or 3");
      t = Affine::rotate_deg(args[0]);
      if (n == 3) t = Affine::translate(args[1], args[2]) * t * Affine::translate(-args[1], -args[2]);
    } else if (name == "skewX") {
      if (n != 1) return bad_count("1");
      t = {1, 0, std::tan(args[0] * std::numbers::pi / 180), 1, 0, 0};
    } else if (name == "skewY") {
      if (n != 1) return bad_count("1");
      t = {1, std::tan(args[0] * std::numbers::pi / 180), 0, 1, 0, 0};
    } else {
      return fail(name_at, "unknown transform '" + name + "'");
    }
    m = m * t;  // the list applies right to left: the last transform acts first
    p = close + 1;
    skip();
  }
  return m;
}

Result<double> parse_length_px(std::string_view s) {
  s = trim(s);
  size_t unit_at = s.size();
  while (unit_at > 0 && (std::isalpha(static_cast<unsigned char>(s[unit_at - 1])) || s[unit_at - 1] == '%'))
    --unit_at;
  auto v = parse_number(s.substr(0, unit_at));
  // Messages are built by appending: GCC 12 at -O3 sees a false -Wrestrict in "'" + std::string(s).
  auto quoted = [&] {
    std::string q = "'";
    q.append(s);
    q += '\'';
    return q;
  };
  if (!v) return Error{"", quoted() + " is not a length"};
  std::string unit = lower(s.substr(unit_at));
  if (unit.empty() || unit == "px") return *v;
  if (unit == "mm") return *v / kMmPerPx;
  if (unit == "cm") return *v * 10 / kMmPerPx;
  if (unit == "in") return *v * 96;
  if (unit == "pt") return *v * 96 / 72;
  if (unit == "pc") return *v * 16;
  if (unit == "q") return *v * 0.25 / kMmPerPx;
  const char* use = ": use mm, cm, in, pt, pc or px";
  if (unit == "%") return Error{"", "percentage lengths (" + quoted() + ") are not supported here" + use};
  if (unit == "em" || unit == "ex" || unit == "rem")
    return Error{"", "font-relative length " + quoted() + " is not supported" + use};
  return Error{"", "unknown unit '" + unit + "' in " + quoted() + use};
}

std::optional<Rgb> parse_color(std::string_view s) {
  s = trim(s);
  if (s.empty()) return std::nullopt;
  if (s[0] == '#') {
    std::string_view h = s.substr(1);
    for (char c : h)
      if (hex_value(c) < 0) return std::nullopt;
    if (h.size() == 3 || h.size() == 4) {  // #rgb(a): each digit doubled
      return static_cast<Rgb>(hex_value(h[0]) * 0x110000 + hex_value(h[1]) * 0x1100 + hex_value(h[2]) * 0x11);
    }
    if (h.size() == 6 || h.size() == 8) {
      Rgb v = 0;
      for (size_t i = 0; i < 6; ++i) v = v * 16 + static_cast<Rgb>(hex_value(h[i]));
      return v;
    }
    return std::nullopt;
  }
  if (auto fn = function_call(s)) {
    if (fn->first != "rgb" && fn->first != "rgba") return std::nullopt;
    std::string_view args = fn->second;
    std::vector<std::string_view> parts;
    size_t start = 0;
    for (size_t i = 0; i <= args.size(); ++i) {
      if (i == args.size() || args[i] == ',' || args[i] == '/') {
        parts.push_back(args.substr(start, i - start));
        start = i + 1;
      }
    }
    if (parts.size() == 1) {  // CSS 4 space-separated form: rgb(255 0 0)
      parts.clear();
      std::string_view a = trim(args);
      while (!a.empty()) {
        size_t e = 0;
        while (e < a.size() && !is_wsp(a[e])) ++e;
        parts.push_back(a.substr(0, e));
        a = trim(a.substr(e));
      }
    }
    if (parts.size() < 3 || parts.size() > 4) return std::nullopt;
    Rgb v = 0;
    for (int i = 0; i < 3; ++i) {
      auto ch = channel(parts[static_cast<size_t>(i)]);
      if (!ch) return std::nullopt;
      v = v * 256 + static_cast<Rgb>(*ch);
    }
    return v;
  }
  std::string name = lower(s);
  for (const auto& nc : kNamedColors)
    if (nc.name == name) return nc.rgb;
  return std::nullopt;
}

std::optional<Paint> parse_paint(std::string_view s) {
  s = trim(s);
  std::string l = lower(s);
  if (l == "none") return Paint{Paint::Kind::None, 0};
  if (l == "currentcolor") return Paint{Paint::Kind::CurrentColor, 0};
  if (l.rfind("url(", 0) == 0) {
    // url(#id) [fallback]: a gradient or pattern; a fallback colour decides `none`.
    auto close = s.find(')');
    if (close == std::string_view::npos) return std::nullopt;
    std::string_view fallback = trim(s.substr(close + 1));
    if (!fallback.empty()) {
      if (lower(fallback) == "none") return Paint{Paint::Kind::None, 0};
      if (auto c = parse_color(fallback)) return Paint{Paint::Kind::Url, *c};
    }
    return Paint{Paint::Kind::Url, 0};
  }
  if (auto c = parse_color(s)) return Paint{Paint::Kind::Color, *c};
  return std::nullopt;
}

std::vector<std::pair<std::string, std::string>> parse_style(std::string_view s) {
  std::vector<std::pair<std::string, std::string>> out;
  size_t start = 0;
  while (start <= s.size()) {
    size_t end = s.find(';', start);
    if (end == std::string_view::npos) end = s.size();
    std::string_view decl = s.substr(start, end - start);
    auto colon = decl.find(':');
    if (colon != std::string_view::npos) {
      std::string_view value = trim(decl.substr(colon + 1));
      if (auto bang = value.find("!important"); bang != std::string_view::npos)
        value = trim(value.substr(0, bang));
      out.emplace_back(lower(trim(decl.substr(0, colon))), std::string(value));
    }
    start = end + 1;
  }
  return out;
}

}  // namespace tranche::geo::svg
