# SPDX-License-Identifier: Apache-2.0
"""Transformed shapes (isect_xform_* / isect_shape.xform): reference and cases.

Seed (Transformed objects): with the object-to-world matrix M = [L | T; 0 0 0 1]
(row-major, 16 numbers), the world ray s + t v becomes the object ray
    s' = L^-1 (s - T),   v' = L^-1 v          (t unchanged: v' is not renormalised),
the object is intersected in object space (eps decisions there), and hits go
back with P_world = M P_object (= s + t v for the same t) and
    N_world = unit(L^-T N_object)   (inverse transpose, renormalised).
Kinds, prims and uv are unchanged (v'.N' has the sign of v.N_world).
L^-1 is computed exactly (adjugate / determinant over the rationals).

isect_xform_init (isect.h): NaN/Inf -> E_NONFINITE; last row not exactly
0 0 0 1 -> E_ARG; |det L| <= 2^-40 |row0||row1||row2| (rows of L) ->
E_DEGENERATE, tested exactly as det^2 <= 2^-80 |row0|^2 |row1|^2 |row2|^2.
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Callable, Sequence

import mpmath

from exact import DesignError, mp, norm2, q, refuse, representable, sub, to_double, unit
from model import TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case

FAMILY = "transformed"

Mat3 = tuple[tuple[Fraction, Fraction, Fraction], ...]


def check(m: Sequence[float]) -> str | None:
    """Status of isect_xform_init for the 16 numbers m (None when valid)."""
    if len(m) != 16:
        raise ValueError("a transform has 16 numbers")
    if any(not math.isfinite(x) for x in m):
        return "E_NONFINITE"
    if list(m[12:]) != [0.0, 0.0, 0.0, 1.0]:
        return "E_ARG"
    L = linear(m)
    det = det3(L)
    bound = Fraction(1, 2**80) * norm2(L[0]) * norm2(L[1]) * norm2(L[2])
    if det * det <= bound:
        return "E_DEGENERATE"
    if det * det <= 16 * bound:
        raise DesignError("transform within a factor 4 of the singularity threshold")
    return None


def linear(m: Sequence[float]) -> Mat3:
    return tuple(tuple(q(m[4 * i + j]) for j in range(3)) for i in range(3))


def translation(m: Sequence[float]) -> tuple[Fraction, ...]:
    return tuple(q(m[4 * i + 3]) for i in range(3))


def det3(L: Mat3) -> Fraction:
    return (L[0][0] * (L[1][1] * L[2][2] - L[1][2] * L[2][1])
            - L[0][1] * (L[1][0] * L[2][2] - L[1][2] * L[2][0])
            + L[0][2] * (L[1][0] * L[2][1] - L[1][1] * L[2][0]))


def inverse3(L: Mat3) -> Mat3:
    """Exact inverse: adjugate / determinant."""
    d = det3(L)

    def cof(i: int, j: int) -> Fraction:
        r = [k for k in range(3) if k != i]
        c = [k for k in range(3) if k != j]
        minor = L[r[0]][c[0]] * L[r[1]][c[1]] - L[r[0]][c[1]] * L[r[1]][c[0]]
        return minor if (i + j) % 2 == 0 else -minor
    return tuple(tuple(cof(j, i) / d for j in range(3)) for i in range(3))


def mul(L: Mat3, v: Sequence) -> tuple:
    return tuple(sum((L[i][j] * v[j] for j in range(3)), Fraction(0)) for i in range(3))


def transpose(L: Mat3) -> Mat3:
    return tuple(tuple(L[j][i] for j in range(3)) for i in range(3))


def _float_exact_affine(A: Mat3, b: Sequence[Fraction], x: Sequence[Fraction]) -> bool:
    """Would doubles compute A x + b exactly from exactly representable A, b, x?"""
    for i in range(3):
        acc, ex = 0.0, Fraction(0)
        for j in range(3):
            p = float(A[i][j]) * float(x[j])
            if Fraction(p) != A[i][j] * x[j]:
                return False
            acc += p
            ex += A[i][j] * x[j]
            if Fraction(acc) != ex:
                return False
        acc += float(b[i])
        if Fraction(acc) != ex + b[i]:
            return False
    return True


def object_ray(m: Sequence[float], r: XRay) -> tuple[XRay, bool]:
    """The exact object-space ray, and whether the library sees exactly it.

    The library's inverse is exact when every row and column of L has one
    nonzero entry, a signed power of two (permutations, mirrors, power-of-two
    scalings): then any inversion method is exact.  The object ray is then
    exact if inv * (s, 1) and inv * (v, 0) are exact in doubles.
    """
    L, T = linear(m), translation(m)
    Li = inverse3(L)
    org = mul(Li, sub(r.org, T))
    d = mul(Li, r.dir)
    simple = all(sum(1 for x in row if x != 0) == 1 for row in L) and all(
        x == 0 or (abs(x).numerator == 1 or abs(x).denominator == 1) and
        (abs(x).numerator & (abs(x).numerator - 1)) == 0 and
        (abs(x).denominator & (abs(x).denominator - 1)) == 0 for row in L for x in row)
    inv_t = tuple(-x for x in mul(Li, T))
    exact = (simple and all(representable(x) for x in inv_t)
             and _float_exact_affine(Li, inv_t, r.org)
             and _float_exact_affine(Li, (Fraction(0),) * 3, r.dir))
    return XRay(org, d, r.tmin, r.tmax), exact


def near_bounds(hits: list[Hit], obj: XRay) -> None:
    """Refuse a hit close to tmin or tmax when the library sees a rounded
    object-space ray (an inexact transform): the rounding of the object-space
    origin, ~1e-16 of its size, moves t by about that much over |v'|, and the
    relative gap of model._bound_ok says nothing about a bound of 0."""
    step = max(abs(mp(x)) for x in obj.dir)
    size = max(abs(mp(x)) for x in obj.org)
    for h in hits:
        for bound in (obj.tmin, obj.tmax):
            if isinstance(bound, float):
                continue
            if abs(mp(h.t) - mp(bound)) * step <= (size + abs(mp(h.t)) * step) * mpmath.mpf(10) ** -9:
                refuse("hit within 1e-9 of its scale from tmin/tmax under an inexact transform")


def solve(m: Sequence[float], solver: Callable[[dict, XRay, Ctx], list[Hit]], shape: dict,
          r: XRay, ctx: Ctx) -> list[Hit]:
    obj, exact = object_ray(m, r)
    hits = solver(shape, obj, Ctx(ctx.eps, ctx.exact and exact))
    if not (ctx.exact and exact):
        near_bounds(hits, obj)
    LiT = transpose(inverse3(linear(m)))
    return [Hit(h.t, unit(mul(LiT, h.normal)), h.kind, h.prim, h.uv) for h in hits]


# ---------------------------------------------------------------- matrices
def affine(L: Sequence[Sequence[float]], T: Sequence[float] = (0, 0, 0)) -> list[float]:
    return [float(L[0][0]), float(L[0][1]), float(L[0][2]), float(T[0]),
            float(L[1][0]), float(L[1][1]), float(L[1][2]), float(T[1]),
            float(L[2][0]), float(L[2][1]), float(L[2][2]), float(T[2]),
            0.0, 0.0, 0.0, 1.0]


def rotation(axis: Sequence[float], degrees: float) -> list[list[float]]:
    """Rodrigues' rotation in doubles; the reference then uses these doubles exactly."""
    n = math.sqrt(sum(x * x for x in axis))
    x, y, z = (a / n for a in axis)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    C = 1 - c
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def matmul(A, B) -> list[list[float]]:
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


ROT_Z30 = affine(rotation((0, 0, 1), 30), (1, 2, 3))
ROT_GEN = affine(rotation((1, 2, 2), 40), (-0.5, 0.25, 2))
SCALE = affine([[2, 0, 0], [0, 0.5, 0], [0, 0, 4]], (1, -2, 3))
ROT_SCALE = affine(matmul(rotation((1, -1, 0.5), 65), [[3, 0, 0], [0, 1, 0], [0, 0, 0.5]]), (0.5, 0.25, -1))
SHEAR = affine([[1, 0.5, 0], [0, 1, 0], [0.25, 0, 1]], (0, 1, 0))
MIRROR = affine([[-1, 0, 0], [0, 1, 0], [0, 0, 1]], (2, 0, 0))
MIRROR_ROT = affine(matmul(rotation((0, 1, 0), 20), [[1, 0, 0], [0, 1, 0], [0, 0, -1]]), (0, 0, 1))
SWAP_XY = affine([[0, 1, 0], [1, 0, 0], [0, 0, 1]], (0.5, -0.25, 0))
TRANSLATE = affine([[1, 0, 0], [0, 1, 0], [0, 0, 1]], (10, -20, 30))
TINY = affine([[2.0**-100, 0, 0], [0, 2.0**-100, 0], [0, 0, 2.0**-100]])
THIN_DIAG = affine([[1, 0, 0], [0, 1, 0], [0, 0, 1e-13]])


def world_ray(m: Sequence[float], o: Sequence[float], d: Sequence[float], **kw) -> dict:
    """A world ray designed in object space: the doubles nearest M o and L d."""
    L, T = linear(m), translation(m)
    wo = [to_double(x + t) for x, t in zip(mul(L, [q(v) for v in o]), T)]
    wd = [to_double(x) for x in mul(L, [q(v) for v in d])]
    return ray(wo, wd, **kw)


def cases() -> list[dict]:
    from cylinder import cyl, icyl
    from box import box
    from convex import CUBE, TETRA
    from ellipsoid import ell
    from plane import plane
    from polygon import poly
    from quadric import quad
    from sphere import sphere
    from triangle import tri

    S = sphere((0, 0, 0), 1)
    c = []

    def add(name, flags, shape, m, o, d, **kw):
        extra = {k: kw.pop(k) for k in ("opts", "tol") if k in kw}
        c.append(case(name, ["transformed"] + flags, shape=shape, transform=m,
                      ray=world_ray(m, o, d, **kw), **extra))

    add("sphere, rotation about z + translation", ["rotation", "translation"], S, ROT_Z30, (-3, 0.25, 0.5), (1, 0, 0))
    add("sphere, non-uniform scale: an ellipsoid", ["scaling", "translation", "exact-transform"], S, SCALE,
        (-3, 0.5, 0.25), (1, 0, 0))
    add("sphere, non-uniform scale, exact tangent", ["scaling", "tangent", "exact-transform"], S, SCALE,
        (1, -3, 0), (0, 1, 0))
    add("sphere, mirror: kinds unchanged", ["mirror", "translation", "exact-transform"], S, MIRROR,
        (-3, 0.5, 0.5), (1, 0, 0))
    add("sphere, shear", ["shear", "translation"], S, SHEAR, (0.25, -3, 0.5), (0, 1, 0))
    add("sphere, uniform scale 2^-100 is not singular", ["scaling", "exact-transform"], S, TINY,
        (-3, 0.5, 0), (1, 0, 0))
    add("sphere, diag(1,1,1e-13) is not singular (row-scaled test)", ["scaling"], S, THIN_DIAG,
        (0.25, 0.5, -3), (0, 0, 1))
    add("sphere, rotation + non-uniform scale, origin inside", ["rotation", "scaling", "inside"], S, ROT_SCALE,
        (0.1, 0.2, -0.3), (0.5, 1, -0.25))
    add("plane, general rotation", ["rotation", "translation"], plane((0, 0, 1), -1), ROT_GEN,
        (0.5, 0.25, 5), (0.1, 0.2, -1))
    add("plane, mirror z: world normal flips, still enter", ["mirror", "rotation", "translation"],
        plane((0, 0, 1), -1), MIRROR_ROT, (0.5, 0.25, 5), (0, 0.25, -1))
    add("plane, cull_back under a mirror", ["mirror", "rotation", "cull-back", "miss"],
        plane((0, 0, 1), -1), MIRROR_ROT, (0.5, 0.25, -5), (0, 0.25, 1), opts=opts(flags=["cull_back"]))
    add("box, rotation about z", ["rotation", "translation"], box((-1, -1, -1), (1, 1, 1)), ROT_Z30,
        (-5, 0.25, 0.5), (1, 0.1, 0))
    add("box, scaling, grazing an edge (touch)", ["scaling", "graze", "exact-transform"],
        box((0, 0, 0), (1, 1, 1)), SCALE, (-1, 0, 0.5), (1, 1, 0))
    add("box, shear, oblique", ["shear", "translation"], box((0, 0, 0), (1, 2, 3)), SHEAR,
        (-2, 0.5, 1), (1, 0.25, 0.5))
    add("triangle, general rotation (uv)", ["rotation", "translation"],
        tri((0, 0, 0), (1, 0, 0), (0, 1, 0)), ROT_GEN, (0.25, 0.3, 2), (0, 0, -1))
    add("triangle, mirror, back side culled", ["mirror", "cull-back", "miss", "exact-transform"],
        tri((0, 0, 0), (1, 0, 0), (0, 1, 0)), MIRROR, (0.25, 0.3, -2), (0, 0, 1),
        opts=opts(flags=["cull_back"]))
    add("triangle, swap x/y, ray through edge ab (exact in object space)",
        ["mirror", "edge", "exact-transform"], tri((0, 0, 0), (1, 0, 0), (0, 1, 0)), SWAP_XY,
        (0.5, 0, -1), (0, 0, 1))
    add("triangle, swap x/y, ray through the hypotenuse (exact in object space)",
        ["mirror", "edge", "exact-transform"], tri((0, 0, 0), (1, 0, 0), (0, 1, 0)), SWAP_XY,
        (0.5, 0.5, 1), (0, 0, -1))
    add("triangle, swap x/y, ray through vertex c", ["mirror", "vertex", "exact-transform"],
        tri((0, 0, 0), (1, 0, 0), (0, 1, 0)), SWAP_XY, (0, 1, 1), (0, 0, -1))
    u_up = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]
    add("concave polygon, shear, through an arm", ["shear", "concave"], poly(u_up), SHEAR,
        (0.5, 2.5, -1), (0, 0, 1))
    add("concave polygon, shear, through the notch", ["shear", "concave", "miss"], poly(u_up), SHEAR,
        (1.5, 2, -1), (0, 0, 1))
    add("concave polygon, scaling, reflex vertex (exact)", ["scaling", "reflex", "vertex", "exact-transform"],
        poly(u_up), SCALE, (2, 1, -1), (0, 0, 1))
    add("polygon, rotation + scale, nonzero rule", ["rotation", "scaling", "nonzero"],
        poly([(0, 3), (2, -3), (-3, 1), (3, 1), (-2, -3)], "nonzero"), ROT_SCALE, (0, 0, 4), (0.01, 0.02, -1))
    add("convex tetrahedron, rotation + scale", ["rotation", "scaling"], TETRA, ROT_SCALE,
        (1, 1, 1), (-1, -1.5, -2))
    add("convex cube, general rotation", ["rotation", "translation"], CUBE, ROT_GEN,
        (-3, -2, 0.5), (2, 1.25, -0.25))
    add("convex cube, mirror, through an edge (tie)", ["mirror", "tie", "edge", "exact-transform"], CUBE,
        MIRROR, (-2, -2, 0.5), (1, 1, 0))
    add("capped cylinder, general rotation: cap then side", ["rotation", "translation", "cap"],
        cyl((0, 0, 0), (0, 0, 2), 1), ROT_GEN, (0, 0, -1), (1, 0, 2))
    add("capped cylinder, scaling, side tangent", ["scaling", "tangent", "exact-transform"],
        cyl((0, 0, 0), (0, 0, 2), 1), SCALE, (1, -5, 1), (0, 1, 0))
    add("open cylinder, rotation + scale", ["rotation", "scaling", "open"],
        cyl((0, 0, 0), (0, 0, 2), 1, False), ROT_SCALE, (-5, 0.25, 1), (1, 0, 0.1))
    add("infinite cylinder, shear", ["shear", "translation"], icyl((0, 0, 0), (0, 0, 1), 1), SHEAR,
        (-4, 0.5, 3), (1, 0, 0.5))
    add("infinite cylinder, mirror + rotation", ["mirror", "rotation", "translation"],
        icyl((1, 0, 0), (1, 1, 0), 0.5), MIRROR_ROT, (0, 3, 0.25), (0, -1, 0))
    add("ellipsoid, rotation about z", ["rotation", "translation"], ell((0, 0, 0), (2, 1, 0.5)), ROT_Z30,
        (-5, 0.25, 0.1), (1, 0, 0))
    add("ellipsoid, general rotation, oblique", ["rotation", "translation"], ell((1, 0, 0), (1, 2, 3)),
        ROT_GEN, (-3, 1, -1), (1, -0.25, 0.5))
    add("ellipsoid, scaling, exact tangent", ["scaling", "tangent", "exact-transform"],
        ell((0, 0, 0), (2, 1, 0.5)), SCALE, (2, -5, 0), (0, 1, 0))
    add("quadric cone, general rotation", ["rotation", "translation"], quad(1, 1, -1, 0, 0, 0, 0, 0, 0, 0),
        ROT_GEN, (0.5, 0, -5), (0, 0, 1))
    add("quadric hyperboloid, mirror", ["mirror", "translation", "exact-transform"],
        quad(1, 1, -1, 0, 0, 0, 0, 0, 0, -1), MIRROR, (-5, 0, 1), (1, 0, 0))
    add("quadric sphere, pure translation", ["translation"], quad(1, 1, 1, 0, 0, 0, 0, 0, 0, -1), TRANSLATE,
        (0, 0, -5), (0, 0, 1))
    add("sphere, pure translation, tmax between the hits", ["translation", "clip"], S, TRANSLATE,
        (0, 0, -5), (0, 0, 1), tmax=5.0)

    # every shape type under the remaining kinds of transform
    add("plane, shear", ["shear", "translation"], plane((1, 2, 2), -3), SHEAR, (0, 0, 0), (0.25, 0.5, 1))
    add("plane, non-uniform scale", ["scaling", "translation", "exact-transform"], plane((0, 1, 0), 0.5), SCALE,
        (0.25, 3, 0.5), (0, -1, 0))
    add("box, mirror + rotation", ["mirror", "rotation", "translation"], box((-1, -1, -1), (1, 1, 1)),
        MIRROR_ROT, (0.25, -5, 0.5), (0.1, 1, 0))
    add("triangle, shear", ["shear", "translation"], tri((0, 0, 0), (2, 0, 0), (0, 2, 1)), SHEAR,
        (0.5, 0.5, -3), (0, 0, 1))
    add("polygon, mirror: normal and kind", ["mirror", "translation", "exact-transform"],
        poly([(0, 0), (2, 0), (2, 2), (0, 2)]), MIRROR, (0.5, 1.5, 1), (0, 0, -1))
    add("convex tetrahedron, shear", ["shear", "translation"], TETRA, SHEAR, (0.2, 0.3, -1), (0, 0, 1))
    add("capped cylinder, mirror + rotation", ["mirror", "rotation", "translation", "cap"],
        cyl((0, 0, 0), (0, 0, 2), 1), MIRROR_ROT, (0.25, 0, -1), (0, 0.125, 1))
    add("open cylinder, shear", ["shear", "translation", "open"], cyl((0, 0, 0), (0, 0, 2), 1, False), SHEAR,
        (-5, 0.25, 1), (1, 0, 0.1))
    add("infinite cylinder, non-uniform scale", ["scaling", "translation", "exact-transform"],
        icyl((0, 0, 0), (0, 0, 1), 1), SCALE, (-5, 0.5, 2), (1, 0, 0))
    add("ellipsoid, shear", ["shear", "translation"], ell((0, 0, 0), (2, 1, 0.5)), SHEAR, (0.5, -4, 0.1),
        (0, 1, 0))
    add("quadric paraboloid, non-uniform scale (linear case)", ["scaling", "translation", "linear",
        "exact-transform"], quad(1, 1, 0, 0, 0, 0, 0, 0, -1, 0), SCALE, (0.5, 0, 5), (0, 0, -1))
    add("quadric hyperboloid, shear", ["shear", "translation"], quad(1, 1, -1, 0, 0, 0, 0, 0, 0, -1), SHEAR,
        (-5, 0, 1), (1, 0, 0))

    # bad transforms
    def bad(name, flags, m):
        c.append(case(name, ["transformed", "bad-input"] + flags, shape=S, transform=m,
                      ray=ray((0, 0, -5), (0, 0, 1))))
    bad("singular: zero row", ["singular"], affine([[1, 0, 0], [0, 0, 0], [0, 0, 1]]))
    bad("singular: row 2 = row 0 + row 1", ["singular"], affine([[1, 2, 3], [4, 5, 6], [5, 7, 9]], (1, 1, 1)))
    bad("singular: all zero", ["singular"], affine([[0, 0, 0], [0, 0, 0], [0, 0, 0]]))
    bad("nearly singular: det 1e-14 relative", ["singular"], affine([[1, 0, 0], [0, 1, 0], [1, 1, 1e-14]]))
    bad("non-affine: last row 0 0 0 2", ["non-affine"], affine(rotation((0, 0, 1), 10))[:15] + [2.0])
    bad("non-affine: last row 0 0 1 1", ["non-affine"], affine([[1, 0, 0], [0, 1, 0], [0, 0, 1]])[:14] + [1.0, 1.0])
    bad("non-affine: last row 1e-300 0 0 1", ["non-affine"],
        affine([[1, 0, 0], [0, 1, 0], [0, 0, 1]])[:12] + [1e-300, 0.0, 0.0, 1.0])
    bad("NaN in the linear part", ["nonfinite"], affine([[1, 0, 0], [0, math.nan, 0], [0, 0, 1]]))
    bad("Inf in the translation", ["nonfinite"], affine([[1, 0, 0], [0, 1, 0], [0, 0, 1]], (0, math.inf, 0)))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0), under
    # transforms whose inverse and object-space rays are exact in doubles
    S5 = sphere((0, 0, 0), 5)
    on = [7.0, 0.0, 3.0]                                   # SCALE (3, 4, 0)
    s_in, s_out = (-2, -1, 2), (2, 0.5, -1)                # L (-1, -2, 0.5), L (1, 1, -0.25)
    for name, o, d in (("on it, inward: enter at t = 0", on, s_in),
                       ("on it, outward: exit at t = 0 only", on, s_out),
                       ("1 ulp outside (x), inward", nudged(on, 0, 1), s_in),
                       ("1 ulp outside (x), outward: no hit", nudged(on, 0, 1), s_out),
                       ("1 ulp inside (x), outward: t ~ +1e-16", nudged(on, 0, -1), s_out),
                       ("2 ulps inside (x), inward: exit only", nudged(on, 0, -2), s_in)):
        c.append(surface_case(f"sphere r = 5, non-uniform scale: {name}", ["transformed", "scaling",
                              "translation", "exact-transform"] + (["miss"] if "no hit" in name else []),
                              shape=S5, transform=SCALE, ray=ray(o, d)))
    slant = tri((1, 0, 0), (0, 1, 0), (0, 0, 1))
    t_on = [0.75, 0.0, 0.5]                                # SWAP_XY (0.25, 0.25, 0.5)
    for name, o, d in (("on it, toward the back: t = 0", t_on, (-2, -1, -3)),
                       ("1 ulp in front (z), toward it", nudged(t_on, 2, 1), (-2, -1, -3)),
                       ("1 ulp behind (z), away: no hit", nudged(t_on, 2, -1), (-2, -1, -3)),
                       ("2 ulps behind (x), toward it (exit)", nudged(t_on, 0, -2), (1, 0.5, 1.5))):
        c.append(surface_case(f"triangle, swap x/y: {name}", ["transformed", "mirror", "exact-transform"]
                              + (["miss"] if "no hit" in name else []), shape=slant, transform=SWAP_XY,
                              ray=ray(o, d)))
    b_on = [3.0, -1.75, 4.0]                               # SCALE (1, 0.5, 0.25) on face +x
    for name, o, d in (("on face +x, inward", b_on, (-1, 0.25, 0.5)),
                       ("on face +x, outward: exit at t = 0 only", b_on, (1, 0.25, 0.5)),
                       ("1 ulp outside face +x, inward", nudged(b_on, 0, 1), (-1, 0.25, 0.5)),
                       ("1 ulp inside face +x, outward: t ~ +1e-16", nudged(b_on, 0, -1), (1, 0.25, 0.5))):
        c.append(surface_case(f"box, non-uniform scale: {name}", ["transformed", "scaling", "translation",
                              "exact-transform"], shape=box((0, 0, 0), (1, 1, 1)), transform=SCALE, ray=ray(o, d)))
    C5 = cyl((1, 2, 3), (1, 5, 7), 5)
    c_on = [1.0, 7.5, 2.0]                                 # MIRROR (1, 7.5, 2): on the side
    for name, o, d in (("on the side, inward", c_on, (-0.5, -1, 0.5)),
                       ("on the side, outward: exit at t = 0 only", c_on, (-0.25, 1, -0.5)),
                       ("1 ulp outside the side (y), inward", nudged(c_on, 1, 1), (-0.5, -1, 0.5)),
                       ("1 ulp inside the side (y), outward: t ~ +1e-16", nudged(c_on, 1, -1),
                        (-0.25, 1, -0.5))):
        c.append(surface_case(f"capped cylinder, mirror: {name}", ["transformed", "mirror", "translation",
                              "exact-transform"], shape=C5, transform=MIRROR, ray=ray(o, d)))

    # --- revision 2: grazing under an exact transform, t to about 4 ulp (object-space design:
    # the line at distance h from the centre along (2, 1, -2)/3, direction (1, 2, 2))
    def graze(h: float) -> tuple[list[float], tuple[int, int, int]]:
        foot = [h * 2 / 3, h / 3, -h * 2 / 3]
        return [x - 10 * v for x, v in zip(foot, (1, 2, 2))], (1, 2, 2)
    for name, h, extra, kw in (("h = 5(1 - 2^-30): two close hits", 5 - 5 * 2.0 ** -30, [], {}),
                               ("h = 5(1 + 2^-30): miss", 5 + 5 * 2.0 ** -30, ["miss"], {}),
                               ("h = 5(1 - 2^-44): touch within eps", 5 - 5 * 2.0 ** -44, [], {}),
                               ("h = 5(1 - 2^-48), eps = 0: two hits", 5 - 5 * 2.0 ** -48, ["eps"],
                                {"opts": opts(eps=0.0)})):
        o, d = graze(h)
        add(f"sphere r = 5, non-uniform scale, grazing: {name}", ["scaling", "translation", "exact-transform",
            "grazing", "near-tangent"] + extra, S5, SCALE, o, d, tol=TIGHT, **kw)

    # --- revision 2: far and small, t to about 4 ulp
    FAR_T = affine([[2.0 ** -10, 0, 0], [0, 2.0 ** -10, 0], [0, 0, 2.0 ** -10]], (1e7, 0, 0))
    c.append(case("far: unit sphere scaled by 2^-10 and moved to x = 1e7", ["transformed", "scaling",
                  "translation", "exact-transform", "far", "loose-normal"], shape=S, transform=FAR_T,
                  ray=ray((0, 3e-4, 0), (1, 0, 0)), tol={"t": 1e-15, "normal": 1e-5}))
    FAR_R = affine(matmul(rotation((1, 2, 2), 40), [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]), (6e6, 8e6, 0))
    c.append(case("far: unit sphere scaled by 1e-3, rotated, moved to (6e6, 8e6, 0)", ["transformed",
                  "scaling", "rotation", "translation", "far", "loose-normal", "loose-point"], shape=S,
                  transform=FAR_R, ray=ray((0, 5e-4, 1e-4), (3, 4, 0)),
                  tol={"t": 1e-15, "point": 1e-8, "normal": 1e-5}))
    c.append(case("far: a 1e-3 box rotated about z at (1e7, 0, 0)", ["transformed", "rotation", "translation",
                  "far", "loose-point"], shape=box((-5e-4, -5e-4, -5e-4), (5e-4, 5e-4, 5e-4)),
                  transform=affine(rotation((0, 0, 1), 30), (1e7, 0, 0)), ray=ray((0, 1e-4, 2e-4), (1, 0, 0)),
                  tol={"t": 1e-15, "point": 1e-8}))
    return c
