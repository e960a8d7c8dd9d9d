#!/usr/bin/env python3
"""A coaster: a disc 30 mm across and 4 mm high (a 96-sided prism)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl",
                  meshgen.cylinder(15, 15, 15, 0, 4, segments=96), "coaster")
