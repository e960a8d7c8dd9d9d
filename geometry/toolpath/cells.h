// Cuts a fill region into cells monotone for the fill angle (geometry/polygon's decompose) and
// labels each cell edge: Real where it lies on the island's fill border (along the innermost
// perimeter), Artificial where it is a cut or the border between a solid and a sparse region.
#pragma once

#include <vector>

#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/zigzag.h"
#include "runtime/base/report.h"

namespace tranche::toolpath {

struct CellShape {
  FillShape shape;  // one ring for a monotone cell
  double area_mm2 = 0;
  bool monotone = true;  // false: decomposition failed here and the zig-zag may need several runs
};

// `region`: rings of one fill region (non-zero fill); `fill_border`: edges of the whole fill
// region of the island; angle in degrees. `where` names the layer/island for warnings.
std::vector<CellShape> make_cells(const geo::Rings& region, double angle_deg, const EdgeGrid& fill_border,
                                  Report& report, const std::string& where);

}  // namespace tranche::toolpath
