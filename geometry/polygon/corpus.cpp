#include "geometry/polygon/corpus.h"

#include <fmt/format.h>

#include <charconv>
#include <fstream>
#include <sstream>

namespace tranche::geo {
namespace {

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

template <class T>
bool number(std::string_view w, T& out) {
  const auto r = std::from_chars(w.data(), w.data() + w.size(), out);
  return r.ec == std::errc() && r.ptr == w.data() + w.size();
}

}  // namespace

Result<PolygonCase> parse_polygon_case(std::string_view text, const std::string& name) {
  PolygonCase c;
  c.name = name;
  bool angles_set = false;
  int line_no = 0;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    ++line_no;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const auto w = words(line);
    if (w.empty()) continue;
    auto bad = [&](const std::string& what) { return Error{fmt::format("{}:{}", name, line_no), what}; };
    if (w[0] == "loop" && w.size() == 1) {
      c.loops.emplace_back();
    } else if (w[0] == "mode" && w.size() == 2) {
      if (w[1] == "additive")
        c.mode = OverlapMode::Additive;
      else if (w[1] == "boolean")
        c.mode = OverlapMode::Boolean;
      else
        return bad("mode must be additive or boolean");
    } else if (w[0] == "angles" && w.size() >= 2) {
      if (!angles_set) c.angles.clear();
      angles_set = true;
      for (size_t i = 1; i < w.size(); ++i) {
        double a = 0;
        if (!number(w[i], a)) return bad(fmt::format("'{}' is not an angle in degrees", w[i]));
        c.angles.push_back(a);
      }
    } else if (w[0] == "expect" && w.size() == 4 && w[1] == "cells") {
      double a = 0;
      int n = 0;
      if (!number(w[2], a) || !number(w[3], n) || n < 0)
        return bad("expect cells needs an angle and a count");
      c.expect_cells.emplace_back(a, n);
    } else if (w[0] == "expect" && w.size() == 3 && (w[1] == "islands" || w[1] == "holes")) {
      int n = 0;
      if (!number(w[2], n) || n < 0) return bad("expect needs a count");
      (w[1] == "islands" ? c.expect_islands : c.expect_holes) = n;
    } else if (w.size() == 2) {
      coord_t x = 0, y = 0;
      if (!number(w[0], x) || !number(w[1], y)) return bad("expected two integers (a point in nm)");
      if (c.loops.empty()) return bad("a point before the first 'loop' line");
      c.loops.back().emplace_back(x, y);
    } else {
      return bad("unknown line: expected loop, mode, angles, expect or a point");
    }
  }
  return c;
}

Result<PolygonCase> load_polygon_case(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, "cannot open the file"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_polygon_case(ss.str(), path);
}

std::string format_polygon_case(const PolygonCase& c) {
  std::string out = fmt::format("mode {}\nangles", c.mode == OverlapMode::Boolean ? "boolean" : "additive");
  for (double a : c.angles) out += fmt::format(" {}", a);
  out += "\n";
  if (c.expect_islands >= 0) out += fmt::format("expect islands {}\n", c.expect_islands);
  if (c.expect_holes >= 0) out += fmt::format("expect holes {}\n", c.expect_holes);
  for (const auto& [a, n] : c.expect_cells) out += fmt::format("expect cells {} {}\n", a, n);
  for (const Ring& r : c.loops) {
    out += "loop\n";
    for (const Point& p : r) out += fmt::format("{} {}\n", p.X, p.Y);
  }
  return out;
}

}  // namespace tranche::geo
