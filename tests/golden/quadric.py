# SPDX-License-Identifier: Apache-2.0
"""General quadric (isect_ray_quadric): reference solver and cases.

Q(x) = Ax^2 + By^2 + Cz^2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J, inside where Q < 0.
Substituting x = o + t v (seed: Ray-Quadric) gives Q = a t^2 + b t + c with
    a = A vx^2 + B vy^2 + C vz^2 + D vx vy + E vx vz + F vy vz,
    b = 2(A ox vx + B oy vy + C oz vz) + D(ox vy + oy vx) + E(ox vz + oz vx)
        + F(oy vz + oz vy) + G vx + H vy + I vz,
    c = Q(o).
isect.h: linear when |a| <= eps S |v|^2, S = max(|A|..|F|) (S = 0 too):
t = -c/b, no hit if b = 0.  Otherwise disc = b^2 - 4ac; TOUCH at -b/(2a)
when |disc| <= eps (b^2 + 4|ac|); else roots (-b -+ sqrt(disc))/(2a).
Normal unit(grad Q), grad Q = (2Ax + Dy + Ez + G, 2By + Dx + Fz + H,
2Cz + Ex + Fy + I); kind from v.grad Q (= 2at + b): < 0 ENTER, > 0 EXIT.
All coefficients zero: degenerate.
"""
from __future__ import annotations

from fractions import Fraction

from exact import DesignError, dot, eps_le, norm2, point_on_ray, qv, sign, sqrt, unit
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case

FAMILY = "quadric"


def grad(k, x) -> tuple:
    A, B, C, D, E, F, G, H, I, _ = k
    return (2 * A * x[0] + D * x[1] + E * x[2] + G,
            2 * B * x[1] + D * x[0] + F * x[2] + H,
            2 * C * x[2] + E * x[0] + F * x[1] + I)


def value(k, x) -> Fraction:
    A, B, C, D, E, F, G, H, I, J = k
    X, Y, Z = x
    return (A * X * X + B * Y * Y + C * Z * Z + D * X * Y + E * X * Z + F * Y * Z
            + G * X + H * Y + I * Z + J)


def along(k, o, v) -> tuple[Fraction, Fraction, Fraction]:
    """(a, b, c) of Q(o + t v) = a t^2 + b t + c."""
    A, B, C, D, E, F, G, H, I, _ = k
    a = A * v[0] ** 2 + B * v[1] ** 2 + C * v[2] ** 2 + D * v[0] * v[1] + E * v[0] * v[2] + F * v[1] * v[2]
    b = (2 * (A * o[0] * v[0] + B * o[1] * v[1] + C * o[2] * v[2])
         + D * (o[0] * v[1] + o[1] * v[0]) + E * (o[0] * v[2] + o[2] * v[0])
         + F * (o[1] * v[2] + o[2] * v[1]) + G * v[0] + H * v[1] + I * v[2])
    return a, b, value(k, o)


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    k = qv(shape["coeffs"])
    if all(x == 0 for x in k):
        return []
    a, b, c = along(k, r.org, r.dir)
    S = max(abs(x) for x in k[:6])

    # grad Q is affine in t: grad(o) + t (grad(v) - grad(0))
    g0 = grad(k, r.org)
    g1 = tuple(a - b for a, b in zip(grad(k, r.dir), grad(k, (0, 0, 0))))

    def hit(t, kind: str | None = None) -> Hit:
        g = point_on_ray(g0, g1, t)
        if all(gi == 0 for gi in g):
            raise DesignError("hit at a singular point of the quadric (zero gradient)")
        if kind is None:
            s = sign(dot(r.dir, g))
            if s == 0:
                raise DesignError("linear-case hit with v.grad = 0")
            kind = "enter" if s < 0 else "exit"
        return Hit(t, unit(g), kind)

    if eps_le(abs(a), ctx.eps * S * norm2(r.dir), "quadric linear case"):
        return [] if b == 0 else [hit(-c / b)]
    disc = b * b - 4 * a * c
    if eps_le(abs(disc), ctx.eps * (b * b + 4 * abs(a * c)), "quadric tangency"):
        return [hit(-b / (2 * a), "touch")]
    if disc < 0:
        return []
    s = sqrt(disc)
    # v.grad Q at (-b + s)/(2a) is +s (EXIT) and at (-b - s)/(2a) is -s (ENTER)
    roots = [((-b - s) / (2 * a), "enter"), ((-b + s) / (2 * a), "exit")]
    if a < 0:
        roots.reverse()
    return [hit(t, kind) for t, kind in roots]


def contains(shape: dict, p) -> bool:
    k = qv(shape["coeffs"])
    return any(x != 0 for x in k) and value(k, p) <= 0


def quad(*k: float) -> dict:
    assert len(k) == 10
    return {"type": "quadric", "coeffs": [float(x) for x in k]}


def cases() -> list[dict]:
    SPH = quad(1, 1, 1, 0, 0, 0, 0, 0, 0, -1)
    CYL = quad(1, 1, 0, 0, 0, 0, 0, 0, 0, -1)
    CONE = quad(1, 1, -1, 0, 0, 0, 0, 0, 0, 0)
    c = []
    c.append(case("unit sphere as a quadric", ["basic"], shape=SPH, ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("sphere quadric, exact tangent", ["tangent"], shape=SPH, ray=ray((1, 0, -5), (0, 0, 1))))
    c.append(case("sphere quadric, exact tangent with eps = 0", ["tangent", "eps"], shape=SPH,
                  ray=ray((0, -1, -5), (0, 0, 2)), opts=opts(eps=0.0)))
    c.append(case("sphere quadric, near-tangent within eps 1e-6", ["near-tangent", "eps"], shape=SPH,
                  ray=ray((1 - 1e-8, 0, -5), (0, 0, 1)), opts=opts(eps=1e-6)))
    c.append(case("sphere quadric, near-tangent outside default eps", ["near-tangent"], shape=SPH,
                  ray=ray((1 - 1e-8, 0, -5), (0, 0, 1))))
    c.append(case("sphere quadric, origin inside", ["inside"], shape=SPH, ray=ray((0.5, 0, 0), (0, 1, 0))))
    c.append(case("sphere quadric, behind, tmin = -inf", ["behind", "negative-t"], shape=SPH,
                  ray=ray((0, 0, 5), (0, 0, 1), tmin=-INF)))
    c.append(case("translated sphere (x-1)^2+(y-2)^2+(z-3)^2 = 4", ["basic", "non-unit-dir"],
                  shape=quad(1, 1, 1, 0, 0, 0, -2, -4, -6, 10), ray=ray((-4, 2.5, 3.5), (2, 0, 0))))
    c.append(case("inverted sphere 1 - |x|^2: outside is inside", ["basic"],
                  shape=quad(-1, -1, -1, 0, 0, 0, 0, 0, 0, 1), ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("tiny coefficients 1e-100 (scale invariance)", ["basic"],
                  shape=quad(1e-100, 1e-100, 1e-100, 0, 0, 0, 0, 0, 0, -1e-100), ray=ray((0.5, 0, -5), (0, 0, 1))))
    c.append(case("cylinder x^2 + y^2 = 1, across", ["basic"], shape=CYL, ray=ray((-5, 0.5, 7), (1, 0, 0.5))))
    c.append(case("cylinder quadric, ray along the axis: a = b = 0", ["linear", "parallel", "miss"],
                  shape=CYL, ray=ray((0.5, 0, 0), (0, 0, 1))))
    c.append(case("cone, ray parallel to the axis crosses both nappes", ["basic"], shape=CONE,
                  ray=ray((0.5, 0, -5), (0, 0, 1))))
    c.append(case("cone, ray parallel to a generator (linear)", ["linear"], shape=CONE,
                  ray=ray((0, 0, -1), (1, 0, 1))))
    c.append(case("cone, parallel to a generator, entering (linear)", ["linear"], shape=CONE,
                  ray=ray((0, 2, 1), (0, -1, 1))))
    c.append(case("cone, across one nappe", ["basic"], shape=CONE, ray=ray((-5, 0, 2), (1, 0, 0))))
    c.append(case("plane z = 1 as a quadric (S = 0, linear)", ["linear"],
                  shape=quad(0, 0, 0, 0, 0, 0, 0, 0, 1, -1), ray=ray((0, 0, 5), (0, 0, -1))))
    c.append(case("plane quadric, parallel ray: a = b = 0", ["linear", "parallel", "miss"],
                  shape=quad(0, 0, 0, 0, 0, 0, 0, 0, 1, -1), ray=ray((0, 0, 5), (1, 0, 0))))
    c.append(case("paraboloid z = x^2 + y^2, vertical ray (linear)", ["linear"],
                  shape=quad(1, 1, 0, 0, 0, 0, 0, 0, -1, 0), ray=ray((0.5, 0, 5), (0, 0, -1))))
    c.append(case("paraboloid, horizontal ray", ["basic"],
                  shape=quad(1, 1, 0, 0, 0, 0, 0, 0, -1, 0), ray=ray((-3, 0, 4), (1, 0, 0))))
    c.append(case("hyperboloid of one sheet, across the waist", ["basic"],
                  shape=quad(1, 1, -1, 0, 0, 0, 0, 0, 0, -1), ray=ray((-5, 0, 1), (1, 0, 0))))
    c.append(case("ray on a ruling line of the hyperboloid: a = b = 0", ["linear", "in-plane", "miss"],
                  shape=quad(1, 1, -1, 0, 0, 0, 0, 0, 0, -1), ray=ray((1, 0, 0), (0, 1, 1))))
    c.append(case("hyperboloid of two sheets along z", ["basic"],
                  shape=quad(-1, -1, 1, 0, 0, 0, 0, 0, 0, -1), ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("rotated ellipsoid with an xy term", ["basic"],
                  shape=quad(2, 2, 1, 2, 0, 0, 0, 0, 0, -1), ray=ray((-3, 0.1, 0.2), (1, 0, 0))))
    c.append(case("general quadric with all ten terms", ["basic", "non-unit-dir"],
                  shape=quad(1.5, 0.75, 2, 0.5, -0.25, 0.125, 0.3, -0.2, 0.1, -2), ray=ray((-4, 1, 0.5), (3, -0.5, 0.25))))
    c.append(case("two parallel planes x^2 = 1", ["basic"], shape=quad(1, 0, 0, 0, 0, 0, 0, 0, 0, -1),
                  ray=ray((-5, 3, 2), (1, 0.5, 0))))
    c.append(case("near-linear cone (a ~ -2^-19), eps 1e-4: linear, one hit", ["linear", "eps"], shape=CONE,
                  ray=ray((0, 0, -1), (1, 0, 1 + 2.0**-20)), opts=opts(eps=1e-4)))
    c.append(case("near-linear cone (a ~ -2^-19), default eps: two hits", ["basic"], shape=CONE,
                  ray=ray((0, 0, -1), (1, 0, 1 + 2.0**-20))))
    c.append(case("sphere quadric, tmax between the hits", ["clip"], shape=SPH,
                  ray=ray((0, 0, -5), (0, 0, 1), tmax=5.0)))
    c.append(case("all coefficients zero is degenerate", ["degenerate", "miss"], shape=quad(*[0] * 10),
                  ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("contains: inside the sphere quadric", ["contains"], op="contains", shape=SPH,
                  point=[0.5, 0.5, 0.5]))
    c.append(case("contains: on the cone", ["contains", "boundary"], op="contains", shape=CONE,
                  point=[3.0, 4.0, 5.0]))
    c.append(case("contains: outside the cylinder", ["contains"], op="contains", shape=CYL,
                  point=[1.0, 1.0, 0.0]))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0)
    HYP = quad(1, 1, -1, 0, 0, 0, 0, 0, 0, -1)      # x^2 + y^2 - z^2 = 1, inside near the axis
    on = (1.0, 1.0, 1.0)                              # grad (2, 2, -2)
    into, out = (-1, -0.5, 0.25), (1, 0.25, -0.5)
    c.append(surface_case("hyperboloid: on it, inward: enter at t = 0", [], shape=HYP, ray=ray(on, into)))
    c.append(surface_case("hyperboloid: on it, outward: exit at t = 0 only", [], shape=HYP, ray=ray(on, out)))
    c.append(surface_case("hyperboloid: 1 ulp outside (x), inward", [], shape=HYP,
                          ray=ray(nudged(on, 0, 1), into)))
    c.append(surface_case("hyperboloid: 1 ulp outside (x), outward: no hit", ["miss"], shape=HYP,
                          ray=ray(nudged(on, 0, 1), out)))
    c.append(surface_case("hyperboloid: 1 ulp inside (z), outward: t ~ +1e-16", [], shape=HYP,
                          ray=ray(nudged(on, 2, 1), out)))
    c.append(surface_case("hyperboloid: 3 ulps inside (y), inward", [], shape=HYP,
                          ray=ray(nudged(on, 1, -3), into)))
    # a quadric with all ten terms through p = (1, 0.5, -0.25), dyadic coefficients
    k9 = [1.5, 0.75, 2, 0.5, -0.25, 0.125, 0.375, -0.625, 0.25]
    p = (1.0, 0.5, -0.25)
    rest = (k9[0] * p[0] ** 2 + k9[1] * p[1] ** 2 + k9[2] * p[2] ** 2 + k9[3] * p[0] * p[1]
            + k9[4] * p[0] * p[2] + k9[5] * p[1] * p[2] + k9[6] * p[0] + k9[7] * p[1] + k9[8] * p[2])
    GEN = quad(*k9, -rest)
    c.append(surface_case("ten-term quadric: on it, inward: enter at t = 0", [], shape=GEN,
                          ray=ray(p, (-1, -0.5, 0.25))))
    c.append(surface_case("ten-term quadric: on it, outward: exit at t = 0 only", [], shape=GEN,
                          ray=ray(p, (1, 0.5, -0.25))))
    c.append(surface_case("ten-term quadric: 2 ulps inside (x), outward: t ~ +1e-16", [], shape=GEN,
                          ray=ray(nudged(p, 0, -2), (1, 0.5, -0.25))))
    c.append(surface_case("ten-term quadric: 2 ulps outside (x), outward: no hit", ["miss"],
                          shape=GEN, ray=ray(nudged(p, 0, 2), (1, 0.5, -0.25))))

    # --- revision 2: grazing the waist of the hyperboloid at (1, 0, 0), direction (0, 1, 0.5):
    # Q = 0.75 s^2 + x^2 - 1 along the line (s = t - 4), t to about 4 ulp
    def graze(x: float) -> dict:
        return ray((x, -4, -2), (0, 1, 0.5))
    c.append(case("hyperboloid: grazing at x = 1 - 2^-30, two close hits", ["grazing", "near-tangent"],
                  shape=HYP, ray=graze(1 - 2.0 ** -30), tol=TIGHT))
    c.append(case("hyperboloid: grazing at x = 1 + 2^-30, miss", ["grazing", "near-tangent", "miss"],
                  shape=HYP, ray=graze(1 + 2.0 ** -30)))
    c.append(case("hyperboloid: grazing at x = 1 - 2^-44, touch within eps", ["grazing", "near-tangent"],
                  shape=HYP, ray=graze(1 - 2.0 ** -44), tol=TIGHT))
    c.append(case("hyperboloid: grazing at x = 1 - 2^-50, eps = 0: two hits", ["grazing", "near-tangent",
                  "eps"], shape=HYP, ray=graze(1 - 2.0 ** -50), opts=opts(eps=0.0), tol=TIGHT))

    # --- revision 2: far and small (a sphere of radius 1e-3 seen from 1e7 away), t to about 4 ulp.
    # The quadric's tangency test is relative to b^2 + 4|ac| (~4e14 here) while b^2 - 4ac is
    # ~4e-6: with the default eps that is a touch, as documented; eps = 0 gives the two roots.
    FAR_TOL = {"t": 1e-15, "point": 1e-8, "normal": 1e-5}
    FAR = ["far", "loose-normal", "loose-point"]
    SMALL = quad(1, 1, 1, 0, 0, 0, 0, 0, 0, -1e-6)
    c.append(case("far: sphere quadric r = 1e-3 seen from x = -1e7, eps = 0: two hits", FAR + ["eps"],
                  shape=SMALL, ray=ray((-1e7, 3e-4, 0), (1, 0, 0)), opts=opts(eps=0.0), tol=FAR_TOL))
    c.append(case("far: the same with the default eps: one touch (the test is relative to b^2)",
                  FAR + ["near-tangent"], shape=SMALL, ray=ray((-1e7, 3e-4, 0), (1, 0, 0)), tol=FAR_TOL))
    c.append(case("far: sphere quadric from (-6e6, -8e6, 0), oblique, eps = 0", FAR + ["non-unit-dir", "eps"],
                  shape=SMALL, ray=ray((-6e6, -8e6, 2e-4), (3, 4, 0)), opts=opts(eps=0.0), tol=FAR_TOL))
    c.append(case("far: cylinder quadric x^2 + y^2 = 1e-6 seen from 1e7 away, eps = 0", FAR + ["eps"],
                  shape=quad(1, 1, 0, 0, 0, 0, 0, 0, 0, -1e-6), ray=ray((-1e7, -5e-4, 3), (1, 0, 0.25)),
                  opts=opts(eps=0.0), tol=FAR_TOL))
    return c
