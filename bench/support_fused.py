#!/usr/bin/python3
"""Where a G-code's support touches its part (bench_support.sh): support that cannot come away.

usage: support_fused.py FILE.gcode [--xy-gap MM] [--z-gap MM] [--width MM] [--layer-height MM]

Beads are the extrusion moves grown by half the bead width (the nominal width: both slicers run
at 0.45 mm in the bench). On each layer k, with S the support's beads (;TYPE: containing
"support") and P the part's:
  xy: the support beads over P grown by xy_gap - width - 0.02 mm, in mm²: issue 12 lets a support
      bead's centre come to xy_gap less half a width from the part's outline (the outer wall's
      outer edge), so its edge to xy_gap less a whole width; what comes closer is fused sideways;
  z:  the support beads under the part's beads of the layers k+1 .. k+n, n = z_gap / layer height
      (rounded up), in mm²: a support top closer than z_gap under the part, fused from below.
Both are opened by 0.1 mm first: a sliver less than 0.2 mm wide (under half a bead) is two bead
edges brushing (a slope's next layer leaning out over the support's turns), not a bond.
Prints one line: "xy AREA z AREA layers N" (N: layers with either above 0.5 mm²). Needs shapely.
"""
import argparse
import math
import sys

from shapely.geometry import LineString, MultiLineString
from shapely.ops import unary_union

import gcode_moves


def layers_of(path):
    """{z: ([support segments], [part segments])} of the extrusion moves, by the nozzle's z."""
    out = {}
    for kind, x0, y0, x, y, de, z in gcode_moves.moves(path, with_z=True):
        if de <= 0 or (x, y) == (x0, y0):
            continue
        k = kind.lower()
        if 'skirt' in k or 'brim' in k or 'wipe' in k:
            continue
        s, p = out.setdefault(round(z, 3), ([], []))
        (s if 'support' in k or 'raft' in k else p).append(((x0, y0), (x, y)))
    return out


def beads(segments, half):
    if not segments:
        return None
    return unary_union(MultiLineString(segments).buffer(half, cap_style=1, resolution=4))


def opened(g, r=0.1):
    return g.buffer(-r, resolution=4).buffer(r, resolution=4) if not g.is_empty else g


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('gcode')
    ap.add_argument('--xy-gap', type=float, default=0.5)
    ap.add_argument('--z-gap', type=float, default=0.2)
    ap.add_argument('--width', type=float, default=0.45)
    ap.add_argument('--layer-height', type=float, default=0.2)
    a = ap.parse_args()
    by_z = layers_of(a.gcode)
    zs = sorted(by_z)
    half = 0.5 * a.width
    above = max(1, math.ceil(a.z_gap / a.layer_height - 1e-6))
    part = {}
    xy_total = z_total = 0.0
    bad_layers = 0
    for i, z in enumerate(zs):
        sup_segs = by_z[z][0]
        if not sup_segs:
            continue
        S = beads(sup_segs, half)
        xy = z_area = 0.0
        for j in range(i, min(len(zs), i + above + 1)):
            if zs[j] not in part:
                part[zs[j]] = beads(by_z[zs[j]][1], half)
            P = part[zs[j]]
            if P is None:
                continue
            if j == i:
                near = a.xy_gap - a.width - 0.02
                xy = opened(S.intersection(P.buffer(near, resolution=4) if near > 0 else P)).area
            else:
                z_area += opened(S.intersection(P)).area
        xy_total += xy
        z_total += z_area
        bad_layers += (xy > 0.5 or z_area > 0.5)
    print('xy %.1f z %.1f layers %d' % (xy_total, z_total, bad_layers))


if __name__ == '__main__':
    sys.exit(main())
