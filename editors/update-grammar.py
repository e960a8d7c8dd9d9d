#!/usr/bin/env python3
"""Rewrites the TextMate grammar's lists of properties, enum values and field prefixes from the
schema (runtime/schema/*.def), after a schema change. editors/test/test-grammar.js checks that
they agree. Usage: editors/update-grammar.py"""
import json
import os
import re
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
grammar_path = os.path.join(root, "editors", "tranche-rules.tmLanguage.json")


def read(name):
    with open(os.path.join(root, "runtime", "schema", name), encoding="utf-8") as f:
        return f.read()


props = re.findall(r'^TRANCHE_PROP\(\w+, "(\w+)"', read("properties.def"), re.M)
values = []
for v in re.findall(r'^TRANCHE_ENUM\(\w+, "\w+",\s*\n\s*"([^"]*)"', read("enums.def"), re.M):
    values += [x for x in v.split() if x not in values]
prefixes = []
for p in re.findall(r'^TRANCHE_FIELD\(\w+, "(\w+)\.', read("fields.def"), re.M):
    if p not in prefixes:
        prefixes.append(p)

with open(grammar_path, encoding="utf-8") as f:
    grammar = json.load(f)
lists = {"support.variable.property": props, "support.constant.enum": values, "variable.language.level": prefixes}
changed = 0
for pattern in grammar["repository"]["expression"]["patterns"]:
    for scope, names in lists.items():
        if pattern.get("name") == scope + ".tranche-rules":
            new = "\\b(" + "|".join(names) + ")\\b"
            if pattern["match"] != new:
                pattern["match"] = new
                changed += 1
with open(grammar_path, "w", encoding="utf-8") as f:
    json.dump(grammar, f, indent=2, ensure_ascii=False)
    f.write("\n")
print(f"update-grammar: {changed} list(s) rewritten in {os.path.relpath(grammar_path, root)}")
