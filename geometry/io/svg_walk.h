// The element walk of SVG input: from a document's elements (groups, <use>, <switch>, nested
// <svg>, shapes) with their inherited styles and transforms to filled shapes on the bed plane,
// with the limits on nesting, elements and points and a warning for everything ignored.
// svg_import.cpp assembles the shapes into a flat drawing or a layer stack.
#pragma once

#include <pugixml.hpp>

#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/io/svg_import.h"
#include "geometry/io/svg_paint.h"
#include "geometry/io/svg_path.h"
#include "geometry/io/svg_source.h"
#include "geometry/io/svg_stack.h"

namespace tranche::geo::svg {

// Inherited presentation properties, as computed for one element.
struct Style {
  Paint fill;            // initial: black
  bool evenodd = false;  // fill-rule
  bool visible = true;   // visibility
  bool stroked = false;  // stroke is not none (for the stroke-only warning)
  Rgb color = 0;         // for currentColor
};

// The element's name without an "svg:" prefix.
std::string local_name(pugi::xml_node n);

// Whether the element is in another namespace (editor metadata: inkscape:, sodipodi:...).
bool is_foreign(pugi::xml_node n);

// Walks elements and collects their filled shapes; errors and warnings name the element.
class Walker {
 public:
  Walker(const SourceMap& src, const SvgImportOptions& opt, Report& report)
      : src_(src), opt_(opt), report_(report) {}

  // Records the elements with an id, for <use>; the first element with an id wins, as in browsers.
  void index_ids(pugi::xml_node root);
  // The size of the nearest viewport in user units, for percentages (0: unknown).
  void set_viewport(Vec2 size) { viewport_ = size; }
  // Reading the layer groups of a layer stack: only class="island" shapes are material.
  void set_stack(bool stack) { stack_ = stack; }
  // Shape elements met so far (filled or not).
  size_t shape_elements() const { return shape_elements_; }

  Status walk_children(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<Shape>& out,
                       int depth);
  Style style_of(pugi::xml_node n, const Style& parent, bool* display_none);
  Result<Affine> transform_of(pugi::xml_node n);

 private:
  Status walk(pugi::xml_node n, const Affine& ctm, const Style& parent, std::vector<Shape>& out, int depth);
  Status use(pugi::xml_node n, const Affine& ctm, const Style& st, std::vector<Shape>& out, int depth);
  Status shape(pugi::xml_node n, const std::string& name, const Affine& ctm, const Style& st,
               std::vector<Shape>& out);
  Result<double> length(pugi::xml_node n, const char* attr, double fallback);
  Result<std::vector<Subpath>> geometry(pugi::xml_node n, const std::string& name, double tol);
  Result<Rings> place(pugi::xml_node n, const std::vector<Subpath>& subpaths, const Affine& ctm);
  Error error_at(pugi::xml_node n, std::string msg) const { return Error{src_.at(n), std::move(msg)}; }
  void warn(pugi::xml_node n, const char* code, std::string msg) {
    report_.warn(code, src_.at(n), std::move(msg));
  }

  const SourceMap& src_;
  const SvgImportOptions& opt_;
  Report& report_;
  std::unordered_map<std::string, pugi::xml_node> ids_;
  std::unordered_set<const void*> active_uses_;  // referenced elements being expanded (cycles)
  size_t elements_ = 0, points_ = 0, shape_elements_ = 0;
  bool warned_css_ = false;
  bool stack_ = false;  // reading the layer groups of a layer stack
  Vec2 viewport_;       // the nearest viewport's size in user units, for percentages (0: unknown)
};

}  // namespace tranche::geo::svg
