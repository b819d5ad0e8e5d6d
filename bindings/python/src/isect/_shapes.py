# SPDX-License-Identifier: Apache-2.0
"""The primitive shape classes, one per C shape type.

Each constructor packs its arguments into the float64 layout the C library
documents for the type (``data`` of ``isect_shape``) and lets libisect validate
them. Thin surfaces (:class:`Plane`, :class:`Triangle`, :class:`Polygon`)
derive from :class:`Shape`; solids derive from :class:`Solid` and so have
``contains``.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ._args import ArrayLike, Rule, as_int32, as_rows, as_rule, as_scalar, as_vector
from ._errors import too_few, value_text
from ._isect import lib
from ._shape import Shape, Solid, readonly_view

_RULE_NAMES = {int(lib.ISECT_EVEN_ODD): "evenodd", int(lib.ISECT_NONZERO): "nonzero"}


def _pack(*parts: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Concatenate vectors and scalars into one fresh contiguous float64 array."""
    return np.ascontiguousarray(np.concatenate([np.ravel(p) for p in parts]), dtype=np.float64)


def _num(x: object, name: str) -> npt.NDArray[np.float64]:
    """One number as a (1,) float64 array."""
    return np.array([as_scalar(x, name)], dtype=np.float64)


def _negative(value: object, name: str) -> str | None:
    """``"radius = -1.0 is negative ..."`` if ``value`` < 0, else None."""
    if float(value) < 0.0:  # type: ignore[arg-type]
        return f"{name} = {value_text(value)} is negative (a radius must be >= 0)"
    return None


def _bad_rule(rule: int) -> str | None:
    """``"rule = 7 is not a fill rule ..."`` for an unknown fill rule."""
    if rule in _RULE_NAMES:
        return None
    return (f"rule = {rule} is not a fill rule: 'evenodd' (ISECT_EVEN_ODD = "
            f"{int(lib.ISECT_EVEN_ODD)}) or 'nonzero' (ISECT_NONZERO = {int(lib.ISECT_NONZERO)})")


class Plane(Shape):
    """The plane ``normal · x + d = 0`` (thin surface; ``ISECT_PLANE``).

    Hits carry the unit normal ``normal/|normal|``; ENTER when the ray runs
    against it. A zero normal is degenerate (never hit).
    """

    __slots__ = ()
    _type = lib.ISECT_PLANE
    _layout = (("normal", 3), ("d", 1))

    def __init__(self, normal: ArrayLike, d: float) -> None:
        """Args: normal — 3 numbers (any length); d — the offset."""
        self._setup(_pack(as_vector(normal, 3, "normal"), _num(d, "d")))

    @property
    def normal(self) -> npt.NDArray[np.float64]:
        """The plane's normal (as given, not normalised)."""
        return readonly_view(self._data[0:3])

    @property
    def d(self) -> float:
        """The plane's offset."""
        return float(self._data[3])

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"normal={self.normal.tolist()}, d={self.d!r}"


class Sphere(Solid):
    """The sphere ``|x - center| = radius`` (solid; ``ISECT_SPHERE``).

    radius < 0 raises InvalidArgumentError; radius 0 is degenerate.
    """

    __slots__ = ()
    _type = lib.ISECT_SPHERE
    _layout = (("center", 3), ("radius", 1))

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: a negative radius."""
        return "radius"

    def _check_values(self) -> str | None:
        """A negative radius."""
        return _negative(self._part("radius"), "radius")

    def __init__(self, center: ArrayLike, radius: float) -> None:
        """Args: center — 3 numbers; radius — >= 0."""
        self._setup(_pack(as_vector(center, 3, "center"), _num(radius, "radius")))

    @property
    def center(self) -> npt.NDArray[np.float64]:
        """The centre."""
        return readonly_view(self._data[0:3])

    @property
    def radius(self) -> float:
        """The radius."""
        return float(self._data[3])

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"center={self.center.tolist()}, radius={self.radius!r}"


class Box(Solid):
    """The closed axis-aligned box ``lo <= x <= hi`` (solid; ``ISECT_AABB``).

    Hit prims are faces 0..5 = -x, +x, -y, +y, -z, +z. lo > hi in any axis
    raises InvalidArgumentError; lo == hi is degenerate. Rotate it with
    :meth:`~Shape.transformed`.
    """

    __slots__ = ()
    _type = lib.ISECT_AABB
    _layout = (("lo", 3), ("hi", 3))

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: lo > hi in some axis."""
        return "lo, hi"

    def _check_values(self) -> str | None:
        """lo > hi in some axis (the first)."""
        lo, hi = self._part("lo"), self._part("hi")
        for axis in range(3):
            if lo[axis] > hi[axis]:
                return (f"lo[{axis}] = {value_text(lo[axis])} > hi[{axis}] = "
                        f"{value_text(hi[axis])} (a box needs lo <= hi in every axis)")
        return None

    def __init__(self, lo: ArrayLike, hi: ArrayLike) -> None:
        """Args: lo, hi — the minimum and maximum corners, 3 numbers each."""
        self._setup(_pack(as_vector(lo, 3, "lo"), as_vector(hi, 3, "hi")))

    @property
    def lo(self) -> npt.NDArray[np.float64]:
        """The minimum corner."""
        return readonly_view(self._data[0:3])

    @property
    def hi(self) -> npt.NDArray[np.float64]:
        """The maximum corner."""
        return readonly_view(self._data[3:6])

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"lo={self.lo.tolist()}, hi={self.hi.tolist()}"


class Triangle(Shape):
    """The triangle a, b, c (thin surface; ``ISECT_TRIANGLE``).

    Watertight (exact edge and vertex rules). The normal is
    unit((b - a) × (c - a)); uv are the barycentric weights of b and c.
    A zero-area triangle is degenerate.
    """

    __slots__ = ()
    _type = lib.ISECT_TRIANGLE
    _layout = (("a", 3), ("b", 3), ("c", 3))

    def __init__(self, a: ArrayLike, b: ArrayLike, c: ArrayLike) -> None:
        """Args: a, b, c — the vertices, 3 numbers each."""
        self._setup(_pack(as_vector(a, 3, "a"), as_vector(b, 3, "b"), as_vector(c, 3, "c")))

    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """The vertices as a (3, 3) array, rows a, b, c."""
        return readonly_view(self._data.reshape(3, 3))

    @property
    def a(self) -> npt.NDArray[np.float64]:
        """Vertex a."""
        return readonly_view(self._data[0:3])

    @property
    def b(self) -> npt.NDArray[np.float64]:
        """Vertex b."""
        return readonly_view(self._data[3:6])

    @property
    def c(self) -> npt.NDArray[np.float64]:
        """Vertex c."""
        return readonly_view(self._data[6:9])

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"a={self.a.tolist()}, b={self.b.tolist()}, c={self.c.tolist()}"


class Polygon(Shape):
    """A planar polygon, convex, concave or self-intersecting (thin surface;
    ``ISECT_POLYGON``).

    The plane is Newell's, the normal follows the right-hand rule over the
    vertex order, and the inside test uses the fill rule: ``"evenodd"``
    (crossing number) or ``"nonzero"`` (winding number). Fewer than 3
    vertices raise InvalidArgumentError; collinear vertices are degenerate.
    """

    __slots__ = ()
    _type = lib.ISECT_POLYGON
    _layout = (("vertices", 0),)

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: fewer than 3 vertices, or an unknown rule."""
        return "vertices" if self._n < 3 else "rule"

    def _check_counts(self) -> str | None:
        """Fewer than 3 vertices, or an unknown rule."""
        return too_few(self._n, 3, "vertices", "a polygon") or _bad_rule(self._flags)

    def __init__(self, vertices: ArrayLike, rule: Rule = "evenodd") -> None:
        """Args: vertices — (n, 3); rule — "evenodd" or "nonzero"."""
        v = as_rows(vertices, 3, "vertices")
        self._setup(v.reshape(-1), n=v.shape[0], flags=as_rule(rule))

    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """The vertices, (n, 3)."""
        return readonly_view(self._data.reshape(-1, 3))

    @property
    def rule(self) -> str:
        """The fill rule, "evenodd" or "nonzero"."""
        return _RULE_NAMES.get(self._flags, str(self._flags))

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"vertices={self.vertices.tolist()}, rule={self.rule!r}"


class ConvexPolyhedron(Solid):
    """The intersection of half-spaces ``a x + b y + c z + d <= 0`` (solid;
    ``ISECT_CONVEX``).

    Planes are rows (a, b, c, d) with outward normals (a, b, c); hit prims are
    plane indices. The polyhedron may be unbounded (then a ray may have only
    an ENTER or only an EXIT hit). At least one plane is required.
    """

    __slots__ = ()
    _type = lib.ISECT_CONVEX
    _layout = (("planes", 0),)

    _row = 4

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: no plane."""
        return "planes"

    def _check_counts(self) -> str | None:
        """No plane."""
        return too_few(self._n, 1, "planes", "a convex polyhedron")

    def __init__(self, planes: ArrayLike) -> None:
        """Args: planes — (m, 4) rows a, b, c, d."""
        p = as_rows(planes, 4, "planes")
        self._setup(p.reshape(-1), n=p.shape[0])

    @property
    def planes(self) -> npt.NDArray[np.float64]:
        """The planes, (m, 4)."""
        return readonly_view(self._data.reshape(-1, 4))

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"planes={self.planes.tolist()}"


class Cylinder(Solid):
    """The finite cylinder of a radius around the segment p0–p1
    (``ISECT_CYLINDER``).

    ``capped=True``: a closed solid (prims: 0 side, 1 cap at p0, 2 cap at
    p1). ``capped=False``: the open side only, a thin surface — ``contains``
    then raises InvalidArgumentError. radius 0 or p0 == p1 is degenerate.
    """

    __slots__ = ()
    _type = lib.ISECT_CYLINDER
    _layout = (("p0", 3), ("p1", 3), ("radius", 1))

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: a capped flag other than 0 / 1, or a negative radius."""
        return "capped" if self._flags not in (0, lib.ISECT_CAPPED) else "radius"

    def _check_counts(self) -> str | None:
        """A capped flag other than 0 and ISECT_CAPPED."""
        if self._flags in (0, lib.ISECT_CAPPED):
            return None
        return (f"capped = {self._flags} is not True, False, 0 or ISECT_CAPPED "
                f"({int(lib.ISECT_CAPPED)})")

    def _check_values(self) -> str | None:
        """A negative radius."""
        return _negative(self._part("radius"), "radius")

    def _contains_refusal(self) -> str | None:
        """An open cylinder is a thin surface."""
        if self._flags == lib.ISECT_CAPPED:
            return None
        return ("capped = False: an open cylinder is a thin surface (its side alone) and has "
                "no inside; make it with capped=True for contains")

    def __init__(self, p0: ArrayLike, p1: ArrayLike, radius: float, capped: bool = True) -> None:
        """Args: p0, p1 — the axis end points; radius — >= 0; capped — closed or open."""
        if isinstance(capped, (bool, np.bool_)):
            flags = lib.ISECT_CAPPED if capped else 0
        else:  # an integer is passed through to C, which accepts 0 and ISECT_CAPPED
            flags = as_int32(capped, "capped")
        data = _pack(as_vector(p0, 3, "p0"), as_vector(p1, 3, "p1"), _num(radius, "radius"))
        self._setup(data, flags=flags)

    @property
    def p0(self) -> npt.NDArray[np.float64]:
        """The axis start point."""
        return readonly_view(self._data[0:3])

    @property
    def p1(self) -> npt.NDArray[np.float64]:
        """The axis end point."""
        return readonly_view(self._data[3:6])

    @property
    def radius(self) -> float:
        """The radius."""
        return float(self._data[6])

    @property
    def capped(self) -> bool:
        """True for the closed solid, False for the open side surface."""
        return bool(self._flags == lib.ISECT_CAPPED)

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return (
            f"p0={self.p0.tolist()}, p1={self.p1.tolist()}, radius={self.radius!r}, "
            f"capped={self.capped!r}"
        )


class InfiniteCylinder(Solid):
    """The infinite cylinder of a radius around the line point + s·axis
    (solid; ``ISECT_CYLINDER_INF``; prim 0). A zero axis is degenerate."""

    __slots__ = ()
    _type = lib.ISECT_CYLINDER_INF
    _layout = (("point", 3), ("axis", 3), ("radius", 1))

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: a negative radius."""
        return "radius"

    def _check_values(self) -> str | None:
        """A negative radius."""
        return _negative(self._part("radius"), "radius")

    def __init__(self, point: ArrayLike, axis: ArrayLike, radius: float) -> None:
        """Args: point — on the axis; axis — its direction (any length); radius — >= 0."""
        data = _pack(
            as_vector(point, 3, "point"), as_vector(axis, 3, "axis"), _num(radius, "radius")
        )
        self._setup(data)

    @property
    def point(self) -> npt.NDArray[np.float64]:
        """A point on the axis."""
        return readonly_view(self._data[0:3])

    @property
    def axis(self) -> npt.NDArray[np.float64]:
        """The axis direction (as given)."""
        return readonly_view(self._data[3:6])

    @property
    def radius(self) -> float:
        """The radius."""
        return float(self._data[6])

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"point={self.point.tolist()}, axis={self.axis.tolist()}, radius={self.radius!r}"


class Ellipsoid(Solid):
    """The axis-aligned ellipsoid sum(((x - center)/radii)²) = 1 (solid;
    ``ISECT_ELLIPSOID``). Negative radii raise InvalidArgumentError, a zero
    radius is degenerate. Rotate it with :meth:`~Shape.transformed`."""

    __slots__ = ()
    _type = lib.ISECT_ELLIPSOID
    _layout = (("center", 3), ("radii", 3))

    def _blame_arg(self) -> str | None:
        """ISECT_E_ARG: a negative radius."""
        return "radii"

    def _check_values(self) -> str | None:
        """A negative radius (the first)."""
        radii = self._part("radii")
        for axis in range(3):
            found = _negative(radii[axis], f"radii[{axis}]")
            if found is not None:
                return found
        return None

    def __init__(self, center: ArrayLike, radii: ArrayLike) -> None:
        """Args: center — 3 numbers; radii — 3 semi-axes >= 0."""
        self._setup(_pack(as_vector(center, 3, "center"), as_vector(radii, 3, "radii")))

    @property
    def center(self) -> npt.NDArray[np.float64]:
        """The centre."""
        return readonly_view(self._data[0:3])

    @property
    def radii(self) -> npt.NDArray[np.float64]:
        """The semi-axes along x, y, z."""
        return readonly_view(self._data[3:6])

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"center={self.center.tolist()}, radii={self.radii.tolist()}"


class Quadric(Solid):
    """The general quadric Ax² + By² + Cz² + Dxy + Exz + Fyz + Gx + Hy + Iz + J
    = 0, inside where negative (solid; ``ISECT_QUADRIC``). All coefficients
    zero is degenerate."""

    __slots__ = ()
    _type = lib.ISECT_QUADRIC
    _layout = (("coeffs", 10),)

    def __init__(self, coeffs: ArrayLike) -> None:
        """Args: coeffs — the 10 coefficients A..J."""
        self._setup(as_vector(coeffs, 10, "coeffs"))

    @property
    def coeffs(self) -> npt.NDArray[np.float64]:
        """The coefficients A..J."""
        return readonly_view(self._data)

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"coeffs={self.coeffs.tolist()}"
