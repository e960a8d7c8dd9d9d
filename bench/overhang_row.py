#!/usr/bin/python3
"""Rows and table for bench_overhangs.sh.

overhang_row.py NAME SLICER FILE.gcode [GCHECK.json|-] [MODEL.stl X,Y]   prints one tab-separated row
overhang_row.py --table ROWS.tsv                                        prints the table

Columns: gcheck's verdict, coverage and band coverage, its unsupported area (mm^2, extrusion over
neither the layer below nor support, beyond nozzle/2 + layer height) and the layers with 1 mm^2
or more of it; the mean speed of the walls (mm/s, by length: the moves of
an outer or inner wall type, PrusaSlicer's "Overhang perimeter" and Cura's WALL-OUTER/WALL-INNER too, layer 0 left out; run with
the slowdown for a short layer's cooling off, as bench_overhangs.sh does); the feed-rate changes
(G0/G1 lines whose F differs from the one in force) and the extruding G1 moves. With the model
and gcheck's offset X,Y, the anchoring of what is laid over air (overhang_anchor.py): mm of
extrusion whose centre is not within half a bead of the layer below (air_mm; in walls: wall_air),
and the longest unanchored span and the one 95% of that length lies within (span_max, span_p95:
mm along the path from the last point resting on the layer below to the next).
"""
import json
import math
import os
import sys
from collections import defaultdict

COLS = ['model', 'slicer', 'verdict', 'coverage', 'band', 'unsup_mm2', 'unsup_lay', 'wall_mm_s',
        'F_changes', 'moves', 'air_mm', 'wall_air', 'span_max', 'span_p95']
WIDTHS = [16, 20, 8, 9, 7, 10, 10, 10, 10, 9, 8, 9, 9, 9]
WALLS = ('External perimeter', 'Perimeter', 'Overhang perimeter', 'WALL-OUTER', 'WALL-INNER')


def gcode_stats(path):
    typ, f, x, y, e, layer = None, None, 0.0, 0.0, 0.0, -1
    rel_e = False
    changes = moves = 0
    by_type = defaultdict(lambda: defaultdict(float))  # type -> F -> mm (layers > 0)
    for line in open(path, errors='replace'):
        if line.startswith(';TYPE:'):
            typ = line[6:].strip()
            continue
        if line.startswith(';LAYER:'):
            layer = int(line[7:])
            continue
        if line.startswith(';LAYER_CHANGE'):
            layer += 1
            continue
        code = line.split(';', 1)[0].split()
        if not code:
            continue
        if code[0] == 'M83':
            rel_e = True
        elif code[0] == 'M82':
            rel_e = False
        elif code[0] == 'G92':
            for w in code[1:]:
                if w[0] == 'E':
                    e = float(w[1:])
        if code[0] not in ('G0', 'G1'):
            continue
        w = {t[0]: float(t[1:]) for t in code[1:] if len(t) > 1 and t[0] in 'XYZEF'}
        if 'F' in w and w['F'] != f:
            changes += 1
            f = w['F']
        nx, ny = w.get('X', x), w.get('Y', y)
        de = 0.0
        if 'E' in w:
            de = w['E'] if rel_e else w['E'] - e
            e = e + w['E'] if rel_e else w['E']
        length = math.hypot(nx - x, ny - y)
        if de > 0 and length > 0:
            moves += 1
            if typ in WALLS and layer > 0:
                by_type[typ][f] += length
        x, y = nx, ny
    mm = sum(sum(fs.values()) for fs in by_type.values())
    mm_min = sum(sum(f_ * l for f_, l in fs.items()) for fs in by_type.values())
    return (mm_min / mm / 60 if mm > 0 else 0.0), changes, moves


def row(name, slicer, gcode, js=None, stl=None, off=None):
    vals = [name, slicer, '-', '-', '-', '-', '-']
    if js and js != '-':
        s = json.load(open(js))['summary']
        vals = [name, slicer, s.get('verdict', '?').split(':')[0], f"{s.get('coverage_mean') or 0:.3f}",
                f"{s.get('band_coverage_mean') or 0:.3f}", f"{s.get('unsupported_area_total') or 0:.1f}",
                str(s.get('unsupported_layers', 0))]
    speed, changes, moves = gcode_stats(gcode)
    anchor = ['-'] * 4
    if stl and off:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        from overhang_anchor import measure
        anchor = [f'{v:.1f}' for v in measure(stl, gcode, off)]
    print('\t'.join(vals + [f'{speed:.1f}', str(changes), str(moves)] + anchor))


def table(path):
    print(' '.join(c.ljust(w) for c, w in zip(COLS, WIDTHS)))
    for l in open(path):
        if l.strip():
            print(' '.join(c.ljust(w) for c, w in zip(l.rstrip('\n').split('\t'), WIDTHS)))


if __name__ == '__main__':
    if sys.argv[1] == '--table':
        table(sys.argv[2])
    else:
        row(*sys.argv[1:])
