#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Every primitive through Python against vectorised numpy (a benchmark, not a test).

For each analytic primitive (the thirteen of ``bench_kernels.c``, with the same
geometry) at N = 10^6 rays, on one thread, in one process:

* ``shape.intersect(origins, directions)`` (which also packs the rays) and
  ``shape.intersect_rays(rays)`` (a prepared ``RAY_DTYPE`` array, zero-copy);
* a vectorised numpy implementation written here of the same closest hit with
  the same outputs: t (inf on a miss), point = org + t*dir, unit normal and
  ENTER/EXIT kind, by the textbook formulas of ``bench_kernels.c``.

The speed-up is numpy's time over the library's; target >= 5x for both forms
(the aim is 10x). The candidates run interleaved, their order rotating from
one repetition to the next; each repetition gives a speed-up (numpy's time
over the library's, three calls made moments apart), reported as the median
over the repetitions with its min-max range, beside each call's median time. Agreement:
the share of rays on which numpy and the library agree on hit or miss, and
the largest relative t difference on rays both hit.

Plus the one-ray Python call on a sphere, a ray that hits it twice:
``Sphere.intersect(origin, direction)`` (one closest-hit record) and
``Sphere.intersect_all(origin, direction)`` (a list of Hit tuples), median
microseconds per call over many timed runs; targets <= 3 us and <= 2 us.

Rays: a fixed-seed generator; origins on the sphere of radius 4 around the
shape's centre aimed at uniform points of a cube around it, whose half-width
is found per primitive by bisection so that numpy hits about half (the plane
and the hyperboloid, unbounded, keep the widest cube: about 51 %).

numpy and its BLAS are held to one thread (OPENBLAS_NUM_THREADS etc. are set
to 1 before numpy is imported), like the library's calls (``threads=1``).
Prints a table and writes bench/results/python_kernels.json. Run:
``.venv/bin/python bench/python_kernels_bench.py`` (``--n``, ``--repeat``,
``--only NAME``).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402  (after the thread limits, before numpy)
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
import timeit  # noqa: E402
from collections.abc import Callable  # noqa: E402
from dataclasses import dataclass, field  # noqa: E402
from functools import partial  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import isect  # noqa: E402
import numpy as np  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results" / "python_kernels.json"
TARGET_SPEEDUP = 5.0
AIM_SPEEDUP = 10.0
TARGET_ONE_RAY_INTERSECT_US = 3.0
TARGET_ONE_RAY_INTERSECT_ALL_US = 2.0
ORIGIN_RADIUS = 4.0
AIM_MIN, AIM_MAX = 0.01, 64.0
SEED = 20240611
MISS, ENTER, EXIT = 0, 1, 2

Array = np.ndarray
Result = dict[str, Array]

# ------------------------------------------------------------ numpy helpers


def dot(a: Array, b: Array) -> Array:
    """Row-wise dot products of two (n, 3) arrays (b may be one (3,) vector)."""
    if b.ndim == 1:
        return a @ b
    return np.einsum("ij,ij->i", a, b)


def unit(v: Array) -> Array:
    """Rows of v scaled to unit length."""
    return v / np.sqrt(dot(v, v))[:, None]


def finish(org: Array, dirs: Array, t: Array, normal: Array, kind: Array) -> Result:
    """The user's outputs: t (inf on a miss), point = org + t*dir, unit normal
    (0 on a miss) and kind."""
    hit = kind != MISS
    t = np.where(hit, t, np.inf)
    point = org + np.where(hit, t, 0.0)[:, None] * dirs
    return {"t": t, "point": point, "normal": np.where(hit[:, None], normal, 0.0), "kind": kind}


def first_of(t0: Array, t1: Array, ok0: Array, ok1: Array) -> tuple[Array, Array]:
    """The first of two candidate hits t0 < t1 with t >= 0 (the rays' tmin; tmax
    is inf): its t, and ENTER for t0, EXIT for t1, MISS for neither."""
    first = ok0 & (t0 >= 0.0)
    second = ~first & ok1 & (t1 >= 0.0)
    return np.where(first, t0, t1), np.where(first, ENTER, np.where(second, EXIT, MISS))


def sphere_first(org: Array, dirs: Array, c: Array, r: float) -> tuple[Array, Array]:
    """Sphere |x - c| = r, f = o - c:
    t = (-(f.d) -+ sqrt((f.d)^2 - |d|^2 (|f|^2 - r^2))) / |d|^2."""
    f = org - c
    a, b, cc = dot(dirs, dirs), dot(f, dirs), dot(f, f) - r * r
    disc = b * b - a * cc
    ok = disc >= 0.0
    sq = np.sqrt(np.where(ok, disc, 0.0))
    return first_of((-b - sq) / a, (-b + sq) / a, ok, ok)


BOX_NORMALS = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1.0]])


def box_first(org: Array, dirs: Array, lo: Array, hi: Array) -> tuple[Array, Array, Array]:
    """Kay-Kajiya slabs: per axis t = (lo - o)/d and (hi - o)/d; enter = the largest
    near t, exit = the smallest far t, a hit when enter <= exit. Returns t, kind
    and the face (0..5 = -x,+x,-y,+y,-z,+z)."""
    rows = np.arange(len(org))
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / dirs
        t_lo, t_hi = (lo - org) * inv, (hi - org) * inv
    flip = inv < 0.0  # the ray meets the hi face first
    near, far = np.where(flip, t_hi, t_lo), np.where(flip, t_lo, t_hi)
    enter_axis, exit_axis = near.argmax(axis=1), far.argmin(axis=1)
    enter, exit_ = near[rows, enter_axis], far[rows, exit_axis]
    enter_face = 2 * enter_axis + flip[rows, enter_axis]
    exit_face = 2 * exit_axis + ~flip[rows, exit_axis]
    hit = enter <= exit_
    t, kind = first_of(enter, exit_, hit, hit)
    return t, kind, np.where(kind == ENTER, enter_face, exit_face)


def cylinder_roots(
    org: Array, dirs: Array, p: Array, a: Array, r: float
) -> tuple[Array, Array, Array]:
    """Side |w - (w.a) a| = r, w = o + t d - p, a the unit axis: with f' and d' the
    parts of o - p and d across the axis, t = (-(f'.d') -+ sqrt(...)) / |d'|^2.
    Returns t0, t1 and where they exist."""
    f = org - p
    fp = f - dot(f, a)[:, None] * a
    dp = dirs - dot(dirs, a)[:, None] * a
    qa, qb, qc = dot(dp, dp), dot(fp, dp), dot(fp, fp) - r * r
    disc = qb * qb - qa * qc
    ok = (disc >= 0.0) & (qa != 0.0)
    sq = np.sqrt(np.where(ok, disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        return (-qb - sq) / qa, (-qb + sq) / qa, ok


def cylinder_normal(org: Array, dirs: Array, t: Array, p: Array, a: Array, r: float) -> Array:
    """Outward radial unit normal of the side at o + t d."""
    w = org + np.where(np.isfinite(t), t, 0.0)[:, None] * dirs - p
    return (w - dot(w, a)[:, None] * a) / r


# ------------------------------------------------------- numpy textbooks


def np_plane(org: Array, dirs: Array, n: Array, d: float) -> Result:
    """Plane n.x + d = 0: t = -(n.o + d)/(n.d); ENTER when n.d < 0."""
    nd = dirs @ n
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -(org @ n + d) / nd
    kind = np.where((nd != 0.0) & (t >= 0.0), np.where(nd < 0.0, ENTER, EXIT), MISS)
    return finish(org, dirs, t, np.broadcast_to(n / np.linalg.norm(n), org.shape), kind)


def np_sphere(org: Array, dirs: Array, c: Array, r: float) -> Result:
    """Sphere: the quadratic above; normal = (p - c)/r."""
    t, kind = sphere_first(org, dirs, c, r)
    p = org + np.where(kind != MISS, t, 0.0)[:, None] * dirs
    return finish(org, dirs, t, (p - c) / r, kind)


def np_box(org: Array, dirs: Array, lo: Array, hi: Array) -> Result:
    """Box: the slabs above."""
    t, kind, face = box_first(org, dirs, lo, hi)
    out = finish(org, dirs, t, BOX_NORMALS[face], kind)
    out["prim"] = np.where(kind != MISS, face, -1)
    return out


def np_triangle(org: Array, dirs: Array, a: Array, b: Array, c: Array) -> Result:
    """Moller-Trumbore: p = d x e2, q = (o - a) x e1, det = e1.p, u = (o - a).p/det,
    v = d.q/det, t = e2.q/det; a hit when u, v >= 0 and u + v <= 1."""
    e1, e2 = b - a, c - a
    p = np.cross(dirs, e2)
    det = p @ e1
    s = org - a
    q = np.cross(s, e1)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
    u, v, t = dot(s, p) * inv, dot(dirs, q) * inv, (q @ e2) * inv
    hit = (det != 0.0) & (u >= 0.0) & (v >= 0.0) & (u + v <= 1.0) & (t >= 0.0)
    kind = np.where(hit, np.where(det > 0.0, ENTER, EXIT), MISS)
    n = np.cross(e1, e2)
    out = finish(org, dirs, t, np.broadcast_to(n / np.linalg.norm(n), org.shape), kind)
    out["uv"] = np.where(hit[:, None], np.column_stack([u, v]), 0.0)
    return out


def np_polygon(org: Array, dirs: Array, v: Array) -> Result:
    """Newell's normal n and d = -n.v0, the plane hit t = -(n.o + d)/(n.d), then the
    crossing number of the hit point, projected onto the two axes other than n's
    largest component (an edge counts when it straddles y = py right of px)."""
    nxt = np.roll(v, -1, axis=0)
    n = np.array(
        [
            np.sum((v[:, 1] - nxt[:, 1]) * (v[:, 2] + nxt[:, 2])),
            np.sum((v[:, 2] - nxt[:, 2]) * (v[:, 0] + nxt[:, 0])),
            np.sum((v[:, 0] - nxt[:, 0]) * (v[:, 1] + nxt[:, 1])),
        ]
    )
    n /= np.linalg.norm(n)
    drop = int(np.argmax(np.abs(n)))
    ax, ay = (drop + 1) % 3, (drop + 2) % 3
    nd = dirs @ n
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -(org @ n - n @ v[0]) / nd
        px, py = org[:, ax] + t * dirs[:, ax], org[:, ay] + t * dirs[:, ay]
        inside = np.zeros(len(org), dtype=bool)
        for i in range(len(v)):
            (xi, yi), (xj, yj) = v[i, [ax, ay]], v[i - 1, [ax, ay]]
            inside ^= ((yi > py) != (yj > py)) & (px < xj + (py - yj) * (xi - xj) / (yi - yj))
    kind = np.where((nd != 0.0) & (t >= 0.0) & inside, np.where(nd < 0.0, ENTER, EXIT), MISS)
    return finish(org, dirs, t, np.broadcast_to(n, org.shape), kind)


def np_convex(org: Array, dirs: Array, planes: Array) -> Result:
    """enterMax/exitMin: plane n.x + d <= 0 meets the ray at t = -(n.o + d)/(n.d), an
    entry when n.d < 0, an exit when n.d > 0 (n.d = 0: outside for ever when
    n.o + d > 0); a hit when the last entry <= the first exit."""
    rows = np.arange(len(org))
    n, d = planes[:, :3], planes[:, 3]
    nd, no = dirs @ n.T, org @ n.T + d
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -no / nd
    enter_plane = np.where(nd < 0.0, t, -np.inf).argmax(axis=1)
    exit_plane = np.where(nd > 0.0, t, np.inf).argmin(axis=1)
    enter, exit_ = t[rows, enter_plane], t[rows, exit_plane]
    hit = ~np.any((nd == 0.0) & (no > 0.0), axis=1) & (enter <= exit_)
    t, kind = first_of(enter, exit_, hit, hit)
    plane = np.where(kind == ENTER, enter_plane, exit_plane)
    out = finish(org, dirs, t, (n / np.linalg.norm(n, axis=1)[:, None])[plane], kind)
    out["prim"] = np.where(kind != MISS, plane, -1)
    return out


def np_cylinder(org: Array, dirs: Array, p0: Array, p1: Array, r: float) -> Result:
    """Capped: the side's interval [t0, t1] meets the caps' slab, where
    s = (o + t d - p0).a runs from 0 to L; enter = max, exit = min of the two."""
    length = np.linalg.norm(p1 - p0)
    a = (p1 - p0) / length
    t0, t1, ok = cylinder_roots(org, dirs, p0, a, r)
    fa, da = dot(org - p0, a), dirs @ a
    with np.errstate(divide="ignore", invalid="ignore"):
        s0, s1 = -fa / da, (length - fa) / da  # caps at p0 (prim 1), p1 (prim 2)
    swap = s0 > s1
    near, far = np.where(swap, s1, s0), np.where(swap, s0, s1)
    near_cap, far_cap = np.where(swap, 2, 1), np.where(swap, 1, 2)
    enter, enter_prim = np.where(near > t0, near, t0), np.where(near > t0, near_cap, 0)
    exit_, exit_prim = np.where(far < t1, far, t1), np.where(far < t1, far_cap, 0)
    hit = ok & (enter <= exit_)
    t, kind = first_of(enter, exit_, hit, hit)
    prim = np.where(kind == ENTER, enter_prim, exit_prim)
    normal = cylinder_normal(org, dirs, t, p0, a, r)
    normal = np.where((prim == 1)[:, None], -a, np.where((prim == 2)[:, None], a, normal))
    out = finish(org, dirs, t, normal, kind)
    out["prim"] = np.where(kind != MISS, prim, -1)
    return out


def np_cylinder_open(org: Array, dirs: Array, p0: Array, p1: Array, r: float) -> Result:
    """Open: the side's roots whose s = (o + t d - p0).a lies in [0, L]."""
    length = np.linalg.norm(p1 - p0)
    a = (p1 - p0) / length
    t0, t1, ok = cylinder_roots(org, dirs, p0, a, r)
    fa, da = dot(org - p0, a), dirs @ a
    s0, s1 = fa + t0 * da, fa + t1 * da
    t, kind = first_of(t0, t1, ok & (s0 >= 0) & (s0 <= length), ok & (s1 >= 0) & (s1 <= length))
    out = finish(org, dirs, t, cylinder_normal(org, dirs, t, p0, a, r), kind)
    out["prim"] = np.where(kind != MISS, 0, -1)
    return out


def np_cylinder_inf(org: Array, dirs: Array, p: Array, axis: Array, r: float) -> Result:
    """Infinite (a solid): the side's roots alone."""
    a = axis / np.linalg.norm(axis)
    t0, t1, ok = cylinder_roots(org, dirs, p, a, r)
    t, kind = first_of(t0, t1, ok, ok)
    out = finish(org, dirs, t, cylinder_normal(org, dirs, t, p, a, r), kind)
    out["prim"] = np.where(kind != MISS, 0, -1)
    return out


def np_ellipsoid(org: Array, dirs: Array, c: Array, radii: Array) -> Result:
    """The unit sphere in coordinates scaled by 1/R (t unchanged); normal =
    unit((p - c)/R^2)."""
    o, d = (org - c) / radii, dirs / radii
    t, kind = sphere_first(o, d, np.zeros(3), 1.0)
    local = o + np.where(kind != MISS, t, 0.0)[:, None] * d
    return finish(org, dirs, t, unit(local / radii), kind)


def np_quadric(org: Array, dirs: Array, q: Array) -> Result:
    """Q(x) = x.Mx + g.x + J along the ray: a t^2 + b t + c with a = d.Md,
    b = grad Q(o).d = (2Mo + g).d, c = Q(o); t = (-b -+ sqrt(b^2 - 4ac))/2a
    (a = 0: t = -c/b); normal = unit(grad Q(p)), ENTER when it points against d."""
    A, B, C, D, E, F, G, H, I, J = q
    m = np.array([[A, D / 2, E / 2], [D / 2, B, F / 2], [E / 2, F / 2, C]])
    g = np.array([G, H, I])
    om = org @ m
    a, b, c = dot(dirs @ m, dirs), dot(2.0 * om + g, dirs), dot(om, org) + org @ g + J
    disc = b * b - 4.0 * a * c
    ok = disc >= 0.0
    sq = np.sqrt(np.where(ok, disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        r0, r1 = (-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a)
        linear = -c / b
    t0 = np.where(a == 0.0, linear, np.minimum(r0, r1))
    t1 = np.where(a == 0.0, np.inf, np.maximum(r0, r1))
    t, kind = first_of(t0, t1, ok | (a == 0.0), ok & (a != 0.0))
    p = org + np.where(kind != MISS, t, 0.0)[:, None] * dirs
    normal = unit(2.0 * p @ m + g)
    kind = np.where(kind != MISS, np.where(dot(normal, dirs) < 0.0, ENTER, EXIT), MISS)
    return finish(org, dirs, t, normal, kind)


def np_xform_sphere(org: Array, dirs: Array, inv: Array) -> Result:
    """The ray to object space by the inverse (t unchanged), the unit sphere there,
    the normal back by the inverse transpose: n = unit(M^-T n')."""
    lin = inv[:3, :3]
    o, d = org @ lin.T + inv[:3, 3], dirs @ lin.T
    t, kind = sphere_first(o, d, np.zeros(3), 1.0)
    local = o + np.where(kind != MISS, t, 0.0)[:, None] * d
    return finish(org, dirs, t, unit(local @ lin), kind)


def np_xform_box(org: Array, dirs: Array, inv: Array) -> Result:
    """The same with the box [-1, 1]^3 in object space."""
    lin = inv[:3, :3]
    o, d = org @ lin.T + inv[:3, 3], dirs @ lin.T
    t, kind, face = box_first(o, d, -np.ones(3), np.ones(3))
    out = finish(org, dirs, t, unit(BOX_NORMALS[face] @ lin), kind)
    out["prim"] = np.where(kind != MISS, face, -1)
    return out


# ------------------------------------------------------------------ shapes


def rotation(axis: Array, angle: float) -> Array:
    """Rotation by angle about axis (Rodrigues), 3x3."""
    x, y, z = axis / np.linalg.norm(axis)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def transform(shift: Array, axis: Array, angle: float, scale: Array) -> tuple[Array, Array]:
    """M = T R S (object to world) and its inverse S^-1 R^T T^-1, from the factors."""
    rot = rotation(axis, angle)
    m, inv = np.eye(4), np.eye(4)
    m[:3, :3] = rot * scale
    m[:3, 3] = shift
    inv[:3, :3] = (rot / scale).T
    inv[:3, 3] = -inv[:3, :3] @ shift
    return m, inv


@dataclass
class Kernel:
    """One primitive: the library's shape, the numpy textbook, where rays aim."""

    name: str
    shape: isect.Shape
    reference: Callable[[Array, Array], Result]
    center: Array = field(default_factory=lambda: np.zeros(3))


def kernels() -> list[Kernel]:
    """The primitives of bench_kernels.c, with the same numbers."""
    v3 = np.array
    # A concave heptagon (a crown with two notches) in the plane through `at`
    # spanned by the orthonormal u, v.
    crown = v3([[-1, -1], [1, -1], [1, 1], [0.4, 0.1], [0, 1], [-0.4, 0.1], [-1, 1.0]])
    u, v, at = v3([2, 2, 1.0]) / 3, v3([-2, 1, 2.0]) / 3, v3([0.1, -0.2, 0.05])
    polygon = at + crown[:, :1] * u + crown[:, 1:] * v
    # Truncated octahedron: the cube |x|,|y|,|z| <= 1 cut by |x| + |y| + |z| <= 1.5.
    squares = [[*(s * e), -1.0] for e in np.eye(3) for s in (-1, 1)]
    hexagons = [[x, y, z, -1.5] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]
    planes = v3(squares + hexagons, dtype=float)
    pn, pd = v3([1.0, 2.0, 2.0]), -0.5
    sc, sr = v3([0.1, -0.2, 0.3]), 1.0
    lo, hi = v3([-1, -0.5, -0.75]), v3([1, 0.5, 0.75])
    a, b, c = v3([-1, -1, 0.2]), v3([1.2, -0.8, -0.1]), v3([0.1, 1.1, 0.3])
    p0, p1, cr = v3([-0.3, -0.6, -0.9]), v3([0.3, 0.6, 0.9]), 0.6
    ip, iaxis, ir = v3([0.1, 0.0, 0.0]), v3([0.2, 0.3, 1.0]), 0.7
    ec, er = v3([0.0, 0.1, -0.1]), v3([1.2, 0.7, 0.9])
    # x^2 + 2y^2 - z^2 + 0.5xy - 0.5 = 0: a hyperboloid of one sheet.
    quadric = v3([1.0, 2.0, -1.0, 0.5, 0, 0, 0, 0, 0, -0.5])
    ms, inv_s = transform(v3([0.2, -0.1, 0.3]), v3([1, 2, 3.0]), 0.7, v3([1.3, 0.6, 0.9]))
    mb, inv_b = transform(v3([-0.1, 0.2, 0.1]), v3([-2, 1, 1.0]), 1.1, v3([0.8, 0.5, 1.1]))
    cube = isect.Box(-np.ones(3), np.ones(3))
    return [
        Kernel("plane", isect.Plane(pn, pd), partial(np_plane, n=pn, d=pd)),
        Kernel("sphere", isect.Sphere(sc, sr), partial(np_sphere, c=sc, r=sr), sc),
        Kernel("box", isect.Box(lo, hi), partial(np_box, lo=lo, hi=hi)),
        Kernel("triangle", isect.Triangle(a, b, c), partial(np_triangle, a=a, b=b, c=c)),
        Kernel("polygon", isect.Polygon(polygon), partial(np_polygon, v=polygon), at),
        Kernel(
            "convex (14 planes)", isect.ConvexPolyhedron(planes), partial(np_convex, planes=planes)
        ),
        Kernel(
            "cylinder capped",
            isect.Cylinder(p0, p1, cr),
            partial(np_cylinder, p0=p0, p1=p1, r=cr),
        ),
        Kernel(
            "cylinder open",
            isect.Cylinder(p0, p1, cr, capped=False),
            partial(np_cylinder_open, p0=p0, p1=p1, r=cr),
        ),
        Kernel(
            "cylinder infinite",
            isect.InfiniteCylinder(ip, iaxis, ir),
            partial(np_cylinder_inf, p=ip, axis=iaxis, r=ir),
        ),
        Kernel("ellipsoid", isect.Ellipsoid(ec, er), partial(np_ellipsoid, c=ec, radii=er), ec),
        Kernel("quadric (hyperboloid)", isect.Quadric(quadric), partial(np_quadric, q=quadric)),
        Kernel(
            "xform sphere",
            isect.Sphere(np.zeros(3), 1.0).transformed(ms),
            partial(np_xform_sphere, inv=inv_s),
            ms[:3, 3].copy(),
        ),
        Kernel(
            "xform box", cube.transformed(mb), partial(np_xform_box, inv=inv_b), mb[:3, 3].copy()
        ),
    ]


# -------------------------------------------------------------------- rays


def make_rays(n: int, center: Array, aim: float) -> tuple[Array, Array]:
    """Origins on the sphere of radius 4 around center aimed at uniform points of
    the cube center +- aim (fixed seed: the same rays for the same arguments)."""
    rng = np.random.default_rng(SEED)
    org = rng.normal(size=(n, 3))
    org *= ORIGIN_RADIUS / np.linalg.norm(org, axis=1)[:, None]
    org += center
    return org, center + rng.uniform(-aim, aim, size=(n, 3)) - org


def calibrate(k: Kernel, n: int) -> float:
    """The aim half-width at which numpy hits about half of n rays (the hit
    fraction falls as the cube grows); the widest cube if it never falls to half."""
    def hits(aim: float) -> float:
        return float(np.mean(k.reference(*make_rays(n, k.center, aim))["kind"] != MISS))

    lo, hi = AIM_MIN, AIM_MAX
    if hits(hi) > 0.5:
        return hi
    for _ in range(30):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if hits(mid) > 0.5 else (lo, mid)
    return hi


# ------------------------------------------------------------------ timing


def timed(fn: Callable[[], Any]) -> float:
    """Wall time of one call, seconds."""
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def bench_kernel(k: Kernel, n: int, repeat: int) -> dict[str, Any]:
    """The three candidates for one primitive, interleaved; medians and agreement."""
    aim = calibrate(k, 20_000)
    org, dirs = make_rays(n, k.center, aim)
    rays = np.empty(n, dtype=isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmin"], rays["tmax"] = org, dirs, 0.0, np.inf

    lib = k.shape.intersect(org, dirs)
    assert lib.tobytes() == k.shape.intersect_rays(rays).tobytes()
    ref = k.reference(org, dirs)
    lib_hit, ref_hit = lib["kind"] != MISS, ref["kind"] != MISS
    both = lib_hit & ref_hit
    rel_dt = np.abs(lib["t"][both] - ref["t"][both]) / np.abs(lib["t"][both])

    runs: dict[str, Callable[[], Any]] = {
        "intersect": lambda: k.shape.intersect(org, dirs, threads=1),
        "intersect_rays": lambda: k.shape.intersect_rays(rays, threads=1),
        "numpy": lambda: k.reference(org, dirs),
    }
    names = list(runs)
    times: dict[str, list[float]] = {key: [] for key in names}
    for rep in range(repeat):
        for key in names[rep % 3 :] + names[: rep % 3]:  # rotate who goes first
            times[key].append(timed(runs[key]))
    med = {key: statistics.median(v) for key, v in times.items()}
    # Speed-ups per repetition (the three calls of one repetition run moments apart).
    ups = {
        form: [num / lib for num, lib in zip(times["numpy"], times[form])]
        for form in ("intersect", "intersect_rays")
    }
    speedup = {form: statistics.median(v) for form, v in ups.items()}
    return {
        "primitive": k.name,
        "n": n,
        "aim_half_width": aim,
        "hit_fraction": float(lib_hit.mean()),
        "intersect_s": med["intersect"],
        "intersect_rays_s": med["intersect_rays"],
        "numpy_s": med["numpy"],
        "speedup_intersect": speedup["intersect"],
        "speedup_intersect_range": [min(ups["intersect"]), max(ups["intersect"])],
        "speedup_intersect_rays": speedup["intersect_rays"],
        "speedup_intersect_rays_range": [min(ups["intersect_rays"]), max(ups["intersect_rays"])],
        "hit_agreement": float(np.mean(lib_hit == ref_hit)),
        "max_rel_dt": float(rel_dt.max()) if both.any() else 0.0,
        "kind_agreement_on_both_hit": (
            float(np.mean(lib["kind"][both] == ref["kind"][both])) if both.any() else 1.0
        ),
        "pass": min(speedup.values()) >= TARGET_SPEEDUP,
    }


def bench_one_ray(repeat: int) -> dict[str, Any]:
    """Median microseconds per one-ray call on a sphere (a ray hitting it twice),
    the two calls' timed runs interleaved."""
    sphere = isect.Sphere([0.1, -0.2, 0.3], 1.0)
    origin, direction = [0.1, -0.2, -5.0], [0.0, 0.0, 1.0]
    assert sphere.intersect(origin, direction)["kind"] == ENTER
    assert len(sphere.intersect_all(origin, direction)) == 2
    number = 20_000
    calls = {
        "intersect": lambda: sphere.intersect(origin, direction),
        "intersect_all": lambda: sphere.intersect_all(origin, direction),
    }
    samples: dict[str, list[float]] = {key: [] for key in calls}
    for rep in range(repeat):
        for key in list(calls)[rep % 2 :] + list(calls)[: rep % 2]:
            samples[key].append(timeit.timeit(calls[key], number=number) / number * 1e6)
    us = {key: statistics.median(v) for key, v in samples.items()}
    return {
        "calls_per_sample": number,
        "samples": repeat,
        "intersect_us": us["intersect"],
        "intersect_us_range": [min(samples["intersect"]), max(samples["intersect"])],
        "intersect_all_us": us["intersect_all"],
        "intersect_all_us_range": [min(samples["intersect_all"]), max(samples["intersect_all"])],
        "intersect_pass": us["intersect"] <= TARGET_ONE_RAY_INTERSECT_US,
        "intersect_all_pass": us["intersect_all"] <= TARGET_ONE_RAY_INTERSECT_ALL_US,
    }


# ------------------------------------------------------------------- main


def verdict(ok: bool) -> str:
    """PASS or FAIL."""
    return "PASS" if ok else "FAIL"


def main() -> None:
    """Run the benchmark, print the table, write the JSON."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="rays per batch (default 1e6)")
    parser.add_argument("--repeat", type=int, default=7, help="interleaved repetitions (median)")
    parser.add_argument("--only", action="append", help="only these primitives (repeatable)")
    parser.add_argument("--out", type=Path, default=RESULTS, help="JSON output file")
    args = parser.parse_args()

    print(
        f"isect {isect.version()}, Python {platform.python_version()}, numpy {np.__version__}: "
        f"shape.intersect vs vectorised numpy, N = {args.n:,} rays, 1 thread,\n"
        f"{args.repeat} interleaved repetitions, medians; speed-up = numpy time / library time "
        f"(target >= {TARGET_SPEEDUP:g}x, aim {AIM_SPEEDUP:g}x)\n"
    )
    head = (
        f"{'primitive':<22} {'hit%':>5} {'intersect':>9} {'int_rays':>9} {'numpy':>9}  "
        f"{'numpy/intersect':<21} {'numpy/intersect_rays':<21} {'agree%':>7} {'max rel dt':>10}"
        f"  >= {TARGET_SPEEDUP:g}x"
    )
    print(head)
    rows = []
    for k in kernels():
        if args.only and k.name not in args.only:
            continue
        r = bench_kernel(k, args.n, args.repeat)
        rows.append(r)
        ups = [
            f"{r[f'speedup_{form}']:5.2f}x ({r[f'speedup_{form}_range'][0]:.2f}-"
            f"{r[f'speedup_{form}_range'][1]:.2f})"
            for form in ("intersect", "intersect_rays")
        ]
        print(
            f"{r['primitive']:<22} {100 * r['hit_fraction']:5.1f} {r['intersect_s'] * 1e3:7.1f}ms "
            f"{r['intersect_rays_s'] * 1e3:7.1f}ms {r['numpy_s'] * 1e3:7.1f}ms  {ups[0]:<21} "
            f"{ups[1]:<21} {100 * r['hit_agreement']:7.3f} {r['max_rel_dt']:10.2g}  "
            f"{verdict(r['pass'])}",
            flush=True,
        )
    one = bench_one_ray(max(args.repeat, 15))
    print(
        f"\none ray on a sphere (median of {one['samples']} x {one['calls_per_sample']:,} calls): "
        f"Sphere.intersect {one['intersect_us']:.2f} us "
        f"(target <= {TARGET_ONE_RAY_INTERSECT_US:g}: {verdict(one['intersect_pass'])}), "
        f"intersect_all {one['intersect_all_us']:.2f} us "
        f"(target <= {TARGET_ONE_RAY_INTERSECT_ALL_US:g}: {verdict(one['intersect_all_pass'])})"
    )

    doc = {
        "benchmark": "bench/python_kernels_bench.py",
        "isect_version": isect.version(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "machine": {"platform": platform.platform(), "cpus": os.cpu_count()},
        "n": args.n,
        "repeat": args.repeat,
        "statistic": "median",
        "targets": {
            "speedup_min": TARGET_SPEEDUP,
            "speedup_aim": AIM_SPEEDUP,
            "one_ray_intersect_us_max": TARGET_ONE_RAY_INTERSECT_US,
            "one_ray_intersect_all_us_max": TARGET_ONE_RAY_INTERSECT_ALL_US,
        },
        "kernels": rows,
        "one_ray": one,
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(f"\nwrote {args.out}")


if __name__ == "__main__":
    main()
