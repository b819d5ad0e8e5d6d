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
from model import INF, Ctx, Hit, XRay, case, opts, ray

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
    return c
