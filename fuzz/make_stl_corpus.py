#!/usr/bin/env python3
"""Writes large seeds for the STL fuzz target (fuzz_stl) into OUT_DIR: a binary STL of 3000
triangles (more than one of the loader's 2048-triangle welding chunks) and an ASCII STL of 600
facets, so that the fuzzer starts from the large-file paths that small seeds never reach.
Generated here so that the repository holds no large binary file. Usage: make_stl_corpus.py OUT_DIR
"""
import math
import os
import struct
import sys


def strip(n):
    """n triangles of a zig-zag strip around a cylinder: every corner shared by neighbours."""
    tris = []
    for i in range(n):
        k = i // 2
        a0, a1 = 2 * math.pi * k / 40, 2 * math.pi * (k + 1) / 40
        z0, z1 = (k // 40) * 0.5, (k // 40) * 0.5 + 0.5
        p = [(10 * math.cos(a0), 10 * math.sin(a0), z0), (10 * math.cos(a1), 10 * math.sin(a1), z0),
             (10 * math.cos(a0), 10 * math.sin(a0), z1), (10 * math.cos(a1), 10 * math.sin(a1), z1)]
        tris.append((p[0], p[1], p[2]) if i % 2 == 0 else (p[1], p[3], p[2]))
    return tris


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    tris = strip(3000)
    b = bytearray(b"generated strip".ljust(80, b"\0")) + struct.pack("<I", len(tris))
    for t in tris:
        b += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v) for v in t) + b"\0\0"
    with open(os.path.join(out, "large.bin.stl"), "wb") as f:
        f.write(b)
    lines = ["solid strip"]
    for t in strip(600):
        lines += ["facet normal 0 0 0", " outer loop"] + [f"  vertex {x:.5f} {y:.5f} {z:.5f}" for x, y, z in t]
        lines += [" endloop", "endfacet"]
    lines.append("endsolid strip")
    with open(os.path.join(out, "large.ascii.stl"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
