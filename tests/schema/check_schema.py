#!/usr/bin/env python3
"""Keeps docs/scene.schema.json in step with the parser.

    check_schema.py FRETWEAR_EXE SCHEMA EXAMPLES_DIR

- every example scene, `fretwear defaults`, and every example's resolved scene validate against the schema;
- every key of every resolved scene (the parser writes each key it knows there) is declared in the schema;
- scenes the parser rejects for a key-level reason are rejected by the schema too.
Prints one line per check and 'N passed, N failed'; exits 1 on any failure.
"""
import glob
import json
import os
import subprocess
import sys

import jsonschema

exe, schema_path, examples = sys.argv[1:4]
schema = json.load(open(schema_path))
validator = jsonschema.Draft202012Validator(schema)
results = []


def check(ok, label, detail=""):
    results.append(ok)
    print(("ok   " if ok else "FAIL ") + label + ("" if ok else ": " + detail))


def resolve(node):
    while "$ref" in node:
        node = schema["$defs"][node["$ref"].split("/")[-1]]
    return node


def declared(node, path):
    """True when the key path (a list) is declared under the schema node (following $ref and oneOf/anyOf)."""
    node = resolve(node)
    if not path:
        return True
    key, rest = path[0], path[1:]
    if key == "[]":
        return "items" in node and declared(node["items"], rest)
    for branch in [node] + node.get("oneOf", []) + node.get("anyOf", []):
        branch = resolve(branch)
        if key in branch.get("properties", {}) and declared(branch["properties"][key], rest):
            return True
    return False


def key_paths(value, prefix=()):
    if isinstance(value, dict):
        for k, v in value.items():
            yield prefix + (k,)
            yield from key_paths(v, prefix + (k,))
    elif isinstance(value, list):
        for v in value:
            if isinstance(v, (dict, list)):
                yield from key_paths(v, prefix + ("[]",))


def errors(instance):
    return sorted(e.message for e in validator.iter_errors(instance))


# Examples with files of their own (a measured profile's CSV) sit in a folder each.
scenes = sorted(glob.glob(os.path.join(examples, "*.json")) + glob.glob(os.path.join(examples, "*", "*.json")))
check(len(scenes) > 0, "examples found")
for path in scenes:
    name = os.path.relpath(path, examples)
    check(not errors(json.load(open(path))), "example %s validates" % name, "; ".join(errors(json.load(open(path))))[:400])
    out = subprocess.run([exe, "validate", "-v", path], capture_output=True, text=True)
    check(out.returncode == 0, "fretwear validates %s" % name, out.stderr[-300:])
    if out.returncode != 0:
        continue
    resolved = json.loads(out.stdout.split("\n", 1)[1])
    check(not errors(resolved), "resolved %s validates" % name, "; ".join(errors(resolved))[:400])
    missing = sorted({"/".join(p) for p in key_paths(resolved) if not declared(schema, list(p))})
    check(not missing, "every key of resolved %s is in the schema" % name, ", ".join(missing))

defaults = json.loads(subprocess.run([exe, "defaults"], capture_output=True, text=True, check=True).stdout)
check(not errors(defaults), "fretwear defaults validates", "; ".join(errors(defaults))[:400])

# The schema rejects what the parser rejects for key-level reasons.
base = json.load(open(os.path.join(examples, "hertz_normal.json")))
bad = {
    "unknown key": dict(base, lod=1),
    "negative modulus": dict(base, materials={"both": {"E": -1, "nu": 0.3}}),
    "too few cells": dict(base, grid={"cells": 8}),
    "unknown profile": dict(base, profile={"type": "cylindre", "R": 0.01}),
    "Q both ways": dict(base, friction=0.5, load={"P": 1e5, "Q": {"ratio": 0.5, "amplitude": 1}},
                        effects={"tangential": {}}),
    "wrong law key": dict(base, friction=0.5, load={"P": 1e5, "Q": {"ratio": 0.5}},
                          effects={"wear": {"law": "energy", "k": 1e-12, "cycles": 10}}),
    "radius below 1 nm": dict(base, profile={"type": "cylinder", "R": 1e-10}),
    "window end beyond 100 m": dict(base, grid={"window": [-1e200, 1e200]}),
    "denormal modulus": dict(base, materials={"both": {"E": 1e-310, "nu": 0.3}}),
    "normal load above 1e12 N/m": dict(base, load={"P": 1e13}),
    "table file with inline x": dict(base, profile={"type": "table", "file": "pad.csv", "x": [0, 1], "h": [0, 1]}),
    "table interpolation typo": dict(base, profile={"type": "table", "x": [-1e-4, 0, 1e-4, 2e-4],
                                                    "h": [1e-6, 0, 1e-6, 4e-6], "interpolation": "spline"}),
    "table unit typo": dict(base, profile={"type": "table", "x": [-100, 0, 100], "h": [1, 0, 1], "x_unit": "micron"}),
    "table checksum inline": dict(base, profile={"type": "table", "x": [-1e-4, 0], "h": [1e-6, 0],
                                                 "checksum": "fnv1a64:0123456789abcdef"}),
    "history stress above 1e12 Pa": dict(base, friction=0.5, effects={"tangential": {}},
                                          load={"P": 1e5, "history": [[0, 1e5, 0, 0], [1, 1e5, 1e4, 2e12],
                                                                      [2, 1e5, 0, 0]]}),
}
tmp = os.environ.get("TMPDIR", "/tmp")
for label, scene in bad.items():
    check(bool(errors(scene)), "schema rejects: %s" % label)
    path = os.path.join(tmp, "fretwear_schema_bad_%d.json" % os.getpid())
    json.dump(scene, open(path, "w"))
    rc = subprocess.run([exe, "validate", path], capture_output=True).returncode
    os.remove(path)
    check(rc == 2, "fretwear rejects: %s" % label, "exit %d" % rc)

n_failed = results.count(False)
print("%d passed, %d failed" % (len(results) - n_failed, n_failed))
sys.exit(1 if n_failed else 0)
