# SPDX-License-Identifier: Apache-2.0
"""Input types (issue 13, item 5): immutable shape arrays, non-numeric and
out-of-range inputs refused with an isect exception that names the argument.

- Every array a shape exposes (its data, matrix, mesh vertices and indices,
  the per-field views) is read-only and cannot be made writeable again.
- complex, datetime64, timedelta64, str, bytes and object inputs (other than
  real numbers) are an InvalidArgumentError naming the argument: no silent
  conversion, no "imaginary part discarded" warning.
- Integers beyond the doubles (10**400) and C int arguments beyond int32
  (rule=2**40) are an InvalidArgumentError naming the argument, not a plain
  OverflowError.
- A sweep over every public function and method: each argument given
  garbage raises an IsectError naming that argument, never another type.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from decimal import Decimal
from fractions import Fraction
from typing import Any

import isect
import numpy as np
import pytest
from strategies import one_of_each

ORG, DIR = [0.0, 0.0, -5.0], [0.0, 0.0, 1.0]
SQ2 = [[0, 0], [1, 0], [1, 1], [0, 1]]
CUBE_V = [[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)]
CUBE_QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
TETS = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
TET_V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
MOVE = [[1, 0, 0, 0.5], [0, 2, 0, 0], [0, 0, 1, -1], [0, 0, 0, 1]]

SHAPES: list[isect.Shape] = one_of_each() + [
    isect.Mesh(TET_V, TETS),
    isect.Mesh(CUBE_V, CUBE_QUADS),
    isect.Mesh(CUBE_V, [list(f) for f in CUBE_QUADS[:5]] + [[1, 3, 7], [1, 7, 5]]),
]
SHAPES += [s.transformed(MOVE) for s in SHAPES]
IDS = [f"{type(s).__name__}{'-moved' if s.matrix is not None else ''}-{i}"
       for i, s in enumerate(SHAPES)]


def _named(error: BaseException, name: str) -> bool:
    """The message names the argument (as a word: "origins", "hits.t", ...)."""
    return re.search(rf"(?<![\w.]){re.escape(name)}(?![\w])", str(error)) is not None


# ------------------------------------------------------- immutable arrays


def _exposed_arrays(shape: isect.Shape) -> dict[str, np.ndarray]:
    """Every numpy array the shape's public properties hand out."""
    arrays: dict[str, np.ndarray] = {}
    for cls in type(shape).__mro__:
        for name, value in vars(cls).items():
            if isinstance(value, property) and not name.startswith("_"):
                got = getattr(shape, name)
                if isinstance(got, np.ndarray):
                    arrays[name] = got
                elif isinstance(got, list) and got and isinstance(got[0], np.ndarray):
                    arrays.update({f"{name}[{i}]": a for i, a in enumerate(got)})
    return arrays


@pytest.mark.parametrize("shape", SHAPES, ids=IDS)
def test_arrays_cannot_be_made_writeable(shape: isect.Shape) -> None:
    """shape.data.flags.writeable = True (and the same on every other exposed
    array or a view of it) raises, and nothing can be written."""
    before = shape.intersect(np.zeros((50, 3)) + [0.25, 0.125, -5], np.tile(DIR, (50, 1)))
    arrays = _exposed_arrays(shape)
    assert "data" in arrays
    if shape.matrix is not None:
        assert "matrix" in arrays
    for name, a in arrays.items():
        for candidate in (a, a.view(), a.reshape(-1), a[...]):
            assert not candidate.flags.writeable, name
            with pytest.raises(ValueError):
                candidate.flags.writeable = True
            with pytest.raises(ValueError):
                candidate.reshape(-1)[0] = 123
    after = shape.intersect(np.zeros((50, 3)) + [0.25, 0.125, -5], np.tile(DIR, (50, 1)))
    assert after.tobytes() == before.tobytes()


def test_pickled_and_copied_shapes_stay_frozen() -> None:
    """Shapes rebuilt by pickle or copied share the guarantee."""
    import copy
    import pickle

    for shape in SHAPES:
        for other in (pickle.loads(pickle.dumps(shape)), copy.copy(shape)):
            with pytest.raises(ValueError):
                other.data.flags.writeable = True


def test_constructor_input_is_copied() -> None:
    """The caller's array stays the caller's (writeable, not shared)."""
    center = np.array([1.0, 2.0, 3.0])
    s = isect.Sphere(center, 1.0)
    center[0] = 99
    assert s.center[0] == 1.0 and center.flags.writeable


# ------------------------------------------------------ non-numeric input

BAD_VECTORS: dict[str, Any] = {
    "datetime64": np.array(["2020-01-01", "2020-01-02", "2020-01-03"], dtype="datetime64[D]"),
    "timedelta64": np.array([1, 2, 3], dtype="timedelta64[s]"),
    "complex": np.array([1 + 2j, 0, 0]),
    "complex zero imag": [1 + 0j, 0.0, 0.0],
    "complex128 scalars": [np.complex128(1), 0.0, 0.0],
    "str": ["1", "2", "3"],
    "str array": np.array(["1.5", "2", "3"]),
    "bytes": [b"1", b"2", b"3"],
    "None": [None, 0.0, 0.0],
    "object": [object(), 0.0, 0.0],
    "decimal": [Decimal("1.5"), 0.0, 0.0],
    "structured": np.zeros(3, dtype=[("x", "f8")]),
}


def _vector_calls() -> list[tuple[str, str, Callable[[Any], Any]]]:
    """(id, argument name, call with the bad value as that 3-vector)."""
    s = isect.Sphere([0, 0, 0], 1.0)
    return [
        ("Sphere.center", "center", lambda v: isect.Sphere(v, 1.0)),
        ("Box.hi", "hi", lambda v: isect.Box([0, 0, 0], v)),
        ("Triangle.b", "b", lambda v: isect.Triangle([0, 0, 0], v, [0, 1, 0])),
        ("Plane.normal", "normal", lambda v: isect.Plane(v, 0.0)),
        ("Cylinder.p1", "p1", lambda v: isect.Cylinder([0, 0, 0], v, 1.0)),
        ("InfiniteCylinder.axis", "axis", lambda v: isect.InfiniteCylinder([0, 0, 0], v, 1)),
        ("Ellipsoid.radii", "radii", lambda v: isect.Ellipsoid([0, 0, 0], v)),
        ("Polygon.vertices", "vertices", lambda v: isect.Polygon([v, [1, 0, 0], [0, 1, 0]])),
        ("Mesh.vertices", "vertices", lambda v: isect.Mesh([v, *TET_V[1:]], TETS)),
        ("intersect origins", "origins", lambda v: s.intersect(v, DIR)),
        ("intersect origins batch", "origins", lambda v: s.intersect([v, v], DIR)),
        ("intersect directions", "directions", lambda v: s.intersect(ORG, v)),
        ("intersect_all origin", "origin", lambda v: s.intersect_all(v, DIR)),
        ("intersect_all direction", "direction", lambda v: s.intersect_all(ORG, v)),
        ("intersect_all_batch origins", "origins", lambda v: s.intersect_all_batch(v, DIR)),
        ("contains points", "points", lambda v: s.contains(v)),
        ("spawn directions", "directions",
         lambda v: s.spawn(s.intersect(ORG, DIR), v)),
        ("polygon_normal", "vertices", lambda v: isect.polygon_normal([v, [1, 0, 0], [0, 1, 0]])),
        ("plane_from_points", "vertices",
         lambda v: isect.plane_from_points([v, [1, 0, 0], [0, 1, 0]])),
        ("point_in_polygon points", "points",
         lambda v: isect.point_in_polygon(SQ2, np.asarray(v)[:2] if isinstance(v, np.ndarray)
                                          else v[:2])),
        ("winding_number polygon", "polygon",
         lambda v: isect.winding_number([np.asarray(v)[:2] if isinstance(v, np.ndarray)
                                         else v[:2], [1, 0], [1, 1]], [0.5, 0.5])),
    ]


VECTOR_CALLS = _vector_calls()


@pytest.mark.parametrize("bad", list(BAD_VECTORS.values()), ids=list(BAD_VECTORS))
@pytest.mark.parametrize(("arg", "call"), [c[1:] for c in VECTOR_CALLS],
                         ids=[c[0] for c in VECTOR_CALLS])
def test_non_numeric_vectors_are_refused(arg: str, call: Callable[[Any], Any], bad: Any) -> None:
    """No conversion, no warning (warnings are errors in this suite): an
    InvalidArgumentError that names the argument."""
    with pytest.raises(isect.InvalidArgumentError) as info:
        call(bad)
    assert _named(info.value, arg), str(info.value)


BAD_SCALARS: dict[str, Any] = {
    "datetime64": np.datetime64("2020-01-01"),
    "timedelta64": np.timedelta64(5, "s"),
    "complex": 0.5 + 0j,
    "complex128": np.complex128(0.5),
    "str": "0.5",
    "bytes": b"0.5",
    "None": None,
    "object": object(),
}

SCALAR_CALLS: list[tuple[str, str, Callable[[Any], Any]]] = [
    ("Sphere.radius", "radius", lambda v: isect.Sphere([0, 0, 0], v)),
    ("Plane.d", "d", lambda v: isect.Plane([0, 0, 1], v)),
    ("intersect tmin", "tmin", lambda v: SHAPES[1].intersect(ORG, DIR, tmin=v)),
    ("intersect tmax", "tmax", lambda v: SHAPES[1].intersect([ORG, ORG], DIR, tmax=v)),
    ("intersect eps", "eps", lambda v: SHAPES[1].intersect(ORG, DIR, eps=v)),
    ("intersect_all tmax", "tmax", lambda v: SHAPES[1].intersect_all(ORG, DIR, tmax=v)),
    ("intersect_all eps", "eps", lambda v: SHAPES[1].intersect_all(ORG, DIR, eps=v)),
]


@pytest.mark.parametrize("bad", list(BAD_SCALARS.values()), ids=list(BAD_SCALARS))
@pytest.mark.parametrize(("arg", "call"), [c[1:] for c in SCALAR_CALLS],
                         ids=[c[0] for c in SCALAR_CALLS])
def test_non_numeric_scalars_are_refused(arg: str, call: Callable[[Any], Any], bad: Any) -> None:
    if bad is None and arg == "eps":
        pytest.skip("eps=None is the default")
    with pytest.raises(isect.InvalidArgumentError) as info:
        call(bad)
    assert _named(info.value, arg), str(info.value)


def test_real_number_types_still_accepted() -> None:
    """bool, ints (beyond int64 too), float16/32, Fraction and object arrays
    of real numbers are numbers, and give the float64 results."""
    s = isect.Sphere([0, 0, 0], 1.0)
    want = s.intersect(ORG, DIR)
    for origin in (
        [0, 0, -5],
        np.array([0, 0, -5], dtype=np.int8),
        np.array([0, 0, -5], dtype=np.float32),
        np.array([0, 0, -5], dtype=np.float16),
        [Fraction(0), False, Fraction(-10, 2)],
        np.array([0, 0, -5], dtype=object),
    ):
        assert s.intersect(origin, DIR).tobytes() == want.tobytes()
        assert s.intersect_all(origin, DIR) == s.intersect_all(ORG, DIR)
    big = isect.Sphere([2**64 + 3, 0, 0], 1.0)  # object array of ints, rounded
    assert big.center[0] == float(2**64 + 3)


def test_structured_rays_with_complex_fields_are_refused() -> None:
    """intersect_rays / spawn: records whose fields are not real numbers."""
    fields = [("org", "c16", (3,)), ("dir", "f8", (3,)), ("tmin", "f8"), ("tmax", "f8")]
    with pytest.raises(isect.InvalidArgumentError) as info:
        SHAPES[1].intersect_rays(np.zeros(2, dtype=fields))
    assert _named(info.value, "rays") and "org" in str(info.value)
    hit = isect.Sphere([0, 0, 0], 1).intersect_all(ORG, DIR)[0]
    with pytest.raises(isect.InvalidArgumentError) as info:
        isect.Sphere([0, 0, 0], 1).spawn(hit._replace(t=1j), DIR)
    assert _named(info.value, "hits.t")


# ------------------------------------------------------------ overflow


OVERFLOWS: list[tuple[str, str, Callable[[], Any]]] = [
    ("intersect origins", "origins", lambda: SHAPES[1].intersect([[10**400, 0, 0]], DIR)),
    ("intersect one origin", "origins", lambda: SHAPES[1].intersect([10**400, 0, 0], DIR)),
    ("intersect tmax", "tmax", lambda: SHAPES[1].intersect(ORG, DIR, tmax=10**400)),
    ("intersect eps", "eps", lambda: SHAPES[1].intersect(ORG, DIR, eps=10**400)),
    ("intersect_all origin", "origin", lambda: SHAPES[1].intersect_all([10**400, 0, 0], DIR)),
    ("intersect_all tmin", "tmin", lambda: SHAPES[1].intersect_all(ORG, DIR, tmin=-(10**400))),
    ("intersect_all_batch", "directions",
     lambda: SHAPES[1].intersect_all_batch(ORG, [[0, 0, 10**400]])),
    ("Sphere radius", "radius", lambda: isect.Sphere([0, 0, 0], 10**400)),
    ("Quadric coeffs", "coeffs", lambda: isect.Quadric([10**400] + [0] * 9)),
    ("transformed", "matrix", lambda: SHAPES[1].transformed([[10**400, 0, 0, 0], [0, 1, 0, 0],
                                                             [0, 0, 1, 0], [0, 0, 0, 1]])),
    ("contains", "points", lambda: SHAPES[1].contains([10**400, 0, 0])),
    ("point_in_polygon rule", "rule", lambda: isect.point_in_polygon(SQ2, [0.5, 0.5], rule=2**40)),
    ("point_in_polygon -rule", "rule",
     lambda: isect.point_in_polygon(SQ2, [0.5, 0.5], rule=-(2**31) - 1)),
    ("Polygon rule", "rule", lambda: isect.Polygon(np.eye(3), rule=2**40)),
    ("Cylinder capped", "capped", lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=2**40)),
    ("Mesh faces", "faces", lambda: isect.Mesh(TET_V, [[0, 1, 10**400]])),
    ("spawn hit prim", "hits.prim",
     lambda: SHAPES[1].spawn(SHAPES[1].intersect_all(ORG, DIR)[0]._replace(prim=2**40), DIR)),
]


@pytest.mark.parametrize(("arg", "call"), [c[1:] for c in OVERFLOWS], ids=[c[0] for c in OVERFLOWS])
def test_overflow_is_an_isect_error(arg: str, call: Callable[[], Any]) -> None:
    """Not a plain OverflowError: an InvalidArgumentError naming the argument."""
    with pytest.raises(isect.IsectError) as info:
        call()
    assert isinstance(info.value, isect.InvalidArgumentError), repr(info.value)
    assert _named(info.value, arg), str(info.value)


def test_in_range_rule_reaches_c() -> None:
    """An int32 rule that is not a rule is still the C library's E_ARG."""
    with pytest.raises(isect.InvalidArgumentError, match="point_in_polygon"):
        isect.point_in_polygon(SQ2, [0.5, 0.5], rule=2**31 - 1)


# ---------------------------------------------------------------- sweep

GARBAGE: list[Any] = [
    object(),
    "x",
    b"xy",
    1j,
    None,
    {"a": 1},
    np.datetime64("2021-01-01"),
    [[1, 2], [3]],
    10**400,
    -(10**400),
]


def _sweep() -> list[tuple[str, str, Callable[[Any], Any]]]:
    """(id, argument, call with that argument replaced) for every argument of
    every public function and method."""
    s, tri, mesh = isect.Sphere([0, 0, 0], 1.0), isect.Triangle(*np.eye(3)), SHAPES[-1]
    hit = s.intersect(ORG, DIR)
    calls: dict[str, tuple[str, Callable[[Any], Any]]] = {
        "Plane.normal": ("normal", lambda v: isect.Plane(v, 1)),
        "Plane.d": ("d", lambda v: isect.Plane([0, 0, 1], v)),
        "Sphere.center": ("center", lambda v: isect.Sphere(v, 1)),
        "Sphere.radius": ("radius", lambda v: isect.Sphere([0, 0, 0], v)),
        "Box.lo": ("lo", lambda v: isect.Box(v, [1, 1, 1])),
        "Triangle.c": ("c", lambda v: isect.Triangle([0, 0, 0], [1, 0, 0], v)),
        "Polygon.vertices": ("vertices", lambda v: isect.Polygon(v)),
        "Polygon.rule": ("rule", lambda v: isect.Polygon(np.eye(3), rule=v)),
        "ConvexPolyhedron.planes": ("planes", lambda v: isect.ConvexPolyhedron(v)),
        "Cylinder.p0": ("p0", lambda v: isect.Cylinder(v, [0, 0, 1], 1)),
        "Cylinder.radius": ("radius", lambda v: isect.Cylinder([0, 0, 0], [0, 0, 1], v)),
        "Cylinder.capped": ("capped", lambda v: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, v)),
        "InfiniteCylinder.point": ("point", lambda v: isect.InfiniteCylinder(v, [0, 0, 1], 1)),
        "InfiniteCylinder.radius": ("radius",
                                    lambda v: isect.InfiniteCylinder([0, 0, 0], [0, 0, 1], v)),
        "Ellipsoid.center": ("center", lambda v: isect.Ellipsoid(v, [1, 1, 1])),
        "Quadric.coeffs": ("coeffs", lambda v: isect.Quadric(v)),
        "Mesh.vertices": ("vertices", lambda v: isect.Mesh(v, TETS)),
        "Mesh.faces": ("faces", lambda v: isect.Mesh(TET_V, v)),
        "transformed": ("matrix", lambda v: s.transformed(v)),
        "intersect.origins": ("origins", lambda v: s.intersect(v, DIR)),
        "intersect.directions": ("directions", lambda v: s.intersect(ORG, v)),
        "intersect.tmin": ("tmin", lambda v: s.intersect(ORG, DIR, tmin=v)),
        "intersect.tmax": ("tmax", lambda v: s.intersect(ORG, DIR, tmax=v)),
        "intersect.eps": ("eps", lambda v: s.intersect(ORG, DIR, eps=v)),
        "intersect.cull_back": ("cull_back", lambda v: s.intersect(ORG, DIR, cull_back=v)),
        "intersect.any_hit": ("any_hit", lambda v: mesh.intersect(ORG, DIR, any_hit=v)),
        "intersect.threads": ("threads", lambda v: s.intersect(ORG, DIR, threads=v)),
        "intersect.errors": ("errors", lambda v: s.intersect(ORG, DIR, errors=v)),
        "intersect.progress": ("progress", lambda v: s.intersect(ORG, DIR, progress=v)),
        "intersect_rays.rays": ("rays", lambda v: s.intersect_rays(v)),
        "intersect_all.origin": ("origin", lambda v: tri.intersect_all(v, DIR)),
        "intersect_all.direction": ("direction", lambda v: tri.intersect_all(ORG, v)),
        "intersect_all.tmin": ("tmin", lambda v: tri.intersect_all(ORG, DIR, tmin=v)),
        "intersect_all.eps": ("eps", lambda v: tri.intersect_all(ORG, DIR, eps=v)),
        "intersect_all.cull_back": ("cull_back",
                                    lambda v: tri.intersect_all(ORG, DIR, cull_back=v)),
        "intersect_all_batch.origins": ("origins", lambda v: s.intersect_all_batch(v, DIR)),
        "intersect_all_batch.tmax": ("tmax", lambda v: s.intersect_all_batch(ORG, DIR, tmax=v)),
        "intersect_all_batch.threads": ("threads",
                                        lambda v: s.intersect_all_batch(ORG, DIR, threads=v)),
        "contains.points": ("points", lambda v: s.contains(v)),
        "contains.threads": ("threads", lambda v: s.contains(ORG, threads=v)),
        "contains.progress": ("progress", lambda v: s.contains(ORG, progress=v)),
        "Mesh.winding_number.progress": ("progress",
                                         lambda v: mesh.winding_number(ORG, progress=v)),
        "spawn.hits": ("hits", lambda v: s.spawn(v, DIR)),
        "spawn.directions": ("directions", lambda v: s.spawn(hit, v)),
        "spawn.threads": ("threads", lambda v: s.spawn(hit, DIR, threads=v)),
        "polygon_normal": ("vertices", lambda v: isect.polygon_normal(v)),
        "plane_from_points": ("vertices", lambda v: isect.plane_from_points(v)),
        "point_in_polygon.polygon": ("polygon", lambda v: isect.point_in_polygon(v, [0, 0])),
        "point_in_polygon.points": ("points", lambda v: isect.point_in_polygon(SQ2, v)),
        "point_in_polygon.rule": ("rule", lambda v: isect.point_in_polygon(SQ2, [0, 0], v)),
        "winding_number.polygon": ("polygon", lambda v: isect.winding_number(v, [0, 0])),
        "winding_number.points": ("points", lambda v: isect.winding_number(SQ2, v)),
    }
    return [(k, a, c) for k, (a, c) in calls.items()]


SWEEP = _sweep()


@pytest.mark.parametrize(("arg", "call"), [c[1:] for c in SWEEP], ids=[c[0] for c in SWEEP])
def test_every_argument_names_itself(arg: str, call: Callable[[Any], Any]) -> None:
    """Garbage in any argument of any public function is an IsectError whose
    message names the argument; no other exception type escapes."""
    for value in GARBAGE:
        if arg == "threads" and isinstance(value, int) and value > 0:
            continue  # any positive count is valid (capped by the chunks), a huge one too
        if arg in ("eps", "threads") and value is None:
            continue  # the default
        try:
            call(value)
        except isect.IsectError as exc:
            assert _named(exc, arg), f"{value!r:.30}: {exc}"
        except Exception as exc:  # noqa: BLE001 - the point of the test
            pytest.fail(f"{arg}={value!r:.30}: {type(exc).__name__}: {exc}")
        else:
            pytest.fail(f"{arg}={value!r:.30} was accepted")


# ------------------------------------------- errors libisect finds, named

NAN, INF = float("nan"), float("inf")
_S = isect.Sphere([0, 0, 0], 1.0)

C_ERRORS: list[tuple[str, str, type[isect.IsectError], Callable[[], Any]]] = [
    ("Sphere nan center", "center", isect.NonFiniteError, lambda: isect.Sphere([NAN, 0, 0], 1)),
    ("Sphere inf radius", "radius", isect.NonFiniteError, lambda: isect.Sphere([0, 0, 0], INF)),
    ("Sphere negative radius", "radius", isect.InvalidArgumentError,
     lambda: isect.Sphere([0, 0, 0], -1)),
    ("Plane nan d", "d", isect.NonFiniteError, lambda: isect.Plane([0, 0, 1], NAN)),
    ("Triangle inf c", "c", isect.NonFiniteError,
     lambda: isect.Triangle([0, 0, 0], [1, 0, 0], [0, INF, 0])),
    ("Box lo > hi", "lo[0] = 1.0 > hi[0] = 0.0", isect.InvalidArgumentError,
     lambda: isect.Box([1, 0, 0], [0, 1, 1])),
    ("Polygon 2 vertices", "vertices", isect.InvalidArgumentError,
     lambda: isect.Polygon([[0, 0, 0], [1, 0, 0]])),
    ("Polygon rule 7", "rule", isect.InvalidArgumentError,
     lambda: isect.Polygon(np.eye(3), rule=7)),
    ("Convex no planes", "planes", isect.InvalidArgumentError,
     lambda: isect.ConvexPolyhedron(np.zeros((0, 4)))),
    ("Cylinder capped 2", "capped", isect.InvalidArgumentError,
     lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=2)),
    ("Cylinder nan p1", "p1", isect.NonFiniteError,
     lambda: isect.Cylinder([0, 0, 0], [0, NAN, 1], 1)),
    ("InfiniteCylinder negative radius", "radius", isect.InvalidArgumentError,
     lambda: isect.InfiniteCylinder([0, 0, 0], [0, 0, 1], -1)),
    ("Ellipsoid negative radii", "radii", isect.InvalidArgumentError,
     lambda: isect.Ellipsoid([0, 0, 0], [1, -1, 1])),
    ("Quadric inf", "coeffs", isect.NonFiniteError, lambda: isect.Quadric([INF] + [0] * 9)),
    ("Mesh nan vertex", "vertices", isect.NonFiniteError,
     lambda: isect.Mesh([[0, 0, NAN], *TET_V[1:]], TETS)),
    ("Mesh index out of range", "faces", isect.InvalidArgumentError,
     lambda: isect.Mesh(TET_V, [[0, 1, 4]])),
    ("Mesh face of 2", "faces", isect.InvalidArgumentError,
     lambda: isect.Mesh(TET_V, [[0, 1, 2], [0, 1]])),
    ("transformed singular", "matrix", isect.DegenerateError,
     lambda: _S.transformed(np.diag([1.0, 0.0, 1.0, 1.0]))),
    ("transformed last row", "matrix", isect.InvalidArgumentError,
     lambda: _S.transformed(np.ones((4, 4)))),
    ("intersect nan origin", "origins", isect.NonFiniteError,
     lambda: _S.intersect([[0, 0, -5], [NAN, 0, 0]], DIR)),
    ("intersect zero direction", "directions", isect.DegenerateError,
     lambda: _S.intersect(ORG, [[0, 0, 1], [0, 0, 0]])),
    ("intersect nan tmin", "tmin", isect.NonFiniteError,
     lambda: _S.intersect(ORG, DIR, tmin=[0.0, NAN])),
    ("intersect nan tmax (general path)", "tmax", isect.NonFiniteError,
     lambda: _S.intersect(np.zeros((2, 1, 3)), np.ones((3, 3)), tmax=[[1.0], [NAN]])),
    ("intersect negative eps", "eps", isect.InvalidArgumentError,
     lambda: _S.intersect(ORG, DIR, eps=-1e-9)),
    ("intersect nan eps", "eps", isect.NonFiniteError, lambda: _S.intersect(ORG, DIR, eps=NAN)),
    ("intersect_all nan origin", "origin", isect.NonFiniteError,
     lambda: _S.intersect_all([NAN, 0, 0], DIR)),
    ("intersect_all zero direction", "direction", isect.DegenerateError,
     lambda: _S.intersect_all(ORG, [0, 0, 0])),
    ("intersect_all nan tmax", "tmax", isect.NonFiniteError,
     lambda: _S.intersect_all(ORG, DIR, tmax=NAN)),
    ("intersect_all inf eps", "eps", isect.NonFiniteError,
     lambda: _S.intersect_all(ORG, DIR, eps=INF)),
    ("intersect_all_batch inf direction", "directions", isect.NonFiniteError,
     lambda: _S.intersect_all_batch(ORG, [[0, 0, 1], [0, INF, 1]])),
    ("intersect_rays nan", "rays", isect.NonFiniteError,
     lambda: _S.intersect_rays(np.full(2, np.nan, isect.RAY_DTYPE))),
    ("contains nan point", "points", isect.NonFiniteError,
     lambda: _S.contains([[0, 0, 0], [NAN, 0, 0]])),
    ("contains open cylinder", "Cylinder.contains", isect.InvalidArgumentError,
     lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=False).contains([0, 0, 0])),
    ("spawn zero direction", "directions", isect.DegenerateError,
     lambda: _S.spawn(_S.intersect(ORG, DIR), [0, 0, 0])),
    ("spawn a MISS record", "hits", isect.InvalidArgumentError,
     lambda: _S.spawn(_S.intersect(ORG, [1, 0, 0]), DIR)),
    ("polygon_normal collinear", "vertices", isect.DegenerateError,
     lambda: isect.polygon_normal([[0, 0, 0], [1, 1, 1], [2, 2, 2]])),
    ("plane_from_points 2 points", "vertices", isect.InvalidArgumentError,
     lambda: isect.plane_from_points([[0, 0, 0], [1, 1, 1]])),
    ("point_in_polygon rule 5", "rule", isect.InvalidArgumentError,
     lambda: isect.point_in_polygon(SQ2, [0.5, 0.5], rule=5)),
    ("point_in_polygon nan vertex", "polygon", isect.NonFiniteError,
     lambda: isect.point_in_polygon([[NAN, 0], [1, 0], [1, 1]], [0, 0])),
    ("point_in_polygon nan point", "points", isect.NonFiniteError,
     lambda: isect.point_in_polygon(SQ2, [[0, 0], [NAN, 0]])),
    ("winding_number 2 vertices", "polygon", isect.InvalidArgumentError,
     lambda: isect.winding_number([[0, 0], [1, 0]], [0, 0])),
    ("winding_number inf point", "points", isect.NonFiniteError,
     lambda: isect.winding_number(SQ2, [INF, 0])),
]


@pytest.mark.parametrize(("arg", "error", "call"), [c[1:] for c in C_ERRORS],
                         ids=[c[0] for c in C_ERRORS])
def test_library_errors_name_the_argument(
    arg: str, error: type[isect.IsectError], call: Callable[[], Any]
) -> None:
    """Errors that libisect reports (or that Python finds by its rules) carry
    the class of their C status and name the argument that holds the value."""
    with pytest.raises(isect.IsectError) as info:
        call()
    assert type(info.value) is error, repr(info.value)
    assert arg in str(info.value), str(info.value)
