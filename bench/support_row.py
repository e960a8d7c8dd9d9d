#!/usr/bin/python3
"""One row of bench_support.sh: what gcheck says a G-code lays on air, and what its support costs.

usage: support_row.py NAME SLICER GCHECK.json FILE.gcode SECONDS [FUSED]
       support_row.py --table ROWS.tsv
FUSED is support_fused.py's line ("xy A z B layers N"): the support fused to the part, in mm².
Support is the extrusion typed support (;TYPE: containing "support", PrusaSlicer's and Cura's
names): its plastic (mm³ of filament), and its trips (runs of travel moves that start or end at a
support extrusion). Handles M82/M83 and G92.
"""
import json
import math
import sys

import gcode_moves

def support_costs(path, filament=1.75):
    """Support plastic (mm³) and support trips: travels that start or end at a support extrusion."""
    fed = 0.0
    trips = 0
    trip_from_support = None  # open trip: did it start at a support extrusion?
    last_was_support = False
    for kind, x0, y0, x, y, de in gcode_moves.moves(path):
        moved = (x, y) != (x0, y0)
        if moved and de > 0:
            sup = 'support' in kind.lower()
            if sup:
                fed += de
            if trip_from_support is not None and (trip_from_support or sup):
                trips += 1
            trip_from_support = None
            last_was_support = sup
        elif moved and trip_from_support is None:
            trip_from_support = last_was_support
    return fed * math.pi * (filament / 2) ** 2, trips


def row(name, slicer, js, gcode, seconds, fused=''):
    s = json.load(open(js))['summary']
    vol, trips = support_costs(gcode)
    cells = [name, slicer, '%.1f' % s.get('unsupported_area_total', float('nan')),
             '%.1f' % s.get('unsupported_area_max', float('nan')), str(s.get('unsupported_layers', '?')),
             '%.0f' % vol, str(trips), seconds, str(s.get('verdict', '?'))]
    if fused:
        w = fused.split()
        cells.append('%.1f' % (float(w[1]) + float(w[3])) if len(w) >= 4 else '?')
    print('\t'.join(cells))


def table(path):
    rows = [l.rstrip('\n').split('\t') for l in open(path) if l.strip()]
    head = ['model', 'slicer', 'air mm²', 'worst layer mm²', 'air layers', 'support mm³', 'support trips', 'time s',
            'gcheck', 'fused mm²']
    widths = [max([len(h)] + [len(r[i]) for r in rows if len(r) > i]) for i, h in enumerate(head)]
    print('  '.join(h.ljust(w) for h, w in zip(head, widths)))
    for r in rows:
        print('  '.join(c.ljust(w) for c, w in zip(r, widths)))
    # Ratios of tranche with support to PrusaSlicer's support, and of its tree to Cura's, per model.
    by = {(r[0], r[1]): r for r in rows if len(r) >= 8}
    peers = {'prusa': 'PrusaSlicer (--support-material --support-material-auto, its normal support)',
             'cura_tree': "CuraEngine's tree support"}
    for mine, peer in (('tranche', 'prusa'), ('tranche_tree', 'prusa'), ('tranche_touch', 'prusa'),
                       ('tranche_tree', 'cura_tree')):
        if not any(k[1] == mine for k in by) or not any(k[1] == peer for k in by):
            continue
        print('\n%s / %s:' % (mine, peers[peer]))
        for m in dict.fromkeys(r[0] for r in rows):
            t, p = by.get((m, mine)), by.get((m, peer))
            if not t or not p:
                continue

            def ratio(i):
                a, b = float(t[i]), float(p[i])
                return 'n/a' if b == 0 else '%.2f' % (a / b)
            print('  %-22s support plastic %s  support trips %s  time %s  air %s vs %s mm² (%s)' % (
                m, ratio(5), ratio(6), ratio(7), t[2], p[2], 'at most' if float(t[2]) <= float(p[2]) else 'MORE'))


if __name__ == '__main__':
    if sys.argv[1] == '--table':
        table(sys.argv[2])
    else:
        row(*sys.argv[1:7])
