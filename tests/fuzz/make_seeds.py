#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the fuzz harnesses' seed corpora from the golden cases.

    python3 tests/fuzz/make_seeds.py tests/cases build/fuzz/seeds

Each case that a harness can express becomes one small input file in
SEEDS/<harness>/, encoded in the byte layout of tests/fuzz/fuzz_input.h
(every double as tag 0 + its 8 IEEE bytes, so it decodes bit for bit):
  shape        intersect and contains cases of the analytic shapes
  spawn        spawn cases of the analytic shapes
  mesh         mesh cases (up to 24 vertices and faces of 3..6 indices)
  mesh_parity  each closed topology unperturbed, a ray along an axis
  polygon2     point_in_polygon2, winding_number2, polygon_normal and
               plane_from_points cases
  corpus       every case as a one-case corpus document
  winding      the octahedron closed, open and inside out, and a soup, at
               points inside, outside, on a vertex and on an edge
The seeds are build products (not committed): `make fuzz-seeds` writes them.
Standard library only, so it runs before any virtual environment exists.
"""
import hashlib
import json
import math
import os
import struct
import sys

TYPES = {"plane": 1, "sphere": 2, "box": 3, "triangle": 4, "polygon": 5, "convex": 6,
         "cylinder": 7, "infinite_cylinder": 8, "ellipsoid": 9, "quadric": 10}
# The scalar argument order of each type's numbers (isect.h, shape types).
KEYS = {"plane": ["normal", "d"], "sphere": ["center", "radius"], "box": ["lo", "hi"],
        "triangle": ["a", "b", "c"], "polygon": ["vertices"], "convex": ["planes"],
        "cylinder": ["p0", "p1", "radius"], "infinite_cylinder": ["point", "axis", "radius"],
        "ellipsoid": ["center", "radii"], "quadric": ["coeffs"]}
RULES = {"evenodd": 0, "nonzero": 1}


class Unsupported(Exception):
    """The case cannot be written in the harness's layout."""


def number(x):
    if isinstance(x, bool):
        raise Unsupported("bool")
    if isinstance(x, (int, float)):
        return float(x)
    if isinstance(x, str):
        low = x.lower()
        if low in ("inf", "+inf", "-inf", "nan"):
            return float(low)
        if "0x" in low:
            return float.fromhex(x)
        return float(x)
    raise Unsupported("not a number: %r" % (x,))


def flat(v):
    if isinstance(v, list):
        out = []
        for e in v:
            out.extend(flat(e))
        return out
    return [number(v)]


def d(x):
    """A double: tag 0 and its IEEE bits, little-endian."""
    return b"\x00" + struct.pack("<d", x)


def u8(v):
    if not 0 <= v <= 255:
        raise Unsupported("byte %d" % v)
    return bytes([v])


def rule_of(shape):
    r = shape.get("rule", "evenodd")
    if isinstance(r, str):
        return RULES[r]
    if r in (0, 1):
        return r
    raise Unsupported("rule")


def shape_bytes(case):
    shape = case["shape"]
    name = shape.get("type")
    if name not in TYPES:
        raise Unsupported("type")
    nums = []
    for key in KEYS[name]:
        nums.extend(flat(shape[key]))
    n, flags = 0, 0
    if name == "polygon":
        n, flags = len(shape["vertices"]), rule_of(shape)
    elif name == "convex":
        n = len(shape["planes"])
    elif name == "cylinder":
        capped = shape.get("capped", True)
        if capped not in (True, False, 0, 1):
            raise Unsupported("capped")
        flags = 1 if capped else 0
    if n >= 24:
        raise Unsupported("count")
    transform = case.get("transform")
    out = u8(TYPES[name]) + u8(n) + u8(flags) + u8(0x03 if transform else 0)
    out += b"".join(d(x) for x in nums)
    if transform:
        out += b"".join(d(x) for x in flat(transform))
    return out


def opts_bytes(case):
    opts = case.get("opts")
    if opts is None:
        return u8(0)
    flags = 0
    for f in opts.get("flags", []):
        flags |= {"cull_back": 1, "any_hit": 2}[f]
    return u8(1) + u8(flags) + d(number(opts.get("eps", 1e-12)))


def ray_bytes(ray):
    out = b"".join(d(x) for x in flat(ray["org"]) + flat(ray["dir"]))
    return out + u8(3) + d(number(ray.get("tmin", 0.0))) + d(number(ray.get("tmax", "inf")))


def shape_seed(case):
    op = case.get("op", "intersect")
    if op == "intersect":
        return shape_bytes(case) + opts_bytes(case) + u8(0) + ray_bytes(case["ray"]) + u8(0)
    if op == "contains":
        # One ray from the point along +x, and the point as an extra point.
        p = flat(case["point"])
        ray = {"org": p, "dir": [1.0, 0.0, 0.0]}
        return (shape_bytes(case) + u8(0) + u8(0) + ray_bytes(ray) + u8(1) +
                b"".join(d(x) for x in p))
    raise Unsupported("op")


def spawn_seed(case):
    if case.get("op") != "spawn":
        raise Unsupported("op")
    return shape_bytes(case) + ray_bytes(case["ray"]) + u8(0) + b"".join(
        d(x) for x in flat(case["dir"]))


def mesh_seed(case):
    shape = case.get("shape", {})
    if shape.get("type") != "mesh" or case.get("transform"):
        raise Unsupported("not a plain mesh")
    verts, faces = shape["vertices"], shape["faces"]
    nv, nf = len(verts), len(faces)
    if nv > 24 or nf > 24 or any(not 3 <= len(f) <= 6 for f in faces):
        raise Unsupported("size")
    csr = any(len(f) != 3 for f in faces)
    out = u8(nv) + b"".join(d(x) for x in flat(verts)) + u8(1 if csr else 0) + u8(nf)
    for f in faces:
        if csr:
            out += u8(len(f) - 3)
        for i in f:
            if not (isinstance(i, int) and 0 <= i < nv):
                raise Unsupported("index")
            out += u8(i)
    op = case.get("op", "intersect")
    if op == "intersect":
        ray = case["ray"]
    elif op == "contains":
        ray = {"org": case["point"], "dir": [1.0, 0.0, 0.0]}
    else:
        ray = {"org": [0.0, 0.0, 0.0], "dir": [1.0, 0.0, 0.0]}
    return out + opts_bytes(case) + u8(0) + ray_bytes(ray)


def polygon2_seed(case):
    op = case.get("op")
    if op in ("point_in_polygon2", "winding_number2"):
        poly = case["polygon"]
        if len(poly) > 16:
            raise Unsupported("size")
        rule = rule_of(case) if op == "point_in_polygon2" else 0
        return (u8(len(poly)) + b"".join(d(x) for x in flat(poly)) + u8(rule) + u8(1) +
                b"".join(d(x) for x in flat(case["point"])[:2]))
    if op in ("polygon_normal", "plane_from_points"):
        v = case["vertices"]
        if len(v) > 16:
            raise Unsupported("size")
        xy = [c for p in v for c in flat(p)[:2]]
        return (u8(len(v)) + b"".join(d(x) for x in xy) + u8(0) + u8(0) +
                b"".join(d(x) for x in flat(v)))
    raise Unsupported("op")


def parity_seeds():
    """Each topology as it is (offsets 0), a ray from outside along +x
    through the middle, reflected back for the spawn check."""
    out = []
    for topology in range(3):
        nv = (4, 6, 8)[topology]
        seed = u8(topology) + u8(0) + (b"\x01\x00" * (3 * nv)) + u8(0) + u8(0)
        seed += ray_bytes({"org": [-10.0, 0.25, 0.375], "dir": [1.0, 0.0, 0.0]})
        seed += b"".join(d(x) for x in (-1.0, 0.5, 0.25))
        out.append(seed)
    return out


def winding_seeds():
    """The octahedron (mode 1 closed, 2 open, 3 inside out; offsets 0) and a
    two-triangle soup (mode 0), at the centre, a far point, a point beside
    a face, vertex 0 and an edge midpoint; mode bit 2 adds a mirror."""
    points = b"".join(u8(0) + b"".join(d(x) for x in p)
                      for p in ((0.0, 0.0, 0.0), (5.0, -3.0, 0.5), (0.5, 0.5, 0.5)))
    points += u8(1) + u8(2 + 4 * 1 + 32 * 2)
    out = []
    for mode in (1, 2, 3, 1 | 4):
        seed = u8(mode) + (b"\x01\x00" * 18) + (u8(3) if mode & 3 == 2 else b"")
        out.append(seed + u8(0) + u8(5) + points)
    soup = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    seed = u8(0) + u8(1) + b"".join(d(x) for v in soup for x in v)
    seed += u8(1) + u8(0) + u8(1) + u8(2) + u8(0) + u8(3) + u8(1)
    out.append(seed + u8(1) + u8(5) + points)
    return out


def corpus_seed(case, header):
    doc = {"schema": header["schema"], "family": header.get("family", "fuzz"),
           "number_of_cases": 1, "cases": [case]}
    return json.dumps(doc, separators=(",", ":")).encode()


def write(root, harness, data):
    folder = os.path.join(root, harness)
    os.makedirs(folder, exist_ok=True)
    name = hashlib.sha1(data).hexdigest()
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    cases_dir, root = argv[1], argv[2]
    makers = {"shape": shape_seed, "spawn": spawn_seed, "mesh": mesh_seed,
              "polygon2": polygon2_seed}
    counts = {h: 0 for h in list(makers) + ["mesh_parity", "corpus", "winding"]}
    for fname in sorted(os.listdir(cases_dir)):
        if not fname.endswith(".json"):
            continue
        with open(os.path.join(cases_dir, fname)) as f:
            header = json.load(f)
        for case in header["cases"]:
            for harness, make in makers.items():
                try:
                    data = make(case)
                except (Unsupported, KeyError, TypeError, ValueError):
                    continue
                write(root, harness, data)
                counts[harness] += 1
            write(root, "corpus", corpus_seed(case, header))
            counts["corpus"] += 1
    for seed in parity_seeds():
        write(root, "mesh_parity", seed)
        counts["mesh_parity"] += 1
    for seed in winding_seeds():
        write(root, "winding", seed)
        counts["winding"] += 1
    print("seeds: " + ", ".join("%s %d" % kv for kv in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
