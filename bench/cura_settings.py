#!/usr/bin/python3
"""Command-line settings for CuraEngine 4.13 that match the benchmark's settings.

CuraEngine's `-j fdmprinter.def.json` only loads each setting's `default_value`; the Cura front
end evaluates every setting's `value` formula (line widths from line_width, infill line distance
from the density, ...) and sends the results. This does the same: it evaluates the formulas of
fdmprinter.def.json and fdmextruder.def.json with our overrides fixed, and prints the argument
list: the global settings, then `-e0` and the extruder's own (fdmextruder.def.json re-defines
material_diameter and machine_nozzle_size, so they must be given again for the extruder).

usage: cura_settings.py DEFINITIONS_DIR OVERRIDES_FILE   (one `key = value` per line, # comments)
prints the arguments NUL-separated (values may hold newlines): read them with `mapfile -d ''`
"""
import json
import math
import os
import sys


def flatten(node, out):
    for key, spec in node.items():
        out[key] = spec
        if 'children' in spec:
            flatten(spec['children'], out)


def parse(value, kind):
    value = value.strip()
    if kind == 'bool':
        return value.lower() in ('true', '1', 'yes')
    if kind in ('float',):
        return float(value)
    if kind == 'int':
        return int(float(value))
    if kind == '[int]':
        return value
    return value


def show(value):
    if isinstance(value, bool):
        return 'True' if value else 'False'
    if isinstance(value, float) and value.is_integer():
        return repr(value)
    return str(value)


def main():
    defs, overrides_file = sys.argv[1], sys.argv[2]
    printer = json.load(open(os.path.join(defs, 'fdmprinter.def.json')))
    extruder = json.load(open(os.path.join(defs, 'fdmextruder.def.json')))
    specs = {}
    flatten(printer['settings'], specs)
    ext_specs = {}
    flatten(extruder['settings'], ext_specs)
    specs.update({k: v for k, v in ext_specs.items() if k not in specs})
    values = {k: s.get('default_value') for k, s in specs.items() if 'type' in s and s['type'] != 'category'}
    fixed = {}
    for line in open(overrides_file):
        line = line.split('#', 1)[0].strip()
        if '=' not in line:
            continue
        key, _, raw = line.partition('=')
        key = key.strip()
        if key not in specs:
            sys.exit(f'cura_settings: unknown Cura setting {key!r}')
        fixed[key] = parse(raw.replace('\\n', '\n'), specs[key].get('type', 'str'))
    values.update(fixed)

    def lookup(key):
        return values[key]

    helpers = {
        'extruderValue': lambda _e, key: lookup(key),
        'extruderValues': lambda key: [lookup(key)],
        'resolveOrValue': lookup,
        'defaultExtruderPosition': lambda: '0',
        'math': math, 'ceil': math.ceil, 'floor': math.floor, 'radians': math.radians, 'tan': math.tan,
        'max': max, 'min': min, 'sum': sum, 'round': round, 'int': int, 'any': any, 'map': map,
    }
    formulas = {k: s['value'] for k, s in specs.items() if 'value' in s and k not in fixed and k in values}
    for _ in range(50):  # until nothing changes: formulas depend on each other in any order
        changed = False
        for key, formula in formulas.items():
            try:
                v = eval(formula if isinstance(formula, str) else repr(formula), dict(helpers), dict(values))
            except Exception:
                continue
            if v != values[key]:
                values[key] = v
                changed = True
        if not changed:
            break
    per_extruder = {k for k, s in specs.items() if s.get('settable_per_extruder') or k in ext_specs}
    out = []
    for key in sorted(values):
        if values[key] is None:
            continue
        out += ['-s', f'{key}={show(values[key])}']
    out.append('-e0')
    for key in sorted(values):
        if key in per_extruder and values[key] is not None:
            out += ['-s', f'{key}={show(values[key])}']
    sys.stdout.write('\0'.join(out) + '\0')


if __name__ == '__main__':
    main()
