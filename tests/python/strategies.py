# SPDX-License-Identifier: Apache-2.0
"""Hypothesis strategies for shapes, rays and transforms, plus the small
amount of test-side geometry the properties need (rotation matrices, plane
sets of boxes). None of it is used by the package itself."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import isect
import numpy as np
from hypothesis import strategies as st


@dataclass(frozen=True)
class Sample:
    """A generated shape, a point to aim rays at, and its size."""

    shape: isect.Shape
    center: np.ndarray
    scale: float

    def __repr__(self) -> str:  # shown in hypothesis' falsifying examples
        return f"Sample({self.shape!r})"


def floats(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


def vec3(lo: float = -10.0, hi: float = 10.0) -> st.SearchStrategy[np.ndarray]:
    return st.tuples(floats(lo, hi), floats(lo, hi), floats(lo, hi)).map(np.array)


def nonzero_vec3(
    lo: float = -1.0, hi: float = 1.0, min_norm: float = 0.05
) -> st.SearchStrategy[np.ndarray]:
    return vec3(lo, hi).filter(lambda v: float(np.linalg.norm(v)) > min_norm)


POSITIVE = floats(0.1, 5.0)


def rotation_from(q: np.ndarray) -> np.ndarray:
    """The 3x3 rotation of a (not necessarily unit) quaternion w, x, y, z."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


rotations: st.SearchStrategy[np.ndarray] = (
    st.tuples(*[floats(-1, 1)] * 4)
    .map(np.array)
    .filter(lambda q: float(np.linalg.norm(q)) > 0.2)
    .map(rotation_from)
)


def affine(linear: np.ndarray, translation: np.ndarray) -> np.ndarray:
    """The 4x4 matrix of x -> linear @ x + translation."""
    m = np.eye(4)
    m[:3, :3] = linear
    m[:3, 3] = translation
    return m


def box_planes(lo: np.ndarray, hi: np.ndarray, m: np.ndarray) -> np.ndarray:
    """The 6 outward planes (-x, +x, -y, +y, -z, +z) of the box lo..hi placed
    by the rigid transform m, as ConvexPolyhedron rows."""
    rows = []
    for axis in range(3):
        for sign, bound in ((-1.0, lo[axis]), (1.0, hi[axis])):
            n_obj = np.zeros(3)
            n_obj[axis] = sign
            p_obj = np.zeros(3)
            p_obj[axis] = bound
            n = m[:3, :3] @ n_obj
            p = m[:3, :3] @ p_obj + m[:3, 3]
            rows.append([*n, -float(n @ p)])
    return np.array(rows)


@st.composite
def spheres(draw: st.DrawFn) -> Sample:
    c, r = draw(vec3(-5, 5)), draw(POSITIVE)
    return Sample(isect.Sphere(c, r), c, r + float(np.abs(c).max()))


@st.composite
def boxes(draw: st.DrawFn) -> Sample:
    lo, size = draw(vec3(-5, 5)), np.array([draw(POSITIVE) for _ in range(3)])
    return Sample(isect.Box(lo, lo + size), lo + size / 2, float(np.abs(lo).max() + size.max()))


@st.composite
def ellipsoids(draw: st.DrawFn) -> Sample:
    c, radii = draw(vec3(-5, 5)), np.array([draw(POSITIVE) for _ in range(3)])
    return Sample(isect.Ellipsoid(c, radii), c, float(np.abs(c).max() + radii.max()))


@st.composite
def cylinders(draw: st.DrawFn, capped: bool | None = None) -> Sample:
    p0, axis = draw(vec3(-5, 5)), draw(nonzero_vec3(-4, 4, 0.2))
    r = draw(POSITIVE)
    cap = draw(st.booleans()) if capped is None else capped
    return Sample(
        isect.Cylinder(p0, p0 + axis, r, capped=cap),
        p0 + axis / 2,
        float(np.abs(p0).max() + np.abs(axis).max() + r),
    )


@st.composite
def infinite_cylinders(draw: st.DrawFn) -> Sample:
    p, axis, r = draw(vec3(-5, 5)), draw(nonzero_vec3(-1, 1, 0.2)), draw(POSITIVE)
    return Sample(isect.InfiniteCylinder(p, axis, r), p, float(np.abs(p).max() + r))


@st.composite
def convex_polyhedra(draw: st.DrawFn) -> Sample:
    """Bounded: the 6 axis planes at random distances plus up to 4 random
    planes, all with the centre inside, then translated."""
    center = draw(vec3(-5, 5))
    normals = [np.eye(3)[i] * s for i in range(3) for s in (-1.0, 1.0)]
    normals += draw(st.lists(nonzero_vec3(-1, 1, 0.3), max_size=4))
    rows = []
    for n in normals:
        off = draw(POSITIVE)
        rows.append([*n, -float(n @ center) - off * float(np.linalg.norm(n))])
    return Sample(isect.ConvexPolyhedron(rows), center, float(np.abs(center).max() + 5))


@st.composite
def ellipsoid_quadrics(draw: st.DrawFn) -> Sample:
    """A rotated, translated ellipsoid written as a general quadric (bounded)."""
    c, rot = draw(vec3(-3, 3)), draw(rotations)
    radii = np.array([draw(floats(0.3, 3.0)) for _ in range(3)])
    a = rot @ np.diag(1.0 / radii**2) @ rot.T  # x^T A x + b.x + k, x -> x - c
    b = -2 * a @ c
    k = float(c @ a @ c) - 1.0
    coeffs = [a[0, 0], a[1, 1], a[2, 2], 2 * a[0, 1], 2 * a[0, 2], 2 * a[1, 2], *b, k]
    return Sample(isect.Quadric(coeffs), c, float(np.abs(c).max() + radii.max()))


@st.composite
def any_quadrics(draw: st.DrawFn) -> Sample:
    """Arbitrary coefficients: cones, cylinders, hyperboloids, paraboloids, planes."""
    coeffs = np.array([draw(floats(-2, 2)) for _ in range(10)])
    if not np.any(coeffs):
        coeffs[9] = -1.0
    return Sample(isect.Quadric(coeffs), np.zeros(3), 5.0)


@st.composite
def planes(draw: st.DrawFn) -> Sample:
    n, d = draw(nonzero_vec3()), draw(floats(-5, 5))
    return Sample(isect.Plane(n, d), -d * n / float(n @ n), abs(d) + 1)


@st.composite
def triangles(draw: st.DrawFn) -> Sample:
    a, b, c = draw(vec3(-5, 5)), draw(vec3(-5, 5)), draw(vec3(-5, 5))
    return Sample(isect.Triangle(a, b, c), (a + b + c) / 3, float(np.abs([a, b, c]).max()))


@st.composite
def polygons(draw: st.DrawFn) -> Sample:
    """A planar polygon (any of convex, concave, self-intersecting) in a random plane."""
    n = draw(st.integers(3, 8))
    pts2 = np.array([[draw(floats(-3, 3)), draw(floats(-3, 3))] for _ in range(n)])
    rot, origin = draw(rotations), draw(vec3(-5, 5))
    verts = origin + pts2[:, :1] * rot[:, 0] + pts2[:, 1:] * rot[:, 1]
    rule = draw(st.sampled_from(["evenodd", "nonzero"]))
    return Sample(isect.Polygon(verts, rule=rule), verts.mean(axis=0), float(np.abs(verts).max()))


def bounded_solids() -> st.SearchStrategy[Sample]:
    """Solids with a bounded inside."""
    return st.one_of(
        spheres(),
        boxes(),
        ellipsoids(),
        cylinders(capped=True),
        convex_polyhedra(),
        ellipsoid_quadrics(),
    )


def any_shapes() -> st.SearchStrategy[Sample]:
    """Every shape type."""
    return st.one_of(
        bounded_solids(),
        cylinders(),
        infinite_cylinders(),
        any_quadrics(),
        planes(),
        triangles(),
        polygons(),
    )


@st.composite
def transformed(draw: st.DrawFn, base: st.SearchStrategy[Sample]) -> Sample:
    """A sample placed by a random rotation, scaling and translation."""
    s = draw(base)
    lin = draw(rotations) @ np.diag([draw(floats(0.5, 2.0)) for _ in range(3)])
    t = draw(vec3(-5, 5))
    m = affine(lin, t)
    return Sample(s.shape.transformed(m), lin @ s.center + t, 2 * s.scale + float(np.abs(t).max()))


@st.composite
def aimed_rays(draw: st.DrawFn, sample: Sample) -> tuple[np.ndarray, np.ndarray]:
    """A ray from a random origin towards a point near the sample's centre."""
    origin = draw(vec3(-20, 20))
    target = sample.center + draw(vec3(-1, 1)) * sample.scale * 0.5
    d = target - origin
    if float(np.linalg.norm(d)) < 1e-6:
        d = np.array([0.0, 0.0, 1.0])
    return origin, d


def one_of_each() -> list[isect.Shape]:
    """One instance of every shape class."""
    return [
        isect.Plane([0, 0, 1], -0.5),
        isect.Sphere([0.1, 0.2, 0.3], 1.5),
        isect.Box([-1, -2, -3], [1, 2, 3]),
        isect.Triangle([-2, -2, 0], [2, -2, 0], [0, 2, 0]),
        isect.Polygon([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [0, 0.2, 0], [-1, 1, 0]]),
        isect.ConvexPolyhedron(
            [
                [1, 0, 0, -1],
                [-1, 0, 0, -1],
                [0, 1, 0, -1],
                [0, -1, 0, -1],
                [0, 0, 1, -1],
                [0, 0, -1, -1],
            ]
        ),
        isect.Cylinder([0, 0, -1], [0, 0, 1], 0.5),
        isect.Cylinder([0, 0, -1], [0, 0, 1], 0.5, capped=False),
        isect.InfiniteCylinder([0, 0, 0], [0, 1, 0], 0.75),
        isect.Ellipsoid([0, 0, 0], [1, 2, 0.5]),
        isect.Quadric([1, 1, 1, 0, 0, 0, 0, 0, 0, -1]),
    ]


# ------------------------------------------------- arguments in every form

#: Ints at the edges of the float64 conversion: beyond 2**53 (rounded), the
#: int64 and uint64 ranges, the largest finite doubles, and beyond (overflow).
EDGE_INTS = [
    2**53 + 1,
    -(2**53) - 3,
    2**63 - 1,
    2**63,
    2**63 + 1025,
    2**64 - 1,
    2**64 + 3,
    -(2**70) - 1,
    2**1023 * 3 // 2,
    2**1024 - 2**970,
    2**1024,
    -(10**400),
]


def number_likes() -> st.SearchStrategy[object]:
    """Anything a caller might pass as one number: Python floats (NaN, inf,
    -0.0, subnormals), ints (huge ones too), bools, numpy scalars of several
    types, complex numbers, strings, None."""
    return st.one_of(
        st.floats(),
        st.integers(),
        st.sampled_from(EDGE_INTS),
        st.booleans(),
        st.floats().map(np.float64),
        st.floats(width=32).map(np.float32),
        st.integers(-(2**63), 2**63 - 1).map(np.int64),
        st.booleans().map(np.bool_),
        st.complex_numbers(max_magnitude=10, allow_nan=False),
        st.complex_numbers(max_magnitude=10, allow_nan=False).map(np.complex128),
        st.sampled_from(["1.5", "x", "", b"2", None]),
    )


def _nearest_int(x: float) -> int | float:
    """The int nearest x; x itself if it is not finite."""
    return round(x) if math.isfinite(x) else x


def _element_form(draw: st.DrawFn, x: float) -> object:
    """One coordinate as a float, an int near it, or a numpy scalar."""
    kind = draw(st.sampled_from(["float", "int", "float64", "float32", "int64", "bool"]))
    if kind == "float":
        return x
    if kind == "int":
        return _nearest_int(x)
    if kind == "float64":
        return np.float64(x)
    if kind == "float32":
        with np.errstate(over="ignore"):
            return np.float32(x)
    if kind == "int64" and abs(x) < 2**62:
        return np.int64(round(x))
    return bool(x)


@st.composite
def vector_forms(draw: st.DrawFn, v: np.ndarray) -> object:
    """The 3-vector v as callers pass one: a list or tuple of floats, ints or
    numpy scalars, or an array (float64 contiguous, strided, read-only,
    float32, int, big-endian, object, (1, 3))."""
    plain = ["list", "tuple", "ints", "mixed list", "mixed tuple", "array", "strided", "read-only"]
    other = ["float32", "int64", "big-endian", "object", "row"]
    form = draw(st.sampled_from(plain if draw(st.integers(0, 3)) else other))
    values = [float(x) for x in v]
    if form == "list":
        return values
    if form == "tuple":
        return tuple(values)
    if form == "ints":
        return [_nearest_int(x) for x in values]
    if form in ("mixed list", "mixed tuple"):
        mixed = [_element_form(draw, x) for x in values]
        return mixed if form == "mixed list" else tuple(mixed)
    if form == "array":
        return np.array(values)
    if form == "strided":
        return np.repeat(np.array(values), 2)[::2]
    if form == "read-only":
        a = np.array(values)
        a.flags.writeable = False
        return a
    if form == "big-endian":
        return np.array(values, dtype=">f8")
    if form == "row":
        return np.array([values])
    if form == "int64":
        return np.array([_nearest_int(x) if abs(x) < 2**62 else 0 for x in values], dtype=np.int64)
    with np.errstate(over="ignore"):
        return np.array(values).astype(np.float32 if form == "float32" else object)


def malformed_vectors() -> st.SearchStrategy[object]:
    """Ray arguments that are not one good 3-vector: 3 odd numbers, too few
    or too many, scalars, strings, nested lists, empty and batch arrays,
    0-d arrays."""
    return st.one_of(
        st.lists(number_likes(), min_size=3, max_size=3),
        st.lists(number_likes(), min_size=3, max_size=3).map(tuple),
        st.lists(st.floats(-5, 5), min_size=0, max_size=5).filter(lambda v: len(v) != 3),
        number_likes(),
        st.sampled_from(["abc", "", [], (), [[0.0, 0.0, 1.0]], [[0.0], [0.0], [1.0]], {}]),
        st.sampled_from(
            [
                np.zeros(0),
                np.zeros((0, 3)),
                np.zeros((2, 3)),
                np.ones((3, 1)),
                np.array(1.0),
                np.array([1.0, 2.0, 3.0], dtype=complex),
                np.array([True, False, True]),
            ]
        ),
    )


@st.composite
def ray_arguments(draw: st.DrawFn, sample: Sample) -> tuple[Any, Any, dict[str, Any]]:
    """(origin, direction, keyword arguments) for ``Shape.intersect``: a ray
    aimed at the sample, a ray with NaN, infinity or a zero direction, or
    malformed arguments, each in any of the forms callers use; tmin and tmax
    left out or given as numbers or arrays of any kind."""
    origin, direction = draw(aimed_rays(sample))
    special = [np.nan, np.inf, -np.inf, 0.0, -0.0, 5e-324, 1e308]
    if draw(st.integers(0, 4)) == 0:  # a bad (or odd) coordinate somewhere
        which = draw(st.sampled_from(["origin", "direction"]))
        v = (origin if which == "origin" else direction).copy()
        v[draw(st.integers(0, 2))] = draw(st.sampled_from(special))
        origin, direction = (v, direction) if which == "origin" else (origin, v)
    if draw(st.integers(0, 9)) == 0:
        direction = np.zeros(3)
    o = draw(malformed_vectors()) if draw(st.integers(0, 5)) == 0 else draw(vector_forms(origin))
    d = draw(malformed_vectors()) if draw(st.integers(0, 5)) == 0 else draw(vector_forms(direction))
    kwargs: dict[str, Any] = {}
    bound = st.one_of(
        st.floats(),
        st.integers(-10, 100),
        st.sampled_from(EDGE_INTS),
        st.floats(-10, 100).map(np.float64),
        st.floats(-10, 100, width=32).map(np.float32),
        st.booleans(),
        st.sampled_from([np.array(1.0), np.array([0.0, 1.0]), "1", None, 1j]),
    )
    for name in ("tmin", "tmax"):
        if draw(st.booleans()):
            kwargs[name] = draw(bound)
    return o, d, kwargs
