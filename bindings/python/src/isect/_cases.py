# SPDX-License-Identifier: Apache-2.0
"""Golden cases (schema ``isect-cases/1``) run against libisect through this
package: the engine of ``python -m isect cases FILE.json...`` and of the
project's own corpus tests (tests/python/corpus.py imports it).

The schema is documented in tests/cases/README.md. Each case runs as the
project's tests run it: an ``intersect`` case through ``intersect_all`` (every
hit, compared with the expectation within the case's tolerances), ``intersect``
(the batch closest hit must equal the first hit bit for bit, or be a MISS) and
``intersect_all_batch`` (the same hits, bit for bit); an error case must raise
the expected error from both the scalar and the batch call. A ``mesh`` shape is
built with :class:`~isect.Mesh` (a creation error is the case's status, whatever
the op); a ``mesh_check`` case compares every field of :meth:`Mesh.check`'s
report. A ``spawn`` case intersects its primary ray (``intersect``: the closest
hit, or the MISS record), spawns the secondary ray with :meth:`Shape.spawn`,
checks its direction, ``tmin``, ``tmax`` and origin (within 8 ulps of the hit
point), and compares that ray's hits like an ``intersect`` case's. A
``winding_number`` case calls :meth:`Mesh.winding_number` on all its points at
once and on each point alone (the library may sum a batch differently), each
value within ``tol.winding``; a ``contains`` case on a mesh passes the shape's
``rule`` to :meth:`Mesh.contains`. Cases flagged ``c-only`` cannot be expressed
through the Python API and are skipped.

A structural problem of a file or case (a missing key, a number that is not
one, an unknown op, shape type, kind, status or flag) is a
:class:`CaseFormatError` naming the field; :func:`run_files` reports it as an
``error`` result naming the file and case instead of raising.
"""

from __future__ import annotations

import dataclasses
import inspect
import json
import math
import re
import struct
import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ._errors import (
    DegenerateError,
    InvalidArgumentError,
    IsectError,
    NonFiniteError,
    OutOfMemoryError,
)
from ._helpers import plane_from_points, point_in_polygon, polygon_normal, winding_number
from ._mesh import Mesh, MeshReport
from ._shape import Shape, Solid
from ._shapes import (
    Box,
    ConvexPolyhedron,
    Cylinder,
    Ellipsoid,
    InfiniteCylinder,
    Plane,
    Polygon,
    Quadric,
    Sphere,
    Triangle,
)
from ._types import HitKind

SCHEMA = "isect-cases/1"
DEFAULT_TOL = 1e-12

STATUS_ERRORS: dict[str, type[IsectError]] = {
    "E_ARG": InvalidArgumentError,
    "E_NONFINITE": NonFiniteError,
    "E_DEGENERATE": DegenerateError,
    "E_NOMEM": OutOfMemoryError,
}
KINDS = {"enter": HitKind.ENTER, "exit": HitKind.EXIT, "touch": HitKind.TOUCH}
KIND_NAMES = {int(v): k for k, v in KINDS.items()}
OPS = (
    "intersect",
    "contains",
    "mesh_check",
    "point_in_polygon2",
    "winding_number2",
    "polygon_normal",
    "plane_from_points",
    "spawn",
    "winding_number",
)
SHAPE_TYPES = (
    "plane",
    "sphere",
    "box",
    "triangle",
    "polygon",
    "convex",
    "cylinder",
    "infinite_cylinder",
    "ellipsoid",
    "quadric",
    "mesh",
)
#: The fields of ``expect.report`` (``isect_mesh_report``): the measures are
#: compared within tolerance, every other field exactly (``closed`` and
#: ``oriented`` as 0 | 1).
REPORT_FIELDS = tuple(f.name for f in dataclasses.fields(MeshReport))
REPORT_MEASURES = ("volume", "area")
REPORT_FLAGS = ("closed", "oriented")
OPT_FLAGS = ("cull_back", "any_hit")
#: op spawn: how far (in ulps of the hit point's largest coordinate) the spawned
#: origin may lie from the hit point, per coordinate
SPAWN_MAX_ULPS = 8
#: Case ids and counts are JSON numbers with an integral value within the
#: range where doubles hold every integer (the C runner's MAX_CASE_ID).
MAX_CASE_ID = 2**53
#: The deepest nesting of arrays and objects a file may have: cJSON's
#: CJSON_NESTING_LIMIT, which makes the C runner refuse a deeper file.
MAX_NESTING = 1000


class CaseFormatError(ValueError):
    """A file or case that does not follow the schema; ``field`` names the
    offending key (dotted path inside the case, e.g. ``shape.radius``)."""

    def __init__(self, field: str, problem: str) -> None:
        super().__init__(f"field {field!r}: {problem}" if field else problem)
        self.field = field
        self.problem = problem


# ------------------------------------------------------------------ reading


def num(x: Any, where: str = "") -> Any:
    """A corpus number ("inf", "-inf", "nan", hex-float strings, JSON numbers),
    recursively through lists. Anything else is a :class:`CaseFormatError`
    naming ``where``."""
    if isinstance(x, list):
        return [num(v, f"{where}[{i}]" if where else f"[{i}]") for i, v in enumerate(x)]
    if isinstance(x, str):
        low = x.strip().lower()
        if low in ("inf", "+inf", "infinity"):
            return math.inf
        if low in ("-inf", "-infinity"):
            return -math.inf
        if low == "nan":
            return math.nan
        try:
            return float.fromhex(x)
        except ValueError:
            raise CaseFormatError(where, f"{x!r} is not a number") from None
    if isinstance(x, bool):
        return x
    if isinstance(x, int):
        try:
            return float(x)
        except OverflowError:  # as the C runner's strtod reads such a literal
            return math.inf if x > 0 else -math.inf
    if isinstance(x, float):
        return x
    raise CaseFormatError(where, f"{x!r} is not a number")


def integer(x: Any, where: str, lo: int = -MAX_CASE_ID, hi: int = MAX_CASE_ID) -> int:
    """A JSON number with an integral value in [lo, hi], as the C runner reads
    integers (``cj_integer_value``): the number as a double, so ``2.0`` is 2
    and ``1.5``, ``1e300``, strings, bools and null are refused."""
    if x is None:
        raise CaseFormatError(where, "missing")
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise CaseFormatError(where, f"{x!r} is not an integer")
    try:
        v = float(x)
    except OverflowError:
        v = math.inf if x > 0 else -math.inf
    if not lo <= v <= hi:
        raise CaseFormatError(where, f"{x!r} is out of range [{lo}, {hi}]")
    if not v.is_integer():
        raise CaseFormatError(where, f"{x!r} is not an integer")
    return int(v)


def need(obj: Any, key: str, where: str = "") -> Any:
    """``obj[key]``, or a CaseFormatError naming the missing field."""
    path = f"{where}.{key}" if where else key
    if not isinstance(obj, dict):
        raise CaseFormatError(where, f"expected a JSON object, got {type(obj).__name__}")
    if key not in obj:
        raise CaseFormatError(path, "missing")
    return obj[key]


def _field(spec: dict[str, Any], key: str, where: str) -> Any:
    """A numeric field of a shape (numbers or lists of numbers)."""
    return num(need(spec, key, where), f"{where}.{key}")


def _rule_value(value: Any, where: str) -> Any:
    """A fill rule: "evenodd", "nonzero", "winding" (a mesh's rule; a polygon
    refuses it) or an integer (passed through)."""
    if isinstance(value, str) and value not in ("evenodd", "nonzero", "winding"):
        raise CaseFormatError(
            where, f"unknown rule {value!r} (evenodd, nonzero, winding or an integer)"
        )
    if not isinstance(value, (str, int)):
        raise CaseFormatError(where, f"{value!r} is not a rule")
    return value


def _faces(spec: dict[str, Any], where: str) -> list[list[int]]:
    """A mesh's faces: a list of lists of integer vertex indices (passed as
    they are, out-of-range and short faces included, for bad-input cases)."""
    faces = need(spec, "faces", where)
    path = f"{where}.faces"
    if not isinstance(faces, list):
        raise CaseFormatError(path, f"{faces!r} is not a list of faces (lists of vertex indices)")
    for i, face in enumerate(faces):
        if not isinstance(face, list):
            raise CaseFormatError(f"{path}[{i}]", f"{face!r} is not a list of vertex indices")
        for j, index in enumerate(face):
            if not isinstance(index, int) or isinstance(index, bool):
                raise CaseFormatError(f"{path}[{i}][{j}]", f"{index!r} is not an integer index")
    return faces


def build_shape(spec: dict[str, Any], where: str = "shape") -> Shape:
    """The Python shape for a case's ``shape`` object (constructor keys)."""
    kind = need(spec, "type", where)
    f = lambda key: _field(spec, key, where)  # noqa: E731
    builders: dict[str, Callable[[], Shape]] = {
        "plane": lambda: Plane(f("normal"), f("d")),
        "sphere": lambda: Sphere(f("center"), f("radius")),
        "box": lambda: Box(f("lo"), f("hi")),
        "triangle": lambda: Triangle(f("a"), f("b"), f("c")),
        "polygon": lambda: Polygon(
            f("vertices"), rule=_rule_value(spec.get("rule", "evenodd"), f"{where}.rule")
        ),
        "convex": lambda: ConvexPolyhedron(f("planes")),
        "cylinder": lambda: Cylinder(
            f("p0"), f("p1"), f("radius"), capped=spec.get("capped", True)
        ),
        "infinite_cylinder": lambda: InfiniteCylinder(f("point"), f("axis"), f("radius")),
        "ellipsoid": lambda: Ellipsoid(f("center"), f("radii")),
        "quadric": lambda: Quadric(f("coeffs")),
        "mesh": lambda: Mesh(f("vertices"), _faces(spec, where)),
    }
    if isinstance(kind, int) and not isinstance(kind, bool):
        raise CaseFormatError(
            f"{where}.type", f"integer type {kind} is c-only (flag the case 'c-only')"
        )
    if kind not in builders:
        raise CaseFormatError(
            f"{where}.type", f"unknown shape type {kind!r} (one of {', '.join(SHAPE_TYPES)})"
        )
    return builders[kind]()


def case_shape(case: dict[str, Any]) -> Shape:
    """The case's shape, transformed if the case has a transform."""
    shape = build_shape(need(case, "shape"))
    if "transform" in case:
        shape = shape.transformed(num(case["transform"], "transform"))
    return shape


def ray_args(case: dict[str, Any]) -> tuple[list[float], list[float], dict[str, Any]]:
    """origin, direction and the keyword options of an ``intersect`` case."""
    ray = need(case, "ray")
    if not isinstance(ray, dict):
        raise CaseFormatError("ray", "expected a JSON object")
    opts = case.get("opts", {})
    if not isinstance(opts, dict):
        raise CaseFormatError("opts", "expected a JSON object")
    flags = opts.get("flags", [])
    if not isinstance(flags, list):
        raise CaseFormatError("opts.flags", "expected a list of flag names")
    unknown = [f for f in flags if f not in OPT_FLAGS]
    if unknown:
        raise CaseFormatError(
            "opts.flags", f"unknown flags {unknown} (known: {', '.join(OPT_FLAGS)})"
        )
    kwargs: dict[str, Any] = {
        "tmin": num(ray.get("tmin", 0.0), "ray.tmin"),
        "tmax": num(ray.get("tmax", "inf"), "ray.tmax"),
        "cull_back": "cull_back" in flags,
        "any_hit": "any_hit" in flags,
    }
    if "eps" in opts:
        kwargs["eps"] = num(opts["eps"], "opts.eps")
    return num(need(ray, "org", "ray"), "ray.org"), num(need(ray, "dir", "ray"), "ray.dir"), kwargs


def close(actual: float, expected: float, tol: float) -> bool:
    """The corpus rule: |a - e| <= tol * max(1, |e|); an expected inf must match."""
    if math.isinf(expected) or math.isnan(expected):
        return actual == expected or (math.isnan(expected) and math.isnan(actual))
    return abs(actual - expected) <= tol * max(1.0, abs(expected))


def tolerances(case: dict[str, Any]) -> dict[str, float]:
    """The case's tolerances with the defaults filled in."""
    tol = {key: DEFAULT_TOL for key in ("t", "point", "normal", "uv", *REPORT_MEASURES, "winding")}
    given = case.get("tol", {})
    if not isinstance(given, dict):
        raise CaseFormatError("tol", "expected a JSON object")
    tol.update({k: float(num(v, f"tol.{k}")) for k, v in given.items()})
    return tol


# ------------------------------------------------------------------ running


class CaseFailure(AssertionError):
    """A case whose result differs from its expectation."""


@dataclass
class Result:
    """The outcome of one case: ``status`` is pass, fail, skip or error."""

    file: str
    id: Any
    name: str
    status: str
    message: str = ""
    expected: Any = None
    actual: Any = None
    extra: dict[str, Any] = field(default_factory=dict)

    def as_json(self) -> dict[str, Any]:
        """The result as plain JSON values (non-finite numbers as strings)."""
        out = {
            "file": self.file,
            "id": self.id,
            "name": self.name,
            "status": self.status,
            "message": self.message,
        }
        if self.status == "fail":
            out["expected"] = jsonable(self.expected)
            out["actual"] = jsonable(self.actual)
        return out


def jsonable(x: Any) -> Any:
    """x with non-finite floats spelled "inf", "-inf", "nan" (as the corpus)."""
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")
    return x


def _bits(x: float) -> bytes:
    return struct.pack("<d", x)


def _hit_dict(hit: Any) -> dict[str, Any]:
    """A Hit as the corpus writes it."""
    return {
        "t": float(hit.t),
        "point": [float(v) for v in hit.point],
        "normal": [float(v) for v in hit.normal],
        "uv": [float(v) for v in hit.uv],
        "prim": int(hit.prim),
        "kind": KIND_NAMES.get(int(hit.kind), str(int(hit.kind))),
    }


def _same_record(record: Any, hit: Any) -> bool:
    """A HIT_DTYPE record and a Hit hold the same bits."""
    ours = [
        float(record["t"]),
        *map(float, record["point"]),
        *map(float, record["normal"]),
        *map(float, record["uv"]),
    ]
    theirs = [hit.t, *hit.point, *hit.normal, *hit.uv]
    return (
        all(_bits(a) == _bits(b) for a, b in zip(ours, theirs))
        and int(record["prim"]) == hit.prim
        and int(record["kind"]) == int(hit.kind)
    )


def status_of(error: BaseException) -> str:
    """The corpus status name of an exception raised by the package."""
    for name, cls in STATUS_ERRORS.items():
        if isinstance(error, cls):
            return name
    return type(error).__name__


def _check_hits(case: dict[str, Any], hits: list[Any]) -> None:
    expect = case["expect"]
    tol = tolerances(case)
    count = integer(need(expect, "count", "expect"), "expect.count", 0, 2**31 - 1)
    wanted = expect.get("hits", [])
    if not isinstance(wanted, list):
        raise CaseFormatError("expect.hits", "expected a list of hits")
    if len(hits) != count:
        raise CaseFailure(f"count: expected {count}, actual {len(hits)}")
    for i, (got, want) in enumerate(zip(hits, wanted)):
        where = f"expect.hits[{i}]"
        t = num(need(want, "t", where), f"{where}.t")
        if not close(got.t, t, tol["t"]):
            raise CaseFailure(f"hit {i} t: expected {t!r}, actual {got.t!r}")
        for key, attr in (("point", got.point), ("normal", got.normal), ("uv", got.uv)):
            if key in want:
                exp = num(want[key], f"{where}.{key}")
                if len(exp) != len(attr) or not all(
                    close(a, e, tol[key]) for a, e in zip(attr, exp)
                ):
                    raise CaseFailure(f"hit {i} {key}: expected {exp}, actual {list(attr)}")
        if "prim" in want and got.prim != want["prim"]:
            raise CaseFailure(f"hit {i} prim: expected {want['prim']}, actual {got.prim}")
        if "kind" in want:
            if want["kind"] not in KINDS:
                raise CaseFormatError(
                    f"{where}.kind", f"unknown kind {want['kind']!r} (enter, exit or touch)"
                )
            if got.kind != KINDS[want["kind"]]:
                raise CaseFailure(
                    f"hit {i} kind: expected {want['kind']}, "
                    f"actual {KIND_NAMES.get(int(got.kind), int(got.kind))}"
                )


def _run_intersect(case: dict[str, Any]) -> dict[str, Any]:
    """An ``intersect`` case expected to succeed; returns the actual result."""
    org, dirn, kwargs = ray_args(case)
    shape = case_shape(case)
    hits = shape.intersect_all(org, dirn, **kwargs)
    actual = {"status": "ok", "count": len(hits), "hits": [_hit_dict(h) for h in hits]}
    try:
        _check_hits(case, hits)
        closest = shape.intersect(org, dirn, **kwargs)
        if hits:
            if not _same_record(closest, hits[0]):
                raise CaseFailure(f"batch closest hit {closest} != first hit {hits[0]}")
        elif not (
            closest["kind"] == HitKind.MISS and closest["t"] == math.inf and closest["prim"] == -1
        ):
            raise CaseFailure(f"batch closest hit {closest} is not a MISS")
        offsets, all_hits = shape.intersect_all_batch(org, dirn, **kwargs)
        if offsets.tolist() != [0, len(hits)] or not all(
            _same_record(r, h) for r, h in zip(all_hits, hits)
        ):
            raise CaseFailure("intersect_all_batch hits differ from intersect_all")
    except CaseFailure as failure:
        failure.actual = actual  # type: ignore[attr-defined]
        raise
    return actual


def _spawn_inputs(case: dict[str, Any]) -> tuple[Shape, Any, list[float]]:
    """The shape, the primary ray's closest-hit record (MISS when it misses)
    and the secondary direction of a ``spawn`` case."""
    org, dirn, kwargs = ray_args(case)
    direction = num(need(case, "dir"), "dir")
    if not isinstance(direction, list) or len(direction) != 3:
        raise CaseFormatError("dir", "expected 3 numbers")
    shape = case_shape(case)
    first = shape.intersect(org, dirn, tmin=kwargs["tmin"], tmax=kwargs["tmax"])
    return shape, first, direction


def _run_spawn(case: dict[str, Any]) -> dict[str, Any]:
    """A ``spawn`` case expected to succeed; returns the secondary ray's hits."""
    shape, first, direction = _spawn_inputs(case)
    try:
        ray = shape.spawn(first, direction)
    except IsectError as error:
        failure = CaseFailure(f"spawn: expected ok, actual {status_of(error)}: {error}")
        failure.actual = {"status": status_of(error), "message": str(error)}  # type: ignore[attr-defined]
        raise failure from None
    org, dirn = [float(v) for v in ray["org"]], [float(v) for v in ray["dir"]]
    point = [float(v) for v in first["point"]]
    unit = float(np.spacing(max(abs(v) for v in point)))
    problems = []
    if [_bits(v) for v in dirn] != [_bits(float(v)) for v in direction]:
        problems.append(f"spawned dir {dirn} != dir {direction}")
    if not (ray["tmin"] == 0.0 and ray["tmax"] == math.inf):
        problems.append(f"spawned tmin, tmax = {float(ray['tmin'])}, {float(ray['tmax'])} (want 0, inf)")
    for k in range(3):
        if not abs(org[k] - point[k]) <= SPAWN_MAX_ULPS * unit:
            problems.append(
                f"spawned org[{k}] {org[k]!r} is {abs(org[k] - point[k]) / unit:.3g} ulps from the "
                f"hit point {point[k]!r} (at most {SPAWN_MAX_ULPS})"
            )
    hits = shape.intersect_all(org, dirn, tmin=float(ray["tmin"]), tmax=float(ray["tmax"]))
    actual = {"status": "ok", "count": len(hits), "hits": [_hit_dict(h) for h in hits]}
    try:
        if problems:
            raise CaseFailure("; ".join(problems))
        _check_hits(case, hits)
        # the batch form: the same ray twice, bit for bit
        twice = shape.spawn(np.stack([first, first]), np.array([direction, direction]))
        if twice.tobytes() != np.stack([ray, ray]).tobytes():
            raise CaseFailure("spawn of a batch of two differs from the single call")
        closest = shape.intersect_rays(np.stack([ray]))[0]  # the zero-copy path of spawned rays
        if hits:
            if not _same_record(closest, hits[0]):
                raise CaseFailure(f"batch closest hit {closest} != first hit {hits[0]}")
        elif not (closest["kind"] == HitKind.MISS and closest["t"] == math.inf):
            raise CaseFailure(f"batch closest hit {closest} is not a MISS")
    except CaseFailure as failure:
        failure.actual = actual  # type: ignore[attr-defined]
        raise
    return actual


def _run_spawn_error(case: dict[str, Any], status: str) -> None:
    shape, first, direction = _spawn_inputs(case)
    _expect_error(status, lambda: shape.spawn(first, direction), "spawn")


def _ray_is_bad(case: dict[str, Any]) -> bool:
    org, dirn, kwargs = ray_args(case)
    try:
        values = [float(v) for v in [*org, *dirn]]
    except (TypeError, ValueError):
        return False
    return (
        not all(math.isfinite(v) for v in values)
        or all(v == 0 for v in dirn)
        or math.isnan(kwargs["tmin"])
        or math.isnan(kwargs["tmax"])
    )


def _expect_error(status: str, call: Callable[[], Any], what: str) -> None:
    """``call`` must raise the error of ``status``."""
    error = STATUS_ERRORS[status]
    try:
        got = call()
    except error:
        return
    except IsectError as other:
        raise CaseFailure(f"{what}: expected {status}, actual {status_of(other)}: {other}") from None
    if isinstance(got, list):  # intersect_all
        actual: Any = {"status": "ok", "count": len(got), "hits": [_hit_dict(h) for h in got]}
    elif isinstance(got, dict):  # an op's result
        actual = {"status": "ok", **got}
    else:
        actual = {"status": "ok", "result": repr(got)}
    failure = CaseFailure(f"{what}: expected {status}, actual ok")
    failure.actual = actual  # type: ignore[attr-defined]
    raise failure


def _run_intersect_error(case: dict[str, Any], status: str) -> None:
    org, dirn, kwargs = ray_args(case)
    _expect_error(status, lambda: case_shape(case).intersect_all(org, dirn, **kwargs), "scalar")
    _expect_error(status, lambda: case_shape(case).intersect(org, dirn, **kwargs), "batch")
    if _ray_is_bad(case):
        # errors="mark": a bad ray is marked INVALID unless the shape or the
        # options are bad too, which raise whatever the ray.
        try:
            record = case_shape(case).intersect(org, dirn, errors="mark", **kwargs)
        except STATUS_ERRORS[status]:
            return
        if not (record["kind"] == HitKind.INVALID and math.isnan(record["t"])):
            raise CaseFailure(f"errors='mark': bad ray not marked INVALID: {record}")


def _contains(case: dict[str, Any]) -> bool:
    shape = case_shape(case)
    if not isinstance(shape, Solid):
        # Thin surfaces have no contains() in Python; C answers E_ARG.
        raise InvalidArgumentError("thin surfaces have no inside")
    point = num(need(case, "point"), "point")
    if isinstance(shape, Mesh):
        # The mesh's containment rule (isect_shape.flags in C).
        rule = _rule_value(case["shape"].get("rule", "evenodd"), "shape.rule")
        return bool(shape.contains(point, rule=rule))
    return bool(shape.contains(point))


def _winding_number(case: dict[str, Any]) -> dict[str, Any]:
    """``Mesh.winding_number`` of all the points at once (the result), and of
    each point alone, which must meet the same tolerance."""
    shape = case_shape(case)
    if not isinstance(shape, Mesh):
        # Only meshes have the method in Python; C answers E_ARG.
        raise InvalidArgumentError("only meshes have a generalized winding number")
    points = num(need(case, "points"), "points")
    accuracy = num(case.get("accuracy", 0.0), "accuracy")
    batch = shape.winding_number(np.array(points, dtype=np.float64).reshape(-1, 3), accuracy)
    got = [float(w) for w in batch]
    expect = case.get("expect", {})
    if expect.get("status") == "ok":
        want = num(need(expect, "winding", "expect"), "expect.winding")
        tol = tolerances(case)["winding"]
        for i, (p, w) in enumerate(zip(points, want)):
            alone = float(shape.winding_number(p, accuracy))
            if not close(alone, w, tol):
                failure = CaseFailure(f"point {i} alone: expected {w!r}, actual {alone!r}")
                failure.actual = {"status": "ok", "winding": got}  # type: ignore[attr-defined]
                raise failure
    return {"winding": got}


def _mesh_check(case: dict[str, Any]) -> dict[str, Any]:
    """``Mesh.check()`` as the corpus writes the report (flags as 0 | 1)."""
    if need(need(case, "shape"), "type", "shape") != "mesh":
        raise CaseFormatError("shape.type", "op 'mesh_check' needs a 'mesh' shape")
    shape = case_shape(case)
    assert isinstance(shape, Mesh)
    report = dataclasses.asdict(shape.check())
    return {"report": {k: int(v) if isinstance(v, bool) else v for k, v in report.items()}}


def _rule(case: dict[str, Any]) -> Any:
    return _rule_value(case.get("rule", "evenodd"), "rule")


def _arg(case: dict[str, Any], key: str) -> Any:
    return num(need(case, key), key)


OP_CALLS: dict[str, Callable[[dict[str, Any]], dict[str, Any]]] = {
    "contains": lambda c: {"inside": int(_contains(c))},
    "mesh_check": _mesh_check,
    "point_in_polygon2": lambda c: {
        "inside": int(point_in_polygon(_arg(c, "polygon"), _arg(c, "point"), rule=_rule(c)))
    },
    "winding_number2": lambda c: {
        "winding": int(winding_number(_arg(c, "polygon"), _arg(c, "point")))
    },
    "polygon_normal": lambda c: {"normal": polygon_normal(_arg(c, "vertices")).tolist()},
    "plane_from_points": lambda c: {"plane": plane_from_points(_arg(c, "vertices")).tolist()},
    "winding_number": _winding_number,
}


def _report_mismatches(expect: Any, actual: dict[str, Any], tol: dict[str, float]) -> list[str]:
    """The fields of a ``mesh_check`` report that differ from ``expect.report``
    (every field must be given)."""
    where = "expect.report"
    if not isinstance(expect, dict):
        raise CaseFormatError(where, "expected a JSON object")
    unknown = sorted(set(expect) - set(REPORT_FIELDS))
    if unknown:
        raise CaseFormatError(
            f"{where}.{unknown[0]}", f"unknown report field (one of {', '.join(REPORT_FIELDS)})"
        )
    wrong = []
    for name in REPORT_FIELDS:
        want, got = need(expect, name, where), actual[name]
        if name in REPORT_MEASURES:
            exp = num(want, f"{where}.{name}")
            if not isinstance(exp, float):
                raise CaseFormatError(f"{where}.{name}", f"{want!r} is not a number")
            if not close(got, exp, tol[name]):
                wrong.append(f"{name}: expected {exp!r}, actual {got!r}")
            continue
        if not isinstance(want, int) or (isinstance(want, bool) and name not in REPORT_FLAGS):
            raise CaseFormatError(f"{where}.{name}", f"{want!r} is not an integer")
        if name in REPORT_FLAGS and want not in (0, 1):
            raise CaseFormatError(f"{where}.{name}", f"{want!r} is not 0 or 1")
        if got != int(want):
            wrong.append(f"{name}: expected {int(want)}, actual {got}")
    return wrong


def _compare(case: dict[str, Any], got: dict[str, Any]) -> None:
    """An op's result against ``expect`` (the keys it gives; a report in full)."""
    expect, tol = case["expect"], tolerances(case)
    wrong: list[str] = []
    for key, value in got.items():
        if key == "report":
            report = need(expect, "report", "expect")
            wrong += [f"report.{w}" for w in _report_mismatches(report, value, tol)]
        elif key not in expect:
            continue
        elif isinstance(value, list):
            exp = num(expect[key], f"expect.{key}")
            t = tol.get(key, tol["normal"])
            if len(value) != len(exp) or not all(close(a, e, t) for a, e in zip(value, exp)):
                wrong.append(f"{key}: expected {exp}, actual {value}")
        elif value != expect[key]:
            wrong.append(f"{key}: expected {expect[key]!r}, actual {value!r}")
    if wrong:
        failure = CaseFailure("; ".join(wrong))
        failure.actual = {"status": "ok", **got}  # type: ignore[attr-defined]
        raise failure


def check_case(case: dict[str, Any]) -> dict[str, Any] | None:
    """Run one case. Returns the actual result (None for a skipped c-only
    case); raises :class:`CaseFailure` (with ``.actual`` when known) if the
    result differs from ``expect``, :class:`CaseFormatError` if the case does
    not follow the schema."""
    if not isinstance(case, dict):
        raise CaseFormatError("", f"a case must be a JSON object, got {type(case).__name__}")
    flags = case.get("flags", [])
    if not isinstance(flags, list):
        raise CaseFormatError("flags", "expected a list of flag names")
    if "c-only" in flags:
        return None
    op = case.get("op", "intersect")
    if op not in OPS:
        raise CaseFormatError("op", f"unknown op {op!r} (one of {', '.join(OPS)})")
    expect = need(case, "expect")
    status = need(expect, "status", "expect")
    if status != "ok" and status not in STATUS_ERRORS:
        raise CaseFormatError(
            "expect.status", f"unknown status {status!r} (ok, {', '.join(STATUS_ERRORS)})"
        )
    if op == "intersect":
        if status == "ok":
            return _run_intersect(case)
        _run_intersect_error(case, status)
        return {"status": status}
    if op == "spawn":
        if status == "ok":
            return _run_spawn(case)
        _run_spawn_error(case, status)
        return {"status": status}
    run = OP_CALLS[op]
    if status != "ok":
        _expect_error(status, lambda: run(case), op)
        return {"status": status}
    try:
        got = run(case)
    except IsectError as error:
        failure = CaseFailure(f"expected ok, actual {status_of(error)}: {error}")
        actual = {"status": status_of(error), "message": str(error)}
        failure.actual = actual  # type: ignore[attr-defined]
        raise failure from None
    _compare(case, got)
    return {"status": "ok", **got}


def load_document(path: Path) -> dict[str, Any]:
    """A case file's parsed document, its header checked; CaseFormatError
    otherwise."""
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise CaseFormatError("", f"cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise CaseFormatError("", "not UTF-8 text") from None
    doc = parse_json(text)
    if not isinstance(doc, dict):
        raise CaseFormatError("", "the file must hold one JSON object")
    if doc.get("schema") != SCHEMA:
        raise CaseFormatError("schema", f"expected {SCHEMA!r}, got {doc.get('schema')!r}")
    cases = need(doc, "cases")
    if not isinstance(cases, list):
        raise CaseFormatError("cases", "expected a list of cases")
    number = integer(doc.get("number_of_cases"), "number_of_cases", 0)
    if number != len(cases):
        raise CaseFormatError("number_of_cases", f"says {number} but there are {len(cases)} cases")
    return doc


def _nesting(text: str) -> int:
    """The deepest nesting of arrays and objects in JSON text (brackets inside
    strings are not counted)."""
    depth = deepest = 0
    for token in _BRACKETS.finditer(text):
        c = token.group()
        if c in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif c in "]}":
            depth -= 1
    return deepest


#: Strings (skipped whole, escapes included) and brackets.
_BRACKETS = re.compile(r'"(?:[^"\\]|\\.)*"?|[\[\]{}]')


def _no_constant(name: str) -> Any:
    """json's hook for NaN / Infinity / -Infinity, which JSON does not have."""
    spelled = "nan" if name == "NaN" else name.lower().replace("infinity", "inf")
    raise CaseFormatError("", f"not valid JSON: {name} (the corpus writes \"{spelled}\")")


def _first_key_wins(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """An object with each key's first value, as the C runner (cJSON) reads a
    repeated key."""
    obj: dict[str, Any] = {}
    for key, value in pairs:
        obj.setdefault(key, value)
    return obj


def parse_json(text: str) -> Any:
    """A file's JSON value, read as the C runner reads it: strict JSON (no
    NaN / Infinity literals), at most MAX_NESTING levels deep, a repeated key
    meaning its first value. Anything else is a CaseFormatError (never a
    RecursionError)."""
    depth = _nesting(text)
    if depth > MAX_NESTING:
        raise CaseFormatError("", f"nested {depth} levels deep (at most {MAX_NESTING})")
    # Room for the parser's recursion at that depth, above the caller's frames.
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, len(inspect.stack(0)) + depth + 100))
    try:
        return json.loads(text, parse_constant=_no_constant, object_pairs_hook=_first_key_wins)
    except json.JSONDecodeError as error:
        raise CaseFormatError(
            "", f"not valid JSON: {error.msg} at line {error.lineno} column {error.colno}"
        ) from None
    except RecursionError:  # pragma: no cover - the depth was checked
        raise CaseFormatError("", "nested too deeply") from None
    finally:
        sys.setrecursionlimit(limit)


def case_id(case: Any) -> int:
    """The case's ``id``: required, an integer within +-2**53."""
    if not isinstance(case, dict):
        raise CaseFormatError("", f"a case must be a JSON object, got {type(case).__name__}")
    return integer(case.get("id"), "id")


def run_case(case: Any, file: str, index: int) -> Result:
    """One case as a :class:`Result` (never raises for a bad case)."""
    name = str(case.get("name", "")) if isinstance(case, dict) else ""
    expected = case.get("expect") if isinstance(case, dict) else None
    try:
        ident: Any = case_id(case)
    except CaseFormatError as error:
        return Result(file, f"#{index}", name, "error", f"bad case: {error}",
                      extra={"field": error.field})
    try:
        actual = check_case(case)
    except CaseFormatError as error:
        return Result(file, ident, name, "error", f"bad case: {error}", extra={"field": error.field})
    except CaseFailure as failure:
        return Result(
            file, ident, name, "fail", str(failure), expected, getattr(failure, "actual", None)
        )
    except IsectError as error:  # an unexpected library error
        return Result(
            file, ident, name, "fail", f"unexpected {status_of(error)}: {error}", expected,
            {"status": status_of(error), "message": str(error)},
        )  # fmt: skip
    except RecursionError:  # a value nested deeper than a field can be
        return Result(file, ident, name, "error", "bad case: a field is nested too deeply")
    except Exception as error:  # noqa: BLE001 - a case shaped in a way not foreseen
        return Result(
            file, ident, name, "error",
            f"bad case: cannot run it ({type(error).__name__}: {error})",
        )  # fmt: skip
    if actual is None:
        return Result(file, ident, name, "skip", "c-only: not expressible through the Python API")
    return Result(file, ident, name, "pass", "", expected, actual)


def run_files(paths: Iterable[str | Path]) -> list[Result]:
    """Every case of every file; a file that cannot be read or does not follow
    the schema gives one ``error`` result (id None)."""
    results: list[Result] = []
    for p in paths:
        path = Path(p)
        try:
            doc = load_document(path)
        except CaseFormatError as error:
            msg = f"bad file: {error}"
            results.append(Result(str(p), None, "", "error", msg, extra={"field": error.field}))
            continue
        seen: set[Any] = set()
        for index, case in enumerate(doc["cases"]):
            result = run_case(case, str(p), index)
            if isinstance(result.id, int):  # a well-formed id
                if result.id in seen:
                    result = Result(
                        str(p), result.id, result.name, "error",
                        f"bad case: field 'id': duplicate id {result.id}", extra={"field": "id"},
                    )  # fmt: skip
                seen.add(result.id)
            results.append(result)
    return results
