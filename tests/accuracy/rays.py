# SPDX-License-Identifier: Apache-2.0
"""The ray classes: reproducible batches of (object, rays) per primitive.

Every class draws its objects and rays from a seeded numpy Generator, so a
(primitive, class, n, seed) always gives the same doubles.  Points "on the
surface" are exact: a random ray is solved by the exact reference and the
exact crossing point P = o + t d (rationals / 80 digits) is what the classes
start from, rounded once to doubles where a ray needs it.

* random   sizes 1e-3..1e3, centres up to 1e7 from the origin (quadrics:
           within 1e3 sizes, see primitives.QUADRICS), origins inside, near
           and far (up to 1e7), aimed or not, directions of length 1e-3..1e3,
           some rays with a finite [tmin, tmax];
* far      objects of size 1e-4..1e-2 seen from 1e6..2e7 away;
* grazing  curved parts: tangent lines moved off the surface by +-1e-16..1e-5
           of the size (straddling the eps = 1e-12 tangency test); planar
           parts: directions tilted out of the plane by +-1e-17..1e-3;
* tangent  curved parts: exactly tangent rays (axis-aligned constructions
           whose doubles are exact) and those off by 1..4 ulps, plus rounded
           tangents at random points; planar shapes: rays through vertices
           and edges (exactly, along an axis, or through the rounded point);
* surface  origins at a rounded exact surface point, nudged by up to 2 ulps
           per coordinate, directions into and out of the solid, tmin = 0;
* secondary  built by the harness from the library's first hits (see harness).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Callable, Sequence

import mpmath
import numpy as np

from . import primitives as P
from . import reference as R
from .reference import exact

CLASSES = ("random", "far", "grazing", "tangent", "surface", "secondary")
RAYS_PER_OBJECT = 25
Rng = np.random.Generator


@dataclass
class Group:
    """One object and a batch of rays at it."""
    inst: P.Instance
    org: np.ndarray
    dir: np.ndarray
    tmin: np.ndarray
    tmax: np.ndarray


def _group(inst: P.Instance, rays: Sequence[tuple]) -> Group:
    o = np.array([r[0] for r in rays], dtype=float).reshape(-1, 3)
    d = np.array([r[1] for r in rays], dtype=float).reshape(-1, 3)
    tmin = np.array([r[2] if len(r) > 2 else 0.0 for r in rays], dtype=float)
    tmax = np.array([r[3] if len(r) > 3 else math.inf for r in rays], dtype=float)
    return Group(inst, o, d, tmin, tmax)


def ulp(x: float) -> float:
    return math.ulp(x) if x != 0 else 5e-324


def nudge(p: Sequence[float], ks: Sequence[int]) -> list[float]:
    """p with k_i whole ulps added to coordinate i (nextafter steps)."""
    out = []
    for x, k in zip(p, ks):
        for _ in range(abs(int(k))):
            x = math.nextafter(x, math.inf if k > 0 else -math.inf)
        out.append(x)
    return out


def placement(name: str, rng: Rng, far: bool = False) -> tuple[float, np.ndarray]:
    """(size, centre) of an object of the class."""
    if far:
        s = P.loguniform(rng, 1e-4, 1e-2)
        if name in P.QUADRICS:
            return s, s * rng.normal(size=3)
        return s, P.unit(rng) * P.loguniform(rng, 1e6, 2e7)
    s = P.loguniform(rng, 1e-3, 1e3)
    if rng.random() < 0.25:
        return s, 3 * s * rng.normal(size=3)
    hi = 1e3 * s if name in P.QUADRICS else 1e7
    return s, P.unit(rng) * P.loguniform(rng, min(1e-3, hi / 10), hi)


def objects(name: str, rng: Rng, n: int, far: bool = False) -> list[tuple[P.Instance, int]]:
    """Enough objects for n rays, and how many rays each gets."""
    k = max(1, math.ceil(n / RAYS_PER_OBJECT))
    counts = [n // k + (i < n % k) for i in range(k)]
    maker = P.PRIMITIVES[name]
    return [(maker(rng, *placement(name, rng, far)), m) for m in counts if m]


def _aim(inst: P.Instance, rng: Rng) -> np.ndarray:
    """A target: a random convex combination of three of the object's points
    (half of the time, when it has them), else a point of its bounding ball."""
    if inst.points is not None and rng.random() < 0.5:
        w = rng.dirichlet(np.ones(3))
        return w @ inst.points[rng.choice(len(inst.points), 3, replace=False)]
    return inst.center + inst.radius * 0.9 * P.unit(rng) * rng.random() ** (1 / 3)


def _length(rng: Rng) -> float:
    return P.loguniform(rng, 1e-3, 1e3)


# ------------------------------------------------------------------ random
def random_rays(name: str, rng: Rng, n: int) -> list[Group]:
    groups = []
    for inst, m in objects(name, rng, n):
        rays = []
        for _ in range(m):
            u = rng.random()
            if u < 0.15:
                o = inst.center + 0.3 * inst.radius * rng.normal(size=3)
            elif u < 0.6:
                o = inst.center + P.unit(rng) * inst.radius * P.loguniform(rng, 1.5, 1e3)
            else:
                o = inst.center + P.unit(rng) * P.loguniform(rng, inst.radius, 1e7)
            d = (_aim(inst, rng) - o) if rng.random() < 0.9 else P.unit(rng)
            d = d / np.linalg.norm(d) * _length(rng)
            if rng.random() < 0.15:
                tm = float(np.linalg.norm(inst.center - o) / np.linalg.norm(d))
                lo = tm * rng.uniform(0, 1.2)
                rays.append((o, d, lo, lo + tm * rng.uniform(0, 1)))
            else:
                rays.append((o, d))
        groups.append(_group(inst, rays))
    return groups


def far_rays(name: str, rng: Rng, n: int) -> list[Group]:
    groups = []
    for inst, m in objects(name, rng, n, far=True):
        rays = []
        for _ in range(m):
            if np.linalg.norm(inst.center) > 1e5:
                o = P.unit(rng) * P.loguniform(rng, 1e-3, 10)
            else:
                o = inst.center + P.unit(rng) * P.loguniform(rng, 1e6, 2e7)
            d = _aim(inst, rng) - o
            rays.append((o, d / np.linalg.norm(d) * _length(rng)))
        groups.append(_group(inst, rays))
    return groups


# ------------------------------------------------------- surface samples
@dataclass(frozen=True)
class SurfacePoint:
    """An exact point on the surface, its exact unit normal and part."""
    p: tuple
    n: tuple
    prim: int


def surface_point(inst: P.Instance, rng: Rng) -> SurfacePoint:
    """A random exact surface point: a crossing of a random line, solved exactly."""
    for _ in range(200):
        o = inst.center + P.unit(rng) * inst.radius * 3
        d = _aim(inst, rng) - o
        try:
            res = R.solve(inst.spec, o, d, -math.inf, math.inf)
        except R.Undecided:
            continue
        if res.hits:
            h = res.hits[int(rng.integers(len(res.hits)))]
            p = exact.point_on_ray(exact.qv(o), exact.qv(d), h.t)
            return SurfacePoint(tuple(exact.mp(x) for x in p), h.normal, h.prim)
    raise RuntimeError(f"{inst.name}: no surface point found")


def _mp_unit(v: Sequence) -> tuple:
    n = mpmath.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def tangent_dir(n: Sequence, rng: Rng) -> tuple:
    """A random unit vector perpendicular to n (80 digits)."""
    v = [mpmath.mpf(float(x)) for x in rng.normal(size=3)]
    vn = sum(a * b for a, b in zip(v, n))
    return _mp_unit([a - vn * b for a, b in zip(v, n)])


def _scaled(d: Sequence, length: float) -> list[float]:
    """The doubles of length * d (one common factor, so the direction is kept)."""
    return [exact.to_double(x * length) for x in d]


def _dbl(v: Sequence) -> list[float]:
    return [exact.to_double(x) if isinstance(x, mpmath.mpf) else float(x) for x in v]


# ---------------------------------------------------------------- grazing
def grazing_rays(name: str, rng: Rng, n: int) -> list[Group]:
    groups = []
    for inst, m in objects(name, rng, n):
        rays = []
        for _ in range(m):
            sp = surface_point(inst, rng)
            t = tangent_dir(sp.n, rng)
            sgn = 1 if rng.random() < 0.5 else -1
            if P.curved(inst, sp.prim):
                off = sgn * P.loguniform(rng, 1e-16, 1e-5) * inst.radius
                d = t
                base = [a + off * b for a, b in zip(sp.p, sp.n)]
            else:
                tilt = sgn * P.loguniform(rng, 1e-17, 1e-3)
                d = _mp_unit([a + tilt * b for a, b in zip(t, sp.n)])
                base = list(sp.p)
            tau = inst.radius * P.loguniform(rng, 0.5, 1e3)
            o = [a - tau * b for a, b in zip(base, d)]
            rays.append((_dbl(o), _scaled(d, _length(rng))))
        groups.append(_group(inst, rays))
    return groups


# ---------------------------------------------------------------- tangent
def _exact_offset(c: float, r: float, sign: int) -> tuple[float, float] | None:
    """(c + sign r', r') with both doubles and c + sign r' exact, r' ~ r."""
    u = ulp(max(abs(c), r)) * 2
    r2 = max(round(r / u), 1) * u
    p = c + sign * r2
    if Fraction(p) - Fraction(c) == sign * Fraction(r2):
        return p, r2
    return None


def exact_tangent(name: str, rng: Rng, s: float, c: np.ndarray) -> tuple[P.Instance, list] | None:
    """An object and rays exactly tangent to it in doubles (axis-aligned), or
    None when the family has no such construction.

    Sphere / ellipsoid: the plane x_k = c_k +- r is tangent at c +- r e_k; a
    ray in it along e_j through that point (other coordinate = c_i) touches.
    Cylinders with axis e_a: the plane x_k = c_k +- r touches along the
    ruling x_j = c_j; any ray in that plane crossing the ruling (d_j != 0)
    touches.  The rays are nudged by 0..4 ulps off the plane afterwards.
    """
    k, j = rng.choice(3, 2, replace=False)
    i = 3 - k - j
    sign = 1 if rng.random() < 0.5 else -1
    out = _exact_offset(float(c[k]), s, sign)
    if out is None:
        return None
    pk, r = out
    if name in ("sphere", "ellipsoid"):
        if name == "sphere":
            inst = P.Instance(name, {"type": "sphere", "center": P.as_list(c), "radius": r},
                              P.isect.Sphere(c, r), max(P.inf_norm(c), r), c, r)
        else:
            radii = s * rng.uniform(0.2, 1, 3)
            radii[k] = r
            inst = P.Instance(name, {"type": "ellipsoid", "center": P.as_list(c), "radii": P.as_list(radii)},
                              P.isect.Ellipsoid(c, radii), max(P.inf_norm(c), s), c, s)

        def ray() -> tuple:
            o = c.copy()
            o[k] = pk
            lam = _length(rng) * (1 if rng.random() < 0.5 else -1)
            o[j] = c[j] - lam * inst.radius * P.loguniform(rng, 1, 1e3)
            d = np.zeros(3)
            d[j] = lam
            return o, d
    elif name in ("cylinder_inf", "cylinder_capped", "cylinder_open"):
        a = i
        h = s * rng.uniform(0.5, 2)
        e = np.eye(3)[a]
        if name == "cylinder_inf":
            inst = P.Instance(name, {"type": "infinite_cylinder", "point": P.as_list(c), "axis": P.as_list(e * h),
                                     "radius": r}, P.isect.InfiniteCylinder(c, e * h, r), max(P.inf_norm(c), r), c,
                              2 * r, True)
            p0 = c
        else:
            p0, p1 = c.copy(), c.copy()
            p1[a] = c[a] + h
            capped = name == "cylinder_capped"
            inst = P.Instance(name, {"type": "cylinder", "p0": P.as_list(p0), "p1": P.as_list(p1), "radius": r,
                                     "capped": capped}, P.isect.Cylinder(p0, p1, r, capped=capped),
                              max(P.inf_norm(p0), P.inf_norm(p1), r), c, h + r)

        def ray() -> tuple:
            d = np.zeros(3)
            d[j] = _length(rng) * (1 if rng.random() < 0.5 else -1)
            d[a] = d[j] * rng.normal()
            tau = r * P.loguniform(rng, 1, 1e3)
            contact = p0[a] + (h * rng.uniform(0.05, 0.95) if name != "cylinder_inf" else 0.0)
            o = np.zeros(3)
            o[k] = pk
            o[j] = c[j] - tau * math.copysign(1, d[j])
            o[a] = contact - (tau / abs(d[j])) * d[a]
            return o, d
    else:
        return None
    rays = []
    for _ in range(RAYS_PER_OBJECT):
        o, d = ray()
        kk = [0, 0, 0]
        if rng.random() < 0.5:
            kk[k] = int(rng.integers(1, 5)) * (1 if rng.random() < 0.5 else -1)
        rays.append((nudge(o, kk), d))
    return inst, rays


def exact_quadric_tangent(name: str, rng: Rng) -> tuple[P.Instance, list]:
    """Quadrics centred at 0 with power-of-two coefficients (times one double
    lam), touched exactly at dyadic points by rays with dyadic doubles:
    hyperboloid x^2 + y^2 - z^2 = rho^2 at (rho, 0, 0) by (0, dy, dz);
    cone x^2 + y^2 = z^2 at (m, 0, m) by (u, v, u);
    paraboloid x^2 + y^2 = k z at (a, 0, a^2/k) by (k u, v, 2 a u)."""
    lam = P.loguniform(rng, 1e-2, 1e2) * (1 if rng.random() < 0.5 else -1)
    e = int(rng.integers(-8, 9))
    sc = 2.0 ** e

    def dy() -> float:
        return float(rng.integers(-64, 65) or 1) / 8

    if name == "hyperboloid":
        coeffs = [lam, lam, -lam, 0, 0, 0, 0, 0, 0, -lam * sc * sc]

        def tangent() -> tuple[list[float], list[float]]:
            return [sc, 0.0, 0.0], [0.0, dy(), dy()]
    elif name == "cone":
        coeffs = [lam, lam, -lam, 0, 0, 0, 0, 0, 0, 0]

        def tangent() -> tuple[list[float], list[float]]:
            u = dy()
            return [sc, 0.0, sc], [u, dy(), u]
    else:
        kq = sc
        coeffs = [lam, lam, 0, 0, 0, 0, 0, 0, -lam * kq, 0]

        def tangent() -> tuple[list[float], list[float]]:
            a = sc * dy()
            u = dy()
            return [a, 0.0, a * a / kq], [kq * u, dy(), 2 * a * u]
    inst = P.Instance(name, {"type": "quadric", "coeffs": coeffs}, P.isect.Quadric(coeffs), sc,
                      np.zeros(3), 2 * sc, True)
    rays = []
    for _ in range(RAYS_PER_OBJECT):
        p, d = tangent()
        tau = 2.0 ** int(rng.integers(-2, 8))
        o = [a - tau * b for a, b in zip(p, d)]
        kk = [0, 0, 0]
        if rng.random() < 0.5:
            kk[int(rng.integers(3))] = int(rng.integers(1, 5)) * (1 if rng.random() < 0.5 else -1)
        rays.append((nudge(o, kk), d))
    return inst, rays


def boundary_point(inst: P.Instance, rng: Rng) -> tuple:
    """An exact point (rationals, world) on an edge or at a vertex of a planar shape."""
    spec = inst.spec
    kind = spec["type"]
    q = exact.qv
    if kind == "box":
        lo, hi = q(spec["lo"]), q(spec["hi"])
        p = [lo[k] + Fraction(rng.random()) * (hi[k] - lo[k]) for k in range(3)]
        for k in rng.choice(3, 3 if rng.random() < 0.3 else 2, replace=False):
            p[k] = lo[k] if rng.random() < 0.5 else hi[k]
        pts = p
    elif kind == "convex":
        pts = convex_boundary(spec, rng)
    elif kind == "cylinder":
        p0, p1 = q(spec["p0"]), q(spec["p1"])
        axis = [float(b - a) for a, b in zip(p0, p1)]
        t = tangent_dir(_mp_unit([mpmath.mpf(x) for x in axis]), rng)
        base = p0 if rng.random() < 0.5 else p1
        pts = [exact.mp(b) + exact.mp(Fraction(spec["radius"])) * x for b, x in zip(base, t)]
    else:
        if kind == "mesh":
            face = spec["faces"][int(rng.integers(len(spec["faces"])))]
            vs = [q(spec["vertices"][k]) for k in face]
        elif kind == "triangle":
            vs = [q(spec[k]) for k in ("a", "b", "c")]
        else:
            vs = [q(v) for v in spec["vertices"]]
        i = int(rng.integers(len(vs)))
        a, b = vs[i], vs[(i + 1) % len(vs)]
        lam = Fraction(0) if rng.random() < 0.3 else Fraction(int(rng.integers(1, 64)), 64)
        pts = [x + lam * (y - x) for x, y in zip(a, b)]
    m = spec.get("transform")
    if m is not None:
        L, T = R.transformed.linear(m), R.transformed.translation(m)
        pts = [x + t for x, t in zip(R.transformed.mul(L, pts), T)]
    return tuple(pts)


def _corners(spec: dict) -> list[tuple[int, int, int]]:
    """The plane triples that meet at a vertex of a convex polyhedron, found in
    doubles (a vertex satisfies every half-space to 1e-9 relative)."""
    pl = np.array(spec["planes"], dtype=float)
    out = []
    m = len(pl)
    for a in range(m):
        for b in range(a + 1, m):
            for c in range(b + 1, m):
                A = pl[[a, b, c], :3]
                if abs(np.linalg.det(A)) < 1e-12 * np.prod(np.linalg.norm(A, axis=1)):
                    continue
                x = np.linalg.solve(A, -pl[[a, b, c], 3])
                tol = 1e-9 * (np.abs(pl[:, :3]) @ np.abs(x) + np.abs(pl[:, 3]))
                if np.all(pl[:, :3] @ x + pl[:, 3] <= tol):
                    out.append((a, b, c))
    return out


def _vertex(spec: dict, triple: tuple[int, int, int]) -> tuple[Fraction, ...]:
    """The exact intersection of three planes (Cramer's rule in rationals)."""
    rows = [exact.qv(spec["planes"][i]) for i in triple]
    A = [r[:3] for r in rows]
    rhs = [-r[3] for r in rows]
    det = R.transformed.det3(A)
    return tuple(R.transformed.det3([[rhs[i] if j == col else A[i][j] for j in range(3)] for i in range(3)])
                 / det for col in range(3))


def convex_boundary(spec: dict, rng: Rng) -> tuple[Fraction, ...]:
    """A vertex, or a point k/8 along an edge (two vertices sharing two planes)."""
    corners = _corners(spec)
    a = corners[int(rng.integers(len(corners)))]
    nbrs = [b for b in corners if len(set(a) & set(b)) == 2]
    if not nbrs or rng.random() < 0.3:
        return _vertex(spec, a)
    va, vb = _vertex(spec, a), _vertex(spec, nbrs[int(rng.integers(len(nbrs)))])
    lam = Fraction(int(rng.integers(1, 8)), 8)
    return tuple(x + lam * (y - x) for x, y in zip(va, vb))


def tangent_rays(name: str, rng: Rng, n: int) -> list[Group]:
    groups = []
    made = 0
    while made < n:
        s, c = placement(name, rng)
        inst = None
        if rng.random() < 0.4:
            if name in P.QUADRICS:
                inst, rays = exact_quadric_tangent(name, rng)
            else:
                got = exact_tangent(name, rng, s, c)
                if got is not None:
                    inst, rays = got
        if inst is None:
            inst = P.PRIMITIVES[name](rng, s, c)
            rays = []
            planar = not any(P.curved(inst, p) for p in (0, -1))
            for _ in range(RAYS_PER_OBJECT):
                if planar or (inst.spec["type"] == "cylinder" and rng.random() < 0.3):
                    rays.append(_through(boundary_point(inst, rng), inst, rng))
                else:
                    sp = surface_point(inst, rng)
                    if not P.curved(inst, sp.prim):
                        rays.append(_through(boundary_point(inst, rng), inst, rng))
                        continue
                    d = tangent_dir(sp.n, rng)
                    tau = inst.radius * P.loguniform(rng, 0.5, 1e3)
                    o = _dbl([a - tau * b for a, b in zip(sp.p, d)])
                    kk = [0, 0, 0]
                    kk[int(np.argmax([abs(float(x)) for x in sp.n]))] = int(rng.integers(-4, 5))
                    rays.append((nudge(o, kk), _scaled(d, _length(rng))))
        rays = rays[:n - made]
        made += len(rays)
        groups.append(_group(inst, rays))
    return groups


def _through(pb: tuple, inst: P.Instance, rng: Rng) -> tuple:
    """A ray through the (rounded) boundary point: along an axis (then the
    line contains the rounded point exactly) or in a random direction."""
    p = _dbl([exact.mp(x) for x in pb])
    if rng.random() < 0.5:
        p = nudge(p, rng.integers(-2, 3, 3))
    tau = inst.radius * P.loguniform(rng, 0.5, 1e3)
    if rng.random() < 0.5:
        k = int(rng.integers(3))
        d = np.zeros(3)
        d[k] = _length(rng) * (1 if rng.random() < 0.5 else -1)
        o = list(p)
        o[k] = p[k] - tau * math.copysign(1, d[k])
        return o, d
    u = P.unit(rng)
    return [a - tau * b for a, b in zip(p, u)], u * _length(rng)


# ---------------------------------------------------------------- surface
def surface_rays(name: str, rng: Rng, n: int) -> list[Group]:
    groups = []
    for inst, m in objects(name, rng, n):
        rays = []
        for _ in range(m):
            sp = surface_point(inst, rng)
            p = _dbl(sp.p)
            if rng.random() < 0.7:
                p = nudge(p, rng.integers(-2, 3, 3))
            u = P.unit(rng)
            nn = np.array([float(x) for x in sp.n])
            want = 1 if rng.random() < 0.5 else -1          # out of / into the solid
            if (u @ nn) * want < 0:
                u = u - 2 * (u @ nn) * nn
            rays.append((p, u * _length(rng)))
        groups.append(_group(inst, rays))
    return groups


GENERATORS: dict[str, Callable[[str, Rng, int], list[Group]]] = {
    "random": random_rays, "far": far_rays, "grazing": grazing_rays, "tangent": tangent_rays,
    "surface": surface_rays, "secondary": random_rays,
}


def applicable(name: str, cls: str) -> bool:
    """The plane has no boundary and no tangency: no tangent class."""
    return not (name == "plane" and cls == "tangent")
