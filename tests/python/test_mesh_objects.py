# SPDX-License-Identifier: Apache-2.0
"""isect.Mesh from mesh objects (a trimesh.Trimesh, any object with vertices
and faces attributes) and Mesh.to_trimesh()."""

from __future__ import annotations

import subprocess
import sys
from types import SimpleNamespace

import isect
import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

CUBE_V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                   [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)
CUBE_QUADS = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]


def l_prism() -> tuple[np.ndarray, list[list[int]]]:
    """A closed prism over an L-shaped (concave) hexagon, outward faces: two
    concave hexagons and six quads."""
    base = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]  # counter-clockwise
    v = np.array([[x, y, 0.0] for x, y in base] + [[x, y, 1.0] for x, y in base])
    bottom = [5, 4, 3, 2, 1, 0]  # seen from below: clockwise from above
    top = [6, 7, 8, 9, 10, 11]
    sides = [[i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6] for i in range(6)]
    return v, [bottom, top, *sides]


def rays(n: int = 2000, seed: int = 0, lo: float = 0.0, hi: float = 1.0
         ) -> tuple[np.ndarray, np.ndarray]:
    """Rays from a sphere of radius 4 around (0.5, 0.5, 0.5) aimed at points
    of the box [lo, hi]^3 (most of them hit a mesh in [0, 1]^3)."""
    rng = np.random.default_rng(seed)
    origins = rng.normal(size=(n, 3))
    origins = 0.5 + 4 * origins / np.linalg.norm(origins, axis=1, keepdims=True)
    return origins, rng.uniform(lo, hi, size=(n, 3)) - origins


def test_mesh_from_a_trimesh() -> None:
    """Mesh(trimesh.Trimesh) is Mesh(tm.vertices, tm.faces): the same bytes."""
    tm = trimesh.creation.icosphere(subdivisions=2)
    a, b = isect.Mesh(tm), isect.Mesh(np.asarray(tm.vertices), np.asarray(tm.faces))
    assert np.array_equal(a.vertices, tm.vertices) and np.array_equal(a.faces, tm.faces)
    o, d = rays()
    assert a.intersect(o, d, threads=1).tobytes() == b.intersect(o, d, threads=1).tobytes()
    assert a.check().closed


def test_mesh_from_any_object_with_vertices_and_faces() -> None:
    """Duck typing: lists, polygon faces, another isect.Mesh (its object-space
    geometry)."""
    duck = SimpleNamespace(vertices=CUBE_V.tolist(), faces=CUBE_QUADS)
    cube = isect.Mesh(duck)
    assert cube.n_faces == 6 and cube.check().volume == 1.0
    again = isect.Mesh(cube.transformed(np.diag([2.0, 2.0, 2.0, 1.0])))
    assert again.matrix is None and again.check().volume == 1.0
    assert isinstance(duck, isect.MeshLike) and not isinstance(CUBE_V, isect.MeshLike)


def test_mesh_object_errors() -> None:
    """Faces missing for an array, or given with a mesh object; bad arrays in
    the object are named as for two arguments."""
    with pytest.raises(isect.InvalidArgumentError, match=r"^faces: missing"):
        isect.Mesh(CUBE_V)  # type: ignore[call-arg]
    with pytest.raises(isect.InvalidArgumentError,
                       match=r"^faces: given, but vertices is a Trimesh"):
        isect.Mesh(trimesh.creation.box(), [[0, 1, 2]])
    with pytest.raises(isect.InvalidArgumentError,
                       match=r"^Mesh: faces\[1\]\[2\] = 8 is outside \[0, 8\)"):
        isect.Mesh(SimpleNamespace(vertices=CUBE_V, faces=[[0, 1, 2], [0, 1, 8]]))
    with pytest.raises(isect.InvalidArgumentError, match=r"^vertices: "):
        isect.Mesh(SimpleNamespace(vertices="abc", faces=[[0, 1, 2]]))


def test_to_trimesh_of_triangles_round_trips() -> None:
    """A triangle mesh: the same vertices and faces (face i = prim i)."""
    tm = trimesh.creation.icosphere(subdivisions=1)
    out = isect.Mesh(tm).to_trimesh()
    assert isinstance(out, trimesh.Trimesh)
    assert np.array_equal(out.vertices, tm.vertices) and np.array_equal(out.faces, tm.faces)
    assert "isect_face" not in out.face_attributes


@pytest.mark.parametrize("polygons", ["cube of quads", "L prism (concave faces)"])
def test_to_trimesh_of_polygons(polygons: str) -> None:
    """Polygon faces become triangles that cover each face exactly, with its
    orientation; isect_face maps them back; the same hits."""
    v, faces = (CUBE_V, CUBE_QUADS) if polygons == "cube of quads" else l_prism()
    mesh = isect.Mesh(v, faces)
    out = mesh.to_trimesh()
    owner = out.face_attributes["isect_face"]
    report = mesh.check()
    assert out.is_watertight and out.is_winding_consistent
    assert out.volume == pytest.approx(report.volume, rel=1e-12)
    assert out.area == pytest.approx(report.area, rel=1e-12)  # no triangle outside or doubled
    assert np.array_equal(np.unique(owner), np.arange(len(faces)))
    assert np.all(np.diff(owner) >= 0)  # the faces' order
    for f, face in enumerate(faces):  # each triangle: its face's corners, its normal
        tri = out.faces[owner == f]
        assert set(tri.ravel()) <= set(face)
        assert len(tri) == len(face) - 2
        normal = isect.polygon_normal(v[face])
        assert np.all(out.face_normals[owner == f] @ normal > 0.999)
    back = isect.Mesh(out)
    o, d = rays(hi=float(v.max()))
    h1 = mesh.intersect(o, d, threads=1)
    h2 = back.intersect(o, d, threads=1)
    hit = h1["kind"] != isect.HitKind.MISS
    assert np.array_equal(hit, h2["kind"] != isect.HitKind.MISS) and hit.sum() > 100
    assert np.array_equal(h1["kind"], h2["kind"])
    assert np.array_equal(owner[h2["prim"][hit]], h1["prim"][hit])
    assert np.allclose(h1["t"][hit], h2["t"][hit], rtol=1e-12, atol=0)


def test_to_trimesh_is_in_world_space() -> None:
    """A transformed mesh's vertices are mapped; a mirror reverses the faces so
    that the volume stays positive and the normals agree with the hits."""
    m = np.array([[0.0, -2, 0, 1], [1, 0, 0, 2], [0, 0, 3, 3], [0, 0, 0, 1]])
    cube = isect.Mesh(CUBE_V, CUBE_QUADS)
    moved = cube.transformed(m).to_trimesh()
    assert np.allclose(moved.vertices, CUBE_V @ m[:3, :3].T + m[:3, 3])
    assert moved.volume == pytest.approx(6.0)
    mirror = np.diag([-1.0, 1.0, 1.0, 1.0])
    tri = isect.Mesh(trimesh.creation.box())
    flipped = tri.transformed(mirror)
    out = flipped.to_trimesh()
    assert out.volume == pytest.approx(1.0) and out.is_winding_consistent
    hits = flipped.intersect([[-5.0, 0.1, 0.2]], [1.0, 0, 0], threads=1)
    assert hits["kind"][0] == isect.HitKind.ENTER
    assert np.allclose(out.face_normals[hits["prim"][0]], hits["normal"][0])


def test_to_trimesh_without_trimesh(monkeypatch: pytest.MonkeyPatch) -> None:
    """A clear ImportError when trimesh is missing."""
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(ImportError, match=r"Mesh.to_trimesh needs the trimesh package.*pip "
                                          r"install trimesh"):
        isect.Mesh(CUBE_V, CUBE_QUADS).to_trimesh()


def test_import_isect_does_not_import_trimesh() -> None:
    """trimesh is imported by to_trimesh and isect.trimesh only."""
    code = ("import sys, isect; isect.Mesh(isect.Mesh([[0,0,0],[1,0,0],[0,1,0]], [[0,1,2]])); "
            "print('trimesh' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_triangulation_of_random_concave_faces() -> None:
    """Star-shaped (often concave) polygons in random planes: k - 2 triangles
    of the face's orientation, inside it, adding up to its area."""
    from isect._triangulate import triangulate

    rng = np.random.default_rng(11)
    for trial in range(200):
        k = int(rng.integers(4, 14))
        # angular gaps below pi: a simple polygon, star-shaped from the origin
        angles = (np.arange(k) + rng.uniform(0, 0.9, k)) * (2 * np.pi / k)
        radii = rng.uniform(0.2, 1.0, k)
        flat = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])
        if trial % 2:
            flat = flat[::-1]  # clockwise too
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        v = np.column_stack([flat, np.zeros(k)]) @ q.T + rng.normal(size=3)
        tris, owner = triangulate(v, np.arange(k, dtype=np.int32), np.array([0, k]))
        assert tris.shape == (k - 2, 3) and np.all(owner == 0)
        area2 = (flat[:, 0] * np.roll(flat[:, 1], -1) - np.roll(flat[:, 0], -1) * flat[:, 1]).sum()
        a, b, c = flat[tris[:, 0]], flat[tris[:, 1]], flat[tris[:, 2]]
        ab, ac = b - a, c - a
        signed = ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0]
        assert np.all(np.sign(signed) == np.sign(area2))  # the face's orientation
        assert signed.sum() == pytest.approx(area2, rel=1e-9)
        assert np.all(isect.point_in_polygon(flat, (a + b + c) / 3))
