# SPDX-License-Identifier: Apache-2.0
"""Textbook double-precision intersection, vectorised over rays (numpy float64).

What a first implementation from the lecture notes computes, for comparison
with libisect on the same rays (no eps policy, no compensated arithmetic):

* quadratic surfaces: a t^2 + b t + c with the plain formula
  t = (-b -+ sqrt(b^2 - 4ac)) / (2a) (sphere: a = d.d, b = 2 (o-c).d,
  c = |o-c|^2 - r^2; ellipsoid in the scaled frame; cylinder side on the
  components perpendicular to the unit axis; quadric from its coefficients,
  t = -c/b when a = 0); one TOUCH when b^2 - 4ac == 0;
* planes and faces: t = -(n.o + d) / (n.d) (polygon: Newell normal through
  the vertex centroid, then a crossing-number / winding test in the plane
  dropping the largest normal component; convex: enterMax / exitMin);
* triangle: Moller-Trumbore; box: slabs with 1/d;
* point = o + t d; normal from the formula ((P - c)/r, (P - c)/R^2, grad Q,
  n/|n|, ...), normalised; transformed shapes through numpy's inverse.

Each returns every hit of every ray as (offsets, HIT_DTYPE records), like
``intersect_all_batch``.
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt
from isect import HIT_DTYPE

Arr = npt.NDArray[np.float64]
ENTER, EXIT, TOUCH = 1, 2, 3


def _dot(a: Arr, b: Arr) -> Arr:
    return np.einsum("...k,...k->...", a, b)


def _normalize(v: Arr) -> Arr:
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / np.linalg.norm(v, axis=-1, keepdims=True)


class Cands:
    """Candidate hits, K per ray: t (NaN = none), kind, prim, normal (N, K, 3)."""

    def __init__(self, n: int) -> None:
        self.t: list[Arr] = []
        self.kind: list[npt.NDArray[np.int32]] = []
        self.prim: list[npt.NDArray[np.int32]] = []
        self.normal: list[Arr] = []
        self.n = n

    def add(self, t: Arr, kind: npt.ArrayLike, prim: int, normal: Arr) -> None:
        self.t.append(np.asarray(t, dtype=float))
        self.kind.append(np.broadcast_to(np.asarray(kind, dtype=np.int32), (self.n,)))
        self.prim.append(np.full(self.n, prim, dtype=np.int32))
        self.normal.append(np.broadcast_to(normal, (self.n, 3)))


def _quadratic(a: Arr, b: Arr, c: Arr) -> tuple[Arr, Arr, Arr]:
    """Roots (t1 <= t2, NaN when none) and a touch mask, by the plain formula."""
    with np.errstate(invalid="ignore", divide="ignore"):
        disc = b * b - 4 * a * c
        s = np.sqrt(disc)
        r1, r2 = (-b - s) / (2 * a), (-b + s) / (2 * a)
        t1, t2 = np.minimum(r1, r2), np.maximum(r1, r2)
        touch = disc == 0
        t2 = np.where(touch, np.nan, t2)
        lin = a == 0
        t1 = np.where(lin, -c / b, t1)
        t2 = np.where(lin, np.nan, t2)
        touch &= ~lin
    return t1, t2, touch


def _kind_of(d: Arr, n: Arr) -> npt.NDArray[np.int32]:
    return np.where(_dot(d, n) < 0, ENTER, EXIT).astype(np.int32)


def _quadric_hits(c: Cands, o: Arr, d: Arr, a: Arr, b: Arr, cc: Arr, grad, prim: int = -1,
                  keep=None) -> None:
    t1, t2, touch = _quadratic(a, b, cc)
    for t, is_touch in ((t1, touch), (t2, np.zeros_like(touch))):
        p = o + t[:, None] * d
        n = _normalize(grad(p))
        if keep is not None:
            t = np.where(keep(p), t, np.nan)
        c.add(t, np.where(is_touch, TOUCH, _kind_of(d, n)), prim, n)


def sphere(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    ctr, r = np.array(spec["center"]), spec["radius"]
    oc = o - ctr
    _quadric_hits(c, o, d, _dot(d, d), 2 * _dot(oc, d), _dot(oc, oc) - r * r, lambda p: (p - ctr) / r)


def ellipsoid(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    ctr, R = np.array(spec["center"]), np.array(spec["radii"])
    os_, ds = (o - ctr) / R, d / R
    _quadric_hits(c, o, d, _dot(ds, ds), 2 * _dot(os_, ds), _dot(os_, os_) - 1, lambda p: (p - ctr) / R**2)


def quadric(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    A, B, C, D, E, F, G, H, I, J = spec["coeffs"]
    x, y, z = o.T
    u, v, w = d.T
    a = A * u * u + B * v * v + C * w * w + D * u * v + E * u * w + F * v * w
    b = (2 * (A * x * u + B * y * v + C * z * w) + D * (x * v + y * u) + E * (x * w + z * u)
         + F * (y * w + z * v) + G * u + H * v + I * w)
    cc = A * x * x + B * y * y + C * z * z + D * x * y + E * x * z + F * y * z + G * x + H * y + I * z + J

    def grad(p: Arr) -> Arr:
        X, Y, Z = p[:, 0], p[:, 1], p[:, 2]
        return np.stack([2 * A * X + D * Y + E * Z + G, 2 * B * Y + D * X + F * Z + H,
                         2 * C * Z + E * X + F * Y + I], axis=1)
    _quadric_hits(c, o, d, a, b, cc, grad)


def _cylinder(p0: Arr, axis: Arr, r: float, o: Arr, d: Arr, c: Cands, length: float | None,
              capped: bool) -> None:
    u = axis / np.linalg.norm(axis)
    w = o - p0
    dp = d - _dot(d, u)[:, None] * u
    wp = w - _dot(w, u)[:, None] * u

    def grad(p: Arr) -> Arr:
        q = p - p0
        return (q - _dot(q, u)[:, None] * u) / r

    def in_slab(p: Arr) -> Arr:
        s = _dot(p - p0, u)
        return (s >= 0) & (s <= length)
    keep = None if length is None else in_slab
    _quadric_hits(c, o, d, _dot(dp, dp), 2 * _dot(wp, dp), _dot(wp, wp) - r * r, grad, 0, keep)
    if not capped or length is None:
        return
    du = _dot(d, u)
    for prim, base, n in ((1, p0, -u), (2, p0 + length * u, u)):
        with np.errstate(invalid="ignore", divide="ignore"):
            t = _dot(base - o, u) / du
        p = o + t[:, None] * d
        q = p - base
        inside = _dot(q, q) - _dot(q, u) ** 2 <= r * r
        c.add(np.where(inside, t, np.nan), _kind_of(d, np.broadcast_to(n, d.shape)), prim, n)


def cylinder(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    p0, p1 = np.array(spec["p0"]), np.array(spec["p1"])
    _cylinder(p0, p1 - p0, spec["radius"], o, d, c, float(np.linalg.norm(p1 - p0)), spec["capped"])


def infinite_cylinder(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    _cylinder(np.array(spec["point"]), np.array(spec["axis"]), spec["radius"], o, d, c, None, False)


def _plane_t(n: Arr, off: float, o: Arr, d: Arr) -> Arr:
    with np.errstate(invalid="ignore", divide="ignore"):
        t = -(o @ n + off) / (d @ n)
    return np.where(np.isfinite(t), t, np.nan)


def plane(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    n = np.array(spec["normal"])
    c.add(_plane_t(n, spec["d"], o, d), _kind_of(d, np.broadcast_to(n, d.shape)), -1, _normalize(n))


def _moller_trumbore(a: Arr, b: Arr, cv: Arr, o: Arr, d: Arr) -> Arr:
    e1, e2 = b - a, cv - a
    pv = np.cross(d, e2)
    det = pv @ e1
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = 1.0 / det
        tv = o - a
        u = _dot(tv, pv) * inv
        qv = np.cross(tv, e1)
        v = _dot(d, qv) * inv
        t = (qv @ e2) * inv
    ok = (det != 0) & (u >= 0) & (u <= 1) & (v >= 0) & (u + v <= 1)
    return np.where(ok, t, np.nan)


def triangle(spec: dict, o: Arr, d: Arr, c: Cands, prim: int = -1) -> None:
    a, b, cv = (np.array(spec[k]) for k in ("a", "b", "c"))
    n = np.cross(b - a, cv - a)
    c.add(_moller_trumbore(a, b, cv, o, d), _kind_of(d, np.broadcast_to(n, d.shape)), prim, _normalize(n))


def polygon(spec: dict, o: Arr, d: Arr, c: Cands, prim: int = -1) -> None:
    v = np.array(spec["vertices"])
    m = v.mean(axis=0)
    w = np.roll(v, -1, axis=0)
    n = np.cross(v - m, w - m).sum(axis=0)                   # Newell
    t = _plane_t(n, -float(n @ m), o, d)
    p = o + t[:, None] * d
    drop = int(np.argmax(np.abs(n)))
    i, j = [k for k in range(3) if k != drop]
    px, py = p[:, i], p[:, j]
    wind = np.zeros(len(o), dtype=int)
    for (x0, y0), (x1, y1) in zip(v[:, [i, j]], w[:, [i, j]]):
        side = (x1 - x0) * (py - y0) - (px - x0) * (y1 - y0)
        up = (y0 <= py) & (y1 > py) & (side > 0)
        down = (y0 > py) & (y1 <= py) & (side < 0)
        wind += up.astype(int) - down.astype(int)
    inside = (wind % 2 == 1) if spec.get("rule", "evenodd") == "evenodd" else (wind != 0)
    c.add(np.where(inside, t, np.nan), _kind_of(d, np.broadcast_to(n, d.shape)), prim, _normalize(n))


def _slabs(planes: list[tuple[Arr, float]], o: Arr, d: Arr, c: Cands) -> None:
    """enterMax / exitMin over half-spaces n.x + off <= 0 (prim = index)."""
    N = len(o)
    t_in, t_out = np.full(N, -np.inf), np.full(N, np.inf)
    p_in, p_out = np.full(N, -1), np.full(N, -1)
    empty = np.zeros(N, dtype=bool)
    for k, (n, off) in enumerate(planes):
        den = d @ n
        side = o @ n + off
        with np.errstate(invalid="ignore", divide="ignore"):
            t = -side / den
        enter, leave = den < 0, den > 0
        empty |= (den == 0) & (side > 0)
        upd = enter & (t > t_in)
        t_in, p_in = np.where(upd, t, t_in), np.where(upd, k, p_in)
        upd = leave & (t < t_out)
        t_out, p_out = np.where(upd, t, t_out), np.where(upd, k, p_out)
    hit = ~empty & (t_in <= t_out)
    normals = np.array([n / np.linalg.norm(n) for n, _ in planes])
    touch = hit & (t_in == t_out)
    n_in = normals[np.maximum(p_in, 0)]
    n_out = normals[np.maximum(p_out, 0)]
    c.t.append(np.where(hit & np.isfinite(t_in), t_in, np.nan))
    c.kind.append(np.where(touch, TOUCH, ENTER).astype(np.int32))
    c.prim.append(p_in.astype(np.int32))
    c.normal.append(n_in)
    c.t.append(np.where(hit & ~touch & np.isfinite(t_out), t_out, np.nan))
    c.kind.append(np.full(N, EXIT, dtype=np.int32))
    c.prim.append(p_out.astype(np.int32))
    c.normal.append(n_out)


def convex(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    _slabs([(np.array(p[:3]), p[3]) for p in spec["planes"]], o, d, c)


def box(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    lo, hi = spec["lo"], spec["hi"]
    planes = []
    for k in range(3):
        e = np.eye(3)[k]
        planes += [(-e, lo[k]), (e, -hi[k])]
    _slabs(planes, o, d, c)


def mesh(spec: dict, o: Arr, d: Arr, c: Cands) -> None:
    v = spec["vertices"]
    for f, face in enumerate(spec["faces"]):
        if len(face) == 3:
            triangle({"a": v[face[0]], "b": v[face[1]], "c": v[face[2]]}, o, d, c, f)
        else:
            polygon({"vertices": [v[k] for k in face], "rule": "evenodd"}, o, d, c, f)


SOLVERS = {"sphere": sphere, "ellipsoid": ellipsoid, "quadric": quadric, "cylinder": cylinder,
           "infinite_cylinder": infinite_cylinder, "plane": plane, "triangle": triangle,
           "polygon": polygon, "convex": convex, "box": box, "mesh": mesh}


def intersect_all(spec: dict, o: Arr, d: Arr, tmin: Arr, tmax: Arr) -> tuple[npt.NDArray[np.int64], np.ndarray]:
    """Every textbook hit in [tmin, tmax], sorted by t, as (offsets, HIT_DTYPE)."""
    N = len(o)
    m = spec.get("transform")
    c = Cands(N)
    if m is None:
        SOLVERS[spec["type"]](spec, o, d, c)
    else:
        M = np.array(m).reshape(4, 4)
        Mi = np.linalg.inv(M)
        oo = o @ Mi[:3, :3].T + Mi[:3, 3]
        dd = d @ Mi[:3, :3].T
        SOLVERS[spec["type"]](spec, oo, dd, c)
        c.normal = [_normalize(np.asarray(n) @ Mi[:3, :3]) for n in c.normal]
    T = np.stack(c.t, axis=1)
    K = T.shape[1]
    kind = np.stack(c.kind, axis=1)
    prim = np.stack(c.prim, axis=1)
    nrm = np.stack([np.broadcast_to(n, (N, 3)) for n in c.normal], axis=1)
    keep = np.isfinite(T) & (T >= tmin[:, None]) & (T <= tmax[:, None])
    order = np.argsort(np.where(keep, T, np.inf), axis=1, kind="stable")
    counts = keep.sum(axis=1)
    offsets = np.zeros(N + 1, dtype=np.int64)
    offsets[1:] = np.cumsum(counts)
    hits = np.zeros(int(offsets[-1]), dtype=HIT_DTYPE)
    rows = np.repeat(np.arange(N), counts)
    cols = order[np.arange(K)[None, :] < counts[:, None]]
    t = T[rows, cols]
    hits["t"] = t
    if m is None:
        hits["point"] = o[rows] + t[:, None] * d[rows]
    else:
        p_obj = oo[rows] + t[:, None] * dd[rows]
        hits["point"] = p_obj @ M[:3, :3].T + M[:3, 3]
    hits["normal"] = nrm[rows, cols]
    hits["prim"] = prim[rows, cols]
    hits["kind"] = kind[rows, cols]
    return offsets, hits
