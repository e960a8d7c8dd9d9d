// Helpers for the SVG input tests: parse a document from a string, measure the result.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "geometry/io/svg_import.h"

namespace tranche::test {

// A document with a 100 x 100 mm page where one user unit is one millimetre.
inline std::string page_mm(const std::string& body, const std::string& root_attrs = "") {
  return R"(<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" )"
         R"(width="100mm" height="100mm" viewBox="0 0 100 100" )" +
         root_attrs + ">\n" + body + "\n</svg>\n";
}

inline geo::SvgModel parse_ok(const std::string& text, Report& report, geo::SvgImportOptions opt = {}) {
  auto r = geo::parse_svg(text, "test.svg", opt, report);
  if (!r) FAIL("unexpected error: " << r.error().to_string());
  return std::move(r).value();
}

inline geo::SvgModel parse_ok(const std::string& text, geo::SvgImportOptions opt = {}) {
  Report report;
  return parse_ok(text, report, opt);
}

// Total material area of a flat drawing, mm².
inline double area_of(const std::string& text, geo::SvgImportOptions opt = {}) {
  geo::SvgModel m = parse_ok(text, opt);
  REQUIRE(m.layers.size() == 1);
  return geo::area_mm2(m.layers[0].polygons);
}

// The error a document gives ("where: message"); fails the test if it parses.
inline Error parse_error(const std::string& text, geo::SvgImportOptions opt = {}) {
  Report report;
  auto r = geo::parse_svg(text, "test.svg", opt, report);
  if (r) FAIL("expected an error, got " << r->layers.size() << " layer(s)");
  return r.error();
}

}  // namespace tranche::test
