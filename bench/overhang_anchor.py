#!/usr/bin/python3
"""Anchoring of the extrusion laid over air, for bench_overhangs.sh (issue 14).

overhang_anchor.py MODEL.stl FILE.gcode X,Y [--paths]   prints one line: air_mm walls_air_mm span_max
                             span_p95 (X,Y: gcheck's --offset, model frame minus G-code frame);
                             --paths first lists each path over air

gcheck's unsupported area says where plastic is laid over air, not how: a shelf bridged by lines
anchored on the layer below and a shelf whose wall loops run round in the air count alike. This
measure follows each extruding path instead. Along it, every 0.1 mm, a point of the bead's centre
line rests on the layer below when the model's slice at the middle of the layer below (the
material there, as the mesh has it: every slicer's output is judged against the same thing) lies
within half a bead of it; the first layer rests on the bed. Rasters of 0.05 mm cells.
- air_mm: the length of extrusion whose centre does not rest on the layer below;
- walls_air_mm: the part of it in wall moves (;TYPE: outer/inner wall or perimeter, PrusaSlicer's
  "Overhang perimeter", Cura's WALL-OUTER/WALL-INNER);
- the unanchored span of a strand over air: the length along its path from the last point that
  rests on the layer below to the next one (or to the path's end: a free end counts whole). Loops
  running along an overhanging edge have long spans (they droop); bridge lines across a gap have
  spans about the gap's width, lines out over a ledge about its depth. span_max is the longest;
  span_p95 the span within which 95% of air_mm lies (length-weighted), so one odd strand does not
  make the number.
A path ends at a travel (a move that feeds no plastic). The bead's width comes from its E (the
rounded rectangle PrusaSlicer's flow assumes, layer height from the z steps; filament 1.75 mm).
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from adaptive_cusp import read_stl  # noqa: E402
from gcode_moves import moves  # noqa: E402

CELL = 0.05  # mm, raster cell
STEP = 0.1  # mm, sample spacing along a path
FIL_AREA = math.pi * 0.875 ** 2
WALLS = ('External perimeter', 'Perimeter', 'Overhang perimeter', 'WALL-OUTER', 'WALL-INNER',
         'Outer wall', 'Inner wall', 'Overhang wall')


def layer_paths(gcode):
    """{z: [path]} where a path is (kind, [(x0, y0, x1, y1, de)]) of consecutive extruding moves."""
    layers = {}
    cur, cur_z = None, None
    for kind, x0, y0, x1, y1, de, z in moves(gcode, with_z=True):
        moved = x0 != x1 or y0 != y1
        if de > 0 and moved:
            if cur is None or cur_z != z or cur[0] != kind:
                cur = (kind, [])
                cur_z = z
                layers.setdefault(round(z, 4), []).append(cur)
            cur[1].append((x0, y0, x1, y1, de))
        elif moved:
            cur = None
    return layers


def slice_segments(tris, z):
    """The segments where the plane at z cuts the triangles (n, 2, 2)."""
    zs = tris[:, :, 2]
    hit = (zs.min(1) < z) & (zs.max(1) > z)
    t = tris[hit]
    out = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        pa, pb = t[:, a], t[:, b]
        cross = (pa[:, 2] - z) * (pb[:, 2] - z) < 0
        f = np.where(cross, (z - pa[:, 2]) / np.where(cross, pb[:, 2] - pa[:, 2], 1), 0)
        pts = pa[:, :2] + (pb[:, :2] - pa[:, :2]) * f[:, None]
        out.append((cross, pts))
    segs = []
    for i in range(len(t)):
        p = [pts[i] for cross, pts in out if cross[i]]
        if len(p) == 2:
            segs.append(p)
    return np.array(segs).reshape(-1, 2, 2)


def raster(segs, x0, y0, nx, ny):
    """Even-odd fill of the closed outline made of `segs` on the grid (cell centres)."""
    grid = np.zeros((ny, nx + 1), dtype=np.int32)
    if len(segs):
        ya, yb = segs[:, 0, 1], segs[:, 1, 1]
        lo, hi = np.minimum(ya, yb), np.maximum(ya, yb)
        r0 = np.ceil((lo - y0) / CELL - 0.5).astype(int)  # first row centre >= lo
        r1 = np.ceil((hi - y0) / CELL - 0.5).astype(int)  # rows centre < hi
        r0, r1 = np.clip(r0, 0, ny), np.clip(r1, 0, ny)
        count = np.maximum(r1 - r0, 0)
        idx = np.repeat(np.arange(len(segs)), count)
        rows = np.concatenate([np.arange(a, b) for a, b in zip(r0, r1) if b > a]) if count.sum() else np.zeros(0, int)
        if len(rows):
            yc = y0 + (rows + 0.5) * CELL
            s = segs[idx]
            f = (yc - s[:, 0, 1]) / (s[:, 1, 1] - s[:, 0, 1])
            xc = s[:, 0, 0] + (s[:, 1, 0] - s[:, 0, 0]) * f
            cols = np.clip(np.ceil((xc - x0) / CELL - 0.5).astype(int), 0, nx)
            np.add.at(grid, (rows, cols), 1)
    return (np.cumsum(grid, axis=1)[:, :nx] % 2).astype(bool)


def dilate(mask, r_cells):
    out = mask.copy()
    r = int(math.ceil(r_cells))
    ny, nx = mask.shape
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            if dx * dx + dy * dy > r_cells * r_cells or (dx == 0 and dy == 0):
                continue
            ys, yd = (slice(0, ny - dy), slice(dy, ny)) if dy >= 0 else (slice(-dy, ny), slice(0, ny + dy))
            xs, xd = (slice(0, nx - dx), slice(dx, nx)) if dx >= 0 else (slice(-dx, nx), slice(0, nx + dx))
            out[yd, xd] |= mask[ys, xs]
    return out


def measure(stl, gcode, offset, detail=None):
    ox, oy = (float(v) for v in offset.split(','))
    tris = read_stl(stl)
    tris[:, :, 2] -= tris[:, :, 2].min()
    tris[:, :, 0] -= ox  # into the G-code's frame
    tris[:, :, 1] -= oy
    layers = layer_paths(gcode)
    zs = sorted(layers)
    air = walls_air = 0.0
    spans = []  # (span, its length over air)
    for li, z in enumerate(zs):
        if li == 0:
            continue  # the bed
        h = z - zs[li - 1]
        h_below = zs[li - 1] - (zs[li - 2] if li >= 2 else 0.0)
        paths = layers[z]
        # Samples of every path: points, piece lengths, bead widths.
        pts, lens, widths, owner = [], [], [], []
        for pi, (kind, segs) in enumerate(paths):
            for x0, y0, x1, y1, de in segs:
                L = math.hypot(x1 - x0, y1 - y0)
                n = max(1, int(math.ceil(L / STEP)))
                t = (np.arange(n) + 0.5) / n
                pts.append(np.column_stack([x0 + (x1 - x0) * t, y0 + (y1 - y0) * t]))
                lens.append(np.full(n, L / n))
                w = de * FIL_AREA / (L * h) + h * (1 - math.pi / 4) if h > 0 else 0.45
                widths.append(np.full(n, min(max(w, 0.1), 2.0)))
                owner.append(np.full(n, pi))
        if not pts:
            continue
        P, Ln, W, O = np.concatenate(pts), np.concatenate(lens), np.concatenate(widths), np.concatenate(owner)
        r = float(np.median(W)) / 2
        x0, y0 = P[:, 0].min() - r - 2 * CELL, P[:, 1].min() - r - 2 * CELL
        nx = int((P[:, 0].max() + r + 2 * CELL - x0) / CELL) + 1
        ny = int((P[:, 1].max() + r + 2 * CELL - y0) / CELL) + 1
        below = raster(slice_segments(tris, zs[li - 1] - 0.5 * h_below + 1e-5), x0, y0, nx, ny)
        near = dilate(below, r / CELL)
        ci = np.clip(((P[:, 0] - x0) / CELL).astype(int), 0, nx - 1)
        cj = np.clip(((P[:, 1] - y0) / CELL).astype(int), 0, ny - 1)
        held = near[cj, ci]
        # Runs over air along each path.
        start = 0
        for pi, (kind, _) in enumerate(paths):
            end = start
            while end < len(O) and O[end] == pi:
                end += 1
            h_run = held[start:end]
            l_run = Ln[start:end]
            over = float(l_run[~h_run].sum())
            air += over
            if kind in WALLS:
                walls_air += over
            run = 0.0
            for ok, l in zip(h_run, l_run):
                if ok:
                    if run > 0:
                        spans.append(run)
                    run = 0.0
                else:
                    run += l
            if run > 0:
                spans.append(run)
            if detail is not None and over > 0:
                detail.append((z, kind, float(l_run.sum()), over, max(spans[-1:] or [0.0])))
            start = end
    if not spans:
        return air, walls_air, 0.0, 0.0
    s = np.sort(np.array(spans))
    cum = np.cumsum(s)  # a run's own length over air is its span
    p95 = float(s[np.searchsorted(cum, 0.95 * cum[-1])])
    return air, walls_air, float(s[-1]), p95


if __name__ == '__main__':
    paths = '--paths' in sys.argv  # also list the paths over air (z, type, length, over air, a span)
    args = [a for a in sys.argv[1:] if a != '--paths']
    if len(args) != 3:
        sys.exit(__doc__)
    detail = [] if paths else None
    a, w, smax, p95 = measure(*args, detail=detail)
    for z, kind, length, over, span in detail or []:
        print(f'# z {z:.2f} {kind}: {length:.1f} mm, {over:.1f} over air, span {span:.1f}')
    print(f'{a:.1f}\t{w:.1f}\t{smax:.1f}\t{p95:.1f}')
