# SPDX-License-Identifier: Apache-2.0
"""Property tests (hypothesis) of the library through the Python API.

Tolerances: where two computations of the same hit take different rounding
paths (a transform against a direct placement), t and points agree within
TOL = 1e-9 relative to the scene's scale, normals within 1e-9; hits lie on
their surface within SURFACE_TOL = 1e-9 × scale (distance estimated as
|F(p)| / |grad F(p)| for implicit surfaces). Configurations within 1e-6 of a
tangency or an edge, where the number of hits itself legitimately flips under
rounding, are filtered out with ``assume`` and checked by the corpus instead.
"""

from __future__ import annotations

import math
import struct

import isect
import numpy as np
from hypothesis import assume, given, note
from hypothesis import strategies as st
from strategies import (
    Sample,
    affine,
    aimed_rays,
    any_shapes,
    bounded_solids,
    box_planes,
    boxes,
    convex_polyhedra,
    cylinders,
    ellipsoids,
    floats,
    infinite_cylinders,
    nonzero_vec3,
    planes,
    polygons,
    rotations,
    spheres,
    transformed,
    triangles,
    vec3,
)

TOL = 1e-9
SURFACE_TOL = 1e-9
CROSSINGS = (isect.HitKind.ENTER, isect.HitKind.EXIT)


def bits(x: float) -> bytes:
    return struct.pack("<d", float(x))


def same_hit_bits(record: np.void, hit: isect.Hit) -> bool:
    ours = [record["t"], *record["point"], *record["normal"], *record["uv"]]
    theirs = [hit.t, *hit.point, *hit.normal, *hit.uv]
    return (
        all(bits(a) == bits(b) for a, b in zip(ours, theirs))
        and int(record["prim"]) == hit.prim
        and int(record["kind"]) == hit.kind
    )


# ----------------------------------------------- closest hit == first of all


@given(st.data(), st.one_of(any_shapes(), transformed(any_shapes())))
def test_closest_hit_is_first_of_all_hits(data: st.DataObject, sample: Sample) -> None:
    """The batch closest hit is, bit for bit, the first hit of intersect_all
    (a MISS when there is none), for every shape, plain and transformed."""
    origin, direction = data.draw(aimed_rays(sample))
    tmin = data.draw(st.sampled_from([0.0, 0.5, -math.inf]))
    hits = sample.shape.intersect_all(origin, direction, tmin=tmin)
    record = sample.shape.intersect(origin, direction, tmin=tmin)
    note(f"hits={hits}")
    if hits:
        assert same_hit_bits(record, hits[0])
        assert [h.t for h in hits] == sorted(h.t for h in hits)
    else:
        assert record["kind"] == isect.HitKind.MISS and record["t"] == math.inf
        assert record["prim"] == -1


# ------------------------------------------------ transformed == placed directly


def assert_hits_close(
    a: list[isect.Hit], b: list[isect.Hit], scale: float, compare_prim: bool = True
) -> None:
    assert len(a) == len(b), (a, b)
    for x, y in zip(a, b):
        tol = TOL * max(1.0, scale, abs(y.t))
        assert abs(x.t - y.t) <= tol, (x, y)
        assert np.allclose(x.point, y.point, rtol=0, atol=TOL * max(1.0, scale)), (x, y)
        assert x.kind == y.kind, (x, y)
        if compare_prim:
            assert x.prim == y.prim, (x, y)
            assert np.allclose(x.normal, y.normal, rtol=0, atol=1e-9), (x, y)


@given(ellipsoids(), vec3(-20, 20), nonzero_vec3())
def test_ellipsoid_equals_transformed_unit_sphere(
    sample: Sample, origin: np.ndarray, direction: np.ndarray
) -> None:
    """Ellipsoid(c, radii) hits like the unit sphere scaled by radii and moved to c."""
    ell = sample.shape
    assert isinstance(ell, isect.Ellipsoid)
    c, radii = ell.center, ell.radii
    sphere = isect.Sphere([0, 0, 0], 1.0).transformed(affine(np.diag(radii), c))
    # keep away from tangency: distance of the scaled ray's line from the origin
    o, d = (origin - c) / radii, direction / radii
    h2 = float(np.sum(np.cross(o, d) ** 2) / (d @ d))
    assume(abs(1.0 - h2) > 1e-6)
    assume(abs(float(o @ o) - 1.0) > 1e-9)  # an origin on the surface: t = 0 may round either way
    assert_hits_close(
        ell.intersect_all(origin, direction),
        sphere.intersect_all(origin, direction),
        sample.scale + 20,
    )


def _box_edge_margin(lo: np.ndarray, hi: np.ndarray, o: np.ndarray, d: np.ndarray) -> float:
    """Relative gap between the slab entries/exits of a ray and an object-space
    box: small when the ray passes near an edge or corner (test-side slab test)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (lo - o) / d, (hi - o) / d
    near, far = np.minimum(t1, t2), np.maximum(t1, t2)
    near = near[np.isfinite(near)]
    far = far[np.isfinite(far)]
    ts = np.sort(np.concatenate([near, far]))
    if len(ts) < 2:
        return math.inf
    scale = max(1.0, float(np.abs(ts).max()))
    gaps = [abs(float(near.max()) - float(x)) for x in near if x != near.max()]
    gaps += [abs(float(far.min()) - float(x)) for x in far if x != far.min()]
    gaps.append(abs(float(far.min()) - float(near.max())))
    return min(gaps) / scale if gaps else math.inf


@given(boxes(), rotations, vec3(-5, 5), vec3(-20, 20), vec3(-1, 1), st.booleans())
def test_moved_box_equals_convex_polyhedron(
    sample: Sample,
    rot: np.ndarray,
    shift: np.ndarray,
    origin: np.ndarray,
    aim: np.ndarray,
    rotate: bool,
) -> None:
    """A box translated (and rotated) by a transform hits like the convex
    polyhedron of its six moved planes: same t, points, kinds, and — the
    planes being listed in face order — the same prims and normals."""
    box = sample.shape
    assert isinstance(box, isect.Box)
    m = affine(rot if rotate else np.eye(3), shift)
    moved = box.transformed(m)
    convex = isect.ConvexPolyhedron(box_planes(box.lo, box.hi, m))
    target = m[:3, :3] @ (sample.center + aim * (box.hi - box.lo) * 0.6) + shift
    direction = target - origin
    assume(float(np.linalg.norm(direction)) > 1e-3)
    o_obj = np.linalg.solve(m[:3, :3], origin - shift)
    d_obj = np.linalg.solve(m[:3, :3], direction)
    assume(_box_edge_margin(box.lo, box.hi, o_obj, d_obj) > 1e-6)
    # an origin on the surface: t = 0 may round either way
    assume(abs(float(np.max(np.maximum(box.lo - o_obj, o_obj - box.hi)))) > 1e-9 * sample.scale)
    assume(np.all(np.abs(d_obj) > 1e-6 * np.linalg.norm(d_obj)))  # not parallel to a face
    a = moved.intersect_all(origin, direction)
    b = convex.intersect_all(origin, direction)
    assert_hits_close(a, b, sample.scale + 25)
    if not rotate:
        direct = isect.Box(box.lo + shift, box.hi + shift)
        assert_hits_close(direct.intersect_all(origin, direction), a, sample.scale + 25)


# --------------------------------------------------- hit points on the surface


def _dist_implicit(value: float, grad: np.ndarray) -> float:
    return abs(value) / max(float(np.linalg.norm(grad)), 1e-300)


def surface_distance(shape: isect.Shape, hit: isect.Hit) -> float:
    """Test-side estimate of the distance of a hit point from the surface."""
    p = np.array(hit.point)
    if isinstance(shape, isect.Sphere):
        return abs(float(np.linalg.norm(p - shape.center)) - shape.radius)
    if isinstance(shape, isect.Ellipsoid):
        q = (p - shape.center) / shape.radii
        return _dist_implicit(float(q @ q) - 1.0, 2 * q / shape.radii)
    if isinstance(shape, isect.Plane):
        return _dist_implicit(float(shape.normal @ p) + shape.d, shape.normal)
    if isinstance(shape, isect.Triangle):
        a, b, c = shape.vertices
        return _dist_implicit(float(np.cross(b - a, c - a) @ (p - a)), np.cross(b - a, c - a))
    if isinstance(shape, isect.Polygon):
        v = shape.vertices
        n = np.sum(np.cross(v, np.roll(v, -1, axis=0)), axis=0)  # Newell
        return _dist_implicit(float(n @ (p - v.mean(axis=0))), n)
    if isinstance(shape, isect.Box):
        inside = float(np.max(np.maximum(shape.lo - p, p - shape.hi)))
        return abs(inside)
    if isinstance(shape, isect.ConvexPolyhedron):
        pl = shape.planes
        return abs(float(np.max((pl[:, :3] @ p + pl[:, 3]) / np.linalg.norm(pl[:, :3], axis=1))))
    if isinstance(shape, (isect.Cylinder, isect.InfiniteCylinder)):
        base, axis = (
            (shape.p0, shape.p1 - shape.p0)
            if isinstance(shape, isect.Cylinder)
            else (shape.point, shape.axis)
        )
        u = axis / np.linalg.norm(axis)
        radial = float(np.linalg.norm((p - base) - ((p - base) @ u) * u))
        if hit.prim == 0:
            return abs(radial - shape.radius)
        cap = base if hit.prim == 1 else base + axis
        return abs(float((p - cap) @ u)) + max(0.0, radial - shape.radius)
    if isinstance(shape, isect.Quadric):
        a, b, c, d, e, f, g, h, i, j = shape.coeffs
        x, y, z = p
        value = (
            a * x * x
            + b * y * y
            + c * z * z
            + d * x * y
            + e * x * z
            + f * y * z
            + g * x
            + h * y
            + i * z
            + j
        )
        grad = np.array(
            [
                2 * a * x + d * y + e * z + g,
                2 * b * y + d * x + f * z + h,
                2 * c * z + e * x + f * y + i,
            ]
        )
        return _dist_implicit(value, grad)
    raise AssertionError(type(shape))


@given(
    st.data(),
    st.one_of(
        spheres(),
        ellipsoids(),
        planes(),
        triangles(),
        polygons(),
        boxes(),
        convex_polyhedra(),
        cylinders(),
        infinite_cylinders(),
    ),
)
def test_hit_points_lie_on_the_surface(data: st.DataObject, sample: Sample) -> None:
    """Every hit point is within SURFACE_TOL × scale of the surface, on the
    ray (org + t·dir, or snapped onto the surface), with a unit normal."""
    origin, direction = data.draw(aimed_rays(sample))
    for hit in sample.shape.intersect_all(origin, direction):
        # coordinates carry a rounding error relative to their own size
        scale = max(1.0, sample.scale, float(np.abs(origin).max()), float(np.abs(hit.point).max()))
        assert surface_distance(sample.shape, hit) <= SURFACE_TOL * scale, hit
        on_ray = origin + hit.t * direction
        assert np.allclose(hit.point, on_ray, rtol=0, atol=1e-8 * scale), hit
        assert abs(float(np.linalg.norm(hit.normal)) - 1.0) <= 1e-12, hit
        if hit.kind in CROSSINGS:
            facing = float(np.dot(direction, hit.normal))
            assert (facing < 0) == (hit.kind == isect.HitKind.ENTER), hit


@given(st.data(), st.one_of(spheres(), ellipsoids(), boxes(), convex_polyhedra()))
def test_transformed_hit_points_lie_on_the_surface(data: st.DataObject, sample: Sample) -> None:
    """Hits of a transformed solid, mapped back to object space, lie on the
    untransformed surface."""
    rot = data.draw(rotations)
    m = affine(rot, data.draw(vec3(-5, 5)))
    moved = Sample(sample.shape.transformed(m), rot @ sample.center + m[:3, 3], sample.scale + 5)
    origin, direction = data.draw(aimed_rays(moved))
    for hit in moved.shape.intersect_all(origin, direction):
        p_obj = rot.T @ (np.array(hit.point) - m[:3, 3])
        local = hit._replace(point=tuple(p_obj))
        assert surface_distance(sample.shape, local) <= SURFACE_TOL * max(moved.scale, 20), hit


# ------------------------------------------------------ translation invariance

GRID = st.integers(-2048, 2048).map(lambda k: k / 64.0)  # exact dyadic values
GRID3 = st.tuples(GRID, GRID, GRID).map(np.array)


@st.composite
def grid_samples(draw: st.DrawFn) -> tuple[str, list[np.ndarray], float]:
    """A shape family and its numbers on the dyadic grid, so that translating
    them (and the ray) by a grid vector is exact."""
    kind = draw(
        st.sampled_from(
            [
                "sphere",
                "box",
                "triangle",
                "polygon",
                "plane",
                "convex",
                "cylinder",
                "infinite_cylinder",
                "ellipsoid",
            ]
        )
    )
    pos = st.integers(8, 256).map(lambda k: k / 64.0)
    pts = [draw(GRID3) for _ in range(4)]
    return kind, pts, draw(pos)


def grid_shape(kind: str, pts: list[np.ndarray], r: float, shift: np.ndarray) -> isect.Shape:
    a, b, c, d = (p + shift for p in pts)
    if kind == "sphere":
        return isect.Sphere(a, r)
    if kind == "box":
        return isect.Box(a, a + r)
    if kind == "triangle":
        return isect.Triangle(a, b, c)
    if kind == "polygon":
        return isect.Polygon([a, b, c, a + (c - b)])  # a parallelogram-like quad (planar)
    if kind == "plane":
        n = pts[1]
        return isect.Plane(n, -float(n @ a))
    if kind == "convex":
        rows = [[*(s * np.eye(3)[i]), -s * (a[i] + s * r)] for i in range(3) for s in (-1.0, 1.0)]
        return isect.ConvexPolyhedron(rows)
    if kind == "cylinder":
        return isect.Cylinder(a, b, r)
    if kind == "infinite_cylinder":
        return isect.InfiniteCylinder(a, pts[1], r)
    return isect.Ellipsoid(a, np.array([r, 2 * r, r / 2]))


@given(grid_samples(), GRID3, GRID3, GRID3)
def test_translating_ray_and_shape_keeps_t(
    sample: tuple[str, list[np.ndarray], float],
    shift: np.ndarray,
    origin: np.ndarray,
    target: np.ndarray,
) -> None:
    """Moving ray and shape by the same vector leaves every t unchanged — bit
    for bit, as all numbers here lie on a dyadic grid where the translation is
    exact — whether the shape is built at the new place or moved there by a
    transform."""
    kind, pts, r = sample
    direction = target - origin
    assume(np.any(direction != 0))
    if kind == "plane":
        assume(np.any(pts[1] != 0))
    try:
        base = grid_shape(kind, pts, r, np.zeros(3))
    except isect.IsectError:
        assume(False)
        return
    ref = [(h.t, h.kind, h.prim) for h in base.intersect_all(origin, direction)]
    moved = grid_shape(kind, pts, r, shift).intersect_all(origin + shift, direction)
    via_xform = base.transformed(affine(np.eye(3), shift)).intersect_all(origin + shift, direction)
    assert [(h.t, h.kind, h.prim) for h in via_xform] == ref
    if kind != "plane":  # a plane's offset d changes by n.shift, rounded
        assert [(h.t, h.kind, h.prim) for h in moved] == ref


@given(spheres(), vec3(-1e3, 1e3), vec3(-20, 20), nonzero_vec3())
def test_translating_far_keeps_t_within_tolerance(
    sample: Sample, shift: np.ndarray, origin: np.ndarray, direction: np.ndarray
) -> None:
    """With arbitrary (rounded) translations, t stays within the relative
    tolerance of the translated numbers."""
    s = sample.shape
    assert isinstance(s, isect.Sphere)
    oc = origin - s.center
    h2 = float(np.sum(np.cross(oc, direction) ** 2) / (direction @ direction))
    assume(abs(s.radius**2 - h2) > 1e-3 * s.radius**2)
    # an origin on the surface: t = 0 may round either way
    assume(abs(float(np.linalg.norm(oc)) - s.radius) > 1e-9 * (1 + float(np.abs(shift).max())))
    a = s.intersect_all(origin, direction)
    b = isect.Sphere(s.center + shift, s.radius).intersect_all(origin + shift, direction)
    assert len(a) == len(b)
    # rounding of the shifted coordinates: |shift| * 2^-52 each, amplified by
    # at most 1/sqrt(disc) near (but not at) tangency
    tol = 1e-12 * (1 + float(np.abs(shift).max())) * 1e3
    for x, y in zip(a, b):
        assert abs(x.t - y.t) <= tol * max(1.0, abs(x.t)) / float(np.linalg.norm(direction)), (x, y)
        assert x.kind == y.kind


# --------------------------------------------------------------- parity


def robustly(shape: isect.Solid, p: np.ndarray, scale: float) -> bool | None:
    """contains(p) if all points 1e-6·scale away along the axes agree, else None."""
    delta = 1e-6 * scale
    probes = np.vstack([p, p + delta * np.eye(3), p - delta * np.eye(3)])
    inside = shape.contains(probes)
    return bool(inside[0]) if inside.all() or not inside.any() else None


@given(st.data(), st.one_of(bounded_solids(), transformed(bounded_solids())))
def test_crossing_parity_of_bounded_solids(data: st.DataObject, sample: Sample) -> None:
    """From an inside point a ray crosses the surface an odd number of times,
    from an outside point an even number (TOUCH hits are not crossings)."""
    shape = sample.shape
    assert isinstance(shape, isect.Solid)
    start = sample.center + data.draw(vec3(-1, 1)) * sample.scale * data.draw(floats(0.0, 1.5))
    inside = robustly(shape, start, sample.scale)
    assume(inside is not None)
    direction = data.draw(nonzero_vec3())
    crossings = sum(h.kind in CROSSINGS for h in shape.intersect_all(start, direction))
    assert crossings % 2 == (1 if inside else 0), (inside, crossings)


@given(st.data(), infinite_cylinders())
def test_crossing_parity_of_infinite_cylinders(data: st.DataObject, sample: Sample) -> None:
    """The same for infinite cylinders, with directions not along the axis
    (which stay inside or outside forever)."""
    shape = sample.shape
    assert isinstance(shape, isect.InfiniteCylinder)
    start = sample.center + data.draw(vec3(-3, 3))
    inside = robustly(shape, start, sample.scale)
    assume(inside is not None)
    direction = data.draw(nonzero_vec3())
    u = shape.axis / np.linalg.norm(shape.axis)
    assume(np.linalg.norm(np.cross(direction, u)) > 1e-3 * np.linalg.norm(direction))
    crossings = sum(h.kind in CROSSINGS for h in shape.intersect_all(start, direction))
    assert crossings % 2 == (1 if inside else 0)


@given(st.data(), floats(0.3, 3.0), floats(0.3, 3.0))
def test_crossing_parity_of_hyperboloids(data: st.DataObject, a: float, c: float) -> None:
    """A non-convex, unbounded quadric (hyperboloid of one sheet): the parity
    of crossings equals inside(start) xor inside(far end of the ray)."""
    shape = isect.Quadric([1 / a**2, 1 / a**2, -1 / c**2, 0, 0, 0, 0, 0, 0, -1])
    start = data.draw(vec3(-4, 4))
    inside = robustly(shape, start, 4.0)
    assume(inside is not None)
    d = data.draw(nonzero_vec3())
    asym = (d[0] ** 2 + d[1] ** 2) / a**2 - d[2] ** 2 / c**2
    assume(abs(asym) > 1e-3 * float(d @ d))
    far_inside = asym < 0
    crossings = sum(h.kind in CROSSINGS for h in shape.intersect_all(start, d))
    assert crossings % 2 == int(inside != far_inside)


@given(st.data(), convex_polyhedra())
def test_convex_from_inside_once_through_twice(data: st.DataObject, sample: Sample) -> None:
    """A ray from the centre of a bounded convex polyhedron leaves it once
    (EXIT); a ray from far outside through the centre enters and leaves."""
    shape = sample.shape
    assert isinstance(shape, isect.ConvexPolyhedron)
    d = data.draw(nonzero_vec3())
    out = [h for h in shape.intersect_all(sample.center, d) if h.kind in CROSSINGS]
    assert len(out) == 1 and out[0].kind == isect.HitKind.EXIT
    far = sample.center - d / np.linalg.norm(d) * 100 * sample.scale
    through = [h.kind for h in shape.intersect_all(far, d) if h.kind in CROSSINGS]
    assert through == [isect.HitKind.ENTER, isect.HitKind.EXIT]
