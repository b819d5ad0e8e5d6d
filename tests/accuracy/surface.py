# SPDX-License-Identifier: Apache-2.0
"""Exact distance from a reported hit point to the exact surface.

For a point P (doubles, so exact rationals) and the face or part ``prim`` that
the exact reference hit, the distance to the surface is

* exact where it is cheap: planes and faces |F(P)| / |grad F| with F affine
  (plane n.x + d, triangle n.(x - a), polygon N.(x - m) with the Newell normal
  N and the centroid m, box faces, convex planes, cylinder caps); the sphere
  | |P - c| - r |; the cylinder side | dist(P, axis) - r |;
* first order elsewhere: |F(P)| / |grad F(P)| (ellipsoid, quadric, and every
  curved surface under a transform), which equals the distance up to a
  relative O(distance / curvature radius), far below the resolution needed.

Under a transform M = [L | T] the object-space function is used at
x = L^-1 (P - T) (exact inverse) with the world gradient L^-T grad F(x), so
|F| / |L^-T grad F| is again exact for planar faces and first order otherwise.
Everything rational is a Fraction; one mpmath square root per point.
"""
from __future__ import annotations

import functools
from fractions import Fraction
from typing import Sequence

import mpmath

from .reference import exact, polygon, quadric, transformed

Vec = tuple[Fraction, Fraction, Fraction]


def _sub(a: Sequence[Fraction], b: Sequence[Fraction]) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _dot(a: Sequence[Fraction], b: Sequence[Fraction]) -> Fraction:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _perp(w: Vec, a: Vec) -> Vec:
    """The part of w perpendicular to a."""
    s = _dot(w, a) / _dot(a, a)
    return (w[0] - s * a[0], w[1] - s * a[1], w[2] - s * a[2])


def _face(spec: dict, prim: int) -> dict:
    """The sub-shape a mesh hit lies on (triangle or polygon of face prim)."""
    from .reference import mesh
    return mesh.face_shape(spec, spec["faces"][prim])


@functools.lru_cache(maxsize=256)
def _newell(vertices: tuple[tuple[float, ...], ...]) -> tuple[Vec, Vec]:
    """(Newell normal, centroid) of a polygon, exactly (memoised)."""
    return polygon.newell([exact.qv(v) for v in vertices])


def level_set(spec: dict, prim: int, x: Vec) -> tuple[Fraction, Vec]:
    """(F(x), grad F(x)) in object space of the surface part ``prim``; F = 0 on it."""
    kind = spec["type"]
    qv = exact.qv
    if kind == "mesh":
        return level_set(_face(spec, prim), -1, x)
    if kind == "plane":
        n = qv(spec["normal"])
        return _dot(n, x) + Fraction(spec["d"]), n
    if kind == "sphere":
        w = _sub(x, qv(spec["center"]))
        return _dot(w, w) - Fraction(spec["radius"]) ** 2, tuple(2 * c for c in w)
    if kind == "box":
        axis, hi = divmod(prim, 2)
        bound = Fraction((spec["hi"] if hi else spec["lo"])[axis])
        g = tuple(Fraction(int(k == axis)) for k in range(3))
        return x[axis] - bound, g
    if kind == "triangle":
        a, b, c = qv(spec["a"]), qv(spec["b"]), qv(spec["c"])
        n = exact.cross(_sub(b, a), _sub(c, a))
        return _dot(n, _sub(x, a)), n
    if kind == "polygon":
        n, m = _newell(tuple(tuple(v) for v in spec["vertices"]))
        return _dot(n, _sub(x, m)), n
    if kind == "convex":
        p = qv(spec["planes"][prim])
        n = p[:3]
        return _dot(n, x) + p[3], n
    if kind in ("cylinder", "infinite_cylinder"):
        p0 = qv(spec["p0"] if kind == "cylinder" else spec["point"])
        a = _sub(qv(spec["p1"]), p0) if kind == "cylinder" else qv(spec["axis"])
        if prim == 1:
            return _dot(_sub(x, p0), a), a
        if prim == 2:
            return _dot(_sub(x, p0), a) - _dot(a, a), a
        w = _perp(_sub(x, p0), a)
        return _dot(w, w) - Fraction(spec["radius"]) ** 2, tuple(2 * c for c in w)
    if kind == "ellipsoid":
        c, R = qv(spec["center"]), qv(spec["radii"])
        u = tuple((x[k] - c[k]) / R[k] for k in range(3))
        return _dot(u, u) - 1, tuple(2 * u[k] / R[k] for k in range(3))
    if kind == "quadric":
        k = qv(spec["coeffs"])
        return quadric.value(k, x), quadric.grad(k, x)
    raise ValueError(kind)


def _norm(v: Sequence[Fraction]) -> mpmath.mpf:
    return mpmath.sqrt(mpmath.mpf(_dot(v, v)))


def distance(spec: dict, prim: int, point: Sequence[float]) -> mpmath.mpf:
    """Distance (exact, or first order for curved transformed/implicit
    surfaces) from ``point`` to the part ``prim`` of the world surface."""
    P = exact.qv(point)
    m = spec.get("transform")
    kind = spec["type"]
    if m is None and kind == "sphere":
        w = _sub(P, exact.qv(spec["center"]))
        return abs(_norm(w) - mpmath.mpf(Fraction(spec["radius"])))
    if m is None and kind in ("cylinder", "infinite_cylinder") and prim == 0:
        p0 = exact.qv(spec["p0"] if kind == "cylinder" else spec["point"])
        a = _sub(exact.qv(spec["p1"]), p0) if kind == "cylinder" else exact.qv(spec["axis"])
        return abs(_norm(_perp(_sub(P, p0), a)) - mpmath.mpf(Fraction(spec["radius"])))
    if m is None:
        f, g = level_set(spec, prim, P)
        return abs(mpmath.mpf(f)) / _norm(g)
    L, T = transformed.linear(m), transformed.translation(m)
    Li = transformed.inverse3(L)
    x = transformed.mul(Li, _sub(P, T))
    f, g = level_set(spec, prim, x)
    return abs(mpmath.mpf(f)) / _norm(transformed.mul(transformed.transpose(Li), g))
