#!/usr/bin/env python3
"""A small table: a 40 x 20 x 3 mm top at 15 mm on four 4 mm legs, 32 mm apart along x (too far
to bridge), and a 1.8 mm ledge round the front left leg at 4 mm (an overhang, but short)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

tris = []
for x in (0, 36):
    for y in (0, 16):
        tris += meshgen.box(x, y, 0, x + 4, y + 4, 15)  # the legs
tris += meshgen.box(0, 0, 15, 40, 20, 18)  # the top
tris += meshgen.box(0, 0, 4, 5.8, 5.8, 6)  # the ledge round the front left leg
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "supports")
