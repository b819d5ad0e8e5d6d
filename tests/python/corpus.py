"""Reading the golden corpus (tests/cases/*.json, schema ``isect-cases/1``) and
turning its cases into calls of the Python API. See tests/cases/README.md."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import isect

CASES_DIR = Path(__file__).resolve().parents[1] / "cases"
SCHEMA = "isect-cases/1"

STATUS_ERRORS: dict[str, type[isect.IsectError]] = {
    "E_ARG": isect.InvalidArgumentError,
    "E_NONFINITE": isect.NonFiniteError,
    "E_DEGENERATE": isect.DegenerateError,
    "E_NOMEM": isect.OutOfMemoryError,
}
KINDS = {"enter": isect.HitKind.ENTER, "exit": isect.HitKind.EXIT, "touch": isect.HitKind.TOUCH}
DEFAULT_TOL = 1e-12


def num(x: Any) -> Any:
    """A corpus number ("inf", "-inf", "nan", hex-float strings, JSON numbers),
    recursively through lists."""
    if isinstance(x, list):
        return [num(v) for v in x]
    if isinstance(x, str):
        low = x.strip().lower()
        if low in ("inf", "+inf", "infinity"):
            return math.inf
        if low in ("-inf", "-infinity"):
            return -math.inf
        if low == "nan":
            return math.nan
        return float.fromhex(x)
    if isinstance(x, bool):
        return x
    return float(x)


def load_files() -> list[tuple[Path, dict[str, Any]]]:
    """Every corpus file with its parsed document, sorted by name."""
    return [
        (path, json.loads(path.read_text(encoding="utf-8")))
        for path in sorted(CASES_DIR.glob("*.json"))
    ]


def build_shape(spec: dict[str, Any]) -> isect.Shape:
    """The Python shape for a case's ``shape`` object (constructor keys)."""
    kind = spec["type"]
    builders: dict[str, Callable[[], isect.Shape]] = {
        "plane": lambda: isect.Plane(num(spec["normal"]), num(spec["d"])),
        "sphere": lambda: isect.Sphere(num(spec["center"]), num(spec["radius"])),
        "box": lambda: isect.Box(num(spec["lo"]), num(spec["hi"])),
        "triangle": lambda: isect.Triangle(num(spec["a"]), num(spec["b"]), num(spec["c"])),
        "polygon": lambda: isect.Polygon(num(spec["vertices"]), rule=spec.get("rule", "evenodd")),
        "convex": lambda: isect.ConvexPolyhedron(num(spec["planes"])),
        "cylinder": lambda: isect.Cylinder(
            num(spec["p0"]), num(spec["p1"]), num(spec["radius"]), capped=spec.get("capped", True)
        ),
        "infinite_cylinder": lambda: isect.InfiniteCylinder(
            num(spec["point"]), num(spec["axis"]), num(spec["radius"])
        ),
        "ellipsoid": lambda: isect.Ellipsoid(num(spec["center"]), num(spec["radii"])),
        "quadric": lambda: isect.Quadric(num(spec["coeffs"])),
    }
    if kind not in builders:
        raise KeyError(f"shape type {kind!r} has no Python constructor")
    shape = builders[kind]()
    return shape


def case_shape(case: dict[str, Any]) -> isect.Shape:
    """The case's shape, transformed if the case has a transform."""
    shape = build_shape(case["shape"])
    if "transform" in case:
        shape = shape.transformed(num(case["transform"]))
    return shape


def ray_args(case: dict[str, Any]) -> tuple[list[float], list[float], dict[str, Any]]:
    """origin, direction and the keyword options of an ``intersect`` case."""
    ray = case["ray"]
    opts = case.get("opts", {})
    flags = opts.get("flags", [])
    unknown = set(flags) - {"cull_back", "any_hit"}
    if unknown:
        raise KeyError(f"unknown opts flags {sorted(unknown)}")
    kwargs: dict[str, Any] = {
        "tmin": num(ray.get("tmin", 0.0)),
        "tmax": num(ray.get("tmax", "inf")),
        "cull_back": "cull_back" in flags,
        "any_hit": "any_hit" in flags,
    }
    if "eps" in opts:
        kwargs["eps"] = num(opts["eps"])
    return num(ray["org"]), num(ray["dir"]), kwargs


def close(actual: float, expected: float, tol: float) -> bool:
    """The corpus rule: |a - e| <= tol * max(1, |e|); an expected inf must match."""
    if math.isinf(expected) or math.isnan(expected):
        return actual == expected or (math.isnan(expected) and math.isnan(actual))
    return abs(actual - expected) <= tol * max(1.0, abs(expected))


def tolerances(case: dict[str, Any]) -> dict[str, float]:
    """The case's tolerances with the defaults filled in."""
    tol = {key: DEFAULT_TOL for key in ("t", "point", "normal", "uv")}
    tol.update({k: float(num(v)) for k, v in case.get("tol", {}).items()})
    return tol
