// Normal support: columns under the overhangs, projected down layer by layer to the bed or to
// the part, with dense interface layers at their tops. The columns are grown top-down: a layer's
// column is the one above plus the contacts placed on it, minus the part; what is printed is the
// column minus the part grown by the xy gap (and minus what lies right on the part's top surface:
// the z gap at the bottom). Pure geometry on model units; the rules' decisions arrive as contacts
// (geometry/plan/support_pass).
#pragma once

#include <span>
#include <vector>

#include "geometry/core/layer.h"

namespace tranche::support {

// An overhang asking for support, placed on the layer where the support's top is printed (the
// overhang's layer minus the z gap).
struct Contact {
  // Model units. A slope's overhangs are slivers a reach apart on successive layers: grown by the
  // reach inside their island (plan/support_pass), they overlap into one band of column.
  geo::Rings region;
  int interface_layers = 2;  // dense layers at the top of the column under it
  bool bed_only = false;     // only where no part lies below (support_on_bed_only)
  bool touching = false;     // support_z_gap 0: it holds the layer right above it, touching it
};

// What a layer prints of support, as regions to fill (model units).
struct SupportLayer {
  geo::Rings base;       // sparse support
  geo::Rings interface;  // dense, under the part
  geo::Rings tree;       // tree branches (geometry/support/tree.h): a wall round each, sparse inside
  double area_mm2 = 0;   // base, interface and branches
};

struct ProjectInput {
  std::span<const geo::Layer> layers;          // the part, bottom to top
  std::vector<std::vector<Contact>> contacts;  // by the layer they are printed on
  std::vector<geo::Rings> keep_out;            // by layer: the part grown by its xy gap (empty: the part itself)
  geo::Rings bed;                              // the bed (model units); empty: not clipped
  int bottom_gap_layers = 1;                   // support does not lie on the part's top for this many layers
  double min_width_mm = 0.45;                  // narrower support is not printed (a bead)
  double merge_mm = 0.45;                      // gaps between columns narrower than this are closed
  bool columns = true;                         // false: only the interface layers under the contacts (tree support)
};

struct ProjectResult {
  std::vector<SupportLayer> layers;  // one per layer of the part
  double off_bed_mm2 = 0;            // area of the columns cut off at the bed's edge
  double blocked_mm2 = 0;            // bed-only overhangs dropped because the part lies below them
};

ProjectResult project(const ProjectInput& in);

// a − b, a ∩ b and a ∪ b, Clipper run only on the rings of `a` whose area may meet the area of a
// ring of `b` (boxes, then exact tests: edges touching, a first vertex inside the other ring); the
// other rings are set aside as they are (left out of the intersection). The same region as the
// plain boolean, for `a` a region as a boolean leaves it (rings that do not cross, winding 0 or 1
// under non-zero fill) and `b` any rings whose non-zero region is meant (the union: winding never
// below 0); the result is again such a region, its rings in another order and ring starts. The
// columns' loop does most of its layers on a few rings of a large column: only those the part or
// a contact reaches are cut.
geo::Rings difference_local(const geo::Rings& a, const geo::Rings& b);
geo::Rings intersection_local(const geo::Rings& a, const geo::Rings& b);
geo::Rings union_local(const geo::Rings& a, const geo::Rings& b);
// (a ∪ add) − cut in one boolean, on the rings of `a` that `add` or `cut` may meet.
geo::Rings union_difference_local(const geo::Rings& a, const geo::Rings& add, const geo::Rings& cut);

// The top gap: what support printed on a layer leaves air under, the part of the layer above
// (`above`) near `box`, but where a contact placed on that layer touches it (`touch`, support_z_gap 0).
geo::Rings part_above(const geo::Rings& above, const geo::Rings& touch, const geo::BBox2& box);

// The bed as a region in model units: a rectangle, or a circle's polygon, given in G-code mm and
// the model's shift into bed coordinates.
geo::Rings bed_region(bool circular, double min_x, double min_y, double max_x, double max_y, const geo::Point& shift);

}  // namespace tranche::support
