# SPDX-License-Identifier: Apache-2.0
"""The Python API's behaviour: shapes, broadcasting, results, helpers, versions."""

from __future__ import annotations

import math
import pickle
import re
import struct
import threading
import time

import isect
import numpy as np
import pytest
from conftest import ROOT
from meshes import icosphere
from strategies import one_of_each

SPHERE = isect.Sphere([0.0, 0.0, 0.0], 1.0)


# ------------------------------------------------------------------ versions


def test_version_matches_header() -> None:
    """version() and abi_version() report the compiled library's macros."""
    text = (ROOT / "libisect" / "include" / "isect.h").read_text()
    vs = re.search(r'#define ISECT_VERSION_STRING "([^"]+)"', text)
    abi = re.search(r"#define ISECT_ABI_VERSION (\d+)", text)
    assert vs and abi
    assert isect.version() == isect.__version__ == vs.group(1)
    assert isect.abi_version() == int(abi.group(1))


def test_public_names() -> None:
    """__all__ lists exactly the public names, each documented."""
    for name in isect.__all__:
        obj = getattr(isect, name)
        if callable(obj):
            assert obj.__doc__, name
    assert {"Mesh", "MeshReport"} <= set(isect.__all__)
    assert issubclass(isect.Mesh, isect.Solid)


# -------------------------------------------------------------------- shapes


@pytest.mark.parametrize("shape", one_of_each(), ids=lambda s: type(s).__name__)
def test_shape_basics(shape: isect.Shape) -> None:
    """Immutable data, repr that rebuilds, pickling, class hierarchy."""
    assert shape.data.dtype == np.float64 and shape.data.flags.c_contiguous
    assert not shape.data.flags.writeable
    with pytest.raises(ValueError):
        shape.data[0] = 1.0
    assert shape.matrix is None
    rebuilt = eval(repr(shape), {"np": np, **{n: getattr(isect, n) for n in isect.__all__}})
    assert type(rebuilt) is type(shape) and rebuilt.data.tolist() == shape.data.tolist()
    clone = pickle.loads(pickle.dumps(shape.transformed(np.diag([2.0, 1, 1, 1]))))
    assert clone.matrix is not None and clone.matrix[0, 0] == 2.0
    thin = isinstance(shape, (isect.Plane, isect.Triangle, isect.Polygon))
    assert isinstance(shape, isect.Solid) != thin


def test_shape_properties() -> None:
    """Each shape exposes its constructor arguments."""
    assert SPHERE.center.tolist() == [0, 0, 0] and SPHERE.radius == 1.0
    b = isect.Box([0, 1, 2], [3, 4, 5])
    assert b.lo.tolist() == [0, 1, 2] and b.hi.tolist() == [3, 4, 5]
    p = isect.Polygon([[0, 0, 0], [1, 0, 0], [0, 1, 0]], rule="nonzero")
    assert p.rule == "nonzero" and p.vertices.shape == (3, 3)
    c = isect.Cylinder([0, 0, 0], [0, 0, 1], 2.0, capped=False)
    assert not c.capped and c.radius == 2.0 and c.p1.tolist() == [0, 0, 1]
    assert isect.Quadric(range(10)).coeffs.tolist() == list(range(10))
    t = isect.Triangle([0, 0, 0], [1, 0, 0], [0, 1, 0])
    assert t.vertices.tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    assert isect.Plane([0, 0, 2], 1).d == 1.0
    assert isect.Ellipsoid([0, 0, 0], [1, 2, 3]).radii.tolist() == [1, 2, 3]
    ic = isect.InfiniteCylinder([1, 2, 3], [0, 0, 1], 0.5)
    assert ic.point.tolist() == [1, 2, 3] and ic.axis.tolist() == [0, 0, 1]
    assert isect.ConvexPolyhedron([[0, 0, 1, -1]]).planes.shape == (1, 4)


def test_shape_copies_its_input() -> None:
    """Changing the caller's array afterwards does not change the shape."""
    center = np.zeros(3)
    s = isect.Sphere(center, 1.0)
    center[0] = 100.0
    assert s.intersect([0, 0, -5], [0, 0, 1])["t"] == 4.0


def test_transformed_composes() -> None:
    """transformed(B) of transformed(A) equals transformed(B @ A) bit for bit."""
    a = np.array([[1, 0, 0, 1], [0, 2, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)
    c, s = math.cos(0.3), math.sin(0.3)
    b = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 3], [0, 0, 0, 1]])
    box = isect.Box([-1, -1, -1], [1, 1, 1])
    two = box.transformed(a).transformed(b)
    one = box.transformed(b @ a)
    assert two.matrix is not None and np.array_equal(two.matrix, b @ a)
    dirs = np.random.default_rng(1).normal(size=(100, 3))
    h1 = one.intersect([0.5, 0.2, 3.1], dirs)
    h2 = two.intersect([0.5, 0.2, 3.1], dirs)
    assert h1.tobytes() == h2.tobytes()
    assert box.matrix is None  # the original is unchanged
    assert two.transformed(np.eye(4)).intersect([0.5, 0.2, 3.1], dirs).tobytes() == h1.tobytes()


def test_transform_accepts_16_numbers() -> None:
    """A flat list of 16 numbers is a row-major 4x4 matrix."""
    m = [1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    moved = SPHERE.transformed(m)
    assert moved.intersect_all([0, 0, 0], [1, 0, 0])[0].t == 4.0


# ------------------------------------------------------------------- queries


def test_intersect_single_ray_is_a_record() -> None:
    """Two (3,) inputs give one HIT_DTYPE record equal to the first hit."""
    rec = SPHERE.intersect([0, 0, -5], [0, 0, 1])
    assert isinstance(rec, np.void) and rec.dtype == isect.HIT_DTYPE
    first = SPHERE.intersect_all([0, 0, -5], [0, 0, 1])[0]
    assert rec["t"] == first.t == 4.0
    assert tuple(rec["point"]) == first.point and tuple(rec["normal"]) == first.normal
    assert rec["kind"] == first.kind == isect.HitKind.ENTER and rec["prim"] == -1


def test_intersect_all_returns_hits() -> None:
    """intersect_all gives Hit tuples with HitKind kinds, sorted by t."""
    hits = SPHERE.intersect_all([0, 0, -5], [0, 0, 2])
    assert [h.t for h in hits] == [2.0, 3.0]
    assert [h.kind for h in hits] == [isect.HitKind.ENTER, isect.HitKind.EXIT]
    assert all(isinstance(h, isect.Hit) and isinstance(h.kind, isect.HitKind) for h in hits)
    assert hits[1].point == (0.0, 0.0, 1.0) and hits[1].normal == (0.0, 0.0, 1.0)
    assert hits[0]._fields == ("t", "point", "normal", "uv", "prim", "kind")
    assert SPHERE.intersect_all([0, 0, -5], [0, 1, 0]) == []
    assert len(SPHERE.intersect_all([0, 0, -5], [0, 0, 1], tmin=4.5, tmax=10)) == 1
    assert len(SPHERE.intersect_all(np.array([0, 0, -5.0]), (0, 0, 1))) == 2


@pytest.mark.parametrize(
    "shape",
    [*one_of_each(), isect.Mesh(*icosphere(1)), SPHERE.transformed(np.diag([2.0, 1, 3, 1]))],
    ids=lambda s: type(s).__name__,
)
def test_intersect_all_holds_the_batch_records(shape: isect.Shape) -> None:
    """intersect_all's Hit tuples hold, bit for bit, the records that
    intersect_all_batch gives for the same ray, as Python floats, an int and
    a HitKind."""
    rng = np.random.default_rng(11)
    for _ in range(40):
        origin = rng.normal(size=3) * 4
        direction = rng.normal(size=3) - origin
        hits = shape.intersect_all(origin, direction)
        offsets, records = shape.intersect_all_batch(origin, direction)
        assert len(hits) == offsets[1] == len(records)
        for hit, record in zip(hits, records, strict=True):
            floats = (hit.t, *hit.point, *hit.normal, *hit.uv)
            assert struct.pack("=9d2i", *floats, hit.prim, hit.kind) == record.tobytes()
            assert all(type(x) is float for x in floats) and type(hit.prim) is int
            assert type(hit.kind) is isect.HitKind
            assert len(hit.point) == len(hit.normal) == 3 and len(hit.uv) == 2


def test_intersect_all_many_hits_grow_the_buffer() -> None:
    """A shape with more hits than the scratch buffer still reports all (the
    scratch grows); analytic shapes have at most 4, so call it from a fresh
    thread to exercise the per-thread buffers too."""
    out: list[list[isect.Hit]] = []
    thread = threading.Thread(
        target=lambda: out.append(
            isect.Box([0, 0, 0], [1, 1, 1]).intersect_all([0.5, 0.5, -1], [0, 0, 1])
        )
    )
    thread.start()
    thread.join()
    assert [h.prim for h in out[0]] == [4, 5]


def test_broadcasting() -> None:
    """One origin against many directions, many origins against one direction,
    grids of rays, and per-ray tmin/tmax."""
    rng = np.random.default_rng(7)
    dirs = rng.normal(size=(50, 3))
    many = SPHERE.intersect([0, 0, -5], dirs)
    assert many.shape == (50,)
    for i in (0, 17, 49):
        assert many[i].tobytes() == SPHERE.intersect([0, 0, -5], dirs[i]).tobytes()
    origins = rng.normal(size=(4, 5, 3)) * 3
    grid = SPHERE.intersect(origins, [0, 0, 1])
    assert grid.shape == (4, 5)
    assert grid[2, 3].tobytes() == SPHERE.intersect(origins[2, 3], [0, 0, 1]).tobytes()
    tmax = np.array([3.0, 4.5, 10.0])
    lim = SPHERE.intersect([0, 0, -5], [0, 0, 1], tmax=tmax[:, None][:, 0])
    assert lim["kind"].tolist() == [isect.HitKind.MISS, isect.HitKind.ENTER, isect.HitKind.ENTER]
    assert math.isinf(lim["t"][0]) and lim["prim"][0] == -1


def test_intersect_rays_zero_copy_equals_intersect() -> None:
    """intersect_rays over a RAY_DTYPE array equals intersect()."""
    rng = np.random.default_rng(3)
    rays = np.zeros(1000, dtype=isect.RAY_DTYPE)
    rays["org"] = rng.normal(size=(1000, 3)) * 4
    rays["dir"] = rng.normal(size=(1000, 3))
    rays["tmax"] = np.inf
    a = SPHERE.intersect_rays(rays)
    b = SPHERE.intersect(rays["org"], rays["dir"])
    assert a.tobytes() == b.tobytes()
    strided = SPHERE.intersect_rays(rays[::2])
    assert strided.tobytes() == a[::2].tobytes()
    assert SPHERE.intersect_rays(rays.reshape(10, 100)).shape == (10, 100)


def test_intersect_all_batch_csr() -> None:
    """offsets/hits agree with intersect_all for every ray."""
    rng = np.random.default_rng(11)
    origins = rng.normal(size=(300, 3)) * 3
    dirs = rng.normal(size=(300, 3))
    for shape in one_of_each():
        offsets, hits = shape.intersect_all_batch(origins, dirs)
        assert offsets.dtype == np.int64 and offsets[0] == 0 and len(offsets) == 301
        assert hits.dtype == isect.HIT_DTYPE and len(hits) == offsets[-1]
        for i in range(0, 300, 7):
            one = shape.intersect_all(origins[i], dirs[i])
            got = hits[offsets[i] : offsets[i + 1]]
            assert len(got) == len(one)
            for rec, hit in zip(got, one):
                assert rec["t"] == hit.t and rec["kind"] == hit.kind and rec["prim"] == hit.prim


def test_contains() -> None:
    """Points in closed solids, as bool arrays (or a bool for one point)."""
    assert SPHERE.contains([0, 0, 0]) is True
    assert SPHERE.contains([0, 0, 1]) is True  # closed set
    assert SPHERE.contains([0, 0, 1.5]) is False
    inside = SPHERE.contains(np.array([[0, 0, 0], [2, 0, 0], [0.5, 0.5, 0.5]]))
    assert inside.dtype == np.bool_ and inside.tolist() == [True, False, True]
    assert SPHERE.contains(np.zeros((2, 3, 3))).shape == (2, 3)
    assert SPHERE.contains(np.zeros((0, 3))).shape == (0,)


def test_empty_batches() -> None:
    """Zero rays give empty results."""
    assert SPHERE.intersect(np.zeros((0, 3)), [0, 0, 1]).shape == (0,)
    offsets, hits = SPHERE.intersect_all_batch(np.zeros((0, 3)), [0, 0, 1])
    assert offsets.tolist() == [0] and len(hits) == 0


def test_errors_mark_and_raise() -> None:
    """errors="mark" marks bad rays INVALID; "raise" names the first bad one."""
    origins = np.zeros((6, 3))
    origins[:, 2] = -5
    origins[3, 0] = np.nan
    dirs = np.tile([0.0, 0.0, 1.0], (6, 1))
    dirs[5] = 0.0
    marked = SPHERE.intersect(origins, dirs, errors="mark")
    assert marked["kind"].tolist() == [1, 1, 1, 4, 1, 4]
    assert np.isnan(marked["t"][[3, 5]]).all()
    with pytest.raises(isect.NonFiniteError, match="ray 3") as info:
        SPHERE.intersect(origins, dirs)
    assert info.value.index == 3
    origins[3, 0] = 0.0
    with pytest.raises(isect.DegenerateError, match="ray 5") as info2:
        SPHERE.intersect(origins, dirs)
    assert info2.value.index == 5
    offsets, hits = SPHERE.intersect_all_batch(origins, dirs, errors="mark")
    assert offsets[6] - offsets[5] == 1 and hits[-1]["kind"] == isect.HitKind.INVALID
    with pytest.raises(isect.DegenerateError) as info3:
        SPHERE.intersect_all_batch(origins, dirs)
    assert info3.value.index == 5


def test_options() -> None:
    """eps, cull_back and any_hit reach the C library."""
    tri = isect.Triangle([-1, -1, 0], [1, -1, 0], [0, 1, 0])  # normal +z
    down, up = [0, 0, 1], [0, 0, -1]
    assert tri.intersect_all([0, 0, -1], down)[0].kind == isect.HitKind.EXIT
    assert tri.intersect_all([0, 0, -1], down, cull_back=True) == []
    assert tri.intersect_all([0, 0, 1], up, cull_back=True)[0].kind == isect.HitKind.ENTER
    assert tri.intersect([0, 0, -1], down, cull_back=True)["kind"] == isect.HitKind.MISS
    # eps reaches C: a plane 1e-9 off parallel is crossed at eps 0 and
    # parallel (not hit) at eps 1e-6; faces use no eps (revision 2)
    grazing = [1.0, 0.0, 1e-9]
    plane = isect.Plane([0, 0, 1], 0.0)
    assert len(plane.intersect_all([-5, 0, -5e-9], grazing, eps=0.0)) == 1
    assert plane.intersect_all([-5, 0, -5e-9], grazing, eps=1e-6) == []
    assert len(tri.intersect_all([-5, 0, -5e-9], grazing, eps=1e-6)) == 1
    rec = SPHERE.intersect([0, 0, -5], [0, 0, 1], any_hit=True)
    assert rec["kind"] in (isect.HitKind.ENTER, isect.HitKind.EXIT)


# ------------------------------------------------------------------- helpers


def test_polygon_helpers() -> None:
    """polygon_normal, plane_from_points, point_in_polygon, winding_number."""
    square = [[0, 0, 2], [1, 0, 2], [1, 1, 2], [0, 1, 2]]
    assert isect.polygon_normal(square).tolist() == [0.0, 0.0, 1.0]
    assert isect.plane_from_points(square).tolist() == [0.0, 0.0, 1.0, -2.0]
    sq2 = [[0, 0], [1, 0], [1, 1], [0, 1]]
    pts = np.array([[0.5, 0.5], [2, 2], [0.25, 0.75]])
    assert isect.point_in_polygon(sq2, pts).tolist() == [True, False, True]
    assert isect.point_in_polygon(sq2, [0.5, 0.5]) is True
    assert isect.winding_number(sq2, pts).tolist() == [1, 0, 1]
    assert isect.winding_number(sq2[::-1], [0.5, 0.5]) == -1
    twice = sq2 + sq2
    assert isect.winding_number(twice, [0.5, 0.5]) == 2
    assert isect.point_in_polygon(twice, [0.5, 0.5], rule="evenodd") is False
    assert isect.point_in_polygon(twice, [0.5, 0.5], rule="nonzero") is True
    assert isect.winding_number(sq2, np.zeros((2, 2, 2))).shape == (2, 2)


def test_half_open_rule_assigns_shared_edges_once() -> None:
    """Two squares sharing an edge: every point on it belongs to exactly one."""
    left = [[0, 0], [1, 0], [1, 1], [0, 1]]
    right = [[1, 0], [2, 0], [2, 1], [1, 1]]
    pts = np.column_stack([np.ones(11), np.linspace(0.05, 0.95, 11)])
    a = isect.point_in_polygon(left, pts)
    b = isect.point_in_polygon(right, pts)
    assert np.all(a ^ b)


# ----------------------------------------------------------------------- GIL


def test_batch_calls_release_the_gil() -> None:
    """While one thread is inside a long C batch call, another thread keeps
    running Python code (it would stall for the whole call if the GIL were
    held)."""
    rng = np.random.default_rng(5)
    n = 400_000
    rays = np.zeros(n, dtype=isect.RAY_DTYPE)
    rays["org"] = rng.normal(size=(n, 3)) * 4
    rays["dir"] = rng.normal(size=(n, 3))
    rays["tmax"] = np.inf
    poly = isect.Polygon(
        np.column_stack(
            [np.cos(np.linspace(0, 6.2, 200)), np.sin(np.linspace(0, 6.2, 200)), np.zeros(200)]
        )
    )
    start = time.perf_counter()
    poly.intersect_rays(rays)
    duration = time.perf_counter() - start

    done = threading.Event()
    gaps: list[float] = []

    def ticker() -> None:
        last = time.perf_counter()
        while not done.is_set():
            now = time.perf_counter()
            gaps.append(now - last)
            last = now
            time.sleep(0.0005)

    thread = threading.Thread(target=ticker)
    thread.start()
    time.sleep(0.01)
    poly.intersect_rays(rays)
    done.set()
    thread.join()
    assert duration > 0.02, "the batch is too short to measure"
    assert max(gaps) < duration / 2, (max(gaps), duration)
