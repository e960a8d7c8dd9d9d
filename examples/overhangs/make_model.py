#!/usr/bin/env python3
"""Three leaning walls, 20 x 6 mm at the base and 12 mm high, leaning 20°, 40° and 55° from
vertical. At 0.2 mm layers each layer of the 20° wall hangs 0.07 mm (16% of a 0.45 mm bead)
over the one below, the 40° wall 0.17 mm (37%), the 55° wall 0.29 mm (63%)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

h = 12.0
tris = []
for i, angle in enumerate((20, 40, 55)):
    y = 28.0 * i
    tris += meshgen.sheared_box(0, y, 6, y + 20, 0, h, h * math.tan(math.radians(angle)))
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "overhangs")
