"""Tiny mesh helpers for the example model scripts: Python 3 standard library only.

A mesh is a list of triangles, each three (x, y, z) points in mm, counter-clockwise seen from
outside. Shapes that overlap are fine: Tranche unites overlapping shells (the additive mode).
"""
import math
import struct


def box(x0, y0, z0, x1, y1, z1):
    """An axis-aligned box from (x0, y0, z0) to (x1, y1, z1)."""
    p = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tris = []
    for a, b, c, d in quads:
        tris.append((p[a], p[b], p[c]))
        tris.append((p[a], p[c], p[d]))
    return tris


def sheared_box(x0, y0, x1, y1, z0, z1, dx):
    """A box whose top is moved by dx along x: its sides lean by atan(dx / (z1 - z0))."""
    p = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0 + dx, y0, z1), (x1 + dx, y0, z1), (x1 + dx, y1, z1), (x0 + dx, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tris = []
    for a, b, c, d in quads:
        tris.append((p[a], p[b], p[c]))
        tris.append((p[a], p[c], p[d]))
    return tris


def prism(outline, z0, z1):
    """A vertical prism over a convex or star-shaped outline (counter-clockwise (x, y) points),
    closed by fans from the outline's centroid."""
    n = len(outline)
    cx = sum(x for x, _ in outline) / n
    cy = sum(y for _, y in outline) / n
    tris = []
    for i in range(n):
        (xa, ya), (xb, yb) = outline[i], outline[(i + 1) % n]
        tris.append(((cx, cy, z0), (xb, yb, z0), (xa, ya, z0)))  # bottom, seen from below
        tris.append(((cx, cy, z1), (xa, ya, z1), (xb, yb, z1)))  # top
        tris.append(((xa, ya, z0), (xb, yb, z0), (xb, yb, z1)))  # side
        tris.append(((xa, ya, z0), (xb, yb, z1), (xa, ya, z1)))
    return tris


def _triangulate(outline):
    """Ear clipping of a simple counter-clockwise polygon: a list of index triples."""
    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def inside(p, a, b, c):
        return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0

    idx = list(range(len(outline)))
    out = []
    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, m = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = outline[i], outline[j], outline[m]
            if cross(a, b, c) <= 0:
                continue  # reflex or flat corner: not an ear
            if any(inside(outline[q], a, b, c) for q in idx if q not in (i, j, m)):
                continue
            out.append((i, j, m))
            del idx[k]
            break
        else:
            raise ValueError("outline is not a simple counter-clockwise polygon")
    out.append(tuple(idx))
    return out


def polygon_prism(outline, z0, z1):
    """A vertical prism over any simple polygon (counter-clockwise (x, y) points, no holes)."""
    tris = []
    for i, j, m in _triangulate(outline):
        a, b, c = outline[i], outline[j], outline[m]
        tris.append(((a[0], a[1], z1), (b[0], b[1], z1), (c[0], c[1], z1)))  # top
        tris.append(((a[0], a[1], z0), (c[0], c[1], z0), (b[0], b[1], z0)))  # bottom
    n = len(outline)
    for i in range(n):
        (xa, ya), (xb, yb) = outline[i], outline[(i + 1) % n]
        tris.append(((xa, ya, z0), (xb, yb, z0), (xb, yb, z1)))
        tris.append(((xa, ya, z0), (xb, yb, z1), (xa, ya, z1)))
    return tris


def tube(outer, inner, z0, z1):
    """A vertical prism with one hole: `outer` and `inner` are counter-clockwise outlines with as
    many points, inner[i] facing outer[i] (a square in a square, a circle in a circle)."""
    n = len(outer)
    assert len(inner) == n
    tris = []
    for i in range(n):
        j = (i + 1) % n
        (oa, ob), (ia, ib) = (outer[i], outer[j]), (inner[i], inner[j])
        tris.append(((oa[0], oa[1], z1), (ob[0], ob[1], z1), (ib[0], ib[1], z1)))  # top
        tris.append(((oa[0], oa[1], z1), (ib[0], ib[1], z1), (ia[0], ia[1], z1)))
        tris.append(((oa[0], oa[1], z0), (ib[0], ib[1], z0), (ob[0], ob[1], z0)))  # bottom
        tris.append(((oa[0], oa[1], z0), (ia[0], ia[1], z0), (ib[0], ib[1], z0)))
        tris.append(((oa[0], oa[1], z0), (ob[0], ob[1], z0), (ob[0], ob[1], z1)))  # outside wall
        tris.append(((oa[0], oa[1], z0), (ob[0], ob[1], z1), (oa[0], oa[1], z1)))
        tris.append(((ia[0], ia[1], z0), (ib[0], ib[1], z1), (ib[0], ib[1], z0)))  # hole wall
        tris.append(((ia[0], ia[1], z0), (ia[0], ia[1], z1), (ib[0], ib[1], z1)))
    return tris


def cylinder(cx, cy, r, z0, z1, segments=48):
    """A vertical cylinder (a regular prism of `segments` sides)."""
    pts = [(cx + r * math.cos(2 * math.pi * i / segments), cy + r * math.sin(2 * math.pi * i / segments))
           for i in range(segments)]
    return prism(pts, z0, z1)


def write_stl(path, triangles, name="tranche-example"):
    """Writes a binary STL."""
    with open(path, "wb") as f:
        f.write(name.encode("ascii")[:80].ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for a, b, c in triangles:
            ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
            vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
            nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
            ln = math.sqrt(nx * nx + ny * ny + nz * nz) or 1.0
            f.write(struct.pack("<3f", nx / ln, ny / ln, nz / ln))
            for p in (a, b, c):
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def write_ascii_stl(path, triangles, name="tranche-example"):
    """Writes an ASCII STL (bigger, but readable in a text editor)."""
    with open(path, "w", encoding="ascii") as f:
        f.write("solid %s\n" % name)
        for a, b, c in triangles:
            f.write("  facet normal 0 0 0\n    outer loop\n")
            for p in (a, b, c):
                f.write("      vertex %.6f %.6f %.6f\n" % p)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)
