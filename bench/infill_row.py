#!/usr/bin/python3
"""Rows and table of bench_infill.sh.

usage: infill_row.py MODEL PATTERN SLICER FILE.gcode USER_SECONDS [GCHECK_VERDICT]  -> one row
       infill_row.py --table ROWS.tsv                               -> the table
A row: model, pattern, slicer (tranche or prusa), layers, trips, retractions, the whole filament
(mm) and the sparse infill's (the moves under ;TYPE:Internal infill, which both slicers write),
the user time (s) and gcheck's verdict (- when not run). A trip is a run of travel moves between two extrusions and a retraction a
run of moves pulling E back (bench/gcode_counts.py).
"""
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gcode_counts  # noqa: E402
import gcode_moves  # noqa: E402

def infill_filament(path):
    """Filament (mm) extruded under ;TYPE:Internal infill."""
    return sum(de for kind, x0, y0, x, y, de in gcode_moves.moves(path)
               if de > 0 and (x, y) != (x0, y0) and kind == 'Internal infill')


def row(model, pattern, slicer, path, secs, verdict='-'):
    layers, _, retracts, fed, _, _, _, trips = gcode_counts.counts(path)
    print('\t'.join(str(v) for v in (model, pattern, slicer, layers, trips, retracts, f'{fed:.1f}',
                                      f'{infill_filament(path):.1f}', secs or 'nan', verdict)))


def table(path):
    data = {}
    verdicts = {}
    models, patterns = [], []
    for line in open(path):
        f = line.rstrip('\n').split('\t')
        if len(f) < 9:
            continue
        model, pattern, slicer = f[:3]
        data[(model, pattern, slicer)] = [float(x) for x in f[3:9]]
        verdicts[(model, pattern, slicer)] = f[9] if len(f) > 9 else '-'
        if model not in models:
            models.append(model)
        if pattern not in patterns:
            patterns.append(pattern)

    def ratio(a, b):
        return a / b if b > 0 else math.nan

    print('| model | pattern | infill mm (ours / prusa) | plastic | trips/layer (ours / prusa) | '
          'retractions/layer (ours / prusa) | time s (ours / prusa) | time / our zigzag | gcheck |')
    print('|---|---|---|---|---|---|---|---|---|')
    sums = defaultdict(list)
    for model in models:
        zig = data.get((model, 'zigzag', 'tranche'))
        for pattern in patterns:
            t = data.get((model, pattern, 'tranche'))
            p = data.get((model, pattern, 'prusa'))
            if not t:
                continue
            lay = max(t[0], 1)
            cells = [model, pattern]
            if p:
                play = max(p[0], 1)
                cells += [f'{t[4]:.0f} / {p[4]:.0f}', f'{ratio(t[4], p[4]):.3f}',
                          f'{t[1] / lay:.2f} / {p[1] / play:.2f}', f'{t[2] / lay:.2f} / {p[2] / play:.2f}',
                          f'{t[5]:.2f} / {p[5]:.2f}']
                sums[pattern].append((ratio(t[4], p[4]), ratio(t[1] / lay, p[1] / play),
                                      ratio(t[2] / lay, p[2] / play), ratio(t[5], zig[5]) if zig else math.nan))
            else:
                cells += [f'{t[4]:.0f} / -', '-', f'{t[1] / lay:.2f} / -', f'{t[2] / lay:.2f} / -', f'{t[5]:.2f} / -']
                sums[pattern].append((math.nan, math.nan, math.nan, ratio(t[5], zig[5]) if zig else math.nan))
            cells.append(f'{ratio(t[5], zig[5]):.2f}' if zig else '-')
            cells.append(verdicts.get((model, pattern, 'tranche'), '-'))
            print('| ' + ' | '.join(cells) + ' |')
    print()
    print('Geometric means over the models (ours / PrusaSlicer\'s same pattern; time: ours / our zigzag):')
    print('| pattern | infill plastic | trips | retractions | time |')
    print('|---|---|---|---|---|')
    for pattern in patterns:
        cols = []
        for k in range(4):
            vals = [v[k] for v in sums[pattern] if v[k] == v[k] and v[k] > 0]
            cols.append(f'{math.exp(sum(map(math.log, vals)) / len(vals)):.3f}' if vals else '-')
        print(f'| {pattern} | ' + ' | '.join(cols) + ' |')


def main():
    if sys.argv[1] == '--table':
        table(sys.argv[2])
    else:
        row(*sys.argv[1:7])


if __name__ == '__main__':
    main()
