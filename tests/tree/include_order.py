#!/usr/bin/env python3
"""Fails when an #include runs up the dependency order of the tree.

Each folder of the code is a component; COMPONENTS lists, bottom to top, what each may include
directly (a component may also include what those include, transitively). An include of a
component not below it, or a file in a folder this table does not know, is an error naming the
file and line: add the folder here, in its place in the order, when the tree grows.
Usage: include_order.py [SOURCE_DIR]
"""
import os
import re
import sys

# Bottom to top. docs/architecture.md draws the same order.
COMPONENTS = [
    ("base", []),
    ("runtime/schema", ["base"]),
    ("runtime/context", ["runtime/schema"]),
    ("runtime/vm", ["runtime/context"]),
    ("grammar/ast", ["runtime/schema", "base"]),
    ("grammar", ["grammar/ast"]),
    ("compiler", ["grammar", "runtime/vm"]),
    ("lsp", ["compiler"]),
    ("geometry/core", ["base"]),
    ("geometry/mesh", ["geometry/core"]),
    ("geometry/plate", ["geometry/mesh"]),
    ("geometry/slice", ["geometry/mesh"]),
    ("geometry/polygon", ["geometry/core"]),
    ("geometry/preview", ["geometry/core", "runtime/schema"]),
    ("geometry/io", ["geometry/polygon", "geometry/slice"]),
    ("geometry/toolpath", ["geometry/polygon", "runtime/schema"]),
    ("geometry/fillangle", ["geometry/core", "runtime/context"]),
    ("geometry/support", ["geometry/toolpath"]),
    ("geometry/setup", ["geometry/support", "runtime/context"]),
    ("geometry/plan", ["geometry/setup"]),
    ("geometry/gcode", ["geometry/plan"]),
    ("geometry/export", ["geometry/plan", "geometry/io"]),
    ("geometry/pipeline", ["geometry/plate", "geometry/export", "geometry/gcode", "geometry/fillangle", "geometry/preview",
                           "runtime/vm"]),
    ("apps", ["geometry/pipeline", "geometry/plate", "compiler", "lsp"]),
]
CODE_ROOTS = ("base", "runtime", "grammar", "compiler", "lsp", "geometry", "apps")


def component(path):
    """The longest COMPONENTS name that is a folder prefix of path, or None."""
    best = None
    for name, _ in COMPONENTS:
        if path == name or path.startswith(name + "/"):
            if best is None or len(name) > len(best):
                best = name
    return best


def closure():
    allowed = {}
    for name, deps in COMPONENTS:
        reach = set()
        for d in deps:
            if d not in allowed:
                raise SystemExit(f"include_order.py: {name} depends on {d}, which is not below it")
            reach |= {d} | allowed[d]
        allowed[name] = reach
    return allowed


def self_test():
    """The check must catch an include up the tree and an unknown folder (a check that cannot
    fail is no check)."""
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as t:
        for rel, text in [("base/a.h", '#include "geometry/core/geom.h"\n'),
                          ("geometry/core/geom.h", '#include "base/a.h"\n'),
                          ("geometry/nowhere/x.cpp", "")]:
            os.makedirs(os.path.dirname(os.path.join(t, rel)), exist_ok=True)
            with open(os.path.join(t, rel), "w", encoding="utf-8") as f:
                f.write(text)
        r = subprocess.run([sys.executable, __file__, t], capture_output=True, text=True)
        ok = r.returncode == 1 and "base/a.h:1: base includes geometry/core/geom.h" in r.stdout \
            and "geometry/nowhere/x.cpp: folder not in" in r.stdout and "geometry/core/geom.h:1" not in r.stdout
        print("include_order self-test:", "ok" if ok else "FAILED\n" + r.stdout)
        return 0 if ok else 1


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    root = os.path.abspath(root)
    allowed = closure()
    errors = []
    include = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
    for top in CODE_ROOTS:
        for d, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                if not f.endswith((".h", ".cpp", ".def")):
                    continue
                rel = os.path.relpath(os.path.join(d, f), root)
                here = component(rel)
                if here is None:
                    errors.append(f"{rel}: folder not in tests/tree/include_order.py's COMPONENTS; add it in its place")
                    continue
                with open(os.path.join(root, rel), encoding="utf-8") as src:
                    for n, line in enumerate(src, 1):
                        m = include.match(line)
                        if not m or m.group(1).split("/")[0] not in CODE_ROOTS:
                            continue
                        there = component(m.group(1))
                        if there is None or (there != here and there not in allowed[here]):
                            errors.append(f"{rel}:{n}: {here} includes {m.group(1)} ({there or 'unknown folder'}), "
                                          f"which is not below it; move the code down or this include up")
    for e in errors:
        print(e)
    print(f"include_order: {len(errors)} problem(s)" if errors else "include_order: every include runs down the tree")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
