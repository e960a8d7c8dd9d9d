#!/usr/bin/env python3
"""A name plate: a 54 x 15.2 x 2 mm plate with the word "SLICE" raised 1 mm on it, in a blocky
5 x 7 pixel font (each pixel a 1.6 mm square: a stroke holds a wall on each side and a bead of
infill). Each letter is one prism over the outline of its pixels."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import meshgen  # noqa: E402

FONT = {  # rows from the top; no holes, and pixels touch along edges only
    "S": ["#####", "#....", "#....", "#####", "....#", "....#", "#####"],
    "L": ["#....", "#....", "#....", "#....", "#....", "#....", "#####"],
    "I": ["#####", "..#..", "..#..", "..#..", "..#..", "..#..", "#####"],
    "C": ["#####", "#....", "#....", "#....", "#....", "#....", "#####"],
    "E": ["#####", "#....", "#....", "####.", "#....", "#....", "#####"],
}
PIXEL = 1.6


def outline(rows):
    """The counter-clockwise outline (grid units, y up) of a 4-connected set of pixels."""
    cells = {(c, len(rows) - 1 - r) for r, row in enumerate(rows) for c, ch in enumerate(row) if ch == "#"}
    edges = {}
    for (i, j) in cells:
        for (a, b, n) in (((i, j), (i + 1, j), (i, j - 1)), ((i + 1, j), (i + 1, j + 1), (i + 1, j)),
                          ((i + 1, j + 1), (i, j + 1), (i, j + 1)), ((i, j + 1), (i, j), (i - 1, j))):
            if n not in cells:
                edges[a] = b
    start = min(edges)
    loop, p = [start], edges[start]
    while p != start:
        loop.append(p)
        p = edges[p]
    # Drop the points in the middle of straight runs.
    n = len(loop)
    return [loop[k] for k in range(n)
            if (loop[k][0] - loop[k - 1][0]) * (loop[(k + 1) % n][1] - loop[k][1])
            != (loop[k][1] - loop[k - 1][1]) * (loop[(k + 1) % n][0] - loop[k][0])]


tris = meshgen.box(0, 0, 0, 6 + 30 * PIXEL, 4 + 7 * PIXEL, 2)
for k, ch in enumerate("SLICE"):
    x0, y0 = 3 + k * 6 * PIXEL, 2
    pts = [(x0 + x * PIXEL, y0 + y * PIXEL) for x, y in outline(FONT[ch])]
    tris += meshgen.polygon_prism(pts, 2, 3)
meshgen.write_stl(sys.argv[1] if len(sys.argv) > 1 else "model.stl", tris, "name-plate")
