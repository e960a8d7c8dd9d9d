#!/usr/bin/python3
"""Thin-feature models for bench_walls.sh, written as ASCII STL prisms 5 mm tall.

walls_models.py OUTDIR      writes NAME.stl for every model and prints "NAME PATH VOLUME_MM3" lines

  wall_0.3 .. wall_1.2   a straight wall 30 mm long, 0.3 to 1.2 mm thick
  wedge                  a wedge from 0 at its tip to 3 mm over 30 mm
  strokes                four letters (E, H, L, T) drawn with 0.6 mm strokes, 8 mm tall
  comb                   a 2 mm spine with ten fins 0.5 mm thick and 8 mm long
  tube                   a tube 16 mm across with a 0.8 mm wall
"""
import math
import os
import sys

HEIGHT = 5.0


def area(poly):
    return 0.5 * sum(poly[i][0] * poly[(i + 1) % len(poly)][1] - poly[(i + 1) % len(poly)][0] * poly[i][1]
                     for i in range(len(poly)))


def ccw(poly):
    return poly if area(poly) > 0 else poly[::-1]


def ear_clip(poly):
    """Triangles of a simple counter-clockwise polygon (ear clipping)."""
    idx = list(range(len(poly)))
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def inside(p, a, b, c):
        return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0

    guard = 0
    while len(idx) > 3 and guard < 100000:
        guard += 1
        for k in range(len(idx)):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = poly[i0], poly[i1], poly[i2]
            if cross(a, b, c) <= 0:
                continue
            if any(inside(poly[j], a, b, c) for j in idx if j not in (i0, i1, i2)):
                continue
            tris.append((i0, i1, i2))
            idx.pop(k)
            break
        else:
            raise ValueError('not a simple polygon')
    tris.append(tuple(idx))
    return tris


def facets_prism(poly, tris):
    """Side walls and caps of `poly` extruded from z = 0 to HEIGHT (outward normals)."""
    out = []
    n = len(poly)
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        a0, b0, a1, b1 = (a[0], a[1], 0), (b[0], b[1], 0), (a[0], a[1], HEIGHT), (b[0], b[1], HEIGHT)
        out += [(a0, b0, b1), (a0, b1, a1)]
    for i, j, k in tris:
        p, q, r = poly[i], poly[j], poly[k]
        out.append(((p[0], p[1], HEIGHT), (q[0], q[1], HEIGHT), (r[0], r[1], HEIGHT)))
        out.append(((p[0], p[1], 0), (r[0], r[1], 0), (q[0], q[1], 0)))
    return out


def prism(poly):
    poly = ccw(poly)
    return facets_prism(poly, ear_clip(poly)), area(poly) * HEIGHT


def tube(r_out, wall, n=128):
    outer = [(r_out * math.cos(2 * math.pi * i / n), r_out * math.sin(2 * math.pi * i / n)) for i in range(n)]
    r_in = r_out - wall
    inner = [(r_in * math.cos(2 * math.pi * i / n), r_in * math.sin(2 * math.pi * i / n)) for i in range(n)]
    out = []
    for i in range(n):
        j = (i + 1) % n
        o0, o1, i0, i1 = outer[i], outer[j], inner[i], inner[j]
        # outer wall (normal out), inner wall (normal towards the axis)
        out += [((*o0, 0), (*o1, 0), (*o1, HEIGHT)), ((*o0, 0), (*o1, HEIGHT), (*o0, HEIGHT))]
        out += [((*i0, 0), (*i1, HEIGHT), (*i1, 0)), ((*i0, 0), (*i0, HEIGHT), (*i1, HEIGHT))]
        # caps: the ring between the circles
        out += [((*o0, HEIGHT), (*o1, HEIGHT), (*i1, HEIGHT)), ((*o0, HEIGHT), (*i1, HEIGHT), (*i0, HEIGHT))]
        out += [((*o0, 0), (*i1, 0), (*o1, 0)), ((*o0, 0), (*i0, 0), (*i1, 0))]
    vol = (area(outer) - area(inner)) * HEIGHT
    return out, vol


def letters(s=0.6, h=8.0, w=5.0, gap=2.0):
    """E, H, L and T as hole-free outlines drawn with strokes `s` wide, side by side."""
    m = h / 2
    E = [(0, 0), (w, 0), (w, s), (s, s), (s, m - s / 2), (w * 0.8, m - s / 2), (w * 0.8, m + s / 2),
         (s, m + s / 2), (s, h - s), (w, h - s), (w, h), (0, h)]
    H = [(0, 0), (s, 0), (s, m - s / 2), (w - s, m - s / 2), (w - s, 0), (w, 0), (w, h), (w - s, h),
         (w - s, m + s / 2), (s, m + s / 2), (s, h), (0, h)]
    L = [(0, 0), (w, 0), (w, s), (s, s), (s, h), (0, h)]
    c = w / 2
    T = [(c - s / 2, 0), (c + s / 2, 0), (c + s / 2, h - s), (w, h - s), (w, h), (0, h), (0, h - s),
         (c - s / 2, h - s)]
    facets, vol = [], 0.0
    for k, shape in enumerate([E, H, L, T]):
        dx = k * (w + gap)
        f, v = prism([(x + dx, y) for x, y in shape])
        facets += f
        vol += v
    return facets, vol


def comb(spine=2.0, fins=10, fin_t=0.5, fin_len=8.0, pitch=3.0):
    length = (fins - 1) * pitch + fin_t + 2.0
    poly = [(0, 0), (length, 0), (length, spine)]
    for k in reversed(range(fins)):
        x0 = 1.0 + k * pitch
        poly += [(x0 + fin_t, spine), (x0 + fin_t, spine + fin_len), (x0, spine + fin_len), (x0, spine)]
    poly.append((0, spine))
    return prism(poly)


def write_stl(path, facets):
    with open(path, 'w') as f:
        f.write('solid m\n')
        for a, b, c in facets:
            ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
            vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
            nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
            ln = math.sqrt(nx * nx + ny * ny + nz * nz) or 1
            f.write(f'facet normal {nx / ln:.6f} {ny / ln:.6f} {nz / ln:.6f}\n outer loop\n')
            for p in (a, b, c):
                f.write(f'  vertex {p[0]:.6f} {p[1]:.6f} {p[2]:.6f}\n')
            f.write(' endloop\nendfacet\n')
        f.write('endsolid m\n')


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    models = {}
    for t in (0.3, 0.45, 0.6, 0.8, 1.0, 1.2):
        models[f'wall_{t}'] = prism([(0, 0), (30, 0), (30, t), (0, t)])
    models['wedge'] = prism([(0, 0), (30, -1.5), (30, 1.5)])
    models['strokes'] = letters()
    models['comb'] = comb()
    models['tube'] = tube(8.0, 0.8)
    for name, (facets, vol) in models.items():
        path = os.path.join(out, name + '.stl')
        write_stl(path, facets)
        print(name, path, f'{vol:.4f}')


if __name__ == '__main__':
    main()
