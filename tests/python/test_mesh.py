# SPDX-License-Identifier: Apache-2.0
"""isect.Mesh: construction, bad input, the validity report, queries, threads."""

from __future__ import annotations

import gc
import math
import pickle
import weakref

import isect
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from isect._errors import error_for
from isect._isect import ffi, lib
from meshes import CUBE_QUADS, CUBE_VERTICES, cube_triangles, icosphere, inradius, torus


@pytest.fixture(scope="module")
def sphere() -> tuple[isect.Mesh, float]:
    """A 1280-triangle unit icosphere and its inradius."""
    v, f = icosphere(3)
    return isect.Mesh(v, f), inradius(v, f)


@pytest.fixture(scope="module")
def ring() -> isect.Mesh:
    """A triangulated torus, R = 2, r = 0.5, around the z axis."""
    return isect.Mesh(*torus())


# ---------------------------------------------------------------- building


def test_triangles_and_polygons() -> None:
    """(F, 3) triangles, a list of quads and an (F, 4) array build the same solid."""
    tri = isect.Mesh(CUBE_VERTICES, cube_triangles())
    quads = isect.Mesh(CUBE_VERTICES, CUBE_QUADS)
    quad_array = isect.Mesh(CUBE_VERTICES, np.array(CUBE_QUADS, dtype=np.uint16))
    assert tri.face_offsets is None and tri.n_faces == 12
    assert quads.face_offsets is not None and quads.face_offsets.tolist() == [0, 4, 8, 12, 16, 20, 24]
    assert quad_array.n_faces == quads.n_faces == 6
    assert [f.tolist() for f in quads.faces] == CUBE_QUADS
    assert tri.faces.shape == (12, 3) and not tri.faces.flags.writeable
    for m in (tri, quads, quad_array):
        hit = m.intersect([0.25, 0.5, -1], [0, 0, 1])
        assert hit["t"] == 1.0 and hit["kind"] == isect.HitKind.ENTER
        assert hit["normal"].tolist() == [0.0, 0.0, -1.0]
        assert m.nbytes > 0
    tris = cube_triangles()
    rest = np.concatenate([tris[1:6], tris[7:]]).tolist()
    mixed = isect.Mesh(CUBE_VERTICES, [CUBE_QUADS[0], *rest])
    assert mixed.check().faces == 11 and mixed.check().closed
    assert repr(quads) == "Mesh(<8 vertices, 6 faces>)"


def test_input_is_copied() -> None:
    """Changing the caller's arrays afterwards does not change the mesh."""
    v = CUBE_VERTICES.copy()
    f = cube_triangles()
    m = isect.Mesh(v, f)
    v += 10
    f[:] = 0
    assert m.check().volume == 1.0
    assert not m.vertices.flags.writeable and m.vertices[6].tolist() == [1.0, 1.0, 1.0]


def test_empty_mesh() -> None:
    """No faces: valid, never hit, an empty report."""
    m = isect.Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int32))
    assert m.intersect([0, 0, -1], [0, 0, 1])["kind"] == isect.HitKind.MISS
    r = m.check()
    assert (r.faces, r.edges, r.vertices, r.area) == (0, 0, 0, 0.0)
    assert isect.Mesh(CUBE_VERTICES, []).n_faces == 0


@pytest.mark.parametrize(
    ("vertices", "faces", "error"),
    [
        (CUBE_VERTICES, [[0, 1, 8]], isect.InvalidArgumentError),  # index == nv
        (CUBE_VERTICES, [[0, 1, -1]], isect.InvalidArgumentError),
        (CUBE_VERTICES, [[0, 1, 2**40]], isect.InvalidArgumentError),
        (CUBE_VERTICES, [[0, 1, 2, 3], [0, 1]], isect.InvalidArgumentError),  # ragged, < 3
        (CUBE_VERTICES, [[0, 1, 2], []], isect.InvalidArgumentError),
        (CUBE_VERTICES, np.array([[0, 1], [1, 2]]), isect.InvalidArgumentError),  # (F, 2)
        (CUBE_VERTICES, [[0.0, 1.0, 2.0]], isect.InvalidArgumentError),  # not integers
        (CUBE_VERTICES, [[[0, 1, 2]]], isect.InvalidArgumentError),  # nested too deep
        (CUBE_VERTICES[:, :2], [[0, 1, 2]], isect.InvalidArgumentError),  # (V, 2)
        (np.where(np.arange(24).reshape(8, 3) == 5, np.nan, CUBE_VERTICES), CUBE_QUADS, isect.NonFiniteError),
        (np.where(np.arange(24).reshape(8, 3) == 0, -np.inf, CUBE_VERTICES), [[0, 1, 2]], isect.NonFiniteError),
    ],
    ids=[
        "index-nv",
        "index-negative",
        "index-huge",
        "face-of-2",
        "face-of-0",
        "array-of-pairs",
        "float-indices",
        "nested",
        "vertices-2d",
        "nan-vertex",
        "inf-vertex",
    ],
)
def test_bad_input(vertices: np.ndarray, faces: object, error: type[Exception]) -> None:
    """Each class of bad input raises its documented error."""
    with pytest.raises(error):
        isect.Mesh(vertices, faces)


def test_bad_counts_from_c() -> None:
    """Negative counts and bad offsets (not expressible through Mesh) are
    ISECT_E_ARG from isect_mesh_create, which maps to InvalidArgumentError;
    *out stays NULL."""
    verts = ffi.new("double[]", CUBE_VERTICES.ravel().tolist())
    idx = ffi.new("int32_t[]", [0, 1, 2, 0, 2, 3])
    out = ffi.new("isect_mesh **")
    for nv, offsets, nf in [(-1, ffi.NULL, 2), (8, ffi.NULL, -1), (8, ffi.new("int64_t[]", [0, 4, 3]), 2)]:
        status = lib.isect_mesh_create(verts, nv, idx, offsets, nf, out)
        assert status == lib.ISECT_E_ARG and out[0] == ffi.NULL
        assert isinstance(error_for(status, "Mesh"), isect.InvalidArgumentError)
    lib.isect_mesh_destroy(ffi.NULL)  # a no-op


def test_handle_lifetime() -> None:
    """The handle outlives the Mesh in transformed copies; the Mesh is freed
    when unreferenced (the finalizer runs with the last holder)."""
    m = isect.Mesh(CUBE_VERTICES, CUBE_QUADS)
    ref = weakref.ref(m)
    moved = m.transformed([[2, 0, 0, 5], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]])
    again = moved.transformed(np.eye(4))
    del m
    gc.collect()
    assert ref() is None
    hits = moved.intersect_all([6, 1, -1], [0, 0, 1])
    assert [h.t for h in hits] == [1.0, 3.0] and [h.prim for h in hits] == [0, 1]
    assert again.contains([6.0, 1.0, 1.0]) and not again.contains([1.0, 1.0, 1.0])
    assert moved.check().volume == 1.0  # object space
    clone = pickle.loads(pickle.dumps(again))
    assert isinstance(clone, isect.Mesh) and np.array_equal(clone.matrix, again.matrix)
    assert clone.intersect([6, 1, -1], [0, 0, 1])["t"] == 1.0


# ----------------------------------------------------------------- report


def test_report_cube() -> None:
    """Cube of quads: V 8, E 12, F 6, chi 2, genus 0, volume 1, area 6."""
    r = isect.Mesh(CUBE_VERTICES, CUBE_QUADS).check()
    assert r == isect.MeshReport(
        vertices=8, edges=12, faces=6, boundary_edges=0, nonmanifold_edges=0,
        misoriented_edges=0, degenerate_faces=0, components=1, euler_characteristic=2,
        genus=0, closed=True, oriented=True, volume=1.0, area=6.0,
    )  # fmt: skip
    with pytest.raises(AttributeError):
        r.volume = 2.0  # type: ignore[misc]


def test_report_torus(ring: isect.Mesh) -> None:
    """Torus: chi 0, genus 1; volume and area near 2 pi^2 R r^2 and 4 pi^2 R r."""
    r = ring.check()
    assert (r.euler_characteristic, r.genus, r.components, r.closed, r.oriented) == (0, 1, 1, True, True)
    assert r.volume == pytest.approx(2 * math.pi**2 * 2 * 0.25, rel=0.07)
    assert r.area == pytest.approx(4 * math.pi**2 * 2 * 0.5, rel=0.03)


def test_report_open_and_flipped() -> None:
    """A cube without its top: 4 boundary edges, not closed, genus -1, no
    contains. One quad flipped: its 4 edges misoriented, volume no longer 1."""
    open_cube = isect.Mesh(CUBE_VERTICES, CUBE_QUADS[:1] + CUBE_QUADS[2:])
    r = open_cube.check()
    assert (r.boundary_edges, r.closed, r.genus, r.faces) == (4, False, -1, 5)
    with pytest.raises(isect.InvalidArgumentError):
        open_cube.contains([0.5, 0.5, 0.5])
    flipped = [list(reversed(CUBE_QUADS[0])), *CUBE_QUADS[1:]]
    r = isect.Mesh(CUBE_VERTICES, flipped).check()
    assert (r.misoriented_edges, r.oriented, r.closed, r.genus) == (4, False, True, -1)
    assert r.volume != 1.0


def test_report_degenerate_face_and_components() -> None:
    """A zero-area face is counted and never hit; two cubes are 2 components
    (the sliver shares edge 0-1 with the first, making it non-manifold)."""
    verts = np.vstack([CUBE_VERTICES, CUBE_VERTICES + 3, [[0.5, 0, 0]]])
    faces = [*CUBE_QUADS, *(np.array(CUBE_QUADS) + 8).tolist(), [0, 16, 1]]
    m = isect.Mesh(verts, faces)
    r = m.check()
    assert (r.degenerate_faces, r.components, r.faces, r.nonmanifold_edges) == (1, 2, 13, 1)
    assert r.volume == 2.0 and r.area == 12.0
    hits = m.intersect_all([0.25, -1e-300, 0], [1, 0, 0], tmax=10)
    assert all(h.prim != 12 for h in hits)


# ---------------------------------------------------------------- queries


def test_contains_icosphere(sphere: tuple[isect.Mesh, float]) -> None:
    """Away from the surface shell [inradius, 1] contains is |p| < 1."""
    mesh, rin = sphere
    rng = np.random.default_rng(7)
    pts = rng.uniform(-1.5, 1.5, size=(20_000, 3))
    r = np.linalg.norm(pts, axis=1)
    pts = pts[(r < rin * (1 - 1e-6)) | (r > 1 + 1e-6)]
    inside = mesh.contains(pts)
    assert inside.dtype == np.bool_ and len(pts) > 15_000
    assert np.array_equal(inside, np.linalg.norm(pts, axis=1) < 1)
    assert mesh.contains(mesh.vertices).all()  # surface points are inside


def test_closest_is_first_of_all(sphere: tuple[isect.Mesh, float]) -> None:
    """intersect == the first record of intersect_all_batch, ray by ray; the
    single-ray intersect_all agrees with the batch."""
    mesh, _ = sphere
    rng = np.random.default_rng(11)
    origins = rng.normal(size=(5000, 3)) * 2
    dirs = rng.uniform(-1, 1, size=(5000, 3)) - origins  # most rays aim at the sphere
    closest = mesh.intersect(origins, dirs)
    offsets, hits = mesh.intersect_all_batch(origins, dirs)
    counts = np.diff(offsets)
    hit = counts > 0
    assert np.array_equal(closest["kind"] != isect.HitKind.MISS, hit)
    assert hit.sum() > 1000
    assert closest[hit].tobytes() == hits[offsets[:-1][hit]].tobytes()
    for i in range(0, 5000, 250):
        single = mesh.intersect_all(origins[i], dirs[i])
        assert [h.t for h in single] == hits["t"][offsets[i] : offsets[i + 1]].tolist()
    anyhit = mesh.intersect(origins, dirs, any_hit=True)
    assert np.array_equal(anyhit["kind"] != isect.HitKind.MISS, hit)


def test_threads_identical(sphere: tuple[isect.Mesh, float]) -> None:
    """threads=2/3 give the bytes of one thread, for every batch query."""
    mesh, _ = sphere
    rng = np.random.default_rng(3)
    origins = rng.normal(size=(40_000, 3)) * 2
    dirs = rng.normal(size=(40_000, 3))
    one = mesh.intersect(origins, dirs)
    offsets, hits = mesh.intersect_all_batch(origins, dirs)
    inside = mesh.contains(origins)
    for threads in (2, 3):
        assert mesh.intersect(origins, dirs, threads=threads).tobytes() == one.tobytes()
        o2, h2 = mesh.intersect_all_batch(origins, dirs, threads=threads)
        assert np.array_equal(o2, offsets) and h2.tobytes() == hits.tobytes()
        assert np.array_equal(mesh.contains(origins, threads=threads), inside)


# --------------------------------------------------------------- parity

_torus_v, _torus_f = torus()
_TORUS = isect.Mesh(_torus_v, _torus_f)
_unit = st.floats(0.0, 1.0)


def _torus_point(u: float, v: float, rho: float) -> np.ndarray:
    """A point at distance rho from the torus core circle (R = 2)."""
    a, b = 2 * math.pi * u, 2 * math.pi * v
    ring = 2.0 + rho * math.cos(b)
    return np.array([ring * math.cos(a), ring * math.sin(a), rho * math.sin(b)])


@given(_unit, _unit, st.floats(0.0, 0.4), st.integers(0, len(_torus_v) - 1), st.booleans())
def test_parity_inside(u: float, v: float, rho: float, k: int, at_vertex: bool) -> None:
    """From a point inside the closed torus every ray crosses it an odd number
    of times — also a ray aimed exactly at a mesh vertex (exactly-once)."""
    p = _torus_point(u, v, rho)
    d = _torus_v[k] - p if at_vertex else _torus_point(v, u, 0.3) - p + [0.1, 0.0, 0.0]
    n = len(_TORUS.intersect_all(p, d, eps=0.0))
    assert n % 2 == 1, (p, d, n)
    assert _TORUS.contains(p)


@given(_unit, _unit, st.floats(0.6, 3.0), st.integers(0, len(_torus_v) - 1))
def test_parity_outside(u: float, v: float, rho: float, k: int) -> None:
    """From a point outside, a ray through a vertex crosses an even number of times."""
    p = _torus_point(u, v, rho)
    n = len(_TORUS.intersect_all(p, _torus_v[k] - p, eps=0.0))
    assert n % 2 == 0, (p, k, n)
    assert not _TORUS.contains(p)
