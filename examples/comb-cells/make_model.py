#!/usr/bin/env python3
"""A comb: a 64 x 6 mm spine with five 4 x 16 mm teeth 9 mm apart, 4 mm from its ends, 4 mm high. Filled with lines along x,
no single zig-zag can cover it: the fill region is cut into cells (the spine and each tooth)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

# The outline, counter-clockwise: along the bottom of the spine, then up and down each tooth
# from right to left.
outline = [(0, 0), (64, 0)]
for i in reversed(range(5)):
    x = 4 + 13.0 * i
    outline += [(x + 4, 6), (x + 4, 22), (x, 22), (x, 6)]
outline.insert(2, (64, 6))
outline.append((0, 6))
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl",
                  meshgen.polygon_prism(outline, 0, 4), "comb")
