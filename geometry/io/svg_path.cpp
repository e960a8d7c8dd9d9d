#include "geometry/io/svg_path.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>

namespace tranche::geo::svg {

namespace {

constexpr double kPi = std::numbers::pi;

Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }

bool is_wsp(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// A cursor over path data or a points list, following the SVG 1.1 path grammar.
class Scanner {
 public:
  explicit Scanner(std::string_view s, size_t pos = 0) : s_(s), pos_(pos) {}

  size_t pos() const { return pos_; }
  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }
  void advance() { ++pos_; }
  void skip_wsp() {
    while (!at_end() && is_wsp(s_[pos_])) ++pos_;
  }
  // comma-wsp?: whitespace, at most one comma, whitespace.
  void skip_comma_wsp() {
    skip_wsp();
    if (peek() == ',') {
      ++pos_;
      skip_wsp();
    }
  }
  bool number_starts() const {
    char c = peek();
    return is_digit(c) || c == '.' || c == '-' || c == '+';
  }

  // Reads a number at the cursor (after optional whitespace). nullopt: no number here, or one
  // out of double range (out_of_range() tells); the cursor stays where the number should start.
  std::optional<double> number() {
    skip_wsp();
    out_of_range_ = false;
    size_t start = pos_, p = pos_;
    bool neg = false;
    if (p < s_.size() && (s_[p] == '+' || s_[p] == '-')) neg = s_[p++] == '-';
    size_t digits_start = p;
    bool any = false;
    while (p < s_.size() && is_digit(s_[p])) ++p, any = true;
    if (p < s_.size() && s_[p] == '.') {
      ++p;
      while (p < s_.size() && is_digit(s_[p])) ++p, any = true;
    }
    if (!any) return std::nullopt;
    if (p < s_.size() && (s_[p] == 'e' || s_[p] == 'E')) {
      size_t q = p + 1;
      if (q < s_.size() && (s_[q] == '+' || s_[q] == '-')) ++q;
      if (q < s_.size() && is_digit(s_[q])) {  // else the 'e' is not part of the number
        while (q < s_.size() && is_digit(s_[q])) ++q;
        p = q;
      }
    }
    double v = 0;
    auto [ptr, ec] = std::from_chars(s_.data() + digits_start, s_.data() + p, v);
    if (ec != std::errc() || ptr != s_.data() + p || !std::isfinite(v)) {
      out_of_range_ = true;
      pos_ = start;
      return std::nullopt;
    }
    pos_ = p;
    return neg ? -v : v;
  }

  // An arc flag: a single '0' or '1', which needs no separator after it.
  std::optional<bool> flag() {
    skip_wsp();
    char c = peek();
    if (c != '0' && c != '1') return std::nullopt;
    ++pos_;
    return c == '1';
  }
  bool out_of_range() const { return out_of_range_; }

 private:
  std::string_view s_;
  size_t pos_ = 0;
  bool out_of_range_ = false;
};

std::string quoted(char c) { return std::string("'") + c + "'"; }

// The state of a path being built: the current point, the subpath start and the last control
// point (for S and T reflection).
class PathBuilder {
 public:
  explicit PathBuilder(double tolerance) : tol_(tolerance) {}

  Vec2 current() const { return cur_; }
  size_t points() const { return done_ + sp_.points.size(); }
  void move_to(Vec2 p) {
    flush();
    sp_.points.push_back(p);
    cur_ = start_ = p;
  }
  void line_to(Vec2 p) {
    begin_if_needed();
    sp_.points.push_back(p);
    cur_ = p;
  }
  void cubic_to(Vec2 c1, Vec2 c2, Vec2 p) {
    begin_if_needed();
    flatten_cubic(cur_, c1, c2, p, tol_, sp_.points);
    cur_ = p;
  }
  void quadratic_to(Vec2 c, Vec2 p) {
    begin_if_needed();
    flatten_quadratic(cur_, c, p, tol_, sp_.points);
    cur_ = p;
  }
  void arc_to(double rx, double ry, double phi, bool large, bool sweep, Vec2 p) {
    begin_if_needed();
    flatten_arc(cur_, rx, ry, phi, large, sweep, p, tol_, sp_.points);
    cur_ = p;
  }
  void close() {
    if (!sp_.points.empty()) {
      sp_.closed = true;
      flush();
    }
    cur_ = start_;
  }
  std::vector<Subpath> finish() {
    flush();
    return std::move(out_);
  }

 private:
  // After Z, a drawing command without a moveto starts a new subpath at the old start.
  void begin_if_needed() {
    if (sp_.points.empty()) sp_.points.push_back(cur_);
  }
  void flush() {
    done_ += sp_.points.size();
    if (!sp_.points.empty()) out_.push_back(std::move(sp_));
    sp_ = Subpath{};
  }

  double tol_;
  Vec2 cur_, start_;
  Subpath sp_;
  std::vector<Subpath> out_;
  size_t done_ = 0;  // points in out_
};

int arg_count(char cmd) {
  switch (cmd) {
    case 'M':
    case 'L':
    case 'T':
      return 2;
    case 'H':
    case 'V':
      return 1;
    case 'C':
      return 6;
    case 'S':
    case 'Q':
      return 4;
    case 'A':
      return 7;
    default:
      return 0;
  }
}

}  // namespace

std::optional<double> parse_number(std::string_view s) {
  Scanner sc(s);
  auto v = sc.number();
  sc.skip_wsp();
  if (!v || !sc.at_end()) return std::nullopt;
  return v;
}

std::optional<double> scan_number(std::string_view s, size_t* pos) {
  Scanner sc(s, *pos);
  auto v = sc.number();
  if (v) *pos = sc.pos();
  return v;
}

namespace {

// One segment of command `up` (upper case; `rel`: its coordinates are relative) with arguments
// `a`; `prev` is the previous segment's command and `last_ctrl` its last control point (for the
// reflections of S and T), updated for curves.
void draw_segment(PathBuilder& pb, char up, bool rel, const double (&a)[7], char prev, Vec2& last_ctrl) {
  Vec2 cur = pb.current();
  Vec2 o = rel ? cur : Vec2{};
  switch (up) {
    case 'M':
      pb.move_to(o + Vec2{a[0], a[1]});
      break;
    case 'L':
      pb.line_to(o + Vec2{a[0], a[1]});
      break;
    case 'H':
      pb.line_to({(rel ? cur.x : 0) + a[0], cur.y});
      break;
    case 'V':
      pb.line_to({cur.x, (rel ? cur.y : 0) + a[0]});
      break;
    case 'C':
    case 'S': {
      Vec2 c1, c2, p;
      if (up == 'C') {
        c1 = o + Vec2{a[0], a[1]}, c2 = o + Vec2{a[2], a[3]}, p = o + Vec2{a[4], a[5]};
      } else {
        c1 = (prev == 'C' || prev == 'S') ? 2.0 * cur - last_ctrl : cur;
        c2 = o + Vec2{a[0], a[1]}, p = o + Vec2{a[2], a[3]};
      }
      pb.cubic_to(c1, c2, p);
      last_ctrl = c2;
      break;
    }
    case 'Q':
    case 'T': {
      Vec2 ctrl, p;
      if (up == 'Q') {
        ctrl = o + Vec2{a[0], a[1]}, p = o + Vec2{a[2], a[3]};
      } else {
        ctrl = (prev == 'Q' || prev == 'T') ? 2.0 * cur - last_ctrl : cur;
        p = o + Vec2{a[0], a[1]};
      }
      pb.quadratic_to(ctrl, p);
      last_ctrl = ctrl;
      break;
    }
    case 'A':
      pb.arc_to(a[0], a[1], a[2], a[3] != 0, a[4] != 0, o + Vec2{a[5], a[6]});
      break;
    default:
      break;
  }
}

}  // namespace

Result<std::vector<Subpath>> parse_path_data(std::string_view d, double tolerance, size_t* error_offset,
                                             size_t max_points) {
  Scanner sc(d);
  PathBuilder pb(tolerance > 0 ? tolerance : 1e-9);
  auto fail = [&](size_t at, std::string msg) -> Error {
    if (error_offset) *error_offset = at;
    return Error{"", std::move(msg)};
  };
  char cmd = 0;    // the command in force (for implicit repeats)
  char prev = 0;   // the previous segment's command, upper case, for S/T reflection
  Vec2 last_ctrl;  // its last control point
  sc.skip_wsp();
  if (sc.at_end()) return std::vector<Subpath>{};
  while (true) {
    sc.skip_wsp();
    if (sc.at_end()) break;
    char c = sc.peek();
    size_t cmd_pos = sc.pos();
    if (std::isalpha(static_cast<unsigned char>(c))) {
      char up = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      if (std::string_view("MLHVCSQTAZ").find(up) == std::string_view::npos)
        return fail(cmd_pos, "unknown path command " + quoted(c));
      if (cmd == 0 && up != 'M')
        return fail(cmd_pos, "path data must start with a moveto (M or m), not " + quoted(c));
      sc.advance();
      cmd = c;
      if (up == 'Z') {
        pb.close();
        prev = 'Z';
        continue;
      }
    } else if (sc.number_starts() && cmd != 0) {
      char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
      if (up == 'Z') return fail(cmd_pos, "unexpected number after closepath " + quoted(cmd));
      if (cmd == 'M') cmd = 'L';  // numbers after a moveto are implicit linetos
      if (cmd == 'm') cmd = 'l';
    } else if (cmd == 0) {
      return fail(cmd_pos, "path data must start with a moveto (M or m), not " + quoted(c));
    } else {
      return fail(cmd_pos, "unexpected character " + quoted(c) + " (expected a command or a number)");
    }

    char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    bool rel = cmd != up;
    double a[7] = {};
    int n = arg_count(up);
    for (int i = 0; i < n; ++i) {
      if (i > 0) sc.skip_comma_wsp();
      if (up == 'A' && (i == 3 || i == 4)) {
        auto f = sc.flag();
        if (!f) return fail(sc.pos(), std::string("expected a flag (0 or 1) for ") + quoted(cmd));
        a[i] = *f ? 1 : 0;
        continue;
      }
      auto v = sc.number();
      if (!v) {
        size_t at = sc.pos();
        bool huge = sc.out_of_range();
        return fail(at, huge ? "number out of range"
                             : std::string("expected a number for ") + quoted(cmd) + " (" +
                                   std::to_string(n) + " per segment)");
      }
      a[i] = *v;
    }
    draw_segment(pb, up, rel, a, prev, last_ctrl);
    prev = up;
    if (pb.points() > max_points)
      return fail(cmd_pos, "the path flattens to more than " + std::to_string(max_points) +
                               " points: raise the curve tolerance (--svg-tolerance)");
    // A comma may separate repeated argument groups, but must be followed by more numbers.
    sc.skip_wsp();
    if (sc.peek() == ',') {
      sc.advance();
      sc.skip_wsp();
      if (!sc.number_starts()) return fail(sc.pos(), "expected a number after ','");
    }
  }
  return pb.finish();
}

Result<std::vector<Vec2>> parse_points(std::string_view s, bool* odd, size_t* error_offset) {
  Scanner sc(s);
  std::vector<double> nums;
  sc.skip_wsp();
  while (!sc.at_end()) {
    auto v = sc.number();
    if (!v) {
      if (error_offset) *error_offset = sc.pos();
      return Error{"", sc.out_of_range() ? "number out of range in the points list"
                                         : "expected a number in the points list"};
    }
    nums.push_back(*v);
    sc.skip_comma_wsp();
  }
  if (odd) *odd = nums.size() % 2 != 0;
  std::vector<Vec2> pts;
  for (size_t i = 0; i + 1 < nums.size(); i += 2) pts.push_back({nums[i], nums[i + 1]});
  return pts;
}

int arc_segments(double r, double sweep, double tolerance) {
  if (!(r > 0) || !(tolerance > 0)) return 1;
  double step = tolerance >= 2 * r ? kPi : 2 * std::acos(1 - tolerance / r);
  double n = std::ceil(std::abs(sweep) / step);
  if (!(n >= 1)) return 1;
  return static_cast<int>(std::min<double>(n, kMaxCurveSegments));
}

std::optional<ArcCenter> arc_endpoint_to_center(Vec2 p0, double rx, double ry, double phi_deg, bool large_arc,
                                                bool sweep, Vec2 p1) {
  if (p0.x == p1.x && p0.y == p1.y) return std::nullopt;
  rx = std::abs(rx), ry = std::abs(ry);
  if (rx == 0 || ry == 0) return std::nullopt;
  double phi = std::fmod(phi_deg, 360.0) * kPi / 180;
  double cp = std::cos(phi), sp = std::sin(phi);
  double dx2 = (p0.x - p1.x) / 2, dy2 = (p0.y - p1.y) / 2;
  double x1 = cp * dx2 + sp * dy2;
  double y1 = -sp * dx2 + cp * dy2;
  double lambda = (x1 * x1) / (rx * rx) + (y1 * y1) / (ry * ry);
  if (lambda > 1) {
    double s = std::sqrt(lambda);
    rx *= s, ry *= s;
  }
  double num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
  double den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
  double coef = std::sqrt(std::max(0.0, num / den)) * (large_arc == sweep ? -1 : 1);
  double cx1 = coef * rx * y1 / ry;
  double cy1 = -coef * ry * x1 / rx;
  ArcCenter a;
  a.rx = rx, a.ry = ry, a.phi = phi;
  a.center = {cp * cx1 - sp * cy1 + (p0.x + p1.x) / 2, sp * cx1 + cp * cy1 + (p0.y + p1.y) / 2};
  auto angle = [](Vec2 u, Vec2 v) { return std::atan2(u.x * v.y - u.y * v.x, u.x * v.x + u.y * v.y); };
  Vec2 u{(x1 - cx1) / rx, (y1 - cy1) / ry};
  Vec2 v{(-x1 - cx1) / rx, (-y1 - cy1) / ry};
  a.theta1 = angle({1, 0}, u);
  double dt = angle(u, v);
  if (!sweep && dt > 0) dt -= 2 * kPi;
  if (sweep && dt < 0) dt += 2 * kPi;
  a.dtheta = dt;
  return a;
}

void flatten_arc(Vec2 p0, double rx, double ry, double phi_deg, bool large_arc, bool sweep, Vec2 p1,
                 double tolerance, std::vector<Vec2>& out) {
  auto arc = arc_endpoint_to_center(p0, rx, ry, phi_deg, large_arc, sweep, p1);
  if (!arc) {
    if (p0.x != p1.x || p0.y != p1.y) out.push_back(p1);  // zero radius: a straight line
    return;
  }
  int n = arc_segments(std::max(arc->rx, arc->ry), arc->dtheta, tolerance);
  double cp = std::cos(arc->phi), sp = std::sin(arc->phi);
  for (int i = 1; i < n; ++i) {
    double t = arc->theta1 + arc->dtheta * i / n;
    double ex = arc->rx * std::cos(t), ey = arc->ry * std::sin(t);
    out.push_back({arc->center.x + cp * ex - sp * ey, arc->center.y + sp * ex + cp * ey});
  }
  out.push_back(p1);  // exactly, so that following segments join without drift
}

void flatten_cubic(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, double tolerance, std::vector<Vec2>& out) {
  // |B''| <= 6 max(|p0 - 2p1 + p2|, |p1 - 2p2 + p3|) and a chord over a parameter step h strays at
  // most h^2/8 max|B''| from the curve, hence n >= sqrt(0.75 M / tol).
  double m = std::max(norm(p0 - 2.0 * p1 + p2), norm(p1 - 2.0 * p2 + p3));
  double nd = std::ceil(std::sqrt(0.75 * m / std::max(tolerance, 1e-12)));
  int n = static_cast<int>(std::clamp(nd, 1.0, static_cast<double>(kMaxCurveSegments)));
  for (int i = 1; i < n; ++i) {
    double t = static_cast<double>(i) / n, s = 1 - t;
    out.push_back(s * s * s * p0 + 3 * s * s * t * p1 + 3 * s * t * t * p2 + t * t * t * p3);
  }
  out.push_back(p3);
}

void flatten_quadratic(Vec2 p0, Vec2 p1, Vec2 p2, double tolerance, std::vector<Vec2>& out) {
  // B'' = 2 (p0 - 2p1 + p2): n >= sqrt(M / (4 tol)).
  double m = norm(p0 - 2.0 * p1 + p2);
  double nd = std::ceil(std::sqrt(m / (4 * std::max(tolerance, 1e-12))));
  int n = static_cast<int>(std::clamp(nd, 1.0, static_cast<double>(kMaxCurveSegments)));
  for (int i = 1; i < n; ++i) {
    double t = static_cast<double>(i) / n, s = 1 - t;
    out.push_back(s * s * p0 + 2 * s * t * p1 + t * t * p2);
  }
  out.push_back(p2);
}

std::vector<Vec2> ellipse_ring(Vec2 center, double rx, double ry, double tolerance) {
  int n = std::max(8, arc_segments(std::max(rx, ry), 2 * kPi, tolerance));
  std::vector<Vec2> pts;
  pts.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    double t = 2 * kPi * i / n;
    pts.push_back({center.x + rx * std::cos(t), center.y + ry * std::sin(t)});
  }
  return pts;
}

}  // namespace tranche::geo::svg
