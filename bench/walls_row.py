#!/usr/bin/python3
"""Rows and table for bench_walls.sh.

walls_row.py NAME SLICER GCHECK.json     prints one tab-separated row from gcheck's summary
walls_row.py --table ROWS.tsv            prints the table, and for tranche's rows the issue's goals:
                                         coverage >= PrusaSlicer Arachne's, volume within 0.95-1.05
                                         of the model's (walls up to 1.2 mm), median overlap <= 1.05,
                                         no flagged layer
"""
import json
import sys

COLS = ['model', 'slicer', 'verdict', 'coverage', 'band', 'overflow', 'volume', 'overlap', 'flagged']
WIDTHS = [10, 17, 8, 9, 7, 9, 7, 8, 8]


def row(name, slicer, js):
    s = json.load(open(js))['summary']
    vals = [name, slicer, s.get('verdict', '?').split(':')[0], f"{s.get('coverage_mean') or 0:.3f}",
            f"{s.get('band_coverage_mean') or 0:.3f}", f"{s.get('overflow_max') or 0:.4f}",
            f"{s.get('volume_ratio') or 0:.3f}", f"{s.get('overlap_ratio_median') or 0:.3f}",
            str(s.get('n_flagged', 0))]
    print('\t'.join(vals))


def table(path):
    rows = [l.rstrip('\n').split('\t') for l in open(path) if l.strip()]
    print(' '.join(c.ljust(w) for c, w in zip(COLS + ['goals'], WIDTHS + [30])))
    by = {}
    for r in rows:
        by.setdefault(r[0], {})[r[1]] = r
    for model, sl in by.items():
        arachne = sl.get('prusa_arachne')
        for s, r in sl.items():
            if len(r) < len(COLS):
                print(f'{model:<10} {s:<17} {" ".join(r[2:])}')
                continue
            goals = ''
            if s.startswith('tranche'):
                cov, vol, ovl, flg = float(r[3]), float(r[6]), float(r[7]), int(r[8])
                miss = []
                if arachne and len(arachne) >= len(COLS) and cov < float(arachne[3]):
                    miss.append('cov<arachne')
                if model.startswith('wall_') and not 0.95 <= vol <= 1.05:
                    miss.append('volume')
                if ovl > 1.05:
                    miss.append('overlap')
                if flg:
                    miss.append('flagged')
                goals = 'ok' if not miss else ' '.join(miss)
            print(' '.join(c.ljust(w) for c, w in zip(r + [goals], WIDTHS + [30])))


if __name__ == '__main__':
    if sys.argv[1] == '--table':
        table(sys.argv[2])
    else:
        row(*sys.argv[1:4])
