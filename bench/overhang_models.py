#!/usr/bin/python3
"""Overhang models for bench_overhangs.sh, written as ASCII STL.

overhang_models.py OUTDIR      writes NAME.stl for every model and prints "NAME PATH" lines

  flare_45   a 32-sided cup flaring 45 deg from vertical: radius 6 mm at the bed to 16 mm at 10 mm
  flare_70   the same flaring 70 deg: radius 6 mm to 17 mm over 4 mm
  shelf      a 10 x 10 mm column 8 mm high under a 30 x 10 x 2 mm plate: 10 mm of flat shelf
             hanging out on two sides
  ledges     a 10 x 10 mm column 8 mm high under a 2 mm plate 10 mm deep that hangs 3 mm out on one
             side and 15 mm out on the other: a narrow ledge (a few wall beads wide) and a wide one
"""
import math
import os
import sys

from walls_models import write_stl  # ASCII STL of facets, shared with the walls bench

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'examples'))
from meshgen import box  # noqa: E402  (the examples' axis-aligned box)


def frustum(r0, r1, h, n=32):
    """Closed frustum, axis z, radius r0 at z = 0 and r1 at z = h (triangles CCW from outside)."""
    ring = lambda r, z: [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n), z) for i in range(n)]
    lo, hi = ring(r0, 0.0), ring(r1, h)
    tris = []
    for i in range(n):
        j = (i + 1) % n
        tris.append((lo[i], lo[j], hi[j]))
        tris.append((lo[i], hi[j], hi[i]))
        tris.append(((0.0, 0.0, 0.0), lo[j], lo[i]))
        tris.append(((0.0, 0.0, h), hi[i], hi[j]))
    return tris


MODELS = {
    'flare_45': lambda: frustum(6.0, 16.0, 10.0),
    'flare_70': lambda: frustum(6.0, 6.0 + 4.0 * math.tan(math.radians(70)), 4.0),
    # Two shells touching at z = 8 (the slicers union them).
    'shelf': lambda: box(10, 0, 0, 20, 10, 8) + box(0, 0, 8, 30, 10, 10),
    'ledges': lambda: box(15, 0, 0, 25, 10, 8) + box(12, 0, 8, 40, 10, 10),
}

if __name__ == '__main__':
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, make in MODELS.items():
        path = os.path.join(out, name + '.stl')
        write_stl(path, make())
        print(name, path)
