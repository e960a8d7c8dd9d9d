#!/usr/bin/python3
"""Layer count and cusp heights of a layer plan on a mesh, for bench_adaptive.sh.

usage: adaptive_cusp.py row NAME SLICER MODEL.stl FILE.gcode GCHECK_VERDICT >> rows.tsv
       adaptive_cusp.py prusa-plan MODEL.stl QUALITY MIN MAX LAYER_H FIRST_H > plan.txt
       adaptive_cusp.py prusa-3mf IN.3mf plan.txt OUT.3mf
       adaptive_cusp.py table ROWS.tsv

The mesh is placed with its lowest point at z = 0 (as every slicer does); the layers are the
G-code's `;Z:` values (tranche's and PrusaSlicer's), or a plan's z tops, one per line.
A layer [z0, z1] of height h leaves on a facet whose unit normal has vertical component n_z the
stair-step (cusp) h·|n_z|, measured across the surface; a horizontal facet strictly inside a
layer leaves its distance to the nearer layer boundary. A facet reaching less than 1 µm into a
layer (the G-code's z resolution) does not count in it. The first layer is left out (every
slicer prints first_layer_height there). Reported: the layer count, the largest cusp of any
layer, the mean cusp over the surface (each facet's cusp in each layer it crosses, weighted
by its area in that layer), and the largest change of height between neighbouring layers
(above the first and below the last two, where the rest under the top is shared: how smooth
the profile is).

`prusa-plan` computes the layer tops PrusaSlicer's adaptive layer heights would give
(PrusaSlicer 2.5's SlicingAdaptive, re-derived from its description: the allowed deviation is
lerp(min, layer_height, 2q) below q = 0.5 and lerp(max, layer_height, 2(1 - q)) above, with
PrusaSlicer's q where 0 is finest; a facet allows min(dev / 0.184, 1.44·dev·sqrt(tan of its slope
from horizontal)); facets already crossing the layer's bottom, then those starting inside the
layer, limit it; a horizontal facet ends the layer on it), because prusa-slicer's command line
cannot turn adaptive layers on (it is a button in its GUI). `prusa-3mf` writes that plan into a
3MF (made by `prusa-slicer --export-3mf`) as the object's layer height profile, the file its GUI
saves (Metadata/Slic3r_PE_layer_heights_profile.txt: z, height pairs, the last at the object's
top), so that prusa-slicer's command line slices with those heights.
"""
import math
import struct
import sys

import numpy as np

EPS = 1e-6
# G-code z values carry 3 decimals: a facet within 1 µm of a layer boundary only touches it.
ZTOL = 1e-3


def read_stl(path):
    data = open(path, 'rb').read()
    tris = []
    if len(data) >= 84 and 84 + 50 * struct.unpack('<I', data[80:84])[0] == len(data):
        n = struct.unpack('<I', data[80:84])[0]
        arr = np.frombuffer(data, dtype=np.uint8, count=n * 50, offset=84).reshape(n, 50)
        v = arr[:, 12:48].copy().view('<f4').reshape(n, 3, 3).astype(np.float64)
        return v
    for line in data.decode('ascii', 'replace').splitlines():
        w = line.split()
        if w and w[0] == 'vertex':
            tris.append([float(w[1]), float(w[2]), float(w[3])])
    return np.array(tris, dtype=np.float64).reshape(-1, 3, 3)


class Facets:
    def __init__(self, path):
        v = read_stl(path)
        v[:, :, 2] -= v[:, :, 2].min()
        n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
        length = np.linalg.norm(n, axis=1)
        keep = length > 0
        v, n, length = v[keep], n[keep], length[keep]
        self.area = 0.5 * length
        self.nz = np.abs(n[:, 2]) / length
        self.ns = np.sqrt(n[:, 0] ** 2 + n[:, 1] ** 2) / length
        self.zmin = v[:, :, 2].min(axis=1)
        self.zmax = v[:, :, 2].max(axis=1)
        self.flat = (self.zmax - self.zmin) < EPS
        self.top = float(self.zmax.max())


def gcode_tops(path):
    zs = set()
    for line in open(path, errors='replace'):
        if line.startswith(';Z:'):
            zs.add(round(float(line[3:]), 6))
    return sorted(zs)


def cusps(f, tops):
    """(layers, max cusp, area-weighted mean cusp), the first layer left out."""
    worst, num, den = 0.0, 0.0, 0.0
    for z0, z1 in zip(tops, tops[1:]):
        h = z1 - z0
        cross = (f.zmax > z0 + ZTOL) & (f.zmin < z1 - ZTOL)
        slope = cross & ~f.flat
        if slope.any():
            c = h * f.nz[slope]
            worst = max(worst, float(c.max()))
            # the facet's area inside the layer, by its share of the z span
            span = f.zmax[slope] - f.zmin[slope]
            inside = (np.minimum(f.zmax[slope], z1) - np.maximum(f.zmin[slope], z0)) / span
            w = f.area[slope] * inside
            num += float((w * c).sum())
            den += float(w.sum())
        flat = cross & f.flat
        if flat.any():
            zf = f.zmin[flat]
            worst = max(worst, float(np.minimum(zf - z0, z1 - zf).max()))
    return len(tops), worst, (num / den if den else 0.0)


def prusa_plan(f, quality, hmin, hmax, hmid, first):
    q = 1 - quality  # PrusaSlicer's factor: 0 finest
    dev = (hmin + (hmid - hmin) * 2 * q) if q < 0.5 else (hmax + (hmid - hmax) * 2 * (1 - q))
    with np.errstate(divide='ignore', invalid='ignore'):
        allow = np.where(f.nz > 1e-5, 1.44 * dev * np.sqrt(f.ns / f.nz), np.inf)
    allow = np.minimum(allow, dev / 0.184)
    order = np.argsort(f.zmin, kind='stable')
    zmin, zmax, allow, flat = f.zmin[order], f.zmax[order], allow[order], f.flat[order]
    tops, z = [first], first
    while z + EPS < f.top:
        h = hmax
        lo = np.searchsorted(zmin, z, side='left')  # facets starting below z
        crossing = (zmax[:lo] > z + EPS)
        if crossing.any():
            h = min(h, float(allow[:lo][crossing].min()))
        h = max(h, hmin)
        hi = np.searchsorted(zmin, z + h, side='left')
        for i in range(lo, hi):  # facets starting inside the layer, by their bottom
            start = zmin[i] - z
            if start >= h:
                break
            if zmax[i] <= z + EPS:
                continue
            if allow[i] < start:
                h = start
            elif allow[i] < h:
                h = allow[i]
        h = max(h, hmin)
        above = zmin[lo:][flat[lo:] & (zmin[lo:] > z + EPS)]
        if above.size and above.min() - z < h and above.min() - z >= hmin:
            h = float(above.min() - z)
        h = min(h, f.top - z)
        z += h
        tops.append(round(z, 6))
    return tops


def prusa_3mf(src, plan, dst):
    import zipfile
    tops = [float(x) for x in open(plan) if x.strip()]
    pairs, z = [], 0.0
    for t in tops:
        pairs += [z, t - z]
        z = t
    pairs += [tops[-1], pairs[-1]]  # PrusaSlicer drops a profile whose last z is not the top
    profile = 'object_id=1|' + ';'.join(f'{v:.6f}' for v in pairs) + '\n'
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, 'w', zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            if item.filename != 'Metadata/Slic3r_PE_layer_heights_profile.txt':
                zout.writestr(item, zin.read(item.filename))
        zout.writestr('Metadata/Slic3r_PE_layer_heights_profile.txt', profile)


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == 'row':
        name, slicer, model, gcode, verdict = sys.argv[2:7]
        f = Facets(model)
        tops = gcode_tops(gcode) if not gcode.endswith('.txt') else [float(x) for x in open(gcode)]
        n, worst, mean = cusps(f, tops)
        hs = [b - a for a, b in zip(tops, tops[1:])][:-2]
        jump = max((abs(b - a) for a, b in zip(hs, hs[1:])), default=0.0)
        print(f'{name}\t{slicer}\t{n}\t{worst:.3f}\t{mean:.4f}\t{verdict}\t{jump:.3f}')
    elif len(sys.argv) >= 2 and sys.argv[1] == 'prusa-plan':
        model, q, hmin, hmax, hmid, first = sys.argv[2], *map(float, sys.argv[3:8])
        for z in prusa_plan(Facets(model), q, hmin, hmax, hmid, first):
            print(f'{z:.6f}')
    elif len(sys.argv) >= 2 and sys.argv[1] == 'prusa-3mf':
        prusa_3mf(*sys.argv[2:5])
    elif len(sys.argv) >= 2 and sys.argv[1] == 'table':
        rows = [l.rstrip('\n').split('\t') for l in open(sys.argv[2]) if l.strip()]
        print(f'{"model":<24} {"slicer":<34} {"layers":>6} {"max cusp":>9} {"mean cusp":>10} {"max step":>9}  gcheck')
        for r in rows:
            step = r[6] if len(r) > 6 else '-'
            print(f'{r[0]:<24} {r[1]:<34} {r[2]:>6} {r[3]:>9} {r[4]:>10} {step:>9}  {r[5]}')
        by = {}
        for r in rows:
            by.setdefault(r[0], {})[r[1]] = r
        print()
        for name, s in by.items():
            a, p = s.get('tranche adaptive q=0.5'), s.get('prusa adaptive q=0.5')
            if a and p:
                print(f'{name}: tranche adaptive / PrusaSlicer adaptive: layers {int(a[2]) / int(p[2]):.2f}, '
                      f'max cusp {float(a[3]) / float(p[3]):.2f}, mean cusp {float(a[4]) / float(p[4]):.2f}')
    else:
        print(__doc__)
        sys.exit(2)


if __name__ == '__main__':
    main()
