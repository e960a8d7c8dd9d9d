#!/usr/bin/env python3
"""A temperature tower: five 20 x 10 x 4 mm blocks, one per temperature, each on a 1 mm neck
(16 x 8 mm) so the steps are easy to see and to break apart. 25 mm high."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

tris = []
for i in range(5):
    z = 5.0 * i
    tris += meshgen.box(2, 1, z, 18, 9, z + 1)       # the neck
    tris += meshgen.box(0, 0, z + 1, 20, 10, z + 5)  # the block
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "temperature-tower")
