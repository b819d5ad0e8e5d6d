# SPDX-License-Identifier: Apache-2.0
"""Dispatch: the expected result of one case (status, hits, inside, ...).

Validation follows the error classes of isect.h; a case must have at most
one kind of defect (otherwise the status would depend on the order of the
checks, which isect.h does not fix), and the reference refuses it.
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Callable

import mpmath

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
import winding
from exact import DesignError, cmp, dot, mp, norm2, point_on_ray, q, qv, to_double
from model import INF, Ctx, EPS_DEFAULT, XRay, finish, hit_json

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


def _solve(shape: dict, m: list | None, r: XRay, ctx: Ctx) -> tuple[list, Ctx]:
    """The hits of a shape (transformed when m is given) and the decision context."""
    solver = SOLVERS[shape["type"]]
    if m is None:
        return solver(shape, r, ctx), ctx
    hits = transformed.solve(m, solver, shape, r, ctx)
    return hits, Ctx(ctx.eps, transformed.object_ray(m, r)[1])


#: op spawn: every crossing but the one left at t = 0 lies this many spawn offsets
#: (8 ulps of the hit point's largest coordinate) away from the exact hit point
SPAWN_MARGIN = 2 ** 16


def evaluate_spawn(c: dict) -> dict:
    """op spawn (isect_spawn_ray): the status, and the hits of the secondary ray.

    The primary ray (default options) must be valid; its first hit is the one
    spawned from, and when it has none the runner passes the MISS record of the
    closest-hit batch (E_ARG). The secondary ray starts at the *exact* first hit
    point P (rational: the case is refused otherwise) in direction dir over
    [0, inf); the crossing of the surface being left (the one hit at t = 0) is
    dropped, and every other crossing must lie far from t = 0 compared with the
    few ulps by which the library's spawned origin differs from P.
    """
    shape, m, d = c["shape"], c.get("transform"), c["dir"]
    st = ray_status(c["ray"]) | shape_status(shape)
    if m is not None and transformed.check(m):
        st.add(transformed.check(m))
    if st:
        raise DesignError(f"{c['name']}: a spawn case's primary ray, shape and transform must be valid")
    if len(d) != 3:
        raise DesignError("dir has 3 numbers")
    dir_status: set[str] = set()
    if not all(math.isfinite(x) for x in d):
        dir_status.add("E_NONFINITE")
    elif all(x == 0 for x in d):
        dir_status.add("E_DEGENERATE")
    r = XRay.from_json(c["ray"])
    ctx = Ctx(q(EPS_DEFAULT))
    hits, ctx1 = _solve(shape, m, r, ctx)
    first = finish(hits, r, ctx1, culls_back(shape), False)
    if not first:
        dir_status.add("E_ARG")          # the MISS record is not a hit
    status = one_status(dir_status, c["name"])
    if status:
        return {"status": status}
    h = first[0]
    if not isinstance(h.t, Fraction):
        raise DesignError("spawn: the first hit point must be rational (exactly known)")
    p = point_on_ray(r.org, r.dir, h.t)
    dq = qv(d)
    dn = mp(dot(dq, h.normal))
    if abs(dn) < mpmath.mpf("1e-3") * mpmath.sqrt(mp(norm2(dq))):
        raise DesignError("spawn: dir nearly tangent to the surface at the hit")
    # tmin = -inf: the range is applied below, after the surface left is dropped
    sec = XRay(p, dq, -INF, INF)
    hits2, _ = _solve(shape, m, sec, ctx)
    at0 = [x for x in hits2 if x.t == 0]
    if len(at0) != 1:
        raise DesignError(f"spawn: {len(at0)} crossings at the exact hit point (want the one surface left)")
    offset = 8 * Fraction(math.ulp(to_double(max(abs(x) for x in p))))
    step = max(abs(x) for x in dq)
    for x in hits2:
        if x.t != 0 and abs(mp(x.t)) * mp(step) < SPAWN_MARGIN * mp(offset):
            raise DesignError("spawn: another crossing within the margin of the spawn offset")
    rest = [x for x in hits2 if x.t != 0 and cmp(x.t, 0) > 0]
    kept = finish(rest, sec, ctx, culls_back(shape), False)
    return {"status": "ok", "count": len(kept), "hits": [hit_json(x, sec) for x in kept]}


def evaluate(c: dict) -> dict:
    """The expect object of a case."""
    op = c.get("op", "intersect")
    if op == "spawn":
        return evaluate_spawn(c)
    if op in ("point_in_polygon2", "winding_number2", "polygon_normal", "plane_from_points"):
        return polygon2d.evaluate(c)
    if op == "winding_number":
        return winding.evaluate_winding(c)      # also sets c["tol"] (the documented bound)
    shape = c["shape"]
    if op == "contains" and shape.get("type") == "mesh" and ("rule" in shape or "transform" in c):
        return winding.evaluate_contains(c)
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

