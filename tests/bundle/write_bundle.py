#!/usr/bin/env python3
"""A bundle written from docs/bundles.md alone, by a program that shares no code with tranche.

Usage: write_bundle.py RULEC TRANCHE

rulec builds a reference bundle from a small rules file; this script reads its sections by the
documented layout, lays them out again (in reverse order: the section table says where each one
is), and writes the header itself, with the documented FNV-1a 64 checksum. tranche must run the
result and make the same G-code as with rulec's bundle. A version 1 bundle (the old checksum) and
a damaged one must be refused with a message that says to rebuild them.
"""
import os
import struct
import subprocess
import sys
import tempfile

FNV_BASIS = 14695981039346656037
FNV_PRIME = 1099511628211
OLD_BASIS = 1469598103934665603  # version 1: the basis without its last digit


def fnv1a64(data, basis=FNV_BASIS):
    h = basis
    for b in data:
        h = ((h ^ b) * FNV_PRIME) & 0xFFFFFFFFFFFFFFFF
    return h


def read_sections(data):
    magic, version, flags, schema, checksum, n, size = struct.unpack_from("<8sIIQQII", data, 0)
    assert magic == b"TRNCHRUL", magic
    sections = []
    for i in range(n):
        sid, zero, off, length = struct.unpack_from("<IIII", data, 40 + 16 * i)
        assert zero == 0 and sid == i + 1
        sections.append(data[off:off + length])
    return version, flags, schema, checksum, sections


def write_bundle(version, flags, schema, sections, basis=FNV_BASIS):
    n = len(sections)
    table_end = 40 + 16 * n
    offset = (table_end + 7) // 8 * 8
    offsets = [0] * n
    for i in reversed(range(n)):  # the last section first: only the table says where they are
        offsets[i] = offset
        offset = (offset + len(sections[i]) + 7) // 8 * 8
    body = bytearray(offset)
    for i in range(n):
        struct.pack_into("<IIII", body, 40 + 16 * i, i + 1, 0, offsets[i], len(sections[i]))
        body[offsets[i]:offsets[i] + len(sections[i])] = sections[i]
    struct.pack_into("<8sIIQQII", body, 0, b"TRNCHRUL", version, flags, schema, 0, n, len(body))
    struct.pack_into("<Q", body, 24, fnv1a64(bytes(body[32:]), basis))
    return bytes(body)


def cube_stl(size=10.0):
    v = [(x, y, z) for x in (0, size) for y in (0, size) for z in (0, size)]
    faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
             (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
    out = bytearray(b"cube".ljust(80, b" ")) + struct.pack("<I", len(faces))
    for a, b, c in faces:
        out += struct.pack("<3f", 0, 0, 0)
        for p in (v[a], v[b], v[c]):
            out += struct.pack("<3f", *p)
        out += b"\0\0"
    return bytes(out)


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def main():
    rulec, tranche = sys.argv[1], sys.argv[2]
    failures = []

    def check(cond, what):
        print(("ok    " if cond else "FAIL  ") + what)
        if not cond:
            failures.append(what)

    with tempfile.TemporaryDirectory(prefix="tranche-bundle-") as d:
        rules = os.path.join(d, "slow.rules")
        with open(rules, "w") as f:
            f.write('rule "slow start" when layer.index < 2 { speed = 20 mm/s }\n'
                    'on layer.start when layer.index == 3 { gcode "M117 layer 3" }\n')
        ref = os.path.join(d, "ref.bundle")
        r = run([rulec, "build", rules, "-o", ref])
        check(r.returncode == 0, "rulec build: " + r.stderr.strip())
        data = open(ref, "rb").read()
        version, flags, schema, checksum, sections = read_sections(data)
        check(version == 2, f"the bundle format version is 2 (got {version})")
        check(fnv1a64(data[32:]) == checksum, "rulec's checksum is the documented FNV-1a 64")

        mine = os.path.join(d, "mine.bundle")
        with open(mine, "wb") as f:
            f.write(write_bundle(version, flags, schema, sections))
        model = os.path.join(d, "cube.stl")
        with open(model, "wb") as f:
            f.write(cube_stl())
        outs = {}
        for name in ("ref", "mine"):
            out = os.path.join(d, name + ".gcode")
            r = run([tranche, "slice", model, "--rules", os.path.join(d, name + ".bundle"), "-o", out, "-q"])
            check(r.returncode == 0, f"tranche slice --rules {name}.bundle: {r.stderr.strip()}")
            outs[name] = [l for l in open(out).read().splitlines() if ".bundle" not in l] if r.returncode == 0 else []
        check(outs["ref"] and outs["ref"] == outs["mine"], "the script's bundle makes the same G-code as rulec's")
        check(any("M117 layer 3" in l for l in outs["mine"]), "the script's bundle's hook is in the G-code")

        old = os.path.join(d, "old.bundle")
        with open(old, "wb") as f:
            f.write(write_bundle(1, flags, schema, sections, OLD_BASIS))
        r = run([tranche, "slice", model, "--rules", old, "-o", os.path.join(d, "old.gcode"), "-q"])
        check(r.returncode == 1 and "older tranche" in r.stderr and "rulec build" in r.stderr,
              "a version 1 bundle is refused, saying to rebuild it: " + r.stderr.strip())
        check(not os.path.exists(os.path.join(d, "old.gcode")), "nothing is written for a refused bundle")

        bad = bytearray(open(mine, "rb").read())
        bad[-1] ^= 0x40
        with open(old, "wb") as f:
            f.write(bad)
        r = run([tranche, "slice", model, "--rules", old, "-o", os.path.join(d, "bad.gcode"), "-q"])
        check(r.returncode == 1 and "checksum" in r.stderr and "rulec build" in r.stderr,
              "a damaged bundle is refused: " + r.stderr.strip())
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
