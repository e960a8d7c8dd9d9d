#!/usr/bin/env python3
"""A stand: a 40 x 40 x 3 mm base with a 10 x 10 mm tower on it, 20 mm high in all."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

tris = meshgen.box(0, 0, 0, 40, 40, 3) + meshgen.box(15, 15, 3, 25, 25, 20)
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "stand")
