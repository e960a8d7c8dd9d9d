#!/usr/bin/python3
"""Counts what a G-code file makes the printer do: layers, travel moves, retractions, filament.

usage: gcode_counts.py FILE.gcode [--filament 1.75]
Prints one line: layers travels retractions filament_mm filament_mm3 extrude_mm travel_mm trips.
A travel is a G0/G1 move in X/Y that does not extrude; a trip is a run of travel moves between
two extrusions (a combed travel of several moves is one trip); a retraction is one run of
consecutive moves that pull E back (as gcheck counts them), or a G10. Handles G90/G91, M82/M83
and G92.
"""
import math
import re
import sys

WORD = re.compile(r'([XYZEF])(-?\d*\.?\d+)')


def counts(path, filament=1.75):
    rel_e = False
    rel_xyz = False
    x = y = e = 0.0
    layers = set()
    z = 0.0
    travels = retracts = 0
    fed = ext_len = trav_len = 0.0
    in_retract = False
    trips = 0
    in_trip = False
    with open(path, errors='replace') as f:
        for line in f:
            line = line.split(';', 1)[0].strip()
            if not line:
                continue
            cmd = line.split(None, 1)[0].upper()
            if cmd == 'M82':
                rel_e = False
            elif cmd == 'M83':
                rel_e = True
            elif cmd == 'G90':
                rel_xyz = False
                rel_e = False
            elif cmd == 'G91':
                rel_xyz = True
                rel_e = True
            elif cmd == 'G92':
                for k, v in WORD.findall(line.upper()):
                    if k == 'E':
                        e = float(v)
            elif cmd == 'G10':
                retracts += 1
            elif cmd in ('G0', 'G1'):
                w = dict(WORD.findall(line.upper()))
                nx = float(w['X']) + (x if rel_xyz else 0) if 'X' in w else x
                ny = float(w['Y']) + (y if rel_xyz else 0) if 'Y' in w else y
                if 'Z' in w:
                    z = float(w['Z']) + (z if rel_xyz else 0)
                de = 0.0
                if 'E' in w:
                    ne = float(w['E']) + (e if rel_e else 0)
                    de = ne - e
                    e = ne
                d = math.hypot(nx - x, ny - y)
                if de < -1e-9:
                    if not in_retract:
                        retracts += 1
                    in_retract = True
                elif de > 1e-9 or d > 0:
                    in_retract = False
                if d > 0 and de > 1e-9:
                    layers.add(round(z, 3))
                    ext_len += d
                    fed += de
                    in_trip = False
                elif d > 0:
                    travels += 1
                    trav_len += d
                    if not in_trip:
                        trips += 1
                    in_trip = True
                elif de > 1e-9:
                    fed += 0  # unretraction: not new plastic
                x, y = nx, ny
    area = math.pi * filament * filament / 4
    return len(layers), travels, retracts, fed, fed * area, ext_len, trav_len, trips


def main():
    path = sys.argv[1]
    fil = float(sys.argv[sys.argv.index('--filament') + 1]) if '--filament' in sys.argv else 1.75
    n, t, r, fed, vol, el, tl, trips = counts(path, fil)
    print(f'{n} {t} {r} {fed:.1f} {vol:.1f} {el:.1f} {tl:.1f} {trips}')


if __name__ == '__main__':
    main()
