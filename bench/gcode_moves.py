"""The moves of a G-code file, as the bench scripts read them (infill_row.py, support_row.py).

moves(path) yields (kind, x0, y0, x, y, de) for every G0/G1: kind is the last ;TYPE: comment (as
written), (x0, y0) -> (x, y) the move in absolute XY, de the filament it feeds (mm; M82/M83 and
G92 handled, negative for a retraction). on_comment, if given, is called with every line that
starts with ';' (;LAYER_CHANGE, ;Z:, ;TYPE:...) as it is read, between the moves around it.
With with_z, each tuple ends with the nozzle's z at the end of the move (overhang_anchor.py).
Also read by scripts/example-pictures.py.
"""
import re

WORD = re.compile(r'([XYZE])(-?\d*\.?\d+)')


def moves(path, on_comment=None, with_z=False):
    rel_e, x, y, z, e = False, 0.0, 0.0, 0.0, 0.0
    kind = ''
    with open(path, errors='replace') as f:
        for raw in f:
            if raw.startswith(';'):
                if on_comment:
                    on_comment(raw)
                if raw.startswith(';TYPE:'):
                    kind = raw[6:].strip()
                continue
            line = raw.split(';', 1)[0].strip()
            if not line:
                continue
            cmd = line.split(None, 1)[0].upper()
            if cmd == 'M82':
                rel_e = False
            elif cmd == 'M83':
                rel_e = True
            elif cmd == 'G92':
                for k, v in WORD.findall(line.upper()):
                    if k == 'E':
                        e = float(v)
            elif cmd in ('G0', 'G1'):
                w = dict(WORD.findall(line.upper()))
                nx, ny = float(w.get('X', x)), float(w.get('Y', y))
                z = float(w.get('Z', z))
                de = 0.0
                if 'E' in w:
                    v = float(w['E'])
                    de = v if rel_e else v - e
                    e = e + v if rel_e else v
                yield (kind, x, y, nx, ny, de, z) if with_z else (kind, x, y, nx, ny, de)
                x, y = nx, ny
