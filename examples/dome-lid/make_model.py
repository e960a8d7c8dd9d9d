#!/usr/bin/env python3
"""A lid: an L-shaped base (30 x 30 mm less a 10 x 10 mm corner, 8 mm tall, its inner corner
at (20, 20)) with a dome of radius 9 mm standing on it, centred at (10, 10): 17 mm tall in all."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402


def dome(cx, cy, z0, r, segments=64, rings=24):
    """A closed half sphere on a flat disc at z0: rings of latitude up to a pole."""
    def p(i, j):  # ring j (0: the base circle) at meridian i
        a, b = 2 * math.pi * i / segments, 0.5 * math.pi * j / rings
        return (cx + r * math.cos(b) * math.cos(a), cy + r * math.cos(b) * math.sin(a), z0 + r * math.sin(b))
    top = (cx, cy, z0 + r)
    tris = []
    for i in range(segments):
        k = (i + 1) % segments
        tris.append(((cx, cy, z0), p(k, 0), p(i, 0)))  # the base disc, facing down
        for j in range(rings - 1):
            tris.append((p(i, j), p(k, j), p(k, j + 1)))
            tris.append((p(i, j), p(k, j + 1), p(i, j + 1)))
        tris.append((p(i, rings - 1), p(k, rings - 1), top))
    return tris


tris = meshgen.polygon_prism([(0, 0), (30, 0), (30, 20), (20, 20), (20, 30), (0, 30)], 0, 8)
tris += dome(10, 10, 8, 9)
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "dome-lid")
