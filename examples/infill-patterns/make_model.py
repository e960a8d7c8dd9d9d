#!/usr/bin/env python3
"""A bracket: a 50 x 30 x 6 mm base plate, a 16 mm square column from it to 26 mm, and a 6 mm
square pin to 14 mm beside the column."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

tris = meshgen.box(0, 0, 0, 50, 30, 6)  # the base
tris += meshgen.box(8, 7, 5, 24, 23, 26)  # the column (overlapping the base: one part)
tris += meshgen.box(36, 12, 5, 42, 18, 14)  # the pin
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "infill-patterns")
