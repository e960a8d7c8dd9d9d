#!/usr/bin/env python3
"""A 20 mm calibration cube with a 10 x 10 mm square hole through it, written as an ASCII STL
(open it in a text editor: every triangle is three `vertex` lines)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

outer = [(0, 0), (20, 0), (20, 20), (0, 20)]
hole = [(5, 5), (15, 5), (15, 15), (5, 15)]
meshgen.write_ascii_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl",
                        meshgen.tube(outer, hole, 0, 20), "cube-with-hole")
