#!/usr/bin/python3
"""Rows and table for bench_quality.sh.

quality_row.py NAME SLICER GCHECK.json FILE.gcode   prints one tab-separated row (GCHECK.json "-":
                                                     counts only, gcheck's columns left empty)
quality_row.py --table ROWS.tsv                      prints the table and tranche's ratios
quality_row.py --offset MODEL.stl X,Y                prints gcheck's --offset for a model whose
                                                     bounding box every slicer centres on X,Y
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gcode_counts import counts  # noqa: E402

COLS = ['model', 'slicer', 'verdict', 'layers', 'band', 'band_p05', 'skin', 'overflow', 'overlap',
        'volume_mm3', 'travels', 'retracts', 'trips']


def row(name, slicer, js, gcode):
    layers, travels, retracts, fed, vol, _, _, trips = counts(gcode)
    if js == '-':
        print('\t'.join([name, slicer, '-', str(layers)] + ['-'] * 5 +
                         [f'{vol:.0f}', str(travels), str(retracts), str(trips)]))
        return
    s = json.load(open(js))['summary']
    L = json.load(open(js))['layers']
    skin_a = sum(l['skin_area'] for l in L if l.get('skin_coverage') is not None)
    skin_c = sum(l['skin_area'] * l['skin_coverage'] for l in L if l.get('skin_coverage') is not None)
    skin = skin_c / skin_a if skin_a > 0 else 1.0
    verdict = s.get('verdict', '?')
    vals = [name, slicer, verdict.split(':')[0], str(layers), f"{s.get('band_coverage_mean', 0):.3f}",
            f"{s.get('band_coverage_p05', 0):.3f}", f'{skin:.3f}', f"{s.get('overflow_max', 0):.4f}",
            f"{s.get('overlap_ratio_median', 0):.3f}", f'{vol:.0f}', str(travels), str(retracts), str(trips)]
    print('\t'.join(vals))


def table(path):
    rows = [l.rstrip('\n').split('\t') for l in open(path) if l.strip()]
    widths = [21, 12, 8, 6, 6, 8, 6, 8, 7, 10, 8, 8, 6]
    print(' '.join(c.ljust(w) for c, w in zip(COLS + ['vol/prusa'], widths + [9])))
    by = {}
    for r in rows:
        by.setdefault(r[0], {})[r[1]] = r
    for model, sl in by.items():
        for s, r in sl.items():
            if len(r) < len(COLS):
                print(f'{model:<21} {s:<12} {" ".join(r[2:])}')
                continue
            ref = sl.get('prusa')
            rel = f'{float(r[9]) / float(ref[9]):.3f}' if ref and len(ref) >= len(COLS) and float(ref[9]) > 0 else '-'
            print(' '.join(c.ljust(w) for c, w in zip(r + [rel], widths + [9])))
    print()
    print('tranche / peer: travel moves, trips (runs of travel moves), retractions; per model, then over')
    print('all models both sliced. tranche_comb = tranche with retract_long_travel=10000, i.e. CuraEngine\'s')
    print('combing policy (retract only when leaving the part, whatever the travel\'s length):')
    for ours in ('tranche', 'tranche_comb'):
        for peer in ('prusa', 'cura'):
            tot = [0, 0, 0, 0, 0, 0]
            parts = []
            for model, sl in by.items():
                a, b = sl.get(ours), sl.get(peer)
                if not a or not b or len(a) < len(COLS) or len(b) < len(COLS):
                    continue
                va = [int(a[10]), int(a[12]), int(a[11])]
                vb = [int(b[10]), int(b[12]), int(b[11])]
                for k in range(3):
                    tot[k] += va[k]
                    tot[k + 3] += vb[k]
                parts.append(f'{model} {"/".join(f"{x / max(y, 1):.2f}" for x, y in zip(va, vb))}')
            if tot[3]:
                print(f'  {ours} vs {peer}: travels {tot[0] / tot[3]:.2f}, trips {tot[1] / max(tot[4], 1):.2f}, '
                      f'retractions {tot[2] / max(tot[5], 1):.2f}   ({", ".join(parts)})')


def offset(stl, centre):
    """Model frame minus G-code frame: the slicers centre the model's bounding box on the bed."""
    import numpy as np
    data = open(stl, 'rb').read()
    n = int.from_bytes(data[80:84], 'little')
    if len(data) == 84 + 50 * n:
        rec = np.frombuffer(data[84:], dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]))
        v = rec['v'].reshape(-1, 3).astype(float)
    else:
        v = np.array([[float(x) for x in l.split()[1:4]] for l in data.decode(errors='replace').splitlines()
                      if l.strip().startswith('vertex')])
    cx, cy = (float(c) for c in centre.split(','))
    lo, hi = v.min(0), v.max(0)
    print(f'{(lo[0] + hi[0]) / 2 - cx:.4f},{(lo[1] + hi[1]) / 2 - cy:.4f}')


if __name__ == '__main__':
    if sys.argv[1] == '--table':
        table(sys.argv[2])
    elif sys.argv[1] == '--offset':
        offset(sys.argv[2], sys.argv[3])
    else:
        row(*sys.argv[1:5])
