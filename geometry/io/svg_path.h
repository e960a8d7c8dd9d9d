// SVG path data (the `d` attribute) and the curves of SVG shapes, flattened to polylines in the
// shape's own user units. Transforms, units and filling are the caller's (svg_import.cpp).
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace tranche::geo::svg {

struct Vec2 {
  double x = 0, y = 0;
};

// One subpath, in user units. Filling closes open subpaths implicitly, as SVG does.
struct Subpath {
  std::vector<Vec2> points;
  bool closed = false;  // ended by Z/z
};

// Parses path data (M L H V C S Q T A Z, absolute and relative, implicit repeats) and flattens
// curves so that no point of a curve is farther than `tolerance` (user units, > 0) from its
// polyline. On malformed data returns an error whose message says what was expected and sets
// *error_offset to the index in `d` of the offending character. More than `max_points` points
// in all is an error too (a tiny tolerance on huge arcs would exhaust memory).
Result<std::vector<Subpath>> parse_path_data(std::string_view d, double tolerance,
                                             size_t* error_offset = nullptr, size_t max_points = 20'000'000);

// Parses a `points` attribute (polygon, polyline): pairs of numbers separated by commas and/or
// whitespace. An odd count drops the last number and sets *odd (SVG renders up to the error).
Result<std::vector<Vec2>> parse_points(std::string_view s, bool* odd, size_t* error_offset = nullptr);

// Parses one SVG number (no unit) that must make up the whole of `s` after trimming whitespace.
std::optional<double> parse_number(std::string_view s);
// Reads the SVG number that starts at s[*pos] (after whitespace) and moves *pos past it;
// nullopt (and *pos unchanged) when there is none or it is out of range.
std::optional<double> scan_number(std::string_view s, size_t* pos);

// The centre parametrisation of an SVG elliptical arc (SVG 1.1 F.6.5), with radii scaled up
// when too small to join the endpoints (F.6.6). Angles in radians; the point at angle t is
// centre + R(phi) * (rx cos t, ry sin t).
struct ArcCenter {
  Vec2 center;
  double rx = 0, ry = 0;  // user units, after correction
  double phi = 0;         // x-axis rotation, radians
  double theta1 = 0;      // start angle
  double dtheta = 0;      // sweep: positive when sweep-flag = 1; |dtheta| <= 2 pi
};
// nullopt when the arc degenerates: equal endpoints (nothing drawn) or a zero radius (a line).
std::optional<ArcCenter> arc_endpoint_to_center(Vec2 p0, double rx, double ry, double phi_deg, bool large_arc,
                                                bool sweep, Vec2 p1);

// Appends the flattened curve to `out`, excluding the start point and including the end point.
// Chord error <= tolerance (user units).
void flatten_cubic(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, double tolerance, std::vector<Vec2>& out);
void flatten_quadratic(Vec2 p0, Vec2 p1, Vec2 p2, double tolerance, std::vector<Vec2>& out);
void flatten_arc(Vec2 p0, double rx, double ry, double phi_deg, bool large_arc, bool sweep, Vec2 p1,
                 double tolerance, std::vector<Vec2>& out);

// A closed, counter-clockwise (in a y-up frame) polygon inscribed in the ellipse, chord error
// <= tolerance (user units). rx, ry > 0.
std::vector<Vec2> ellipse_ring(Vec2 center, double rx, double ry, double tolerance);

// Number of segments for an arc of radius r (user units) sweeping |sweep| radians with chord
// error <= tolerance; at least 1, at most kMaxCurveSegments.
int arc_segments(double r, double sweep, double tolerance);
inline constexpr int kMaxCurveSegments = 1 << 16;

}  // namespace tranche::geo::svg
