# SPDX-License-Identifier: Apache-2.0
"""Rays, options, hits and cases of the golden reference (shared by all families).

The library's documented output rules live here, evaluated on exact values:
hits are kept for tmin <= t <= tmax (closed), sorted by t then prim;
ISECT_CULL_BACK drops EXIT hits of thin surfaces; point = org + t*dir.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Sequence

from exact import NEAR, Real, cmp, point_on_ray, q, qv, refuse, rel_gap, representable, to_double

EPS_DEFAULT = 1e-12
INF = math.inf
NAN = math.nan


# ----------------------------------------------------------------- the ray
@dataclass(frozen=True)
class XRay:
    """A ray with exact coordinates; tmin/tmax exact or +-inf (a float)."""
    org: tuple[Fraction, Fraction, Fraction]
    dir: tuple[Fraction, Fraction, Fraction]
    tmin: Fraction | float
    tmax: Fraction | float

    @staticmethod
    def from_json(r: dict) -> "XRay":
        def bound(x: float) -> Fraction | float:
            return x if math.isinf(x) else q(x)
        return XRay(qv(r["org"]), qv(r["dir"]),
                    bound(r.get("tmin", 0.0)), bound(r.get("tmax", INF)))


@dataclass(frozen=True)
class Ctx:
    """Decision context of one solve.

    eps:   the exact eps of the options.
    exact: the library sees exactly this ray (no transform, or a transform
           whose inverse and object-space ray are exact in doubles), so an
           exact tie in the reference is a tie in the library too.  When
           False, cases must keep every decision away from a tie.
    """
    eps: Fraction
    exact: bool = True


@dataclass
class Hit:
    """One hit before it is put in world space and rounded."""
    t: Real
    normal: Sequence[Real]
    kind: str                       # "enter" | "exit" | "touch"
    prim: int = -1
    uv: tuple[Real, Real] = (Fraction(0), Fraction(0))


# --------------------------------------------------------------- filtering
def _bound_ok(t: Real, bound: Fraction | float, want: int, ctx: Ctx, what: str) -> bool:
    """t >= bound (want = 1) or t <= bound (want = -1), closed."""
    if isinstance(bound, float):           # an infinite bound
        return (bound < 0) if want > 0 else (bound > 0)
    c = cmp(t, bound)
    if c == 0:
        # A hit exactly at tmin/tmax: the library must compute t exactly.
        if not (isinstance(t, Fraction) and representable(t) and ctx.exact):
            refuse(f"hit at t = {what} is not exactly computable")
        return True
    if rel_gap(t, bound) < NEAR:
        refuse(f"hit within 1e-12 (relative) of {what}: the library's rounding could decide")
    return c == want


def in_range(t: Real, ray: XRay, ctx: Ctx) -> bool:
    return _bound_ok(t, ray.tmin, 1, ctx, "tmin") and _bound_ok(t, ray.tmax, -1, ctx, "tmax")


def finish(hits: list[Hit], ray: XRay, ctx: Ctx, thin: bool, cull_back: bool) -> list[Hit]:
    """Range filter, back-face culling and the (t, prim) order of the API."""
    kept = [h for h in hits if in_range(h.t, ray, ctx)]
    if cull_back and thin:
        kept = [h for h in kept if h.kind != "exit"]

    def order(a: Hit, b: Hit) -> int:
        c = cmp(a.t, b.t) if a.t != b.t else 0
        return c if c else (a.prim > b.prim) - (a.prim < b.prim)
    return sorted(kept, key=functools.cmp_to_key(order))


def hit_json(h: Hit, ray: XRay) -> dict:
    """Round an exact hit to doubles; point = org + t*dir (on the surface)."""
    p = point_on_ray(ray.org, ray.dir, h.t)
    return {"t": to_double(h.t),
            "point": [to_double(x) for x in p],
            "normal": [to_double(x) for x in h.normal],
            "uv": [to_double(x) for x in h.uv],
            "prim": h.prim,
            "kind": h.kind}


# ---------------------------------------------------------- case builders
def ray(org: Sequence[float], d: Sequence[float], tmin: float = 0.0, tmax: float = INF) -> dict:
    return {"org": [float(x) for x in org], "dir": [float(x) for x in d],
            "tmin": float(tmin), "tmax": float(tmax)}


def opts(eps: float | None = None, flags: Sequence[str] = ()) -> dict:
    o: dict[str, Any] = {}
    if eps is not None:
        o["eps"] = float(eps)
    if flags:
        o["flags"] = list(flags)
    return o


def fl(v: Sequence[float]) -> list[float]:
    return [float(x) for x in v]


def nudge(x: float, k: int) -> float:
    """x moved by k ulps (toward +inf for k > 0, toward -inf for k < 0)."""
    for _ in range(abs(k)):
        x = math.nextafter(x, math.inf if k > 0 else -math.inf)
    return x


def nudged(v: Sequence[float], axis: int, k: int) -> list[float]:
    """The point v with coordinate ``axis`` moved by k ulps."""
    out = [float(x) for x in v]
    out[axis] = nudge(out[axis], k)
    return out


#: tol of the revision-2 accuracy contract (t within about 4 ulp)
TIGHT = {"t": 1e-15}
#: tol of op spawn (the spawned origin is a few ulps off the exact hit point)
SPAWN_TOL = {"t": 1e-9, "point": 1e-9, "normal": 1e-9, "uv": 1e-9}


def origin_tol(expect: dict) -> dict:
    """tol.t of an origin-on-surface case, from its expected hits: the only
    hit is checked to about 4 ulp of its own t (exactly when t = 0), several
    hits to 1e-15 relative."""
    hits = expect.get("hits", [])
    if len(hits) == 1:
        t = abs(hits[0]["t"])
        return {"t": 0.0 if t == 0 else 1e-15 * min(t, 1.0)}
    return dict(TIGHT)


CASE_KEYS = ("name", "flags", "op", "shape", "transform", "ray", "dir", "point", "points", "accuracy",
             "polygon", "rule", "vertices", "opts", "expect", "tol")


@dataclass
class Group:
    """A consistency check over several cases (the exactly-once guarantee).

    kind "one":        exactly one case of the group has a hit (and only one).
    kind "even":       the total number of hits of the group is even.
    kind "enter-exit": the group has exactly two hits, one enter and one exit.
    kind "one-inside": exactly one point_in_polygon2 case says inside.
    """
    name: str
    kind: str
    members: list[dict] = field(default_factory=list)


def surface_case(name: str, flags: Sequence[str], **fields: Any) -> dict:
    """An origin-on-surface case: tol.t is set from the expected hits by the
    generator (``origin_tol``)."""
    c = case(name, ["origin-on-surface", *flags], **fields)
    c["_tol"] = origin_tol
    return c


def case(name: str, flags: Sequence[str], group: Group | None = None, **fields: Any) -> dict:
    """A case dict in canonical key order (expect is filled in by the generator)."""
    c: dict[str, Any] = {"name": name, "flags": list(flags)}
    for k, v in fields.items():
        if k not in CASE_KEYS:
            raise KeyError(f"unknown case key {k}")
        if v is not None:
            c[k] = v
    if group is not None:
        group.members.append(c)
        c["_group"] = group          # private: checked and removed by the generator
    return c


# ------------------------------------------------------------------- notes
#: every flag a case may carry, with the explanation written into the header
NOTES: dict[str, str] = {
    "basic": "An ordinary configuration far from every special case.",
    "miss": "The ray (or its line) misses the object: count 0.",
    "behind": "The object lies behind the ray origin (t < tmin) and is not reported; "
              "with tmin = -inf it is.",
    "inside": "The ray origin is inside the solid: the entry lies at t < 0.",
    "on-surface": "The ray origin lies exactly on the surface, so a hit has t = 0 exactly "
                  "(kept, since tmin = 0 is inclusive).",
    "tangent": "The ray touches a curved surface exactly (zero discriminant in exact "
               "arithmetic): one hit of kind touch.",
    "near-tangent": "The ray passes near tangency; the documented scale-invariant test against "
                    "eps decides between one touch and two hits (never close to the threshold).",
    "parallel": "The ray is parallel to a plane, a convex face or a cylinder cap (|n.d| <= eps|n||d|) "
                "or to a cylinder axis (|d x a| <= eps|d||a|): a parallel plane is not hit; a parallel "
                "convex face constrains by the side of the origin (on the plane = inside). A triangle, "
                "polygon or mesh face is parallel only when n.d = 0 exactly (SPEC revision 2: no eps for "
                "them) and is then not hit.",
    "touch-snap": "A touch decided by a large eps while the ray passes at distance r - h from the "
                  "surface: isect.h lets the point be org + t*dir (expected here) or that point "
                  "snapped onto the surface (sphere, ellipsoid); they differ by about r - h, so "
                  "tol.point is loosened to 1e-4 to accept both.",
    "near-parallel": "The ray is almost parallel. For a plane, a convex face or a cylinder cap eps decides "
                     "(never close to the threshold). Triangles, polygons and mesh faces use no eps at all "
                     "(SPEC revision 2): the exact test in the sheared frame alone decides whether they are "
                     "crossed, so a nearly parallel ray that crosses one is a hit at every eps.",
    "in-plane": "The ray lies in the plane of a thin surface or face.",
    "vertex": "The ray passes exactly through a vertex. Decided without tolerance by the exact "
              "symbolic perturbation of isect.h (sheared frame, query point moved by "
              "(-e^2, -e)); the sheared projection of these inputs is exact in doubles.",
    "edge": "The ray passes exactly through an edge (interior of the edge); decided by the "
            "exact perturbation rule, sheared projection exact in doubles.",
    "horizontal-edge": "In the sheared (or 2D) frame an edge lies on the horizontal line through "
                       "the query point: it counts for neither side (ray parallel to an edge in "
                       "the point-in-polygon test).",
    "watertight": "One case of a group that share an edge or vertex (named in the case name): "
                  "the reference checks that exactly one of the group reports the crossing, or "
                  "an even number for a graze.",
    "frame-swap": "dir[kz] < 0, so the sheared frame swaps kx and ky.",
    "frame-tie": "Two or three |dir| components are equal: kz is the lowest index.",
    "rounded-frame": "The ray passes within a rounding error of an edge and its sheared projection is not "
                     "exact in doubles: the expectation is decided exactly on the given doubles, as the "
                     "face tests decide (issue 13's ray that a rounded projection counted once).",
    "graze": "The ray touches a box or polyhedron only at an edge or corner (entry == exit): "
             "one touch hit, prim the lowest face index involved.",
    "tie": "Several faces are reached at the same t (the ray crosses an edge or corner): "
           "the lowest face index is reported.",
    "concave": "A concave polygon (a notch); the ray goes through the notch or beside it.",
    "reflex": "The ray passes through a reflex vertex of a concave polygon.",
    "collinear": "The polygon has three consecutive collinear vertices (a vertex in the middle "
                 "of a straight edge).",
    "duplicate-vertex": "The polygon repeats a vertex (a zero-length edge).",
    "self-intersecting": "A self-intersecting polygon: even-odd and nonzero rules differ where "
                         "the winding number is 2.",
    "evenodd": "Polygon rule ISECT_EVEN_ODD (inside where the crossing number is odd).",
    "nonzero": "Polygon rule ISECT_NONZERO (inside where the winding number is not 0).",
    "clip": "tmin/tmax remove some hits (the interval [tmin, tmax] is closed).",
    "clip-exact": "A hit lies exactly at tmin or tmax and is kept (closed interval); t is exact "
                  "in doubles.",
    "empty-interval": "tmin > tmax: no hits, not an error.",
    "negative-t": "tmin is negative (or -inf), so hits behind the origin are reported.",
    "non-unit-dir": "The direction is not unit length; t is in units of dir (never renormalised).",
    "far": "Small object far from the origin (e.g. sphere radius 1e-3 at distance ~1e7): needs "
           "cancellation-free formulas (Haines et al.). The far spheres carry tol.t = 4e-16 relative "
           "(about 2 ulp). Cases added with SPEC revision 2, whose accuracy contract promises t within "
           "4 ulp for every primitive at every scale and position, carry tol.t = 1e-15 relative "
           "(about 4 ulp); the older far cases of other shapes keep the default tolerance.",
    "loose-normal": "The normal tolerance is loosened to 1e-5 because coordinates of ~1e7 cancel in "
                    "p - c (or in org + t*dir near a small object seen from 1e7 away): the normal of a "
                    "radius-1e-3 surface is only determined to about ulp(1e7)/r ~ 2e-6 by a "
                    "double-precision point.",
    "loose-point": "tol.point is loosened to 1e-8 (and tol.uv to 1e-6 for mesh faces): the ray comes "
                   "from ~1e7 away at an angle, so org + t*dir cancels, and a t accurate to a few ulps "
                   "fixes the point only to about ulp(1e7) ~ 2e-9 where the library does not snap it onto "
                   "the surface; the barycentrics of a 2e-3 face are then only determined to ~1e-6.",
    "eps": "The case sets a non-default eps in opts.",
    "cull-back": "opts.flags has cull_back: EXIT hits of thin surfaces (plane, triangle, "
                 "polygon, open cylinder) are dropped; solids are unaffected.",
    "cap": "The hit is on a cylinder cap (prim 1 at p0, prim 2 at p1).",
    "open": "An open cylinder (capped false): the side only, a thin surface with the outward "
            "radial normal.",
    "unbounded": "An unbounded convex polyhedron: only an enter or only an exit hit.",
    "linear": "Quadric linear case (a = 0 along the ray: ray parallel to a cone generator or a "
              "plane given as a quadric): t = -c/b; a = b = 0 gives no hit.",
    "degenerate": "Degenerate geometry that is not an error (zero area, collinear, zero radius, "
                  "zero-length axis, flat box, zero normal, all-zero quadric): status ok, "
                  "never hit.",
    "contains": "op contains: closed solid, a point on the boundary is inside (the boundary "
                "points used evaluate F(p) = 0 exactly in doubles).",
    "boundary": "The query point lies exactly on the boundary.",
    "robust": "A naive double-precision orientation test gets this sign wrong; the exact "
              "predicate must be used.",
    "transformed": "The shape has an object-to-world transform: the ray goes to object space "
                   "by the inverse (t unchanged), points by M, normals by the inverse transpose "
                   "(renormalised).",
    "rotation": "The transform contains a rotation (entries are the doubles of cos/sin; the "
                "reference uses those doubles exactly).",
    "scaling": "The transform scales (uniformly or not).",
    "shear": "The transform shears.",
    "mirror": "The transform has negative determinant (mirroring); normals stay outward, kinds "
              "unchanged.",
    "translation": "The transform translates.",
    "exact-transform": "The transform's inverse and the object-space ray are exact in doubles, "
                       "so exact edge/tangency decisions carry over.",
    "bad-input": "Invalid input: expect.status is the error; nothing else is checked. For op spawn the "
                 "primary ray is valid and the status is isect_spawn_ray's (a MISS record, a zero or "
                 "non-finite direction).",
    "nonfinite": "A NaN or Inf where a finite number is required: E_NONFINITE.",
    "singular": "The transform's linear part is singular: |det| <= 2^-40 |row0||row1||row2| "
                "(rows of the 3x3 linear part): E_DEGENERATE.",
    "non-affine": "The transform's last row is not exactly 0 0 0 1: E_ARG.",
    "c-only": "Only expressible through the C API (integer shape type, integer capped): "
              "other runners skip it and count it as skipped.",
    "neg-zero": "An input is -0.0, which compares equal to 0 (not negative).",
    "winding": "op winding_number2 (integer winding number, counter-clockwise +1).",
    "normal-op": "op polygon_normal or plane_from_points (Newell's method about the centroid).",
    "polygon-faces": "A mesh with faces of more than 3 vertices, built through CSR offsets; those faces "
                     "hit like polygons under the even-odd rule (Newell normal, uv 0).",
    "mixed-faces": "A mesh mixing triangles and quads (CSR offsets): the 3-vertex faces still hit as "
                   "triangles (barycentric uv).",
    "parity": "A ray against a closed mesh from an origin off the surface over [0, inf): the "
              "generator checks that the hit count is odd exactly when the origin is inside, by a "
              "containment reference that shares nothing with the ray tests (exactly-once).",
    "edge-graze": "The ray touches a closed mesh only along an edge or at a vertex without entering it: "
                  "the faces there claim the crossing an even number of times (0 or 2).",
    "genus": "A mesh with handles (torus: genus 1; a block with two holes: genus 2) made of coplanar "
             "quads that share edges and vertices.",
    "open-mesh": "A mesh with boundary edges (a cube with a face removed): rays hit the faces that are "
                 "there; contains is ISECT_E_ARG.",
    "misoriented": "One face has the opposite vertex order: its hits have the other kind; the report "
                   "counts its edges as misoriented; containment still follows crossing parity.",
    "components": "A mesh of two disjoint pieces.",
    "nonmanifold": "Three faces share one edge: the report counts it; contains is ISECT_E_ARG.",
    "empty-mesh": "A mesh with vertices but no faces: valid, never hit, an all-zero report.",
    "report": "op mesh_check: the isect_mesh_report of the mesh; integer fields exact, volume and area "
              "within tol.",
    "any-hit": "opts.flags has any_hit: isect_intersect reports the first hit the traversal finds, "
               "so these cases have at most one hit in [tmin, tmax] (with several, which one is "
               "unspecified).",
    "tiling": "One of a set of polygons tiling the plane around the query point: exactly one "
              "of the group contains it.",
    "origin-on-surface": "tmin = 0 and the ray origin lies exactly on the surface (a point chosen so "
                         "that it is exactly representable there) or 1 to 3 ulps off it on either "
                         "side, the ray going into or away from the surface. SPEC revision 2, "
                         "'Interval decisions are exact': the crossing at t ~ 0 is reported exactly "
                         "when its exact t is >= 0 (its sign is never rounded into or out of the "
                         "interval), and its t is 0 exactly when the origin is on the surface. Where "
                         "that crossing is the case's only hit, tol.t checks it to about 4 ulp of its "
                         "own value (tol.t = 0 for t = 0, 1e-15 * |t| for a t of ~1e-16); otherwise "
                         "tol.t = 1e-15 relative.",
    "grazing": "A ray nearly tangent to a curved surface or nearly parallel to a planar one, decided "
               "exactly by the reference and kept clear of every eps threshold by the design margin "
               "(a factor 2 on the tested quantity): two close crossings, one touch within eps, or a "
               "miss. t is checked to tol.t = 1e-15 relative (about 4 ulp, the accuracy contract of "
               "SPEC revision 2).",
    "spawn": "op spawn (isect_spawn_ray, SPEC revision 2): the runner intersects the primary ray, takes "
             "its first hit (the MISS record of the closest-hit batch when there is none), spawns a "
             "secondary ray from it in direction dir, checks out.dir == dir, out.tmin == 0, out.tmax == "
             "+inf and out.org within 8 ulps (of the largest coordinate of the hit point) of the hit "
             "point, then intersects out: expect lists those hits. The reference computes them from the "
             "exact first hit point in direction dir over [0, inf), without the surface being left at "
             "t = 0; every other crossing is far from t = 0 compared with the spawn offset. tol 1e-9: "
             "the spawned origin is a few ulps off the exact point.",
    # op winding_number and the containment rules of meshes (tests/golden/winding.py)
    "winding-number": "op winding_number (isect_winding_number_batch, Python Mesh.winding_number): the "
                      "generalized winding number w of the mesh at each point, (1/4pi) times the sum of the "
                      "faces' signed solid angles, faces oriented by the right-hand rule (w = 1 inside a closed "
                      "mesh whose faces point out); a polygon face counts as its fan (v0, vi, vi+1). Each w "
                      "passes within tol.winding (relative to max(1, |w|)); the reference computes the solid "
                      "angles in 80 digits (Van Oosterom & Strackee, exact determinants) and, off the surface of "
                      "a closed oriented mesh, also the signed crossing count, exactly.",
    "exact-integer": "A closed, consistently oriented mesh (every edge used once each way) and points off its "
                     "surface: w is the exact integer, the signed crossing count (isect.h), whatever the "
                     "accuracy: tol.winding = 0.",
    "principal-value": "Points on a closed oriented mesh's faces, edges or vertices: isect.h gives the principal "
                       "value by direct summation (a face whose plane holds the point contributes 0), e.g. 1/2 "
                       "on a face, the interior dihedral angle over 2pi on an edge, the corner's solid angle "
                       "over 4pi at a vertex. tol.winding is the documented error bound (see open-surface).",
    "open-surface": "A mesh that is not closed and consistently oriented (here: faces removed): w is the direct "
                    "sum of the solid angles, within the error bound isect.h and src/mesh/winding.c document: "
                    "(1/4pi) sum over fan triangles of (pi E/|z| + 8 pi u) + 2u|w|, E = 10u sum_k |a_k| P_k + "
                    "64u |a||b||c| (a = A - p, ..., P the permanents of (B - A) x (C - A)), z = den + i num of "
                    "Van Oosterom & Strackee's formula, each term at most 4pi, 0 for a triangle whose plane holds "
                    "the point. The reference evaluates that bound on the exact numbers (in object space) and "
                    "rounds it up to two digits: tol.winding. Rules evenodd and nonzero refuse such a mesh "
                    "(E_ARG); rule winding takes it.",
    "on-edge": "A query point lies exactly on an edge of the mesh (or on a fan diagonal of a polygon face).",
    "on-vertex": "A query point is exactly a vertex of the mesh.",
    "crossing-ray-edge": "The library counts crossings along +x from the point (isect.h, isect_contains): for "
                         "some points of the case that ray passes exactly through an edge or a vertex, or lies "
                         "in a face's plane; the exactly-once rule keeps the count exact.",
    "near-edge": "Points very near an edge or a polygon's fan diagonal (1e-9, 2^-20): the documented bound grows "
                 "as 1/distance there (to ~1e-6), however accurate the library's refined (double-double) "
                 "evaluation is.",
    "fan": "A fan of triangles around an apex (a cone), or a dome of quads and triangles, open at its base; "
           "points in the base's plane inside the rim have w = 1/2 exactly (the closed surface's principal "
           "value).",
    "soup": "A triangle soup: triangles that share no vertex (so no edge), overlapping or crossing; not closed, "
            "so w is the direct sum (rule nonzero is E_ARG).",
    "self-intersecting-mesh": "One mesh of two overlapping closed cubes: w = 2 where they overlap, so rule evenodd "
                              "says outside there and rules nonzero and winding inside.",
    "nested": "A cube inside a cube in one mesh, with the same orientation (w = 2 inside the inner one) or the "
              "inner one reversed (a hollow shell: w = 0 inside it).",
    "inward": "Faces turned inward (reversed vertex order): w = -1 inside; rule nonzero says inside (w != 0), rule "
              "winding outside (w < 1), rule evenodd inside.",
    "flipped-face": "A closed cube with one face's vertex order reversed: closed but not oriented, so w is the direct "
                    "sum (2/3 at the centre) and rule nonzero is E_ARG.",
    "nonmanifold-winding": "Three faces share one edge (a book): not closed, so rule evenodd is E_ARG; rule winding "
                           "and winding_number take it.",
    "far-field": "accuracy > 0: the hierarchical far-field evaluation (Barill et al. 2018), which isect.h promises "
                 "within accuracy of the accuracy-0 value: tol.winding = accuracy plus the documented bound. A "
                 "closed oriented mesh still gets the exact integer.",
    "point-transform": "The mesh has an object-to-world transform and w is that of the mesh in the world "
                       "(vertices mapped by M, faces in the same order). The transforms here (signed powers of "
                       "two in a permutation, dyadic translations) map the points to object space exactly, so "
                       "the library sees the exact object point and its documented bound applies.",
    "mirror-winding": "The transform mirrors (negative determinant): the faces turn the other way by the right-hand "
                      "rule, so w is negated (isect.h). A mirrored closed cube has w = -1 inside: rules evenodd "
                      "and nonzero say inside, rule winding (w >= 1) outside.",
    "mesh-rule": "op contains on a mesh whose shape has a \"rule\" (isect_shape.flags of ISECT_MESH): evenodd "
                 "(crossing parity; closed meshes, else E_ARG), nonzero (the exact integer w != 0; closed, "
                 "consistently oriented meshes, else E_ARG) or winding (w >= 1/2, any mesh: the exact integer on "
                 "a closed oriented mesh, so w >= 1, the direct sum elsewhere, never within four times its bound "
                 "of 1/2 here). On a closed mesh a point on a face, edge or vertex is inside under every rule. "
                 "\"winding\" is a mesh rule only (a polygon with it is E_ARG).",
    "rule-evenodd": "Mesh rule evenodd (ISECT_EVEN_ODD).",
    "rule-nonzero": "Mesh rule nonzero (ISECT_NONZERO).",
    "rule-winding": "Mesh rule winding (ISECT_WINDING).",
}


def check_flags(cases: list[dict]) -> dict[str, str]:
    """The notes of the flags used in a file (every flag must be documented)."""
    used = sorted({f for c in cases for f in c["flags"]})
    missing = [f for f in used if f not in NOTES]
    if missing:
        raise KeyError(f"undocumented flags: {missing}")
    return {f: NOTES[f] for f in used}
