"""Dispatch: the expected result of one case (status, hits, inside, ...).

Validation follows the error classes of isect.h; a case must have at most
one kind of defect (otherwise the status would depend on the order of the
checks, which isect.h does not fix), and the reference refuses it.
"""
from __future__ import annotations

import math
from typing import Any, Callable

import box
import convex
import cylinder
import ellipsoid
import mesh
import plane
import polygon
import polygon2d
import quadric
import sphere
import transformed
import triangle
from exact import DesignError, q, qv
from model import Ctx, EPS_DEFAULT, XRay, finish, hit_json

Solver = Callable[[dict, XRay, Ctx], list]

SOLVERS: dict[str, Solver] = {
    "plane": plane.solve, "sphere": sphere.solve, "box": box.solve, "triangle": triangle.solve,
    "polygon": polygon.solve, "convex": convex.solve, "cylinder": cylinder.solve_finite,
    "infinite_cylinder": cylinder.solve_infinite, "ellipsoid": ellipsoid.solve, "quadric": quadric.solve,
    "mesh": mesh.solve,
}

CONTAINS = {
    "sphere": sphere.contains, "box": box.contains, "convex": convex.contains,
    "cylinder": cylinder.contains_finite, "infinite_cylinder": cylinder.contains_infinite,
    "ellipsoid": ellipsoid.contains, "quadric": quadric.contains,
    "mesh": mesh.contains,
}

#: the numeric keys of each shape, all of which must be finite
NUMBERS = {
    "plane": ("normal", "d"), "sphere": ("center", "radius"), "box": ("lo", "hi"),
    "triangle": ("a", "b", "c"), "polygon": ("vertices",), "convex": ("planes",),
    "cylinder": ("p0", "p1", "radius"), "infinite_cylinder": ("point", "axis", "radius"),
    "ellipsoid": ("center", "radii"), "quadric": ("coeffs",), "mesh": ("vertices",),
}


def _flat(x: Any) -> list[float]:
    if isinstance(x, (list, tuple)):
        return [y for e in x for y in _flat(e)]
    return [x]


def culls_back(shape: dict) -> bool:
    """ISECT_CULL_BACK applies: thin surfaces and the faces of meshes."""
    return is_thin(shape) or shape["type"] == "mesh"


def is_thin(shape: dict) -> bool:
    t = shape["type"]
    return t in ("plane", "triangle", "polygon") or (t == "cylinder" and not shape["capped"])


def shape_status(shape: dict) -> set[str]:
    """Statuses a shape alone provokes."""
    t = shape["type"]
    if isinstance(t, int):
        return {"E_ARG"}        # 0 and 12+ are unknown; 11 (mesh) has no mesh here
    if t == "mesh":
        return mesh.status(shape)
    out: set[str] = set()
    if not all(math.isfinite(x) for k in NUMBERS[t] for x in _flat(shape[k])):
        out.add("E_NONFINITE")
    if t == "sphere" and shape["radius"] < 0:
        out.add("E_ARG")
    if t in ("cylinder", "infinite_cylinder") and shape["radius"] < 0:
        out.add("E_ARG")
    if t == "cylinder" and shape["capped"] not in (True, False, 0, 1):
        out.add("E_ARG")
    if t == "ellipsoid" and any(r < 0 for r in shape["radii"]):
        out.add("E_ARG")
    if t == "box" and any(a > b for a, b in zip(shape["lo"], shape["hi"])):
        out.add("E_ARG")
    if t == "polygon":
        if len(shape["vertices"]) < 3 or shape["rule"] not in ("evenodd", "nonzero", 0, 1):
            out.add("E_ARG")
    if t == "convex" and len(shape["planes"]) < 1:
        out.add("E_ARG")
    return out


def ray_status(r: dict) -> set[str]:
    out: set[str] = set()
    if not all(math.isfinite(x) for x in r["org"] + r["dir"]):
        out.add("E_NONFINITE")
    if math.isnan(r.get("tmin", 0.0)) or math.isnan(r.get("tmax", math.inf)):
        out.add("E_NONFINITE")
    if all(x == 0 for x in r["dir"]):
        out.add("E_DEGENERATE")
    return out


def opts_eps(o: dict | None) -> tuple[float, set[str]]:
    eps = (o or {}).get("eps", EPS_DEFAULT)
    if math.isnan(eps) or math.isinf(eps):
        return eps, {"E_NONFINITE"}
    if eps < 0:
        return eps, {"E_ARG"}
    return eps, set()


def one_status(statuses: set[str], name: str) -> str | None:
    if len(statuses) > 1:
        raise DesignError(f"{name}: several error classes at once {sorted(statuses)}")
    return next(iter(statuses), None)


def evaluate(c: dict) -> dict:
    """The expect object of a case."""
    op = c.get("op", "intersect")
    if op in ("point_in_polygon2", "winding_number2", "polygon_normal", "plane_from_points"):
        return polygon2d.evaluate(c)
    shape = c["shape"]
    if op == "mesh_check":
        status = one_status(shape_status(shape), c["name"])
        return {"status": status} if status else {"status": "ok", "report": mesh.report(shape)}
    if op == "contains":
        st = shape_status(shape)
        if not all(math.isfinite(x) for x in c["point"]):
            st.add("E_NONFINITE")
        if not isinstance(shape["type"], int) and is_thin(shape):
            st.add("E_ARG")
        if shape["type"] == "mesh" and not st and not mesh.is_closed(shape):
            st.add("E_ARG")
        status = one_status(st, c["name"])
        if status:
            return {"status": status}
        return {"status": "ok", "inside": int(CONTAINS[shape["type"]](shape, qv(c["point"])))}
    if op != "intersect":
        raise ValueError(op)

    eps, st = opts_eps(c.get("opts"))
    st |= ray_status(c["ray"]) | shape_status(shape)
    m = c.get("transform")
    if m is not None:
        ts = transformed.check(m)
        if ts:
            st.add(ts)
    status = one_status(st, c["name"])
    if status:
        return {"status": status}

    r = XRay.from_json(c["ray"])
    ctx = Ctx(q(eps))
    solver = SOLVERS[shape["type"]]
    if m is not None:
        hits = transformed.solve(m, solver, shape, r, ctx)
        ctx = Ctx(ctx.eps, transformed.object_ray(m, r)[1])
    else:
        hits = solver(shape, r, ctx)
    cull = "cull_back" in (c.get("opts") or {}).get("flags", [])
    kept = finish(hits, r, ctx, culls_back(shape), cull)
    if "any_hit" in (c.get("opts") or {}).get("flags", []):
        # isect.h: the first hit found (a mesh's traversal order decides which),
        # for analytic shapes the closest. Only cases with one candidate are
        # decided by the contract alone.
        if len(kept) > 1 and shape["type"] == "mesh":
            raise DesignError("any_hit on a mesh with several hits: which one is unspecified")
        kept = kept[:1]
    return {"status": "ok", "count": len(kept), "hits": [hit_json(h, r) for h in kept]}

