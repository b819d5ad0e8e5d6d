#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Export the golden corpus tests/cases/*.json as flat text for the Fortran runner.

    python3 tests/golden/export_flat.py           # write tests/cases/flat/<family>.txt
    python3 tests/golden/export_flat.py --check   # exit 1 if those files are out of date
    python3 tests/golden/export_flat.py --export CASES.json OUT.txt
                                                  # one file (e.g. a scratch JSON)

Fortran should not parse JSON, so each tests/cases/<family>.json becomes
tests/cases/flat/<family>.txt, which tests/fortran/corpus_runner.f90 reads. The
JSON stays the source of truth; the flat files are committed so a Fortran-only
runner needs no Python, and `--check` (run by the tests) fails when they no
longer match the JSON. Pure Python 3 (no packages).

Flat format `isect-flat/4`
--------------------------
Line-oriented text. Each line is a key and its values separated by single
spaces; a line starting with `#` is a comment. Lines have no length limit
(the runner reads them in chunks; a mesh's lines hold all its numbers). A file is

    # comment lines
    format isect-flat/4
    family <family>
    cases <number of case blocks that follow>
    case ... end      (one block per case, in the JSON's order)

A case block, in this order (lines in brackets appear only when they apply):

    case <id> <op>                 op: intersect | contains | mesh_check |
                                   point_in_polygon2 | winding_number2 |
                                   polygon_normal | plane_from_points | spawn |
                                   winding_number
    name <text to the end of the line>
    [flags <flag> ...]             the case's flags (informational)
    [malformed <reason>]           the JSON case breaks the schema: a failure
    [skip <reason>]                a case this runner does not run yet (a shape
                                   type or op added after this export): skipped
    [shape <type> <n> <flags> <named> <has_data> <ndata>]
                                   intersect / contains / mesh_check / spawn /
                                   winding_number: isect_shape
                                   fields as integers (type: ISECT_* value, possibly
                                   a raw bad-input value); named = 1 when the JSON
                                   names the type (then it has a scalar function,
                                   except a mesh); has_data = 0 when data is NULL (a
                                   raw type with no known keys, a mesh); ndata =
                                   number of doubles that follow. A mesh (type
                                   "mesh", or a raw type with "faces", as the C
                                   runner reads it) is `shape <type> 0 <flags> <named> 0 0`
                                   (flags: a named mesh's containment rule, its
                                   "rule" as an ISECT_* value, ISECT_EVEN_ODD when
                                   absent; 0 for a raw type) followed by its four
                                   mesh lines:
    [mesh <nv> <nf>]               vertex and face counts
    [mverts <x1> <y1> <z1> ... <x_nv> <y_nv> <z_nv>]
                                   the vertices (no values when nv = 0)
    [mfaces <size_1> ... <size_nf>]
                                   each face's index count (none when nf = 0)
    [midx <i1> ... <i_total>]      the faces' 0-based indices concatenated
                                   (total = sum of the sizes; none when 0), each
                                   an int32; an index with no int32 form (not an
                                   integer, out of range) is written as -1, which
                                   no mesh accepts, as the C runner passes it. The
                                   runner calls isect_mesh_create
                                   with offsets NULL and idx as given when every
                                   size is 3 (also when nf = 0), else with CSR
                                   offsets 0, size_1, size_1 + size_2, ...
                                   (tests/cases/README.md, "Meshes"); a creation
                                   error is the case's result, whatever the op
    [data <x1> ... <x_ndata>]      the shape's numbers, in the order of its scalar
                                   function's arguments. A runner pads them with
                                   zeros (max(ndata, 4n) + 16 doubles, as the C
                                   runner does): a raw type may name a type whose
                                   function reads more numbers than were given
    [transform <m1> ... <m16>]     row-major object-to-world matrix (intersect,
                                   contains, spawn, winding_number; mesh_check reports
                                   the mesh as given)
    [ray <ox> <oy> <oz> <dx> <dy> <dz> <tmin> <tmax>]            intersect; spawn: the
                                   primary ray
    [opts <flags> <eps>]           intersect; absent: pass NULL (the defaults)
    [sdir <x> <y> <z>]             spawn: the direction of the secondary ray
    [point <k> <x1> ... <xk>]      contains (k = 3), 2D ops (k = 2)
    [points <n> <x1> <y1> <z1> ... <xn> <yn> <zn>]               winding_number
    [accuracy <a>]                 winding_number (0 when the JSON has none)
    [polygon <n> <x1> <y1> ... <xn> <yn>]                        2D ops
    [rule <r>]                     point_in_polygon2 (integer, passed through)
    [vertices <n> <x1> <y1> <z1> ... ]       polygon_normal / plane_from_points
    tol <t> <point> <normal> <uv> <volume> <area>
    [wtol <winding>]               winding_number: the tolerance of each w
    status <s>                     expected status (ISECT_OK or ISECT_E_*), integer
    [count <c> <listed>]           intersect, status ok: hit count; listed = 1 when
                                   the hit lines follow (else only the count is checked);
                                   spawn, status ok: the same for the secondary ray's hits
                                   (status is isect_spawn_ray's)
    [hit <t> <px> <py> <pz> <nx> <ny> <nz> <u> <v> <has_uv> <prim> <kind>]
                                   one per hit, in order; kind an ISECT_* integer;
                                   has_uv = 0: uv was absent and is not checked
    [inside <0|1>]                 contains / point_in_polygon2, status ok
    [winding <w>]                  winding_number2, status ok
    [windings <n> <w1> ... <wn>]   winding_number, status ok: w at each point
    [normal <x> <y> <z>]           polygon_normal, status ok
    [plane <a> <b> <c> <d>]        plane_from_points, status ok
    [report <vertices> <edges> <faces> <boundary_edges> <nonmanifold_edges>
            <misoriented_edges> <degenerate_faces> <components>
            <euler_characteristic> <genus> <closed> <oriented> <volume> <area>]
                                   mesh_check, status ok: the isect_mesh_report
                                   fields in the struct's order (12 integers, then
                                   2 doubles), on one line; closed and oriented
                                   are 0 or 1, the counts within +-2^53
    end

Version 2 (meshes) added the mesh lines, `report`, the op mesh_check and the
volume and area tolerances of `tol`; version 3 (secondary rays) the op spawn
and its `sdir` line; version 4 (winding numbers) the op winding_number with
its `points`, `accuracy`, `wtol` and `windings` lines, and a named mesh's
containment rule in the flags of its `shape` line (always 0 before; "winding"
is also a valid rule name, ISECT_WINDING). A runner of an older version
rejects a newer file at its `format` line instead of misreading it; a version 4
runner reads version 3 files too (they are version 4 files without the new
lines).

Numbers: every double is written as Python's repr() of the exact double (the
shortest decimal that reads back as the same double; hex-float strings of the
JSON are converted exactly), and as `Inf`, `-Inf`, `NaN` for the non-finite
values, which Fortran's list-directed READ accepts. A correctly rounding
reader (gfortran's is: it uses strtod) therefore gets every bit back. Integer
codes (types, statuses, kinds, rules, flags) are the values of the ISECT_*
macros, read from libisect/include/isect.h.
"""
from __future__ import annotations

import argparse
import json
import math
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FORMAT = "isect-flat/4"
DEFAULT_TOLERANCE = 1e-12
# The tolerances of `tol`, in the order of the flat `tol` line.
TOLERANCE_KEYS = ("t", "point", "normal", "uv", "volume", "area")
# The isect_mesh_report fields of a mesh_check `report`, in the struct's (and
# the flat `report` line's) order: the integers, then the doubles.
REPORT_INTEGERS = ("vertices", "edges", "faces", "boundary_edges", "nonmanifold_edges",
                   "misoriented_edges", "degenerate_faces", "components",
                   "euler_characteristic", "genus", "closed", "oriented")
REPORT_DOUBLES = ("volume", "area")
INT32_MIN, INT32_MAX = -2**31, 2**31 - 1
# A mesh index with no int32 form is passed as this (as the C runner does):
# no mesh accepts it, so the library still reports the case's E_ARG.
NOT_AN_INDEX = -1
# Report counts: where a JSON number (a double) holds an integer exactly.
MAX_EXACT_COUNT = 2**53


class Malformed(Exception):
    """The JSON case does not follow tests/cases/README.md: a failure."""


class SkipCase(Exception):
    """A valid case this runner does not run yet (counted as skipped)."""


def header_constants(header: Path) -> dict[str, float]:
    """The numeric #define ISECT_* values of isect.h: integers (`0x1u` and `(-1)`
    included) and ISECT_EPS_DEFAULT."""
    values: dict[str, float] = {}
    eps = re.search(r"^#define\s+ISECT_EPS_DEFAULT\s+(\S+)", header.read_text(), re.M)
    if eps:
        values["ISECT_EPS_DEFAULT"] = float(eps.group(1))
    pattern = re.compile(
        r"^#define\s+(ISECT_[A-Z0-9_]+)\s+\(?\s*(-?(?:0x[0-9a-fA-F]+|\d+))u?\s*\)?(?:\s|$)")
    for line in header.read_text().splitlines():
        m = pattern.match(line)
        if m:
            values[m.group(1)] = int(m.group(2), 0)
    return values


class Codes:
    """The corpus's names as the library's integers."""

    def __init__(self, c: dict[str, float]):
        self.eps_default = c["ISECT_EPS_DEFAULT"]
        self.status = {"ok": c["ISECT_OK"], "E_ARG": c["ISECT_E_ARG"],
                       "E_NONFINITE": c["ISECT_E_NONFINITE"],
                       "E_DEGENERATE": c["ISECT_E_DEGENERATE"], "E_NOMEM": c["ISECT_E_NOMEM"]}
        self.kind = {"miss": c["ISECT_MISS"], "enter": c["ISECT_ENTER"],
                     "exit": c["ISECT_EXIT"], "touch": c["ISECT_TOUCH"],
                     "invalid": c["ISECT_INVALID"]}
        self.rule = {"evenodd": c["ISECT_EVEN_ODD"], "nonzero": c["ISECT_NONZERO"],
                     "winding": c["ISECT_WINDING"]}
        self.opts_flag = {"cull_back": c["ISECT_CULL_BACK"], "any_hit": c["ISECT_ANY_HIT"]}
        self.capped = c["ISECT_CAPPED"]
        # The keys of each named type in the order of its scalar function's
        # arguments (= the order of isect_shape.data); width 1 is a number,
        # > 1 a vector, < 0 a list of rows of -width numbers (their count is n).
        self.layouts = [
            ("plane", c["ISECT_PLANE"], [("normal", 3), ("d", 1)]),
            ("sphere", c["ISECT_SPHERE"], [("center", 3), ("radius", 1)]),
            ("box", c["ISECT_AABB"], [("lo", 3), ("hi", 3)]),
            ("triangle", c["ISECT_TRIANGLE"], [("a", 3), ("b", 3), ("c", 3)]),
            ("polygon", c["ISECT_POLYGON"], [("vertices", -3)]),
            ("convex", c["ISECT_CONVEX"], [("planes", -4)]),
            ("cylinder", c["ISECT_CYLINDER"], [("p0", 3), ("p1", 3), ("radius", 1)]),
            ("infinite_cylinder", c["ISECT_CYLINDER_INF"],
             [("point", 3), ("axis", 3), ("radius", 1)]),
            ("ellipsoid", c["ISECT_ELLIPSOID"], [("center", 3), ("radii", 3)]),
            ("quadric", c["ISECT_QUADRIC"], [("coeffs", 10)]),
        ]
        self.polygon = c["ISECT_POLYGON"]
        self.cylinder = c["ISECT_CYLINDER"]
        self.mesh = c["ISECT_MESH"]


# ------------------------------------------------------------- values
def number(value, where: str) -> float:
    """A corpus number: JSON number, "inf", "-inf", "nan" or a hex-float string."""
    if isinstance(value, bool):
        raise Malformed(f"{where}: a boolean where a number is expected")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        text = value.strip().lower()
        if text in ("inf", "+inf", "-inf", "nan"):
            return float(text)
        try:
            return float.fromhex(value)
        except ValueError:
            pass
    raise Malformed(f"{where}: {value!r} is not a number")


def integer(value, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or value != int(value):
        raise Malformed(f"{where}: {value!r} is not an integer")
    return int(value)


def vector(value, n: int, where: str) -> list[float]:
    if not isinstance(value, list) or len(value) != n:
        raise Malformed(f"{where}: expected {n} numbers")
    return [number(x, f"{where}[{i}]") for i, x in enumerate(value)]


def rows(value, width: int, where: str) -> list[list[float]]:
    """A list of rows of `width` numbers; any number of rows (bad-input cases)."""
    if not isinstance(value, list):
        raise Malformed(f"{where}: expected a list of rows")
    return [vector(row, width, f"{where}[{i}]") for i, row in enumerate(value)]


def fmt(x: float) -> str:
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "Inf" if x > 0 else "-Inf"
    return repr(x)


def fmts(xs) -> str:
    return " ".join(fmt(x) for x in xs)


def one_line(text: str) -> str:
    return " ".join(str(text).split())


def line(key: str, values) -> str:
    """`key v1 v2 ...`, or just `key` when there are no values (no trailing
    space)."""
    return " ".join([key, *values])


# -------------------------------------------------------------- cases
def rule_value(obj: dict, key: str, codes: Codes, where: str) -> int:
    if key not in obj:
        return codes.rule["evenodd"]
    value = obj[key]
    if isinstance(value, str):
        if value not in codes.rule:
            raise Malformed(f"{where}.{key}: unknown rule {value!r}")
        return codes.rule[value]
    return integer(value, f"{where}.{key}")


def capped_value(shape: dict, codes: Codes) -> int:
    if "capped" not in shape:
        return codes.capped          # the Python constructor's default
    value = shape["capped"]
    if isinstance(value, bool):
        return codes.capped if value else 0
    return integer(value, "shape.capped")


def shape_lines(shape, codes: Codes) -> list[str]:
    """`shape` and `data` lines, mirroring tests/c/corpus_shape.c."""
    if not isinstance(shape, dict) or "type" not in shape:
        raise Malformed("shape: an object with a type is required")
    kind = shape["type"]
    if is_mesh(shape):
        # Before the layouts (a mesh's "vertices" would pass for a
        # polygon's), as tests/c/corpus_shape.c does.
        if kind == "mesh":
            return mesh_lines(shape, codes.mesh, 1, rule_value(shape, "rule", codes, "shape"))
        return mesh_lines(shape, integer(kind, "shape.type"), 0, 0)
    if isinstance(kind, str):
        matches = [lay for lay in codes.layouts if lay[0] == kind]
        if not matches:
            raise SkipCase(f"shape type {kind!r} is not run by this runner")
        layout, named, type_value = matches[0], 1, matches[0][1]
    else:
        type_value, named = integer(kind, "shape.type"), 0
        # A raw type takes the keys of the first named type whose keys are
        # all present (bad-input cases), or no data at all.
        layout = next((lay for lay in codes.layouts
                       if all(key in shape for key, _ in lay[2])), None)
    data: list[float] = []
    n = 0
    if layout is not None:
        for key, width in layout[2]:
            if key not in shape:
                raise Malformed(f"shape.{key} is missing")
            if width < 0:
                table = rows(shape[key], -width, f"shape.{key}")
                n = len(table)
                data += [x for row in table for x in row]
            elif width == 1:
                data.append(number(shape[key], f"shape.{key}"))
            else:
                data += vector(shape[key], width, f"shape.{key}")
    flags = 0
    if (named and type_value == codes.polygon) or (not named and "rule" in shape):
        flags = rule_value(shape, "rule", codes, "shape")
    elif (named and type_value == codes.cylinder) or (not named and "capped" in shape):
        flags = capped_value(shape, codes)
    has_data = 0 if layout is None else 1
    lines = [f"shape {type_value} {n} {flags} {named} {has_data} {len(data)}"]
    if data:
        lines.append("data " + fmts(data))
    return lines


def is_mesh(shape) -> bool:
    """A mesh shape: type "mesh", or a raw (integer) type with "faces"
    (bad-input cases), as the C runner reads them."""
    if not isinstance(shape, dict) or "type" not in shape:
        return False
    kind = shape["type"]
    return kind == "mesh" or (not isinstance(kind, str) and "faces" in shape)


def mesh_index(value, where: str) -> int:
    """An index as the int32 isect_mesh_create takes: a corpus number that is
    an integer in int32 range as it is, however wrong for the mesh; any other
    number NOT_AN_INDEX (tests/c/corpus_mesh.c does the same)."""
    x = number(value, where)
    if math.isfinite(x) and x == int(x) and INT32_MIN <= int(x) <= INT32_MAX:
        return int(x)
    return NOT_AN_INDEX


def mesh_lines(shape: dict, type_value: int, named: int, flags: int) -> list[str]:
    """`shape` (data NULL, n 0, flags the containment rule: the runner sets
    isect_shape.mesh) and the four mesh lines. Face sizes are passed as they
    are (a face of fewer than 3 indices is a creation error the runner must
    see)."""
    vertices = rows(shape.get("vertices"), 3, "shape.vertices")
    faces = shape.get("faces")
    if not isinstance(faces, list):
        raise Malformed("shape.faces: expected a list of index lists")
    indices: list[int] = []
    for f, face in enumerate(faces):
        if not isinstance(face, list):
            raise Malformed(f"shape.faces[{f}]: expected a list of indices")
        indices += [mesh_index(index, f"shape.faces[{f}][{k}]")
                    for k, index in enumerate(face)]
    return [f"shape {type_value} 0 {flags} {named} 0 0",
            f"mesh {len(vertices)} {len(faces)}",
            line("mverts", (fmt(x) for row in vertices for x in row)),
            line("mfaces", (str(len(face)) for face in faces)),
            line("midx", (str(i) for i in indices))]


OPS = ("intersect", "contains", "mesh_check", "point_in_polygon2", "winding_number2",
       "polygon_normal", "plane_from_points", "spawn", "winding_number")


def case_body(case: dict, op: str, codes: Codes) -> list[str]:
    """The lines between `name`/`flags` and `end`."""
    out: list[str] = []
    if op in ("intersect", "contains", "mesh_check", "spawn", "winding_number"):
        if op == "mesh_check" and not is_mesh(case.get("shape")):
            raise Malformed("mesh_check: the shape must be a mesh")
        out += shape_lines(case.get("shape"), codes)
        # mesh_check has no transform: the report describes the mesh as given.
        if "transform" in case and op != "mesh_check":
            out.append("transform " + fmts(vector(case["transform"], 16, "transform")))
    if op in ("intersect", "spawn"):
        ray = case.get("ray")
        if not isinstance(ray, dict):
            raise Malformed("ray: an object is required")
        values = vector(ray.get("org"), 3, "ray.org") + vector(ray.get("dir"), 3, "ray.dir")
        values.append(number(ray.get("tmin", 0.0), "ray.tmin"))
        values.append(number(ray.get("tmax", "inf"), "ray.tmax"))
        out.append("ray " + fmts(values))
        if op == "spawn":
            # No opts: the primary and the secondary ray use the defaults.
            out.append("sdir " + fmts(vector(case.get("dir"), 3, "dir")))
        elif "opts" in case:
            opts = case["opts"]
            if not isinstance(opts, dict):
                raise Malformed("opts: an object is required")
            flags = 0
            for i, flag in enumerate(opts.get("flags", [])):
                if isinstance(flag, str):
                    if flag not in codes.opts_flag:
                        raise Malformed(f"opts.flags[{i}]: unknown flag {flag!r}")
                    flags |= codes.opts_flag[flag]
                else:
                    flags |= integer(flag, f"opts.flags[{i}]")
            eps = number(opts.get("eps", codes.eps_default), "opts.eps")
            out.append(f"opts {flags} {fmt(eps)}")
    elif op == "contains":
        out.append("point 3 " + fmts(vector(case.get("point"), 3, "point")))
    elif op == "mesh_check":
        pass                            # the mesh is all its input
    elif op == "winding_number":
        points = rows(case.get("points"), 3, "points")
        out.append(line("points", [str(len(points))] + [fmt(x) for row in points for x in row]))
        out.append("accuracy " + fmt(number(case.get("accuracy", 0.0), "accuracy")))
    elif op in ("point_in_polygon2", "winding_number2"):
        polygon = rows(case.get("polygon"), 2, "polygon")
        out.append("point 2 " + fmts(vector(case.get("point"), 2, "point")))
        out.append(f"polygon {len(polygon)} " + fmts(x for row in polygon for x in row))
        if op == "point_in_polygon2":
            out.append(f"rule {rule_value(case, 'rule', codes, 'case')}")
    else:
        vertices = rows(case.get("vertices"), 3, "vertices")
        out.append(f"vertices {len(vertices)} " + fmts(x for row in vertices for x in row))

    tol = case.get("tol", {})
    if not isinstance(tol, dict):
        raise Malformed("tol: an object is required")
    out.append("tol " + fmts(number(tol.get(k, DEFAULT_TOLERANCE), f"tol.{k}")
                             for k in TOLERANCE_KEYS))
    if op == "winding_number":
        out.append("wtol " + fmt(number(tol.get("winding", DEFAULT_TOLERANCE), "tol.winding")))
        # expect_lines needs the point count to check the length of expect.winding
        return out + expect_lines(case.get("expect"), op, codes, len(points))
    out += expect_lines(case.get("expect"), op, codes)
    return out


def expect_lines(expect, op: str, codes: Codes, npoints: int = 0) -> list[str]:
    if not isinstance(expect, dict) or expect.get("status") not in codes.status:
        raise Malformed("expect.status: missing or unknown")
    out = [f"status {codes.status[expect['status']]}"]
    if expect["status"] != "ok":
        return out                      # for an error nothing else is checked
    if op in ("intersect", "spawn"):
        count = integer(expect.get("count"), "expect.count")
        hits = expect.get("hits")
        out.append(f"count {count} {0 if hits is None else 1}")
        if hits is not None:
            if not isinstance(hits, list) or len(hits) != count:
                raise Malformed("expect.hits: must list `count` hits")
            for i, hit in enumerate(hits):
                where = f"expect.hits[{i}]"
                if not isinstance(hit, dict) or hit.get("kind") not in codes.kind:
                    raise Malformed(f"{where}: an object with a known kind is required")
                uv = vector(hit["uv"], 2, f"{where}.uv") if "uv" in hit else [0.0, 0.0]
                values = ([number(hit.get("t"), f"{where}.t")]
                          + vector(hit.get("point"), 3, f"{where}.point")
                          + vector(hit.get("normal"), 3, f"{where}.normal") + uv)
                out.append(f"hit {fmts(values)} {1 if 'uv' in hit else 0} "
                           f"{integer(hit.get('prim'), where + '.prim')} "
                           f"{codes.kind[hit['kind']]}")
    elif op in ("contains", "point_in_polygon2"):
        out.append(f"inside {integer(expect.get('inside'), 'expect.inside')}")
    elif op == "winding_number2":
        out.append(f"winding {integer(expect.get('winding'), 'expect.winding')}")
    elif op == "winding_number":
        values = vector(expect.get("winding"), npoints, "expect.winding")
        out.append(line("windings", [str(npoints)] + [fmt(x) for x in values]))
    elif op == "mesh_check":
        report = expect.get("report")
        if not isinstance(report, dict):
            raise Malformed("expect.report: an object is required")
        missing = [k for k in REPORT_INTEGERS + REPORT_DOUBLES if k not in report]
        if missing:
            raise Malformed("expect.report: missing " + ", ".join(missing))
        counts = [integer(report[k], f"expect.report.{k}") for k in REPORT_INTEGERS]
        for k, value in zip(REPORT_INTEGERS, counts):
            limit = 1 if k in ("closed", "oriented") else MAX_EXACT_COUNT
            low = 0 if k in ("closed", "oriented") else -MAX_EXACT_COUNT
            if not low <= value <= limit:
                raise Malformed(f"expect.report.{k}: {value} is outside [{low}, {limit}]")
        out.append(line("report", [str(v) for v in counts]
                        + [fmt(number(report[k], f"expect.report.{k}"))
                           for k in REPORT_DOUBLES]))
    elif op == "polygon_normal":
        out.append("normal " + fmts(vector(expect.get("normal"), 3, "expect.normal")))
    else:
        out.append("plane " + fmts(vector(expect.get("plane"), 4, "expect.plane")))
    return out


def case_block(case, index: int, codes: Codes) -> list[str]:
    if not isinstance(case, dict):
        return [f"case {index} intersect", f"name [{index}]",
                "malformed the case is not an object", "end"]
    case_id = case.get("id", index)
    if isinstance(case_id, bool) or not isinstance(case_id, int):
        case_id = index
    op = case.get("op", "intersect")
    head = [f"case {case_id} {op if op in OPS else 'intersect'}",
            "name " + (one_line(case.get("name", "")) or f"[{index}]")]
    flags = case.get("flags", [])
    if isinstance(flags, list) and flags:
        head.append("flags " + " ".join(one_line(f).replace(" ", "_") for f in flags))
    try:
        if op not in OPS:
            # A later schema's op: the C runner may know it, this one not yet.
            raise SkipCase(f"op {op!r} is not run by this runner")
        body = case_body(case, op, codes)
    except Malformed as e:
        body = [f"malformed {one_line(e)}"]
    except SkipCase as e:
        body = [f"skip {one_line(e)}"]
    return head + body + ["end"]


def export(json_path: Path, codes: Codes) -> str:
    doc = json.loads(json_path.read_text())
    cases = doc.get("cases", []) if isinstance(doc, dict) else []
    family = doc.get("family", json_path.stem) if isinstance(doc, dict) else json_path.stem
    # The source as a repository path (tests/cases/<family>.json), or as given
    # for a file elsewhere (--export of a scratch file).
    try:
        source = json_path.resolve().relative_to(ROOT).as_posix()
    except ValueError:
        source = str(json_path)
    lines = [f"# Generated by tests/golden/export_flat.py from {source}"
             " (format: see that script); do not edit.",
             f"format {FORMAT}", f"family {one_line(family)}", f"cases {len(cases)}"]
    for i, case in enumerate(cases):
        lines += case_block(case, i, codes)
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="fail if the flat files differ from a fresh export")
    parser.add_argument("--cases", type=Path, default=ROOT / "tests" / "cases")
    parser.add_argument("--out", type=Path, default=None,
                        help="output directory (default: <cases>/flat)")
    parser.add_argument("--header", type=Path, default=ROOT / "libisect" / "include" / "isect.h")
    parser.add_argument("--export", type=Path, nargs=2, metavar=("JSON", "TXT"),
                        help="export one JSON file to one flat file (nothing else)")
    args = parser.parse_args()
    out_dir = args.out or args.cases / "flat"
    codes = Codes(header_constants(args.header))

    if args.export:
        source, target = args.export
        target.write_text(export(source, codes))
        print(f"wrote {target}")
        return 0

    wanted = {f"{p.stem}.txt": export(p, codes) for p in sorted(args.cases.glob("*.json"))}
    if not wanted:
        print(f"no *.json in {args.cases}", file=sys.stderr)
        return 1
    if args.check:
        stale = []
        for name, text in wanted.items():
            path = out_dir / name
            if not path.is_file() or path.read_text() != text:
                stale.append(name)
        extra = sorted(p.name for p in out_dir.glob("*.txt") if p.name not in wanted)
        for name in stale:
            print(f"FAIL {out_dir / name}: out of date with its JSON")
        for name in extra:
            print(f"FAIL {out_dir / name}: no JSON file exports to it")
        if stale or extra:
            print("run: python3 tests/golden/export_flat.py")
            return 1
        print(f"flat corpus in sync: {len(wanted)} files")
        return 0
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, text in wanted.items():
        (out_dir / name).write_text(text)
    for path in out_dir.glob("*.txt"):
        if path.name not in wanted:
            path.unlink()
    print(f"wrote {len(wanted)} files to {out_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
