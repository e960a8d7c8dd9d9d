#!/usr/bin/env python3
"""A 50 x 14 x 1 mm plate carrying five 10 mm pins of 1.5, 2, 3, 5 and 8 mm diameter: the small
ones print in a few seconds a layer and slump unless they are slowed and cooled."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

tris = meshgen.box(0, 0, 0, 50, 14, 1)
x = 4.0
for d in (1.5, 2, 3, 5, 8):
    tris += meshgen.cylinder(x, 7, d / 2, 0.5, 11, segments=32)
    x += d / 2 + 5 + ({1.5: 2, 2: 3, 3: 5, 5: 8}.get(d, 0)) / 2
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "small-pins")
