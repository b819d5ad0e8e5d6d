# SPDX-License-Identifier: Apache-2.0
"""Cross-checks of the reference against itself (run by ``generate.py --selftest``).

The corpus must not depend on one derivation only, so each solver is
compared with a second, differently derived computation on random generic
inputs, and the symbolic perturbation is compared with an explicit tiny
numeric perturbation:

1. triangle (sheared-frame winding + 2D barycentrics) vs a direct 3x3
   Cramer solve of o + t v = a + u (b - a) + w (c - a) (seed: Bernstein);
2. triangle vs the same three vertices as a polygon (Newell plane);
3. polygon inside test vs a crossing-number test on the hit point projected
   to the plane of the two smallest normal coordinates (seed: CSE 681);
4. box vs the convex solver over its six planes; sphere vs ellipsoid with
   equal radii vs quadric vs a uniformly scaled transformed unit sphere;
5. every curved-surface hit lies on its surface (residual < 1e-60);
6. the symbolic rule (-e^2, -e) vs the winding number at the explicitly
   perturbed rational point with e = 2^-40, on random small-integer polygons
   and query points on vertices and edges;
7. mesh containment (generic-direction parity) vs the cells of grid solids
   (cube, L prism, torus, genus 2) on quarter-lattice points, many on faces,
   edges and vertices; and exactly-once of the per-face ray reference: rays
   from lattice points aimed at mesh vertices and edge midpoints hit a
   closed mesh an odd number of times exactly when they start inside;
8. op spawn: the hits of every spawn case of the corpus (from the exact hit
   point, the surface left dropped at t = 0) equal those of an ordinary ray
   from the hit point moved 2^-40 along dir, over [0, inf);
9. winding numbers: a triangle's solid angle by Van Oosterom & Strackee vs
   Girard's spherical excess (the three dihedral angles at the point) on
   random triangles and points; and on the grid solids, at points k/4 + 1/8
   (off the surface), the solid-angle sum and the signed crossing count both
   equal the cells' indicator (and its negation with every face reversed).
"""
from __future__ import annotations

import random
from fractions import Fraction

import mpmath

import box
import convex
import cylinder
import ellipsoid
import mesh
import polygon
import quadric
import sphere
import transformed
import triangle
from exact import DesignError, cross, dot, mp, norm2, point_on_ray, qv, sub
from model import Ctx, XRay
from sheared import winding_at, winding_perturbed

CTX = Ctx(Fraction(1, 10**12))


def _dy(rng: random.Random, lo: int = -8, hi: int = 8) -> float:
    """A random dyadic number k/8."""
    return rng.randint(lo * 8, hi * 8) / 8


def _ray(rng: random.Random) -> XRay:
    o = [_dy(rng) for _ in range(3)]
    d = [_dy(rng, -2, 2) or 0.5 for _ in range(3)]
    return XRay(qv(o), qv(d), Fraction(-100), Fraction(100))


def _close(a, b, what: str) -> None:
    if abs(mp(a) - mp(b)) > mpmath.mpf(10) ** -60 * max(1, abs(mp(a))):
        raise AssertionError(f"selftest {what}: {a} != {b}")


def _cramer_triangle(a, b, c, r: XRay):
    """Solve o + t v = a + u (b - a) + w (c - a) by Cramer's rule (seed: Bernstein)."""
    e1, e2 = sub(b, a), sub(c, a)
    cols = [e1, e2, tuple(-x for x in r.dir)]
    rhs = sub(r.org, a)

    def det(m0, m1, m2):
        return dot(m0, cross(m1, m2))
    D = det(*cols)
    if D == 0:
        return None
    u = det(rhs, cols[1], cols[2]) / D
    w = det(cols[0], rhs, cols[2]) / D
    t = det(cols[0], cols[1], rhs) / D
    return t, u, w


def check_triangles(rng: random.Random, n: int = 300) -> int:
    done = 0
    for _ in range(n):
        a, b, c = ([_dy(rng) for _ in range(3)] for _ in range(3))
        r = _ray(rng)
        shape = {"type": "triangle", "a": a, "b": b, "c": c}
        try:
            hits = triangle.solve(shape, r, CTX)
        except DesignError:
            continue
        sol = _cramer_triangle(qv(a), qv(b), qv(c), r)
        if sol is None:
            continue
        t, u, w = sol
        if 0 in (u, w, 1 - u - w):
            continue                     # on an edge: decided by the perturbation, not here
        inside = u > 0 and w > 0 and u + w < 1
        if inside != bool(hits):
            raise AssertionError(f"selftest triangle inside mismatch {shape} {r}")
        if hits:
            _close(hits[0].t, t, "triangle t")
            _close(hits[0].uv[0], u, "triangle u")
            _close(hits[0].uv[1], w, "triangle v")
            ph = polygon.solve({"type": "polygon", "vertices": [a, b, c], "rule": "nonzero"}, r, CTX)
            assert len(ph) == 1 and ph[0].kind == hits[0].kind
            _close(ph[0].t, t, "triangle as polygon t")
            for x, y in zip(ph[0].normal, hits[0].normal):
                _close(x, y, "triangle as polygon normal")
        done += 1
    return done


def _crossing_number_3d(vs, p, n) -> int:
    """Crossing number of p in the polygon projected along the largest |n| axis."""
    k = max(range(3), key=lambda i: abs(n[i]))
    i, j = [x for x in range(3) if x != k]
    pts = [(v[i] - p[i], v[j] - p[j]) for v in vs]
    cnt = 0
    for s in range(len(pts)):
        (x1, y1), (x2, y2) = pts[s], pts[(s + 1) % len(pts)]
        if (y1 > 0) != (y2 > 0):
            x = x1 + (0 - y1) * (x2 - x1) / (y2 - y1)
            if x > 0:
                cnt += 1
    return cnt


def check_polygons(rng: random.Random, n: int = 200) -> int:
    done = 0
    for _ in range(n):
        # a random star-shaped or self-intersecting polygon in a random plane
        m = rng.randint(3, 8)
        pts2 = [(Fraction(_dy(rng)), Fraction(_dy(rng))) for _ in range(m)]
        u, w = [_dy(rng) for _ in range(3)], [_dy(rng) for _ in range(3)]
        base = [_dy(rng) for _ in range(3)]
        vs = [[float(Fraction(base[k]) + x * Fraction(u[k]) + y * Fraction(w[k])) for k in range(3)]
              for x, y in pts2]
        if any(Fraction(vs[i][k]) != Fraction(base[k]) + pts2[i][0] * Fraction(u[k]) + pts2[i][1] * Fraction(w[k])
               for i in range(m) for k in range(3)):
            continue
        r = _ray(rng)
        shape = {"type": "polygon", "vertices": vs, "rule": "evenodd"}
        try:
            hits = polygon.solve(shape, r, CTX)
        except DesignError:
            continue
        nrm, cen = polygon.newell([qv(v) for v in vs])
        nv = dot(nrm, r.dir)
        if nv == 0 or norm2(nrm) == 0:
            continue
        t = dot(nrm, sub(cen, r.org)) / nv
        p = point_on_ray(r.org, r.dir, t)
        q3 = [qv(v) for v in vs]
        # skip points on an edge's line in the projection (ties are the perturbation's job)
        k = max(range(3), key=lambda i: abs(nrm[i]))
        i, j = [x for x in range(3) if x != k]
        if any(v[j] == p[j] for v in q3):
            continue
        inside = _crossing_number_3d(q3, p, nrm) % 2 == 1
        if inside != bool(hits):          # revision 2: no eps for polygons, nv != 0 is enough
            raise AssertionError(f"selftest polygon inside mismatch {shape} {r}")
        done += 1
    return done


def check_solids(rng: random.Random, n: int = 200) -> int:
    done = 0
    for _ in range(n):
        r = _ray(rng)
        lo = [_dy(rng, -4, 0) for _ in range(3)]
        hi = [x + rng.randint(1, 24) / 4 for x in lo]
        try:
            hb = box.solve({"type": "box", "lo": lo, "hi": hi}, r, CTX)
            planes = [list(n_) + [d] for n_, d in box.faces(qv(lo), qv(hi))]
            hc = convex.solve({"type": "convex", "planes": [[float(x) for x in p] for p in planes]}, r, CTX)
        except DesignError:
            continue
        assert [(h.t, h.kind, h.prim) for h in hb] == [(h.t, h.kind, h.prim) for h in hc], (lo, hi, r)

        c, rad = [_dy(rng, -2, 2) for _ in range(3)], rng.randint(1, 16) / 4
        try:
            hs = sphere.solve({"type": "sphere", "center": c, "radius": rad}, r, CTX)
            he = ellipsoid.solve({"type": "ellipsoid", "center": c, "radii": [rad] * 3}, r, CTX)
            k = [1, 1, 1, 0, 0, 0, -2 * c[0], -2 * c[1], -2 * c[2], sum(x * x for x in c) - rad * rad]
            hq = quadric.solve({"type": "quadric", "coeffs": [float(x) for x in k]}, r, CTX)
            m = transformed.affine([[rad, 0, 0], [0, rad, 0], [0, 0, rad]], c)
            ht = transformed.solve(m, sphere.solve, {"type": "sphere", "center": [0, 0, 0], "radius": 1.0}, r, CTX)
        except DesignError:
            continue
        for other in (he, hq, ht):
            assert len(other) == len(hs) and all(a.kind == b.kind for a, b in zip(hs, other)), (c, rad, r)
            for a, b in zip(hs, other):
                _close(a.t, b.t, "sphere family t")
                for x, y in zip(a.normal, b.normal):
                    _close(x, y, "sphere family normal")
        for h in hs:
            pt = point_on_ray(r.org, r.dir, h.t)
            _close(norm2(sub(pt, qv(c))), Fraction(rad) ** 2, "sphere residual")

        p0 = [_dy(rng, -2, 2) for _ in range(3)]
        p1 = [x + _dy(rng, -2, 2) for x in p0]
        if p0 == p1:
            continue
        shape = {"type": "cylinder", "p0": p0, "p1": p1, "radius": rad, "capped": True}
        try:
            hcyl = cylinder.solve_finite(shape, r, CTX)
        except DesignError:
            continue
        a = sub(qv(p1), qv(p0))
        for h in hcyl:
            pt = point_on_ray(r.org, r.dir, h.t)
            rel = sub(pt, qv(p0))
            s = dot(rel, a) / norm2(a)
            d2 = norm2(tuple(x - s * y for x, y in zip(rel, a)))
            if h.prim == 0:
                _close(d2, Fraction(rad) ** 2, "cylinder side residual")
            else:
                _close(s, 0 if h.prim == 1 else 1, "cylinder cap residual")
                assert mp(d2) <= mp(Fraction(rad) ** 2) * (1 + mpmath.mpf(10) ** -50)
        done += 1
    return done


def check_perturbation(rng: random.Random, n: int = 2000) -> int:
    e = Fraction(1, 2**40)
    done = 0
    for _ in range(n):
        m = rng.randint(3, 7)
        poly = [(Fraction(rng.randint(-4, 4)), Fraction(rng.randint(-4, 4))) for _ in range(m)]
        # query on a vertex, on an edge midpoint, or on a random lattice point
        choice = rng.randint(0, 2)
        if choice == 0:
            p = poly[rng.randrange(m)]
        elif choice == 1:
            i = rng.randrange(m)
            a, b = poly[i], poly[(i + 1) % m]
            p = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        else:
            p = (Fraction(rng.randint(-4, 4)), Fraction(rng.randint(-4, 4)))
        symbolic = winding_at(poly, p)
        moved = (p[0] - e * e, p[1] - e)
        rel = [(v[0] - moved[0], v[1] - moved[1]) for v in poly]
        # the moved point is generic: a plain crossing count (no ties possible) must agree
        assert all(v[1] != 0 for v in rel)
        numeric, _ = winding_perturbed(rel)
        if symbolic != numeric:
            raise AssertionError(f"selftest perturbation: {poly} at {p}: {symbolic} != {numeric}")
        done += 1
    return done


def check_meshes(rng: random.Random, n: int = 150) -> int:
    solids = [([(0, 0)], 1, 1, []), ([(0, 0), (1, 0), (0, 1)], 2, 2, None),
              (None, 3, 3, [(1, 1)]), (None, 5, 3, [(1, 1), (3, 1)])]
    done = 0
    for cells, w, h, holes in solids:
        if cells is None:
            cells = [(x, y) for y in range(h) for x in range(w) if (x, y) not in holes]
        shape = mesh.grid_solid(w, h, [(x, y) for y in range(h) for x in range(w) if (x, y) not in cells])
        verts = [qv(v) for v in shape["vertices"]]
        for _ in range(n):
            p = tuple(Fraction(rng.randint(-2, 4 * w + 2), 4) for _ in range(3))
            cell_in = 0 <= p[2] <= 1 and any(x <= p[0] <= x + 1 and y <= p[1] <= y + 1 for x, y in cells)
            if mesh.contains(shape, p) != cell_in:
                raise AssertionError(f"selftest mesh contains: {p} in cells {cells}")
            f = shape["faces"][rng.randrange(len(shape["faces"]))]
            k = rng.randrange(len(f))
            a, b = verts[f[k]], verts[f[(k + 1) % len(f)]]
            target = a if rng.random() < 0.5 else tuple((x + y) / 2 for x, y in zip(a, b))
            d = sub(target, p)
            if all(x == 0 for x in d):
                continue
            r = XRay(p, d, Fraction(0), float("inf"))
            try:
                hits = mesh.solve(shape, r, Ctx(Fraction(0)))
            except DesignError:
                continue       # the sheared projection of this ray is not exact in doubles
            if mesh.on_surface(shape, p):
                continue       # origin on the surface: parity says nothing
            hits = [h for h in hits if h.t > 0]       # solve() reports the whole line
            if len(hits) % 2 != int(mesh.contains(shape, p)):
                raise AssertionError(f"selftest mesh exactly-once: ray {p} -> {target}: {len(hits)} hits")
            done += 1
    return done


def check_spawn() -> int:
    """Spawn expectations vs the ray from the hit point moved 2^-40 along dir."""
    import reference
    import spawn
    from exact import q
    from model import INF, finish
    done = 0
    for c in spawn.cases():
        want = reference.evaluate(dict(c))
        if want["status"] != "ok":
            continue
        r = XRay.from_json(c["ray"])
        ctx = Ctx(q(1e-12))
        hits, ctx1 = reference._solve(c["shape"], c.get("transform"), r, ctx)
        first = finish(hits, r, ctx1, reference.culls_back(c["shape"]), False)[0]
        d = qv(c["dir"])
        moved = tuple(p + Fraction(1, 2**40) * x for p, x in zip(point_on_ray(r.org, r.dir, first.t), d))
        sec = XRay(moved, d, Fraction(0), INF)
        got, _ = reference._solve(c["shape"], c.get("transform"), sec, ctx)
        got = sorted((h.kind, h.prim) for h in got if h.t > 0)
        if got != sorted((h["kind"], h["prim"]) for h in want["hits"]):
            raise AssertionError(f"selftest spawn: {c['name']}: {got} != {want['hits']}")
        done += 1
    return done


def _girard(A, B, C, p) -> mpmath.mpf:
    """Solid angle of triangle A, B, C at p as the spherical excess alpha + beta + gamma - pi
    of its projection on the unit sphere (sign: det[a b c])."""
    a, b, c = (tuple(mp(x) for x in sub(v, p)) for v in (A, B, C))

    def angle(u, v, w):                 # at u, between the great circles to v and to w
        n1, n2 = cross(u, v), cross(u, w)
        return mpmath.acos(dot(n1, n2) / mpmath.sqrt(dot(n1, n1) * dot(n2, n2)))
    det = dot(sub(A, p), cross(sub(B, p), sub(C, p)))
    excess = angle(a, b, c) + angle(b, c, a) + angle(c, a, b) - mpmath.pi
    return excess if det > 0 else -excess


def check_winding(rng: random.Random, n: int = 150) -> int:
    import winding
    done = 0
    for _ in range(n):
        A, B, C, p = (qv([_dy(rng, -4, 4) for _ in range(3)]) for _ in range(4))
        if norm2(cross(sub(B, A), sub(C, A))) == 0 or dot(sub(A, p), cross(sub(B, p), sub(C, p))) == 0:
            continue                # degenerate, or p in the plane (0 by both)
        vos, gir = winding.triangle_angle(A, B, C, p), _girard(A, B, C, p)
        if abs(vos - gir) > mpmath.mpf(10) ** -50:
            raise AssertionError(f"selftest solid angle: {A} {B} {C} at {p}: {vos} != {gir}")
        done += 1
    for w, h, holes in ((1, 1, []), (3, 3, [(1, 1)]), (5, 3, [(1, 1), (3, 1)])):
        shape = mesh.grid_solid(w, h, holes)
        cells = [(x, y) for y in range(h) for x in range(w) if (x, y) not in holes]
        faces = shape["faces"]
        for sign, fs in ((1, faces), (-1, [f[::-1] for f in faces])):
            vs = winding.vertices(shape, None)
            for _ in range(n // 3):
                p = tuple(Fraction(rng.randint(-2, 4 * w + 2), 4) + Fraction(1, 8) for _ in range(3))
                if winding.on_surface(vs, fs, p):
                    continue
                cell_in = 0 <= p[2] <= 1 and any(x <= p[0] <= x + 1 and y <= p[1] <= y + 1 for x, y in cells)
                want = sign * int(cell_in)
                if winding.signed_crossings(vs, fs, p) != want or \
                        abs(winding.generalized(vs, fs, p) - want) > mpmath.mpf(10) ** -40:
                    raise AssertionError(f"selftest winding: {p} in cells {cells}, sign {sign}")
                done += 1
    return done


def run() -> None:
    rng = random.Random(20240611)
    counts = {
        "triangle vs Cramer": check_triangles(rng),
        "polygon vs crossing number": check_polygons(rng),
        "solids": check_solids(rng),
        "symbolic vs explicit perturbation": check_perturbation(rng),
        "meshes": check_meshes(rng),
        "spawn": check_spawn(),
        "winding numbers": check_winding(rng),
    }
    print("selftest ok: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
