# SPDX-License-Identifier: Apache-2.0
"""libisect demo: two pictures rendered through the Python API (``isect``).

``demo/scene.png``
    Every primitive of libisect in one scene — sphere, box, a concave polygon,
    a self-intersecting pentagram under each fill rule (even-odd: hollow
    centre; non-zero: filled), a convex polyhedron, a capped cylinder, an
    ellipsoid, a clipped quadric (a hyperboloid of one sheet, kept where the
    hit lies in a box), a rotated and sheared box, and a closed triangle mesh
    (a torus) — each in its own colour, shaded by its normal. Every object is
    intersected with all camera rays in one threaded batch call; the closest
    hit of a pixel is the smallest t over the per-object results. All hit
    points and normals come from libisect; Python only makes camera rays and
    shades. The caption gives the throughput.

``demo/exactly_once.png``
    Why the library exists: a closed mesh (a sphere of integer-coordinate
    triangles) and rays from inside it aimed exactly at every vertex and every
    edge midpoint — the places where a ray meets two to six triangles at once.
    Such a ray leaves the solid once, so it must cross the surface exactly once:
    0 crossings is a leak, 2 or more a double hit (either breaks the parity of
    a crossing-count inside test). Left: libisect's mesh (``intersect_all_batch``,
    every crossing). Right: Embree through ``embreex``, counting every
    triangle Embree reports as hit (as an all-hits traversal does; triangles
    that share a vertex are put in different scenes so each decision is seen).
    Dots show the targets on the camera side: green once, red leak, yellow
    double hit. Without embreex the right half says so and is skipped.

``demo/winding.png``
    Containment of a mesh that is not closed: a torus with a window cut into
    its outer wall, sliced by the plane of its equator, each point coloured by
    the generalized winding number (``Mesh.winding_number``: blue 0 outside,
    red 1 inside, fractional near the window) with the w = 1/2 iso-line, the
    boundary of ``contains(rule="winding")``, in black.

Usage: ``python demo/render.py [--size 800x600] [--out DIR] [--threads N]``
(``make demo`` runs it in the project's virtual environment).
"""

from __future__ import annotations

import argparse
import colorsys
import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import isect
import numpy as np
from PIL import Image, ImageDraw, ImageFont

HERE = Path(__file__).resolve().parent
BACKGROUND_TOP = np.array([22.0, 24.0, 30.0])
BACKGROUND_BOTTOM = np.array([52.0, 54.0, 62.0])
LIGHT = np.array([-0.45, 0.8, 0.55]) / np.linalg.norm([-0.45, 0.8, 0.55])
AMBIENT = 0.3  # shading: colour * (AMBIENT + (1 - AMBIENT) * max(0, n . light))


# ------------------------------------------------------------------ scene


@dataclass
class SceneObject:
    """One object of the scene: its libisect shape, colour and (for the
    clipped quadric) the box its visible hits must lie in."""

    name: str
    shape: isect.Shape
    color: tuple[int, int, int]
    clip: tuple[np.ndarray, np.ndarray] | None = None


def palette(n: int) -> list[tuple[int, int, int]]:
    """n saturated colours of evenly spaced hues (all told apart by hue, so a
    shaded pixel's object can be recognised from its colour)."""
    out = []
    for i in range(n):
        r, g, b = colorsys.hsv_to_rgb(i / n, 0.78, 1.0)
        out.append((round(255 * r), round(255 * g), round(255 * b)))
    return out


def torus_mesh(
    center: tuple[float, float, float], big: float, small: float, nu: int = 40, nv: int = 20
) -> tuple[np.ndarray, np.ndarray]:
    """A closed triangulated torus around the y axis: vertices (nu*nv, 3),
    faces (2*nu*nv, 3), outward orientation."""
    u = np.arange(nu) * (2 * math.pi / nu)
    v = np.arange(nv) * (2 * math.pi / nv)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    ring = big + small * np.cos(vv)
    verts = np.stack(
        [ring * np.cos(uu), small * np.sin(vv), ring * np.sin(uu)], axis=-1
    ).reshape(-1, 3) + np.asarray(center)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = i * nv + j
    b = ((i + 1) % nu) * nv + j
    c = ((i + 1) % nu) * nv + (j + 1) % nv
    d = i * nv + (j + 1) % nv
    faces = np.concatenate(
        [np.stack([a, d, c], -1).reshape(-1, 3), np.stack([a, c, b], -1).reshape(-1, 3)]
    )
    return verts, faces.astype(np.int32)


def star(center: np.ndarray, radius: float, tilt: float) -> np.ndarray:
    """A pentagram {5/2} (self-intersecting) facing the camera, turned by
    ``tilt`` radians about the vertical axis."""
    ang = math.pi / 2 + np.arange(5) * (4 * math.pi / 5)
    local = np.stack([radius * np.cos(ang), radius * np.sin(ang), np.zeros(5)], -1)
    c, s = math.cos(tilt), math.sin(tilt)
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return local @ rot.T + center


def hyperboloid(center: np.ndarray, a: float, c: float) -> isect.Quadric:
    """The hyperboloid of one sheet ((x-cx)² + (z-cz)²)/a² - (y-cy)²/c² = 1
    (a waisted tube around the vertical axis) as quadric coefficients."""
    cx, cy, cz = center
    ia, ic = 1 / a**2, 1 / c**2
    return isect.Quadric(
        [ia, -ic, ia, 0, 0, 0, -2 * cx * ia, 2 * cy * ic, -2 * cz * ia,
         (cx**2 + cz**2) * ia - cy**2 * ic - 1]
    )  # fmt: skip


def build_scene() -> list[SceneObject]:
    """The demo scene: every primitive, each with its own colour.

    The mesh object needs ``isect.Mesh``; without it the scene has no mesh
    (a message says so)."""
    has_mesh = hasattr(isect, "Mesh")
    colors = iter(palette(11))
    objs: list[SceneObject] = []

    def add(name: str, shape: isect.Shape, clip: Any = None) -> None:
        objs.append(SceneObject(name, shape, next(colors), clip))

    # front row (z = 1)
    add("sphere", isect.Sphere([-4.3, 0.75, 1.0], 0.75))
    add("box", isect.Box([-3.2, 0.0, 0.4], [-2.0, 1.2, 1.6]))
    concave = np.array(
        [[-1.5, 0.0], [-0.2, 0.0], [-0.2, 1.5], [-0.7, 0.9], [-1.0, 1.5], [-1.5, 0.7], [-1.0, 0.5]]
    )
    add("concave polygon", isect.Polygon(np.c_[concave, np.full(7, 1.2)], rule="nonzero"))
    add("pentagram even-odd", isect.Polygon(star(np.array([0.75, 0.8, 1.2]), 0.85, 0.25)))
    add(
        "pentagram non-zero",
        isect.Polygon(star(np.array([2.55, 0.8, 1.2]), 0.85, -0.25), rule="nonzero"),
    )
    octa = [[sx, sy, sz, -1.0] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    cube = [[s * (i == 0), s * (i == 1), s * (i == 2), -0.72] for i in range(3) for s in (-1, 1)]
    planes = np.array(octa + cube, dtype=float) * [0.8, 0.8, 0.8, 0.8]
    center = np.array([4.3, 0.85, 0.9])
    planes[:, 3] -= planes[:, :3] @ center  # move to center: n.(x - c) + d
    add("convex polyhedron", isect.ConvexPolyhedron(planes))
    # back row (z = -2.5)
    add("capped cylinder", isect.Cylinder([-4.9, 0.0, -2.3], [-4.3, 1.7, -2.7], 0.6))
    add("ellipsoid", isect.Ellipsoid([-2.4, 0.8, -2.5], [1.0, 0.6, 0.7]))
    add(
        "hyperboloid (clipped quadric)",
        hyperboloid(np.array([0.0, 1.0, -2.5]), 0.55, 0.8),
        clip=(np.array([-3.0, 0.0, -6.0]), np.array([3.0, 2.0, 1.0])),
    )
    ang = math.radians(35)
    rot = np.array(
        [[math.cos(ang), 0, math.sin(ang)], [0, 1, 0], [-math.sin(ang), 0, math.cos(ang)]]
    )
    rot_x = np.array(
        [[1, 0, 0], [0, math.cos(0.4), -math.sin(0.4)], [0, math.sin(0.4), math.cos(0.4)]]
    )
    shear = np.array([[1, 0.6, 0], [0, 1, 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = rot @ rot_x @ shear
    m[:3, 3] = [2.3, 1.0, -2.5]
    add("rotated, sheared box", isect.Box([-0.6, -0.6, -0.6], [0.6, 0.6, 0.6]).transformed(m))
    if has_mesh:
        verts, faces = torus_mesh((4.7, 0.9, -2.6), 0.85, 0.38)
        mesh = isect.Mesh(verts, faces).transformed(_rotation_x(1.1, (4.7, 0.9, -2.6)))
        add("torus (triangle mesh)", mesh)
    else:
        print("note: isect.Mesh is not available in this build; the scene has no mesh object")
    return objs


def _rotation_x(angle: float, about: tuple[float, float, float]) -> np.ndarray:
    """A 4x4 rotation by angle about the x-parallel axis through ``about``."""
    c, s = math.cos(angle), math.sin(angle)
    r = np.eye(4)
    r[1:3, 1:3] = [[c, -s], [s, c]]
    t = np.eye(4)
    t[:3, 3] = about
    ti = np.eye(4)
    ti[:3, 3] = -np.asarray(about)
    return t @ r @ ti


# ------------------------------------------------------------------ camera


@dataclass
class Camera:
    """A pinhole camera: eye, orthonormal right/up/forward, horizontal FOV."""

    eye: np.ndarray
    right: np.ndarray
    up: np.ndarray
    fwd: np.ndarray
    tan_half: float
    width: int
    height: int

    @classmethod
    def look_at(
        cls, eye: Any, target: Any, hfov_deg: float, width: int, height: int
    ) -> Camera:
        eye = np.asarray(eye, float)
        fwd = np.asarray(target, float) - eye
        fwd /= np.linalg.norm(fwd)
        right = np.cross(fwd, [0.0, 1.0, 0.0])
        right /= np.linalg.norm(right)
        up = np.cross(right, fwd)
        return cls(eye, right, up, fwd, math.tan(math.radians(hfov_deg) / 2), width, height)

    def directions(self) -> np.ndarray:
        """One ray direction per pixel centre, (height, width, 3), unit length."""
        w, h = self.width, self.height
        x = ((np.arange(w) + 0.5) / w * 2 - 1) * self.tan_half
        y = (1 - (np.arange(h) + 0.5) / h * 2) * self.tan_half * h / w
        d = self.fwd + x[None, :, None] * self.right + y[:, None, None] * self.up
        return d / np.linalg.norm(d, axis=-1, keepdims=True)

    def project(self, points: np.ndarray) -> np.ndarray:
        """Pixel coordinates (x, y) of world points in front of the camera."""
        v = points - self.eye
        z = v @ self.fwd
        x = (v @ self.right) / z / self.tan_half
        y = (v @ self.up) / z / (self.tan_half * self.height / self.width)
        return np.stack([(x + 1) / 2 * self.width, (1 - y) / 2 * self.height], -1)


def background(height: int, width: int) -> np.ndarray:
    """A vertical grey gradient, (height, width, 3) float."""
    f = np.linspace(0, 1, height)[:, None, None]
    return np.broadcast_to(BACKGROUND_TOP + f * (BACKGROUND_BOTTOM - BACKGROUND_TOP),
                           (height, width, 3)).copy()  # fmt: skip


def shade(normal: np.ndarray, dirs: np.ndarray, color: Any) -> np.ndarray:
    """Lambert shading by the normal (turned to face the viewer: thin
    surfaces and the inside of the open hyperboloid are seen from both
    sides); returns colour * intensity."""
    n = np.where(np.sum(normal * dirs, -1, keepdims=True) > 0, -normal, normal)
    lam = np.clip(n @ LIGHT, 0.0, 1.0)
    return (AMBIENT + (1 - AMBIENT) * lam)[:, None] * np.asarray(color, float)


def first_hit_in_box(
    offsets: np.ndarray, hits: np.ndarray, lo: np.ndarray, hi: np.ndarray, n: int
) -> tuple[np.ndarray, np.ndarray]:
    """From the CSR result of intersect_all_batch, each ray's first hit whose
    point lies in the box [lo, hi]: (t, normal), t = inf where there is none."""
    t = np.full(n, np.inf)
    normal = np.zeros((n, 3))
    pts = hits["point"]
    inside = np.all((pts >= lo) & (pts <= hi), axis=1) & np.isfinite(hits["t"])
    ray_of = np.repeat(np.arange(n), np.diff(offsets))
    idx = np.flatnonzero(inside)
    rays, first = np.unique(ray_of[idx], return_index=True)
    t[rays] = hits["t"][idx[first]]
    normal[rays] = hits["normal"][idx[first]]
    return t, normal


def render_scene(width: int, height: int, threads: int) -> tuple[Image.Image, dict[str, Any]]:
    """The scene picture (with its caption) and statistics."""
    objs = build_scene()
    cam = Camera.look_at([0.0, 6.8, 9.0], [0.0, 0.5, -0.9], 56.0, width, height)
    dirs = cam.directions().reshape(-1, 3)
    n = dirs.shape[0]
    best_t = np.full(n, np.inf)
    best_obj = np.full(n, -1)
    best_normal = np.zeros((n, 3))
    rays = np.zeros(n, dtype=isect.RAY_DTYPE)  # handed to C as it is (zero-copy)
    rays["org"], rays["dir"], rays["tmax"] = cam.eye, dirs, np.inf
    start = time.perf_counter()
    for k, obj in enumerate(objs):
        if obj.clip is None:
            hits = obj.shape.intersect_rays(rays, threads=threads)
            t, normal = hits["t"], hits["normal"]
        else:
            offsets, hits = obj.shape.intersect_all_batch(cam.eye, dirs, threads=threads)
            t, normal = first_hit_in_box(offsets, hits, *obj.clip, n)
        closer = t < best_t
        best_t[closer] = t[closer]
        best_obj[closer] = k
        best_normal[closer] = normal[closer]
    elapsed = time.perf_counter() - start

    img = background(height, width).reshape(-1, 3)
    colors = np.array([o.color for o in objs], float)
    hit = best_obj >= 0
    intensity = shade(best_normal[hit], dirs[hit], [1.0, 1.0, 1.0])
    img[hit] = intensity * colors[best_obj[hit]]
    pixels = np.round(img).clip(0, 255).astype(np.uint8).reshape(height, width, 3)

    queries = n * len(objs)
    stats = {
        "objects": [o.name for o in objs],
        "colors": [o.color for o in objs],
        "pixels_per_object": np.bincount(best_obj[hit], minlength=len(objs)).tolist(),
        "rays": n,
        "queries": queries,
        "seconds": elapsed,
        "queries_per_second": queries / elapsed,
        "threads": threads,
    }
    caption = (
        f"libisect {isect.__version__} via Python: {len(objs)} objects x {width}x{height} "
        f"camera rays = {queries / 1e6:.2f} M ray-object queries in {elapsed:.2f} s = "
        f"{_rate(queries / elapsed)} rays/s ({threads} threads)"
    )
    legend = [(o.name, o.color) for o in objs]
    return with_caption(Image.fromarray(pixels), [caption], legend), stats


# ------------------------------------------------------------------ captions


def _rate(x: float) -> str:
    """A throughput with a unit prefix: '12.3 M', '45.6 k'."""
    for scale, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if x >= scale:
            return f"{x / scale:.1f} {prefix}"
    return f"{x:.0f}"


def _font(size: int) -> Any:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType: the fixed bitmap font
        return ImageFont.load_default()


def with_caption(
    picture: Image.Image, lines: list[str], legend: list[tuple[str, tuple[int, int, int]]]
) -> Image.Image:
    """The picture with a black strip below holding text lines and a legend
    of coloured names (outside the picture, so it never counts as a pixel of
    an object)."""
    size = max(11, picture.width // 62)
    font = _font(size)
    line_h = size + 6
    legend_rows: list[list[tuple[str, tuple[int, int, int]]]] = []
    draw_probe = ImageDraw.Draw(picture)
    row: list[tuple[str, tuple[int, int, int]]] = []
    x = 8.0
    for name, color in legend:
        w = draw_probe.textlength(name, font=font) + 18
        if row and x + w > picture.width - 8:
            legend_rows.append(row)
            row, x = [], 8.0
        row.append((name, color))
        x += w
    if row:
        legend_rows.append(row)
    wrapped: list[str] = []
    for text in lines:  # wrap at word boundaries to the picture's width
        words = text.split(" ")
        current = words[0]
        for word in words[1:]:
            if draw_probe.textlength(current + " " + word, font=font) > picture.width - 16:
                wrapped.append(current)
                current = "    " + word
            else:
                current += " " + word
        wrapped.append(current)
    lines = wrapped
    strip = line_h * (len(lines) + len(legend_rows)) + 10
    out = Image.new("RGB", (picture.width, picture.height + strip), (0, 0, 0))
    out.paste(picture, (0, 0))
    draw = ImageDraw.Draw(out)
    y = picture.height + 5
    for text in lines:
        draw.text((8, y), text, fill=(235, 235, 235), font=font)
        y += line_h
    for row in legend_rows:
        x = 8.0
        for name, color in row:
            draw.text((x, y), name, fill=color, font=font)
            x += draw.textlength(name, font=font) + 18
        y += line_h
    return out


# ------------------------------------------------------------------ exactly once


def integer_sphere(n: int, radius: int) -> tuple[np.ndarray, np.ndarray]:
    """A closed triangle mesh close to a sphere, with integer vertex
    coordinates (so vertices and edge midpoints are exact in float32 and
    float64): the n x n grid of each face of a cube, pushed out to the
    sphere and rounded. Returns vertices (V, 3) float64 and faces (F, 3)
    int32, outward orientation."""
    index: dict[tuple[int, int, int], int] = {}
    verts: list[tuple[int, int, int]] = []
    faces: list[tuple[int, int, int]] = []

    def vid(p: tuple[int, int, int]) -> int:
        if p not in index:
            index[p] = len(verts)
            verts.append(p)
        return index[p]

    for axis in range(3):
        for side in (-n, n):
            u_ax, v_ax = [a for a in range(3) if a != axis]
            for i in range(-n, n, 2):
                for j in range(-n, n, 2):
                    quad = []
                    for du, dv in ((0, 0), (2, 0), (2, 2), (0, 2)):
                        p = [0, 0, 0]
                        p[axis], p[u_ax], p[v_ax] = side, i + du, j + dv
                        quad.append(vid((p[0], p[1], p[2])))
                    a, b, c, d = quad
                    tris = [(a, b, c), (a, c, d)] if (i + j) % 4 == 0 else [(a, b, d), (b, c, d)]
                    faces.extend(tris)
    lattice = np.array(verts, dtype=float)
    v = np.round(lattice / np.linalg.norm(lattice, axis=1, keepdims=True) * radius)
    f = np.array(faces, dtype=np.int32)
    # orient outward (the sphere contains the origin)
    tri = v[f]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    flip = np.sum(normal * tri.sum(axis=1), axis=1) < 0
    f[flip] = f[flip][:, ::-1]
    return v, f


def edge_midpoints(faces: np.ndarray, verts: np.ndarray) -> np.ndarray:
    """The midpoint of every undirected edge (exact: integer vertices)."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e = np.unique(np.sort(e, axis=1), axis=0)
    return (verts[e[:, 0]] + verts[e[:, 1]]) / 2


def embree_counts(
    verts: np.ndarray, faces: np.ndarray, origins: np.ndarray, dirs: np.ndarray
) -> np.ndarray | None:
    """How many triangles Embree reports as hit by each ray, or None when
    embreex is not installed.

    Embree returns one hit per query, so the triangles are split into groups
    in which no two share a vertex (a greedy colouring), each group is one
    Embree scene, and a ray's count is the number of scenes it hits: the
    number of triangles Embree's own hit test accepts, as an all-hits
    traversal (a crossing-count inside test) would count them."""
    try:
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh
    except ImportError:
        return None
    used: list[set[int]] = []
    group = np.empty(len(faces), dtype=np.int64)
    for k, face in enumerate(faces.tolist()):
        for g, taken in enumerate(used):
            if not taken.intersection(face):
                taken.update(face)
                group[k] = g
                break
        else:
            used.append(set(face))
            group[k] = len(used) - 1
    counts = np.zeros(len(origins), dtype=np.int64)
    o32 = np.ascontiguousarray(origins, dtype=np.float32)
    d32 = np.ascontiguousarray(dirs, dtype=np.float32)
    for g in range(len(used)):
        scene = rtcore_scene.EmbreeScene()
        TriangleMesh(scene, np.ascontiguousarray(verts[faces[group == g]], dtype=np.float32))
        prim = scene.run(o32, d32)
        counts += np.asarray(prim) >= 0
    return counts


def render_exactly_once(size: int, threads: int) -> tuple[Image.Image, dict[str, Any]]:
    """The exactly-once picture and its counts."""
    if not hasattr(isect, "Mesh"):
        raise RuntimeError("isect.Mesh is not available in this build")
    radius = 1000
    verts, faces = integer_sphere(8, radius)
    mesh = isect.Mesh(verts, faces)
    targets = np.concatenate([verts, edge_midpoints(faces, verts)])
    n_vertex = len(verts)
    # rays from a few interior points with integer coordinates: the direction
    # target - origin is exact, so the ray passes exactly through the target
    interior = np.array([[0, 0, 0], [170, -90, 230], [-310, 120, -50], [40, 280, -160]], float)
    origins = np.repeat(interior, len(targets), axis=0)
    dirs = np.tile(targets, (len(interior), 1)) - origins

    start = time.perf_counter()
    offsets, _ = mesh.intersect_all_batch(origins, dirs, threads=threads)
    elapsed = time.perf_counter() - start
    ours = np.diff(offsets)
    theirs = embree_counts(verts, faces, origins, dirs)

    cam = Camera.look_at([1900.0, 1500.0, 2600.0], [0.0, 0.0, 0.0], 40.0, size, size)
    view = cam.directions().reshape(-1, 3)
    hits = mesh.intersect(cam.eye, view, threads=threads)
    base = background(size, size).reshape(-1, 3)
    hit = np.isfinite(hits["t"])
    base[hit] = shade(hits["normal"][hit], view[hit], (150, 150, 160))
    base_img = np.round(base).clip(0, 255).astype(np.uint8).reshape(size, size, 3)

    facing = targets @ (cam.eye / np.linalg.norm(cam.eye)) > 0.25 * radius
    pix = cam.project(targets)

    def panel(counts: np.ndarray | None, title: str) -> Image.Image:
        img = Image.fromarray(base_img)
        draw = ImageDraw.Draw(img)
        font = _font(max(12, size // 32))
        if counts is None:
            img = Image.new("RGB", (size, size), (40, 40, 44))
            draw = ImageDraw.Draw(img)
            draw.text((12, 12), title, fill=(235, 235, 235), font=font)
            draw.text((12, size // 2), "skipped: embreex is not installed",
                      fill=(255, 200, 80), font=font)  # fmt: skip
            draw.text((12, size // 2 + max(12, size // 32) + 8), "(pip install embreex)",
                      fill=(200, 200, 200), font=font)  # fmt: skip
            return img
        per_target = counts.reshape(len(interior), len(targets))
        leak = (per_target == 0).any(axis=0)
        double = (per_target >= 2).any(axis=0)
        order = np.argsort(leak | double)  # errors drawn last, on top
        for i in order:
            if not facing[i]:
                continue
            x, y = pix[i]
            r = 3 if i < n_vertex else 2
            if leak[i] or double[i]:
                r += 2
            color = (255, 60, 60) if leak[i] else (255, 220, 0) if double[i] else (60, 210, 90)
            draw.ellipse([x - r, y - r, x + r, y + r], fill=color)
        draw.text((12, 12), title, fill=(235, 235, 235), font=font)
        return img

    def summary(counts: np.ndarray | None) -> dict[str, int] | None:
        if counts is None:
            return None
        return {
            "once": int(np.sum(counts == 1)),
            "leaks": int(np.sum(counts == 0)),
            "double_hits": int(np.sum(counts >= 2)),
        }

    s_ours, s_theirs = summary(ours), summary(theirs)
    left = panel(ours, "libisect (isect.Mesh)")
    right = panel(theirs, "Embree (embreex)")
    pic = Image.new("RGB", (2 * size + 8, size), (0, 0, 0))
    pic.paste(left, (0, 0))
    pic.paste(right, (size + 8, 0))
    nrays = len(origins)
    lines = [
        f"{nrays} rays from inside a closed {len(faces)}-triangle mesh, aimed exactly at its "
        f"{n_vertex} vertices and {len(targets) - n_vertex} edge midpoints: each must cross "
        "the surface exactly once",
        f"libisect: {s_ours['leaks']} leaks, {s_ours['double_hits']} double hits "
        f"({_rate(nrays / elapsed)} rays/s)   |   "
        + (
            f"Embree: {s_theirs['leaks']} leaks, {s_theirs['double_hits']} double hits "
            "(every triangle it reports hit, as an all-hits traversal counts)"
            if s_theirs
            else "Embree: skipped (embreex not installed)"
        ),
    ]
    legend = [("once", (60, 210, 90)), ("leak (0 crossings)", (255, 60, 60)),
              ("double hit (2+)", (255, 220, 0))]  # fmt: skip
    stats = {"rays": nrays, "libisect": s_ours, "embree": s_theirs, "seconds": elapsed}
    return with_caption(pic, lines, legend), stats


# ------------------------------------------------------------------ main


# ------------------------------------------------------------------ winding


def render_winding(size: int, threads: int) -> tuple[Image.Image, dict[str, Any]]:
    """The slice y = 0 through an open torus, coloured by its winding number."""
    nu, nv = 64, 32
    verts, faces = torus_mesh((0.0, 0.0, 0.0), 1.0, 0.45, nu, nv)
    # faces come as two blocks of nu * nv, face (i, j) at i * nv + j in each;
    # the window: 10 steps around the ring, 8 around the tube's outer side
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    window = ((i < 10) & ((j < 4) | (j >= nv - 4))).reshape(-1)
    keep = ~np.concatenate([window, window])
    closed = isect.Mesh(verts, faces)
    opened = isect.Mesh(verts, faces[keep])
    half = 1.7
    coords = (np.arange(size) + 0.5) * (2 * half / size) - half
    xx, zz = np.meshgrid(coords, coords[::-1])
    pts = np.stack([xx, np.zeros_like(xx), zz], -1).reshape(-1, 3)
    t0 = time.perf_counter()
    w = opened.winding_number(pts, threads=threads).reshape(size, size)
    seconds = time.perf_counter() - t0
    inside_closed = closed.contains(pts, threads=threads).reshape(size, size)
    inside_open = opened.contains(pts, rule="winding", threads=threads).reshape(size, size)
    # blue (0) -> white (1/2) -> red (1)
    x = np.clip(w, 0.0, 1.0)[..., None]
    blue, white, red = np.array([40, 90, 200.0]), np.array([245, 245, 245.0]), np.array([205, 45, 40.0])
    rgb = np.where(x < 0.5, blue + (white - blue) * (2 * x), white + (red - white) * (2 * x - 1))
    above = w >= 0.5
    iso = np.zeros_like(above)
    iso[:, :-1] |= above[:, :-1] != above[:, 1:]
    iso[:-1, :] |= above[:-1, :] != above[1:, :]
    rgb[iso] = 0.0
    picture = Image.fromarray(rgb.astype(np.uint8))
    n = size * size
    st = {"faces": int(keep.sum()), "removed": int((~keep).sum()), "points": n,
          "seconds": seconds, "points_per_second": n / seconds,
          "fractional": int(((w > 0.02) & (w < 0.98)).sum()),
          "differ_from_closed": int((inside_open != inside_closed).sum())}
    lines = [
        f"Generalized winding number on the plane of the equator of a torus with a window "
        f"cut into its outer wall ({st['faces']} triangles, {st['removed']} removed: not closed). "
        "Blue 0, white 1/2, red 1; black: w = 1/2, the boundary of contains(rule='winding').",
        f"{n} points in {seconds:.2f} s ({_rate(n / seconds)} points/s on {threads} threads), "
        f"exact to the rounding of the terms; {st['fractional']} points fractional, "
        f"{st['differ_from_closed']} classified otherwise than by the closed torus.",
    ]
    return with_caption(picture, lines, []), st


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Render the libisect demo pictures.")
    parser.add_argument("--size", default="800x600", help="scene size WIDTHxHEIGHT")
    parser.add_argument("--out", default=str(HERE), help="output directory (default demo/)")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args(argv)
    try:
        width, height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        parser.error(f"--size: expected WIDTHxHEIGHT, got {args.size!r}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()

    scene, st = render_scene(width, height, args.threads)
    scene_path = out / "scene.png"
    scene.save(scene_path)
    print(f"wrote {scene_path}")

    once_path = out / "exactly_once.png"
    eo: dict[str, Any] | None = None
    try:
        picture, eo = render_exactly_once(max(240, min(width, height)), args.threads)
    except RuntimeError as error:
        print(f"skipped {once_path}: {error}")
    else:
        picture.save(once_path)
        print(f"wrote {once_path}")
        if eo["embree"] is None:
            print("note: embreex is not installed; the Embree half of exactly_once.png is skipped")

    winding_path = out / "winding.png"
    picture, wn = render_winding(max(200, min(width, height, 400)), args.threads)
    picture.save(winding_path)
    print(f"wrote {winding_path}")

    line = (
        f"summary: {len(st['objects'])} objects, {st['rays']} camera rays, "
        f"{_rate(st['queries_per_second'])} ray-object queries/s on {args.threads} threads"
    )
    if eo is not None:
        line += (
            f"; exactly-once: libisect {eo['libisect']['leaks']} leaks/"
            f"{eo['libisect']['double_hits']} double hits"
        )
        if eo["embree"] is not None:
            line += (
                f", Embree {eo['embree']['leaks']} leaks/{eo['embree']['double_hits']} double hits"
            )
        line += f" of {eo['rays']} rays"
    line += (
        f"; winding numbers of an open torus: {_rate(wn['points_per_second'])} points/s"
        f"; total {time.perf_counter() - t0:.1f} s"
    )
    print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
