# SPDX-License-Identifier: Apache-2.0
"""Shape.spawn (isect_spawn_ray, SPEC revision 2): secondary rays through the Python API.

Every shape class (meshes and transformed shapes included) spawns rays from
its own hits: the result is ``RAY_DTYPE`` (a record for one hit), carries the
direction unchanged, tmin 0, tmax +inf and an origin within a few ulps of the
hit point; batches broadcast, equal the one-hit calls bit for bit, split over
threads without changing a byte, and run as one C loop (no Python loop per
row). Bad rows raise the typed error naming their index. Properties
(hypothesis): the spawned ray never meets the surface it leaves at t ~ 0 —
for convex solids and flat surfaces an outgoing ray meets nothing at all —
and a solid contains the spawned origin exactly when the direction points
inwards.

The golden corpus (tests/cases/spawn.json) checks the secondary hits
against the exact reference; these tests check the API and the invariants.
"""

from __future__ import annotations

import math
import struct
from collections import Counter
from typing import Any

import isect
import isect._shape as shape_module
import numpy as np
import pytest
from hypothesis import assume, given, note
from hypothesis import strategies as st
from meshes import CUBE_QUADS, CUBE_VERTICES, cube_triangles
from strategies import (
    Sample,
    affine,
    aimed_rays,
    bounded_solids,
    nonzero_vec3,
    one_of_each,
    planes,
    polygons,
    rotations,
    transformed,
    triangles,
    vec3,
)

#: The spawned origin lies within this many ulps (of the hit point's largest
#: coordinate) of the hit point, per coordinate (the corpus runners' bound).
MAX_ULPS = 8
HITS = (isect.HitKind.ENTER, isect.HitKind.EXIT, isect.HitKind.TOUCH)


def bits(a: Any) -> bytes:
    return np.asarray(a).tobytes()


def cube_mesh(quads: bool) -> isect.Mesh:
    return isect.Mesh(CUBE_VERTICES, CUBE_QUADS if quads else cube_triangles())


def every_shape() -> list[tuple[str, isect.Shape, np.ndarray]]:
    """(name, shape, a point inside or on it to aim primary rays at)."""
    out = [(type(s).__name__ + str(i), s, np.array([0.05, 0.1, 0.15])) for i, s in enumerate(one_of_each())]
    out += [
        ("Mesh-triangles", cube_mesh(False), np.array([0.5, 0.4, 0.3])),
        ("Mesh-quads", cube_mesh(True), np.array([0.5, 0.4, 0.3])),
    ]
    m = affine(np.array([[0.0, -2.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.5]]), np.array([1.0, 2.0, 3.0]))
    out += [
        ("Sphere-transformed", isect.Sphere([0, 0, 0], 1).transformed(m), np.array([1.0, 2.0, 3.0])),
        ("Mesh-transformed", cube_mesh(False).transformed(m), m[:3, :3] @ [0.5, 0.4, 0.3] + m[:3, 3]),
    ]
    return out


SHAPES = every_shape()
ORIGIN = np.array([7.0, 5.0, 9.0])


def first_hit(shape: isect.Shape, target: np.ndarray) -> Any:
    hit = shape.intersect(ORIGIN, target - ORIGIN)
    assert hit["kind"] in HITS, "the primary ray must hit"
    return hit


def near_point(ray: Any, point: Any) -> bool:
    """ray's origin lies within MAX_ULPS ulps of point, per coordinate."""
    p = np.asarray(point, dtype=np.float64)
    unit = np.spacing(np.abs(p).max())
    return bool(np.all(np.abs(np.asarray(ray["org"]) - p) <= MAX_ULPS * unit))


def directions_at(hit: Any) -> list[np.ndarray]:
    """Outgoing, inward and reflected directions at a hit."""
    n = np.asarray(hit["normal"])
    d = np.asarray([-0.3, 0.2, -1.0])
    return [n + [0.1, -0.2, 0.05], -n + [0.05, 0.1, -0.1], d - 2 * (d @ n) * n]


@pytest.mark.parametrize(("name", "shape", "target"), SHAPES, ids=[s[0] for s in SHAPES])
def test_spawn_one_hit(name: str, shape: isect.Shape, target: np.ndarray) -> None:
    """One hit, one direction: a RAY_DTYPE record with dir, tmin 0, tmax inf
    and an origin a few ulps from the hit point, on the side dir points into."""
    hit = first_hit(shape, target)
    for d in directions_at(hit):
        ray = shape.spawn(hit, d)
        assert isinstance(ray, np.void) and ray.dtype == isect.RAY_DTYPE
        assert bits(ray["dir"]) == bits(np.asarray(d, dtype=np.float64))
        assert ray["tmin"] == 0.0 and ray["tmax"] == math.inf
        assert near_point(ray, hit["point"]), (ray, hit)
        side = float(np.asarray(ray["org"]) @ hit["normal"] - np.asarray(hit["point"]) @ hit["normal"])
        assert side * float(d @ hit["normal"]) >= 0  # never on the wrong side of the tangent plane
        solid = isinstance(shape, isect.Solid) and not (isinstance(shape, isect.Cylinder) and not shape.capped)
        if solid:
            assert shape.contains(ray["org"]) == bool(d @ hit["normal"] < 0)


@pytest.mark.parametrize(("name", "shape", "target"), SHAPES, ids=[s[0] for s in SHAPES])
def test_spawn_forms_agree(name: str, shape: isect.Shape, target: np.ndarray) -> None:
    """A Hit tuple, a record, a (1,) array and batches give the same bytes."""
    hit = first_hit(shape, target)
    d = directions_at(hit)[1]
    one = shape.spawn(hit, d)
    as_tuple = shape.spawn(shape.intersect_all(ORIGIN, target - ORIGIN)[0], d)
    assert bits(as_tuple) == bits(one)
    assert bits(shape.spawn(np.asarray([hit]), [d])[0]) == bits(one)
    hits = np.stack([hit] * 5)
    dirs = np.stack([d] * 5)
    assert bits(shape.spawn(hits, dirs)) == bits(np.stack([one] * 5))
    assert bits(shape.spawn(hits, d)) == bits(np.stack([one] * 5))  # one direction for many hits
    assert bits(shape.spawn(hit, dirs)) == bits(np.stack([one] * 5))  # one hit, many directions
    assert bits(shape.spawn([shape.intersect_all(ORIGIN, target - ORIGIN)[0]] * 2, d)) == bits(
        np.stack([one] * 2)
    )


def test_spawn_batch_shapes_and_rows() -> None:
    """Broadcasting gives the batch shape; each row equals its one-hit call."""
    s = isect.Sphere([0.1, -0.2, 0.3], 1.25)
    rng = np.random.default_rng(7)
    dirs_in = rng.normal(size=(2, 3, 3))
    hits = s.intersect(np.zeros(3) + [5, 5, 5], dirs_in * 0.1 + [-5.1, -5.2, -4.7])
    assert hits.shape == (2, 3) and np.all(hits["kind"] == int(isect.HitKind.ENTER))
    new_dirs = rng.normal(size=(2, 3, 3))
    rays = s.spawn(hits, new_dirs)
    assert rays.shape == (2, 3) and rays.dtype == isect.RAY_DTYPE
    for i in range(2):
        for j in range(3):
            assert bits(rays[i, j]) == bits(s.spawn(hits[i, j], new_dirs[i, j]))
    assert s.spawn(hits[0], new_dirs[:, :1]).shape == (2, 3)  # (3,) hits against (2, 1, 3) dirs
    assert s.spawn(hits[0, :0], np.zeros((0, 3))).shape == (0,)


def test_spawn_threads_give_the_same_bytes() -> None:
    """Splitting a batch over threads changes nothing."""
    mesh = cube_mesh(False)
    rng = np.random.default_rng(3)
    n = 20000
    targets = rng.uniform(0.05, 0.95, size=(n, 3))
    hits = mesh.intersect(ORIGIN, targets - ORIGIN)
    dirs = rng.normal(size=(n, 3))
    assert np.all(np.isin(hits["kind"], [1, 2, 3]))
    assert bits(mesh.spawn(hits, dirs, threads=3)) == bits(mesh.spawn(hits, dirs))


def test_spawn_million_is_one_c_loop(monkeypatch: pytest.MonkeyPatch) -> None:
    """A batch of 10^6 is handed to the extension's C loop: isect_spawn_ray is
    never called from Python, pyisect_spawn_batch once per thread chunk."""
    real = shape_module.lib
    calls: Counter[str] = Counter()

    class CountingLib:
        def __getattr__(self, name: str) -> Any:
            calls[name] += 1
            return getattr(real, name)

    s = isect.Sphere([0, 0, 0], 1)
    hit = s.intersect([0, 0, -5], [0, 0, 1])
    n = 10**6
    dirs = np.random.default_rng(1).normal(size=(n, 3))
    monkeypatch.setattr(shape_module, "lib", CountingLib())
    rays = s.spawn(hit, dirs, threads=2)
    assert rays.shape == (n,)
    assert calls["isect_spawn_ray"] == 0
    assert 1 <= calls["pyisect_spawn_batch"] <= 2
    assert bits(rays["dir"]) == bits(dirs)
    assert np.all(rays["tmin"] == 0) and np.all(rays["tmax"] == math.inf)


# ---------------------------------------------------------------- bad input


def test_spawn_miss_and_invalid_records_raise_naming_the_row() -> None:
    """A MISS or INVALID record is not a hit: InvalidArgumentError for its row."""
    s = isect.Sphere([0, 0, 0], 1)
    origins = np.array([[0, 0, -5], [0, 0, -5], [0, 0, -5], [5, 5, -5.0]])
    hits = s.intersect(origins, [0, 0, 1])
    assert hits["kind"][3] == int(isect.HitKind.MISS)
    with pytest.raises(isect.InvalidArgumentError, match="hit 3") as info:
        s.spawn(hits, [0, 0, 1])
    assert info.value.index == 3
    marked = s.intersect([[0, 0, -5], [0, 0, math.nan]], [0, 0, 1], errors="mark")
    with pytest.raises(isect.InvalidArgumentError) as info:
        s.spawn(marked, [0, 0, 1])
    assert info.value.index == 1


def test_spawn_bad_directions_raise_naming_the_row() -> None:
    s = isect.Sphere([0, 0, 0], 1)
    hit = s.intersect([0, 0, -5], [0, 0, 1])
    dirs = np.array([[0, 0, -1], [1, 0, 0], [0, 0, 0], [0, 1, 0.0]])
    with pytest.raises(isect.DegenerateError) as info:
        s.spawn(hit, dirs)
    assert info.value.index == 2
    dirs[2] = [0, math.nan, 1]
    with pytest.raises(isect.NonFiniteError) as info:
        s.spawn(hit, dirs)
    assert info.value.index == 2
    with pytest.raises(isect.NonFiniteError):
        s.spawn(hit, [math.inf, 0, 0])


def test_spawn_bad_hit_records_raise() -> None:
    """A zero normal, a non-finite point or a mesh face index out of range."""
    mesh = cube_mesh(True)
    hit = mesh.intersect([0.5, 0.5, 2], [0, 0, -1])
    bad = hit.copy()
    bad["prim"] = 6
    with pytest.raises(isect.InvalidArgumentError):
        mesh.spawn(bad, [0, 0, 1])
    bad = hit.copy()
    bad["normal"] = 0
    with pytest.raises(isect.InvalidArgumentError):
        mesh.spawn(bad, [0, 0, 1])
    bad = hit.copy()
    bad["point"][1] = math.nan
    with pytest.raises(isect.NonFiniteError):
        mesh.spawn(bad, [0, 0, 1])


@pytest.mark.parametrize(
    ("hits", "dirs"),
    [
        (None, [0, 0, 1]),  # the NULL of C
        (np.zeros(3), [0, 0, 1]),  # not HIT_DTYPE
        ("hit", [0, 0, 1]),
        ("RECORD", [0, 1]),  # directions not (..., 3)
        ("RECORDS", np.zeros((4, 3))),  # (3,) hits against 4 directions
    ],
)
def test_spawn_malformed_arguments(hits: Any, dirs: Any) -> None:
    s = isect.Sphere([0, 0, 0], 1)
    hit = s.intersect([0, 0, -5], [0, 0, 1])
    hits = {"RECORD": hit, "RECORDS": np.stack([hit] * 3)}.get(hits, hits) if isinstance(hits, str) else hits
    with pytest.raises(isect.InvalidArgumentError):
        s.spawn(hits, dirs)


# ---------------------------------------------------------------- properties


def _hit_and_direction(data: st.DataObject, sample: Sample) -> tuple[Any, np.ndarray, float]:
    """A primary hit of a random aimed ray (its origin off the surface: the
    corpus covers origins on it), a unit direction clearly off the tangent
    plane there, and d.n."""
    origin, d = data.draw(aimed_rays(sample))
    hit = sample.shape.intersect(origin, d)
    assume(int(hit["kind"]) in (int(isect.HitKind.ENTER), int(isect.HitKind.EXIT)))
    assume(float(hit["t"]) * float(np.linalg.norm(d)) > 1e-6 * sample.scale)
    new = data.draw(nonzero_vec3(-1, 1, 0.2))
    new = new / np.linalg.norm(new)
    dn = float(new @ hit["normal"])
    assume(abs(dn) > 1e-3)
    return hit, new, dn


def _spawned_hits(sample: Sample, ray: Any) -> list[isect.Hit]:
    """Every hit of the spawned ray with the shape it left."""
    hits = sample.shape.intersect_all(ray["org"], ray["dir"], tmin=float(ray["tmin"]))
    note(f"spawned {ray}, hits {hits}")
    return hits


CONVEX = st.one_of(bounded_solids(), transformed(bounded_solids()))


@given(data=st.data(), sample=CONVEX)
def test_spawned_ray_never_meets_the_convex_surface_it_leaves(data: st.DataObject, sample: Sample) -> None:
    """Convex solids: an outgoing spawned ray meets nothing; an inward one
    leaves once (never entering again at t ~ 0; near an edge its exit may
    legitimately be close)."""
    hit, d, dn = _hit_and_direction(data, sample)
    hits = _spawned_hits(sample, sample.shape.spawn(hit, d))
    if dn > 0:
        assert hits == []
    else:
        assert [h.kind for h in hits] in ([isect.HitKind.EXIT], [isect.HitKind.TOUCH]), hits


@given(data=st.data(), sample=CONVEX)
def test_spawned_origin_is_on_the_side_it_leaves_to(data: st.DataObject, sample: Sample) -> None:
    """Solids contain the spawned origin exactly when dir points inwards."""
    hit, d, dn = _hit_and_direction(data, sample)
    ray = sample.shape.spawn(hit, d)
    assert sample.shape.contains(ray["org"]) == (dn < 0)


FLAT = st.one_of(planes(), triangles(), polygons(), transformed(st.one_of(planes(), triangles())))


@given(data=st.data(), sample=FLAT)
def test_spawned_ray_never_meets_the_flat_surface_it_leaves(data: st.DataObject, sample: Sample) -> None:
    """Planes, triangles and polygons: a spawned ray meets the surface it
    leaves nowhere, on either side (reflection or transmission)."""
    hit, d, _ = _hit_and_direction(data, sample)
    assert _spawned_hits(sample, sample.shape.spawn(hit, d)) == []


@st.composite
def placed_cubes(draw: st.DrawFn) -> Sample:
    """The unit cube mesh (triangles or quads), rotated, scaled and moved."""
    mesh = cube_mesh(draw(st.booleans()))
    scale = draw(st.floats(0.25, 4.0))
    lin = draw(rotations) * scale
    t = draw(vec3(-5, 5))
    m = affine(lin, t)
    return Sample(mesh.transformed(m), lin @ np.array([0.5, 0.5, 0.5]) + t, float(np.abs(t).max() + 2 * scale))


@given(data=st.data(), sample=placed_cubes())
def test_spawned_rays_of_a_closed_mesh(data: st.DataObject, sample: Sample) -> None:
    """A closed (convex) mesh: the origin is on the side dir points into, an
    outgoing ray meets nothing and an inward one leaves once."""
    hit, d, dn = _hit_and_direction(data, sample)
    ray = sample.shape.spawn(hit, d)
    assert sample.shape.contains(ray["org"]) == (dn < 0)
    hits = _spawned_hits(sample, ray)
    if dn > 0:
        assert hits == []
    else:
        assert [h.kind for h in hits] == [isect.HitKind.EXIT], hits


def test_bits_helper() -> None:
    """The byte comparison used above tells doubles apart by their bits."""
    assert bits(np.float64(0.0)) != bits(np.float64(-0.0))
    assert struct.pack("<d", 1.0) == bits(np.float64(1.0))
