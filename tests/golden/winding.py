# SPDX-License-Identifier: Apache-2.0
"""Generalized winding numbers of meshes and the containment rules of meshes:
reference and cases (op winding_number, op contains with a mesh "rule").

The quantity (SPEC.md, "Winding numbers and containment of any mesh"; isect.h,
isect_winding_number_batch).  For a mesh and a point p,
    w(p) = (1/4pi) sum over faces of the signed solid angle the face subtends at p,
faces oriented by the right-hand rule over their vertex order (w = 1 inside a
closed mesh whose faces point out).  The reference computes it twice, by two
methods that share nothing:

* Solid angles (any mesh).  A polygon face is the fan of triangles (v0, vi,
  vi+1) (isect.h: a polygon face's solid angle is its fan's).  For a triangle
  A, B, C and a = A - p, b = B - p, c = C - p (Van Oosterom & Strackee 1983)
      tan(Omega / 2) = det[a b c] / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|),
  Omega = 2 atan2(num, den), with det[a b c] and the dot products exact
  (Fractions of the given doubles) and the lengths, den and atan2 in mpmath at
  80 digits.  det[a b c] = 0 exactly (p in the triangle's plane) gives 0: off the
  triangle that is its solid angle, on it (inside, on an edge or a vertex) it is
  the principal value, the mean of the two one-sided limits +-2pi or +-pi.  This
  is the value isect.h documents on the surface ("the principal value by direct
  summation (1/2 on a face of a simple solid)").
* Signed crossings (closed, consistently oriented meshes, p off the surface).
  The ray from p in a generic rational direction d (a fixed list, the first one
  that passes no edge or vertex and lies in no face plane it meets, all decided
  exactly with Fractions) crosses faces; each crossing counts sign(d . n), +1
  where the ray leaves through a face's front.  The sum is the exact integer w.
  The generator asserts that both methods agree (to 1e-40) on every such point.

What the library does (isect.h, src/mesh/winding.c), which the expectations
follow: on a closed, consistently oriented mesh (every edge used once each way)
w off the surface is the exact integer (tol 0) whatever `accuracy` is; on its
surface, and everywhere on any other mesh, w is the sum of the fan triangles'
solid angles, with the documented error bound
    |w - exact| <= (1/4pi) sum over fan triangles (pi E/|z| + 8 pi u) + 2u|w|,
    E = E_num + E_den,  E_num = 10u sum_k |a_k| P_k,  E_den = 64u |a||b||c|,
    z = den + i num (num = a . ((B - A) x (C - A)) = det[a b c]),
P_k the permanents of (B - A) x (C - A) (P_x = |e1_y e2_z| + |e1_z e2_y|, ...),
u = 2^-53; a fan triangle whose plane holds p contributes exactly 0 (its sign
is taken exactly), a term is at most 4pi.  The case tolerance `tol.winding` is
that bound, evaluated here on the exact numbers and rounded up to two
significant digits, relative as every corpus tolerance (divided by
max(1, |w|)); with accuracy > 0 (the far-field evaluation) `accuracy` is added:
isect.h promises |w - (accuracy 0)| <= accuracy.

Transforms.  w is that of the mesh placed in the world: its vertices mapped by
the 4x4 matrix, faces in the same vertex order (a mirror reverses the
right-hand rule, so it negates w, as isect.h says).  The reference maps the
vertices (exactly) and evaluates at the world point.  The library maps the
point to object space instead; the cases keep to transforms whose inverse and
object-space points are exact in doubles (signed powers of two in a
permutation, dyadic translations), so the library sees the exact object point.
For a similarity (uniform scaling, rotation, mirror) the library sums in object
space, which agrees with the world value exactly (asserted here), and its
documented bound is evaluated in object space; for a non-uniform scaling solid
angles change, and isect.h says the library sums over the faces' world images
(exact here), so the bound is evaluated on the world faces.

Containment rules (isect.h, isect_contains; the mesh shape's "rule"):
"evenodd" needs a closed mesh (every edge used exactly twice) else E_ARG, and
is the crossing parity; "nonzero" needs a closed, consistently oriented mesh
else E_ARG, and is w != 0 (the exact integer); "winding" takes any mesh: on a
closed, consistently oriented mesh w >= 1 (the exact integer, a mirroring
transform negating it), on any other mesh w >= 1/2 (the sum; a case whose w
lies within four times its bound of 1/2 is refused).  Under every rule a point
on a closed mesh's face, edge or vertex is inside (solids are closed sets).
"""
from __future__ import annotations

import functools
import math
from fractions import Fraction
from typing import Sequence

import mpmath

import mesh
import transformed
from exact import DesignError, U, cross, dot, is_zero, mp, q, qv, sub, to_double
from model import XRay, case, nudge
from mesh import CUBE_QUADS, CUBE_V, V3, cube_quads, cube_tris, with_faces

FAMILY = "winding"

RULES = ("evenodd", "nonzero", "winding")
PI = mpmath.pi
#: the library's floor on each error term (winding.c: WINDING_TINY)
TINY = Fraction(1, 2**1000)


# ------------------------------------------------------------ geometry
def faces_of(shape: dict) -> list[list[int]]:
    return [list(f) for f in shape["faces"]]


def vertices(shape: dict, m: Sequence[float] | None) -> list[V3]:
    """The mesh's vertices in the world: M v exactly (the object vertices without a transform)."""
    vs = [qv(v) for v in shape["vertices"]]
    if m is None:
        return vs
    L, T = transformed.linear(m), transformed.translation(m)
    return [tuple(x + t for x, t in zip(transformed.mul(L, v), T)) for v in vs]


def object_point(m: Sequence[float] | None, p: Sequence[float]) -> V3:
    """p in object space, refused unless the library computes it exactly."""
    if m is None:
        return qv(p)
    obj, exact = transformed.object_ray(m, XRay(qv(p), qv((1, 0, 0)), Fraction(0), math.inf))
    if not exact:
        raise DesignError("the object-space point is not exact in doubles")
    return obj.org


def fan(vs: Sequence[V3], face: Sequence[int]):
    """The face's fan triangles (v0, vi, vi+1)."""
    for k in range(1, len(face) - 1):
        yield vs[face[0]], vs[face[k]], vs[face[k + 1]]


def vos(A: V3, B: V3, C: V3, p: V3) -> tuple[Fraction, mpmath.mpf, mpmath.mpf]:
    """num = det[a b c] (exact), den of Van Oosterom & Strackee's formula and |a||b||c|.

    den cancels where p nears an edge line of the triangle (it vanishes on one), so it is
    computed with as many digits as it takes to know it to 10^-70 of |z| = |den + i num|:
    80, then twice as many, up to 5120 (a point 1 ulp off a face near an edge)."""
    a, b, c = sub(A, p), sub(B, p), sub(C, p)
    num = dot(a, cross(b, c))
    if num == 0:
        return num, mpmath.mpf(0), mpmath.mpf(0)     # p in the plane: the callers need only num
    dps = 80
    while True:
        with mpmath.workdps(dps):
            la, lb, lc = (mpmath.sqrt(mpmath.mpf(dot(v, v))) for v in (a, b, c))
            size = la * lb * lc
            den = size + mpmath.mpf(dot(a, b)) * lc + mpmath.mpf(dot(a, c)) * lb + mpmath.mpf(dot(b, c)) * la
            noise = 8 * size * mpmath.mpf(10) ** -dps
            z = mpmath.sqrt(mpmath.mpf(num) ** 2 + den ** 2)
            if noise <= z * mpmath.mpf(10) ** -70:
                return num, +den, +size
        dps *= 2
        if dps > 5120:
            raise DesignError("Van Oosterom & Strackee's denominator cannot be resolved")


def triangle_angle(A: V3, B: V3, C: V3, p: V3) -> mpmath.mpf:
    """Signed solid angle of A, B, C at p (Van Oosterom & Strackee); 0 in its plane."""
    num, den, _ = vos(A, B, C, p)
    if num == 0:
        return mpmath.mpf(0)
    return 2 * mpmath.atan2(mp(num), den)


def generalized(vs: Sequence[V3], faces: Sequence[Sequence[int]], p: V3) -> mpmath.mpf:
    """w(p) by the solid angles (the principal value on the surface)."""
    return _sums(tuple(vs), tuple(map(tuple, faces)), p)[0]


@functools.lru_cache(maxsize=None)
def _sums(vs: tuple, faces: tuple, p: V3) -> tuple[mpmath.mpf, mpmath.mpf]:
    """(w, the documented bound without its 2u|w| term) at p: one pass over the fan
    triangles (several cases share a mesh and its points)."""
    u = mp(U)
    total, bound = mpmath.mpf(0), mpmath.mpf(0)
    for f in faces:
        for A, B, C in fan(vs, f):
            num, den, size = vos(A, B, C, p)
            if num == 0:
                continue            # p in the plane: 0, and exactly 0 in the library too
            total += 2 * mpmath.atan2(mp(num), den)
            # winding.c: E_num = 10u sum_k |a_k| P_k, E_den = 64u |a||b||c|, each + 2^-1000
            a, e1, e2 = sub(A, p), sub(B, A), sub(C, A)
            perm = (abs(e1[1] * e2[2]) + abs(e1[2] * e2[1]),
                    abs(e1[2] * e2[0]) + abs(e1[0] * e2[2]),
                    abs(e1[0] * e2[1]) + abs(e1[1] * e2[0]))
            e_num = 10 * u * mp(sum(abs(a[k]) * perm[k] for k in range(3))) + mp(TINY)
            e_den = 64 * u * size + mp(TINY)
            z = mpmath.sqrt(mp(num) ** 2 + den ** 2)
            bound += min(PI * (e_num + e_den) / z + 8 * PI * u, 4 * PI)
    return total / (4 * PI), bound / (4 * PI)


def documented_bound(vs: Sequence[V3], faces: Sequence[Sequence[int]], p: V3) -> mpmath.mpf:
    """sum over fan triangles of (pi E/|z| + 8 pi u), each at most 4 pi, over 4 pi
    (isect.h / winding.c; the 2u|w| term is added by the caller)."""
    return _sums(tuple(vs), tuple(map(tuple, faces)), p)[1]


def planar(vs: Sequence[V3], faces: Sequence[Sequence[int]]) -> list[tuple[list[V3], V3]]:
    """(vertices, Newell normal) of the faces with nonzero area."""
    out = []
    for f in faces:
        fv = [vs[i] for i in f]
        n = mesh.newell(fv)
        if not is_zero(n):
            out.append((fv, n))
    return out


def on_surface(vs: Sequence[V3], faces: Sequence[Sequence[int]], p: V3) -> bool:
    return any(dot(n, sub(p, fv[0])) == 0 and mesh.locate(fv, n, p) != "outside"
               for fv, n in planar(vs, faces))


def signed_crossings(vs: Sequence[V3], faces: Sequence[Sequence[int]], p: V3) -> int:
    """The exact integer w at p off the surface: crossings of a generic ray, each sign(d . n)."""
    pf = planar(vs, faces)
    for d in mesh.DIRECTIONS:
        total = 0
        for fv, n in pf:
            den, num = dot(n, d), dot(n, sub(fv[0], p))
            if den == 0:
                if num == 0:
                    break           # the ray lies in this face's plane: another direction
                continue
            t = num / den
            if t <= 0:
                continue
            where = mesh.locate(fv, n, tuple(p[k] + t * d[k] for k in range(3)))
            if where == "boundary":
                break               # through an edge or vertex: another direction
            if where == "inside":
                total += 1 if den > 0 else -1
        else:
            return total
    raise DesignError("no generic direction for the signed crossing count")


def oriented(shape: dict) -> bool:
    """Closed and consistently oriented: every edge used exactly twice, once each way."""
    return all(len(u) == 2 and u[0][1] != u[1][1] for u in mesh.edge_uses(shape).values())


def round_up(x: mpmath.mpf) -> float:
    """x rounded up to two significant digits, as a double >= x."""
    if x <= 0:
        return 0.0
    e = int(mpmath.floor(mpmath.log10(x))) - 1
    m = int(mpmath.ceil(x / mpmath.mpf(10) ** e))
    v = float(f"{m}e{e}")
    while mp(Fraction(v)) < x:
        v = math.nextafter(v, math.inf)
    return v


# ------------------------------------------------------------- evaluation
def _status(shape: dict, m: Sequence[float] | None) -> set[str]:
    st = set(mesh.status(shape)) if shape["type"] == "mesh" else set()
    if m is not None:
        ts = transformed.check(m)
        if ts:
            st.add(ts)
    return st


def _one(st: set[str], name: str) -> str | None:
    if len(st) > 1:
        raise DesignError(f"{name}: several error classes at once {sorted(st)}")
    return next(iter(st), None)


def is_similarity(m) -> bool:
    """L^T L = s^2 I exactly (the cases' transforms are exact: signed powers of two in a
    permutation, rotations by exact Pythagorean triples)."""
    lin = transformed.linear(m)
    g = [[sum(lin[k][i] * lin[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return all(g[i][j] == (g[0][0] if i == j else 0) for i in range(3) for j in range(3))


def point_value(shape: dict, m, p: Sequence[float]) -> tuple[mpmath.mpf | int, mpmath.mpf, bool]:
    """(w, its documented bound, exact) at the world point p. Under a similarity the
    object-space value times the sign of det (where the library sums) must equal the
    world value; under any other transform the library sums the world faces."""
    faces = faces_of(shape)
    world = vertices(shape, m)
    wp = qv(p)
    obj = object_point(m, p)
    objv = vertices(shape, None)
    w = generalized(world, faces, wp)
    similarity = m is None or is_similarity(m)
    if m is not None and similarity:
        sign = 1 if transformed.det3(transformed.linear(m)) > 0 else -1
        w_obj = sign * generalized(objv, faces, obj)
        if abs(w_obj - w) > mpmath.mpf(10) ** -40:
            raise DesignError(f"a similarity changed the winding number: {w}, {w_obj}")
    if oriented(shape) and not on_surface(world, faces, wp):
        k = signed_crossings(world, faces, wp)
        if abs(w - k) > mpmath.mpf(10) ** -40:
            raise AssertionError(f"solid angles {w} and signed crossings {k} disagree at {p}")
        return k, mpmath.mpf(0), True
    bound = (documented_bound(objv, faces, obj) if similarity
             else documented_bound(world, faces, wp)) + 2 * mp(U) * abs(w)
    return w, bound, False


def evaluate_winding(c: dict) -> dict:
    """op winding_number: status, and w at each point (the tolerance goes to c["tol"])."""
    shape, m, pts = c["shape"], c.get("transform"), c["points"]
    acc = c.get("accuracy", 0.0)
    st = _status(shape, m)
    if shape["type"] != "mesh":
        st.add("E_ARG")
    if not (acc >= 0):                      # negative or NaN
        st.add("E_ARG")
    if not all(math.isfinite(x) for pt in pts for x in pt):
        st.add("E_NONFINITE")
    status = _one(st, c["name"])
    if status:
        return {"status": status}
    values = [point_value(shape, m, pt) for pt in pts]
    tol = mpmath.mpf(0)
    for w, bound, exact in values:
        if exact:
            continue
        if acc > 0 and not oriented(shape):
            bound += mp(q(acc))
        tol = max(tol, bound / max(1, abs(w)))
    c["tol"] = {"winding": round_up(tol)}
    return {"status": "ok", "winding": [float(w) if e else to_double(zero_snapped(w)) for w, _, e in values]}


def zero_snapped(w: mpmath.mpf) -> mpmath.mpf:
    """w, or 0 when it is 0 to the working precision (a point in the plane of an open
    mesh's missing face, outside it: the solid angles cancel exactly, and 80-digit
    rounding leaves ~1e-83). No case has a nonzero |w| below 1e-60."""
    return mpmath.mpf(0) if abs(w) < mpmath.mpf(10) ** -(mpmath.mp.dps - 20) else w


def evaluate_contains(c: dict) -> dict:
    """op contains on a mesh with a rule (and maybe a transform)."""
    shape, m, p = c["shape"], c.get("transform"), c["point"]
    rule = shape.get("rule", "evenodd")
    if isinstance(rule, int) and 0 <= rule < len(RULES):
        raise DesignError("write a valid rule by its name")
    st = _status(shape, m)
    if not all(math.isfinite(x) for x in p):
        st.add("E_NONFINITE")
    if rule not in RULES:
        st.add("E_ARG")
    elif not st:
        if rule == "evenodd" and not mesh.is_closed(shape):
            st.add("E_ARG")
        if rule == "nonzero" and not oriented(shape):
            st.add("E_ARG")
    status = _one(st, c["name"])
    if status:
        return {"status": status}
    faces = faces_of(shape)
    world, wp = vertices(shape, m), qv(p)
    object_point(m, p)
    if rule == "winding" and not oriented(shape):
        w, bound, _ = point_value(shape, m, p)
        if abs(w - mpmath.mpf(1) / 2) <= 4 * bound:
            raise DesignError(f"{c['name']}: w = {w} is within its bound of 1/2")
        return {"status": "ok", "inside": int(w >= mpmath.mpf(1) / 2)}
    if on_surface(world, faces, wp):
        return {"status": "ok", "inside": 1}
    # A generic ray's crossings: their signed sum has the parity of their number.
    k = signed_crossings(world, faces, wp)
    if rule == "evenodd":
        return {"status": "ok", "inside": k % 2}
    return {"status": "ok", "inside": int(k != 0 if rule == "nonzero" else k >= 1)}


# ---------------------------------------------------------------- meshes
def combine(*parts: dict) -> dict:
    """Several meshes as one (vertex indices offset): one shape, several shells."""
    vs: list = []
    fs: list = []
    for m in parts:
        fs += [[i + len(vs) for i in f] for f in m["faces"]]
        vs += m["vertices"]
    return {"type": "mesh", "vertices": vs, "faces": fs}


def reversed_faces(m: dict) -> dict:
    return with_faces(m, [f[::-1] for f in m["faces"]])


def tetrahedron() -> dict:
    """The corner (0,0,0), (1,0,0), (0,1,0), (0,0,1), faces outward."""
    return mesh.mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
                     [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def ring(n: int, radius: float, z: float) -> list[tuple[float, float, float]]:
    """n points (cos, sin) * radius at height z, rounded to doubles."""
    out = []
    for k in range(n):
        t = 2 * math.pi * k / n
        out.append((radius * math.cos(t), radius * math.sin(t), z))
    return out


def cone(n: int = 8) -> dict:
    """A fan of n triangles from the apex (0, 0, 1) over a ring of radius 1 at z = 0, open at
    the base, faces outward."""
    vs = [(0.0, 0.0, 1.0)] + ring(n, 1.0, 0.0)
    return mesh.mesh(vs, [[0, 1 + k, 1 + (k + 1) % n] for k in range(n)])


def frustum_dome(n: int = 8) -> dict:
    """A frustum of quads from the ring of radius 1 at z = 0 to the ring of radius 1/2 at
    z = 3/4 (its xy exactly half of the lower ring's: every quad lies exactly in the plane
    through (0, 0, 3/2)), capped by a fan of triangles to the apex (0, 0, 1); open at the
    base, faces outward (mixed quads and triangles)."""
    low = ring(n, 1.0, 0.0)
    high = [(0.5 * x, 0.5 * y, 0.75) for x, y, _ in low]
    vs = low + high + [(0.0, 0.0, 1.0)]
    fs = [[k, (k + 1) % n, n + (k + 1) % n, n + k] for k in range(n)]
    fs += [[n + k, n + (k + 1) % n, 2 * n] for k in range(n)]
    return mesh.mesh(vs, fs)


def dome(rings: int = 8, segments: int = 16) -> dict:
    """A hemisphere of radius 1 over z >= 0 in triangles (rings of polar angles k/rings * 90
    degrees, coordinates rounded to doubles), open at the base, faces outward."""
    vs = [(0.0, 0.0, 1.0)]
    for k in range(1, rings + 1):
        phi = math.pi / 2 * k / rings
        s, c = math.sin(phi), math.cos(phi) if k < rings else 0.0
        vs += [(s * math.cos(2 * math.pi * j / segments), s * math.sin(2 * math.pi * j / segments), c)
               for j in range(segments)]
    fs = [[0, 1 + j, 1 + (j + 1) % segments] for j in range(segments)]
    for k in range(1, rings):
        a, b = 1 + (k - 1) * segments, 1 + k * segments
        for j in range(segments):
            j1 = (j + 1) % segments
            fs += [[a + j, b + j, b + j1], [a + j, b + j1, a + j1]]
    return mesh.mesh(vs, fs)


def soup_cube() -> dict:
    """The cube's 12 triangles, each with its own three vertices: no shared edge."""
    ct = cube_tris()
    vs = [ct["vertices"][i] for f in ct["faces"] for i in f]
    return {"type": "mesh", "vertices": vs, "faces": [[3 * k, 3 * k + 1, 3 * k + 2] for k in range(12)]}


def soup_crossing() -> dict:
    """Three triangles: one in z = 0, one standing through it, and a reversed copy of the first
    lifted by 1/2 (overlapping in projection, opposite orientation)."""
    return mesh.mesh([(0, 0, 0), (2, 0, 0), (0, 2, 0), (0.5, 0.25, -1), (0.5, 0.25, 1), (1.5, 1.25, 0),
                      (0, 0, 0.5), (0, 2, 0.5), (2, 0, 0.5)],
                     [[0, 1, 2], [3, 5, 4], [6, 7, 8]])


def world_points(m: Sequence[float], pts) -> list[list[float]]:
    """The world points M p of object points p (exact in doubles, checked)."""
    L, T = transformed.linear(m), transformed.translation(m)
    out = []
    for p in pts:
        w = [x + t for x, t in zip(transformed.mul(L, qv(p)), T)]
        if any(Fraction(float(x)) != x for x in w):
            raise DesignError("world point not exact in doubles")
        out.append([float(x) for x in w])
    return out


# ------------------------------------------------------------------ cases
ROT90 = transformed.affine([[0, -1, 0], [1, 0, 0], [0, 0, 1]], (0.5, -0.25, 2))
SCALE2 = transformed.affine([[2, 0, 0], [0, 2, 0], [0, 0, 2]], (1, -1, 0.5))
MIRROR = transformed.affine([[-1, 0, 0], [0, 1, 0], [0, 0, 1]], (2, 0, 0))
ROT_SCALE = transformed.affine([[0, 0, 0.5], [0.5, 0, 0], [0, 0.5, 0]], (-3, 0.25, 8))
STRETCH = transformed.affine([[4, 0, 0], [0, 1, 0], [0, 0, 1]])


def cases() -> list[dict]:
    cq, ct, oc, tet = cube_quads(), cube_tris(), mesh.octahedron(), tetrahedron()
    inward = reversed_faces(cq)
    overlap = combine(cube_quads((0, 0, 0), 2), cube_quads((1, 1, 1), 2))
    nested = combine(cube_quads((0, 0, 0), 3), cube_quads((1, 1, 1), 1))
    hollow = combine(cube_quads((0, 0, 0), 3), reversed_faces(cube_quads((1, 1, 1), 1)))
    open_q = with_faces(cq, CUBE_QUADS[:5])                    # the z = 1 face removed
    open_t = with_faces(ct, ct["faces"][:10])                  # its two triangles removed
    flipped = with_faces(cq, CUBE_QUADS[:4] + [CUBE_QUADS[4][::-1]] + CUBE_QUADS[5:])
    tri = mesh.mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 2]])
    lp = mesh.l_prism()
    open_l = with_faces(lp, [lp["faces"][0]] + lp["faces"][2:])   # the L's top removed
    far_open = with_faces(cube_quads((1e7, 0, 0), 2.0 ** -10), CUBE_QUADS[:5])
    far_closed = cube_quads((1e7, 0, 0), 2.0 ** -10)
    dm = dome()
    c: list[dict] = []

    def wn(name, flags, shape, points, **kw):
        c.append(case(name, ["winding-number"] + flags, op="winding_number", shape=shape,
                      points=[[float(x) for x in p] for p in points], **kw))

    def inside(name, flags, shape, rule, p, **kw):
        c.append(case(name, ["mesh-rule", f"rule-{rule}" if rule in RULES else "bad-input"] + flags,
                      op="contains", shape={**shape, "rule": rule}, point=[float(x) for x in p], **kw))

    # --- closed, consistently oriented: the exact integer off the surface (tol 0)
    wn("cube (quads): inside and outside", ["exact-integer", "polygon-faces"], cq,
       [(0.5, 0.5, 0.5), (0.25, 0.75, 0.125), (1.5, 0.5, 0.5), (-0.5, -0.5, -0.5), (0.5, 2, 0.5)])
    wn("cube (triangles): +x rays through a face diagonal, along an edge and a face", ["exact-integer",
                                                                                    "crossing-ray-edge"], ct,
       [(0.5, 0.5, 0.5), (0.25, 0.25, 0.75), (-1, 0, 0.5), (-1, 0, 0), (-1, 1, 1), (-1, 0.5, 0.5)])
    wn("octahedron: +x rays through vertices and edges", ["exact-integer", "crossing-ray-edge"], oc,
       [(-0.5, 0, 0), (0.5, 0.25, 0), (-1.5, 0, 0), (-2, 0.5, 0.5), (0, 0, 0)])
    wn("tetrahedron: inside, outside, a ray grazing an edge", ["exact-integer", "crossing-ray-edge"], tet,
       [(0.125, 0.25, 0.125), (1, 1, 1), (-1, 0.5, 0.5), (-1, 0.25, 0.25), (0.25, 0.25, -1)])
    wn("two overlapping cubes in one mesh: 2 in the overlap", ["exact-integer", "self-intersecting-mesh",
                                                             "polygon-faces", "crossing-ray-edge"], overlap,
       [(1.5, 1.5, 1.5), (0.5, 0.5, 0.5), (2.5, 2.5, 2.5), (0.5, 2.5, 0.5), (2.5, 0.5, 0.5), (0.5, 1, 1.5)])
    wn("nested cubes, same orientation: 2 in the inner one", ["exact-integer", "nested", "polygon-faces"], nested,
       [(1.5, 1.5, 1.5), (0.5, 0.5, 0.5), (3.5, 1.5, 1.5), (0.5, 1.5, 1.5)])
    wn("nested cubes, inner one reversed (a hollow shell): 0 inside it", ["exact-integer", "nested", "inward",
                                                                         "polygon-faces"], hollow,
       [(1.5, 1.5, 1.5), (0.5, 0.5, 0.5), (3.5, 1.5, 1.5), (0.5, 1.5, 1.5)])
    wn("cube with inward faces: -1 inside", ["exact-integer", "inward", "polygon-faces"], inward,
       [(0.5, 0.5, 0.5), (1.5, 0.5, 0.5)])
    e, h = 2.0 ** -10, 2.0 ** -11
    wn("far: cube of side 2^-10 at x = 1e7, points 1 ulp inside and outside its faces",
       ["exact-integer", "far", "polygon-faces"], far_closed,
       [(1e7 + h, h, h), (nudge(1e7 + e, -1), h, h), (nudge(1e7 + e, 1), h, h), (nudge(1e7, -1), h, h),
        (1e7 + h, nudge(e, -1), h), (1e7 + h, h, nudge(0.0, -1))])
    wn("cube: far points", ["exact-integer", "far", "polygon-faces"], cq,
       [(1e6, -2e6, 3e6), (-1e300, 0.5, 0.5), (0.5, 0.5, 1e300)])
    wn("cube: accuracy 0.25 still gives the exact integer", ["exact-integer", "far-field", "polygon-faces"], cq,
       [(0.5, 0.5, 0.5), (3, 4, 5), (0.25, 0.5, 0.75)], accuracy=0.25)
    wn("empty mesh: 0 everywhere", ["exact-integer", "empty-mesh"], mesh.mesh(CUBE_V, []),
       [(0.5, 0.5, 0.5), (0, 0, 0)])

    # --- the principal value on a closed mesh's surface (direct sum, documented bound)
    wn("cube (quads): on a face (1/2), an edge (1/4), a vertex (1/8)", ["principal-value", "boundary", "on-edge",
                                                                     "on-vertex", "polygon-faces"], cq,
       [(1, 0.25, 0.5), (0.5, 0.5, 0), (1, 0.25, 1), (0, 0.5, 0), (1, 1, 0), (0, 0, 0)])
    wn("cube (triangles): on a face diagonal and inside a face triangle", ["principal-value", "boundary", "on-edge"],
       ct, [(0.5, 0.5, 0), (0.25, 0.75, 1), (1, 0.5, 0.5)])
    wn("tetrahedron: on its faces, an edge of dihedral angle arccos(1/sqrt 3), vertices",
       ["principal-value", "boundary", "on-edge", "on-vertex"], tet,
       [(0.25, 0.25, 0), (0.25, 0.25, 0.5), (0.5, 0.5, 0), (0, 0.5, 0), (0, 0, 0), (1, 0, 0)])
    wn("two overlapping cubes: on one's surface inside the other (3/2, 5/4, 9/8), on both (1)",
       ["principal-value", "boundary", "self-intersecting-mesh", "on-edge", "on-vertex", "polygon-faces"], overlap,
       [(2, 1.5, 1.5), (2, 2, 1.5), (1, 1, 1), (2, 1, 1.5)])
    wn("hollow shell: on the reversed inner cube (1/2)", ["principal-value", "boundary", "nested", "inward",
                                                          "polygon-faces"], hollow,
       [(1, 1.5, 1.5), (2, 2, 2)])

    # --- open meshes: the generalized winding number (direct sum, documented bound)
    wn("open cube (quads, top removed): inside (5/6), the hole (1/2), above, below", ["open-surface",
                                                                                     "polygon-faces"], open_q,
       [(0.5, 0.5, 0.5), (0.5, 0.5, 1), (0.25, 0.75, 1), (1.5, 0.5, 1), (0.5, 0.5, 1.5), (0.5, 0.5, -0.5),
        (0.5, 0.5, 0.9)])
    wn("open cube (triangles, top removed)", ["open-surface"], open_t,
       [(0.5, 0.5, 0.5), (0.5, 0.5, 1), (0.5, 0.5, 1.25), (0.25, 0.5, 0.75)])
    wn("open cube: on a face, on the rim, at rim and bottom vertices", ["open-surface", "boundary", "on-edge",
                                                                         "on-vertex", "polygon-faces"], open_q,
       [(0.5, 0.5, 0), (0, 0.5, 0.5), (0.5, 0, 1), (0, 0, 1), (0, 0, 0), (1, 0.5, 0)])
    wn("a single triangle: above, below, in its plane, on it, its edges and vertices", ["open-surface",
                                                                                        "boundary", "on-edge",
                                                                                        "on-vertex"], tri,
       [(0.25, 0.25, 1), (0.25, 0.25, -1), (0.25, 0.25, 2.0 ** -30), (2, 2, 0), (0.25, 0.25, 0), (0.5, 0, 0),
        (0.5, 0.5, 0), (0, 0, 0)])
    wn("a single triangle: 1e-9 above an edge (the bound grows as 1/distance)", ["open-surface", "near-edge"],
       tri, [(0.5, 0, 1e-9), (0.5, -1e-9, 0)])
    wn("cone: a fan of 8 triangles open at its base", ["open-surface", "fan"], cone(),
       [(0, 0, 0.25), (0.25, 0.125, 0.5), (0, 0, 0), (0.25, 0.5, 0), (0, 0, -0.5), (0, 0, 2), (2, 0, 0)])
    wn("cone: on its apex and on a fan edge", ["open-surface", "fan", "boundary", "on-vertex", "on-edge"], cone(),
       [(0, 0, 1), (0.5, 0, 0.5)])
    fd = frustum_dome()
    wn("dome of quads and triangles, open at its base", ["open-surface", "fan", "mixed-faces"], fd,
       [(0, 0, 0.3), (0, 0, 0), (0.125, 0.25, 0), (0, 0, -1), (0, 0, 2), (0.75, 0, 0.375), (0, 0, 1)])
    wn("triangle soup: the cube's triangles, no shared vertex", ["soup"], soup_cube(),
       [(0.5, 0.5, 0.5), (0.25, 0.5, 0.75), (1.5, 0.5, 0.5), (0.5, 0.5, -2), (1, 0.25, 0.5)])
    wn("triangle soup: the same, 8 points (a batch sums clusters through their boundaries)", ["soup"],
       soup_cube(), [(0.5, 0.5, 0.5), (0.25, 0.5, 0.75), (1.5, 0.5, 0.5), (0.5, 0.5, -2), (0.125, 0.875, 0.5),
                     (3, 2, 1), (-1, 0.5, 0.25), (0.5, 0.25, 0.125)])
    wn("triangle soup: crossing and overlapping triangles", ["soup"], soup_crossing(),
       [(0.25, 0.25, 0.25), (0.25, 0.25, 0.75), (0.25, 0.25, -0.25), (1, 0.5, 0.5), (0.75, 0.625, 0)])
    wn("L prism without its top: concave bottom whose fan folds over the notch", ["open-surface", "concave",
                                                                                    "polygon-faces"],
       open_l, [(0.5, 1.5, 0.5), (1.5, 1.5, 0.5), (1.5, 1.1875, 2.0 ** -20), (1.5, 1.1875, 0),
                (1.5, 1.125, -0.25)])
    wn("L prism without its top: 2^-20 above a fan diagonal of the concave bottom", ["open-surface", "concave",
                                                                                      "near-edge", "polygon-faces"],
       open_l, [(1.5, 1.25, 2.0 ** -20), (1.5, 1.25, -(2.0 ** -20)), (1.5, 1.25, 0)])
    wn("book: three faces on one edge (non-manifold)", ["nonmanifold-winding"], mesh.book(),
       [(0.5, 0.5, 0.5), (-0.5, 0, 0.5), (0, 0, 0.5), (0, -1, 0.25)])
    wn("cube with one face flipped (closed, not oriented): 2/3 inside", ["flipped-face", "polygon-faces"],
       flipped, [(0.5, 0.5, 0.5), (0.5, 0.5, 0.05), (0.5, 0.5, 1.5), (0.5, 0.5, -0.5)])
    wn("open cube: far points", ["open-surface", "far", "polygon-faces"], open_q,
       [(1e3, 2e3, -3e3), (0.5, 0.5, 1e6), (0.5, 0.5, -1e6), (1e6, -2e6, 3e6)])
    wn("far: open cube of side 2^-10 at x = 1e7, points near it", ["open-surface", "far", "polygon-faces"],
       far_open, [(1e7 + h, h, h), (1e7 + h, h, e), (1e7 + h, h, 2 * e), (1e7 - e, h, h), (1e7 + h, h, 1.0)])

    # --- transforms (exact in doubles); a mirror negates w
    obj = [(0.5, 0.5, 0.5), (0.5, 0.5, 1.5), (0.5, 0.5, 0), (0.25, 0.75, 1)]
    for tname, m, more in (("rotated 90 degrees about z and moved", ROT90, ["rotation", "translation"]),
                           ("scaled 2 and moved", SCALE2, ["scaling", "translation"]),
                           ("mirrored in x: w negated", MIRROR, ["mirror-winding", "translation"])):
        wn(f"open cube {tname}", ["open-surface", "transformed", "point-transform", "polygon-faces"] + more,
           open_q, world_points(m, obj), transform=m)
    wn("closed cube mirrored in x: -1 inside (exact)", ["exact-integer", "transformed", "point-transform",
                                                         "mirror-winding", "polygon-faces"], cq,
       world_points(MIRROR, [(0.5, 0.5, 0.5), (1.5, 0.5, 0.5)]), transform=MIRROR)
    wn("triangle cube rotated, scaled 1/2 and moved: exact integers", ["exact-integer", "transformed",
                                                                       "point-transform", "rotation", "scaling",
                                                                       "translation"], ct,
       world_points(ROT_SCALE, [(0.5, 0.5, 0.5), (0.25, 0.5, 0.75), (1.5, 0.5, 0.5), (-1, 0.5, 0.5)]),
       transform=ROT_SCALE)
    wn("open cube stretched 4x along x: world solid angles (not a similarity: summed over the world faces)",
       ["open-surface", "transformed", "point-transform", "scaling", "polygon-faces"],
       open_q, world_points(STRETCH, [(0.5, 0.5, 0.5), (0.5, 0.5, 1.5)]), transform=STRETCH)

    # --- accuracy > 0: the far field, within accuracy of the direct sum
    far_pts = [(0, 0, 5), (3, 4, 0.5), (-6, 1, 2), (10, 10, 10), (0, 0, -3), (0, 0, 0.5), (0.25, 0.125, 0.25),
               (2, -2, -1)]
    wn("dome of 240 triangles, accuracy 0 (a batch sums clusters through their boundaries)", ["open-surface"],
       dm, far_pts)
    for acc in (1e-2, 1e-6):
        wn(f"dome of 240 triangles, accuracy {acc:g}", ["open-surface", "far-field"], dm, far_pts, accuracy=acc)
    wn("open cube, accuracy 0.1, 3 points", ["open-surface", "far-field", "polygon-faces"], open_q,
       [(0.5, 0.5, 0.5), (5, 5, 5), (0.5, 0.5, 3)], accuracy=0.1)

    # --- bad input
    wn("not a mesh (a sphere)", ["bad-input"], {"type": "sphere", "center": [0.0, 0.0, 0.0], "radius": 1.0},
       [(0, 0, 0)])
    wn("accuracy negative", ["bad-input"], open_q, [(0.5, 0.5, 0.5)], accuracy=-1.0)
    wn("accuracy NaN", ["bad-input"], open_q, [(0.5, 0.5, 0.5)], accuracy=math.nan)
    wn("a NaN point (C: status ok and w NaN there; Python raises)", ["bad-input", "nonfinite"], open_q,
       [(0.5, 0.5, 0.5), (math.nan, 0.5, 0.5), (0.5, 0.5, 1.5)])
    wn("an infinite point of a closed mesh", ["bad-input", "nonfinite", "polygon-faces"], cq,
       [(math.inf, 0.5, 0.5)])
    wn("mesh with an index out of range", ["bad-input"], mesh.mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 3]]),
       [(0, 0, 1)])
    wn("mesh with a NaN vertex", ["bad-input", "nonfinite"],
       mesh.mesh([(0, 0, 0), (1, math.nan, 0), (0, 1, 0)], [[0, 1, 2]]), [(0, 0, 1)])
    wn("singular transform", ["bad-input", "transformed"], open_q, [(0.5, 0.5, 0.5)],
       transform=transformed.affine([[1, 0, 0], [0, 1, 0], [0, 0, 0]]))

    # --- containment rules
    for rule in ("nonzero", "winding"):
        inside(f"cube: centre, rule {rule}", ["polygon-faces"], cq, rule, (0.5, 0.5, 0.5))
        inside(f"cube: on a vertex, rule {rule}", ["boundary", "on-vertex", "polygon-faces"], cq, rule, (1, 1, 0))
        inside(f"cube: outside, +x ray along an edge, rule {rule}", ["crossing-ray-edge", "polygon-faces"], cq, rule,
               (-1, 1, 1))
    for rule in RULES:
        inside(f"overlapping cubes: in the overlap (w = 2), rule {rule}", ["self-intersecting-mesh",
                                                                           "polygon-faces"], overlap, rule,
               (1.5, 1.5, 1.5))
        inside(f"nested cubes: in the inner one (w = 2), rule {rule}", ["nested", "polygon-faces"], nested, rule,
               (1.5, 1.5, 1.5))
        inside(f"hollow shell: in the reversed inner cube (w = 0), rule {rule}", ["nested", "inward",
                                                                                  "polygon-faces"], hollow, rule,
               (1.5, 1.5, 1.5))
        inside(f"cube with inward faces: centre (w = -1), rule {rule}", ["inward", "polygon-faces"], inward, rule,
               (0.5, 0.5, 0.5))
        inside(f"cube with a flipped face: centre (w = 2/3), rule {rule}", ["flipped-face", "polygon-faces"],
               flipped, rule, (0.5, 0.5, 0.5))
        inside(f"open cube: centre (w = 5/6), rule {rule}", ["open-surface", "polygon-faces"], open_q, rule,
               (0.5, 0.5, 0.5))
        inside(f"closed cube mirrored in x: centre (w = -1), rule {rule}",
               ["transformed", "point-transform", "mirror-winding", "polygon-faces"], cq, rule,
               world_points(MIRROR, [(0.5, 0.5, 0.5)])[0], transform=MIRROR)
    inside("overlapping cubes: on one's face inside the other, rule evenodd", ["self-intersecting-mesh",
                                                                               "boundary", "polygon-faces"],
           overlap, "evenodd", (2, 1.5, 1.5))
    inside("overlapping cubes: in one only, rule nonzero", ["self-intersecting-mesh", "polygon-faces"], overlap,
           "nonzero", (0.5, 0.5, 0.5))
    inside("hollow shell: between the shells, rule winding", ["nested", "inward", "polygon-faces"], hollow,
           "winding", (0.5, 0.5, 0.5))
    inside("hollow shell: on the inner cube, rule winding (closed set)", ["nested", "inward", "boundary",
                                                                          "polygon-faces"], hollow, "winding",
           (1, 1.5, 1.5))
    inside("cube with inward faces: on a face, rule winding (closed set)", ["inward", "boundary",
                                                                             "polygon-faces"], inward, "winding",
           (1, 0.5, 0.5))
    inside("cube with a flipped face: near the flipped face, rule winding", ["flipped-face", "polygon-faces"],
           flipped, "winding", (0.5, 0.5, 0.05))
    for name, p in (("below the hole", (0.5, 0.5, 0.875)), ("above the hole", (0.5, 0.5, 1.125)),
                    ("on the bottom face", (0.5, 0.5, 0)), ("outside", (1.5, 0.5, 0.5))):
        inside(f"open cube: {name}, rule winding", ["open-surface", "polygon-faces"], open_q, "winding", p)
    inside("a single triangle: just above it, rule winding", ["open-surface"], tri, "winding", (0.25, 0.25, 0.125))
    inside("triangle soup cube: centre, rule winding", ["soup"], soup_cube(), "winding", (0.5, 0.5, 0.5))
    inside("triangle soup cube: outside, rule winding", ["soup"], soup_cube(), "winding", (0.5, 1.5, 0.5))
    inside("triangle soup cube: rule nonzero", ["soup", "bad-input"], soup_cube(), "nonzero", (0.5, 0.5, 0.5))
    inside("cone: inside, rule winding", ["open-surface", "fan"], cone(), "winding", (0, 0, 0.25))
    inside("L prism without its top: in the arm, rule winding", ["open-surface", "concave", "polygon-faces"], open_l,
           "winding", (0.5, 1.5, 0.5))
    inside("book: between two pages, rule winding", ["nonmanifold-winding"], mesh.book(), "winding",
           (-0.25, 0.125, 0.5))
    inside("book: rule evenodd", ["nonmanifold-winding", "bad-input"], mesh.book(), "evenodd", (0, 0, 0.5))
    inside("open cube mirrored in x: centre (w = -5/6), rule winding", ["open-surface", "transformed",
                                                                        "point-transform", "mirror-winding",
                                                                        "polygon-faces"], open_q, "winding",
           world_points(MIRROR, [(0.5, 0.5, 0.5)])[0], transform=MIRROR)
    inside("open cube scaled 2 and moved: centre, rule winding", ["open-surface", "transformed", "point-transform",
                                                                 "scaling", "polygon-faces"], open_q, "winding",
           world_points(SCALE2, [(0.5, 0.5, 0.5)])[0], transform=SCALE2)
    inside("unknown rule 3", ["polygon-faces"], cq, 3, (0.5, 0.5, 0.5))
    inside("NaN point, rule winding", ["open-surface", "nonfinite", "bad-input"], open_q, "winding",
           (math.nan, 0.5, 0.5))
    c.append(case("a polygon with rule winding (meshes only)", ["bad-input", "mesh-rule"],
                  shape={"type": "polygon", "vertices": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                         "rule": "winding"}, ray={"org": [0.25, 0.25, -1.0], "dir": [0.0, 0.0, 1.0],
                                                   "tmin": 0.0, "tmax": math.inf}))
    return c


def check_case(c: dict) -> None:
    """The flags say which kind of expectation a winding_number case has."""
    if c.get("op") != "winding_number" or c["expect"]["status"] != "ok":
        return
    tol = c["tol"]["winding"]
    if ("exact-integer" in c["flags"]) != (tol == 0):
        raise DesignError(f"flag exact-integer but tol.winding = {tol}")
    if "exact-integer" in c["flags"] and not all(float(w).is_integer() for w in c["expect"]["winding"]):
        raise DesignError("exact-integer case with a non-integer w")

