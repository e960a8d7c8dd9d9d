#!/usr/bin/env python3
"""Three bars, 40 x 5 mm and 4 mm high, lying at 0°, 60° and 120° on the bed."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

tris = []
for i, angle in enumerate((0, 60, 120)):
    cx, cy = 32.0 * i, 0.0
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    corners = [(-20, -2.5), (20, -2.5), (20, 2.5), (-20, 2.5)]
    outline = [(cx + x * c - y * s, cy + x * s + y * c) for x, y in corners]
    tris += meshgen.prism(outline, 0, 4)
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "bars")
