# SPDX-License-Identifier: Apache-2.0
"""The measured primitives: random instances at a given size and position.

Each instance carries its shape twice: ``spec``, the numbers in the golden
reference's format (tests/golden, plus ``transform`` for transformed shapes),
and ``shape``, the same doubles as an ``isect`` object.  Both see exactly the
same doubles, so the reference answers exactly the question the library was
asked.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import isect
import numpy as np

Rng = np.random.Generator


@dataclass
class Instance:
    """One object: reference spec, library shape, and where to aim at it.

    scale: the object's own scale (sphere max(|c|_inf, r), box max|corner|,
    ...); for unbounded surfaces the point metric also takes the hit point.
    points: points of the object (vertices, corners) that rays may aim at
    through random convex combinations; None: aim into the ball (center,
    radius).
    """
    name: str
    spec: dict
    shape: isect.Shape
    scale: float
    center: np.ndarray
    radius: float
    unbounded: bool = False
    points: np.ndarray | None = None


def unit(rng: Rng) -> np.ndarray:
    """A random unit vector (uniform on the sphere)."""
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def rotation(rng: Rng) -> np.ndarray:
    """A random rotation matrix (QR of a Gaussian matrix, det +1)."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def loguniform(rng: Rng, lo: float, hi: float) -> float:
    return float(10 ** rng.uniform(math.log10(lo), math.log10(hi)))


def inf_norm(v: np.ndarray) -> float:
    return float(np.max(np.abs(v)))


def as_list(v: np.ndarray) -> list[float]:
    return [float(x) for x in v]


# ----------------------------------------------------------- the families
def plane(rng: Rng, s: float, c: np.ndarray) -> Instance:
    n = unit(rng) * loguniform(rng, 1e-2, 1e2)
    d = -float(n @ c)
    spec = {"type": "plane", "normal": as_list(n), "d": d}
    return Instance("plane", spec, isect.Plane(n, d), abs(d) / float(np.linalg.norm(n)), c, s, True)


def sphere(rng: Rng, s: float, c: np.ndarray) -> Instance:
    spec = {"type": "sphere", "center": as_list(c), "radius": s}
    return Instance("sphere", spec, isect.Sphere(c, s), max(inf_norm(c), s), c, s)


def box(rng: Rng, s: float, c: np.ndarray) -> Instance:
    lo, hi = c - s * rng.uniform(0.2, 1, 3), c + s * rng.uniform(0.2, 1, 3)
    spec = {"type": "box", "lo": as_list(lo), "hi": as_list(hi)}
    corners = np.array([[(lo, hi)[(k >> j) & 1][j] for j in range(3)] for k in range(8)])
    return Instance("box", spec, isect.Box(lo, hi), max(inf_norm(lo), inf_norm(hi)), c, 1.8 * s, points=corners)


def triangle(rng: Rng, s: float, c: np.ndarray) -> Instance:
    v = c + s * 0.6 * rng.normal(size=(3, 3))
    spec = {"type": "triangle", "a": as_list(v[0]), "b": as_list(v[1]), "c": as_list(v[2])}
    return Instance("triangle", spec, isect.Triangle(*v), inf_norm(v), v.mean(axis=0),
                    float(np.max(np.linalg.norm(v - v.mean(axis=0), axis=1))), points=v)


def _polygon(name: str, rng: Rng, s: float, c: np.ndarray, star: bool) -> Instance:
    k = int(rng.integers(5, 9))
    th = np.sort(rng.uniform(0, 2 * math.pi, k))
    rho = rng.uniform(0.7, 1.0, k)
    if star:                                  # a concave star: 2k vertices, alternating radii
        mid = th + np.diff(np.append(th, th[0] + 2 * math.pi)) / 2
        th = np.ravel(np.column_stack([th, mid]))
        rho = np.ravel(np.column_stack([rho, rng.uniform(0.2, 0.4, k)]))
    R = rotation(rng)
    v = c + s * (np.outer(rho * np.cos(th), R[0]) + np.outer(rho * np.sin(th), R[1]))
    rule = "nonzero" if star else "evenodd"
    spec = {"type": "polygon", "vertices": [as_list(x) for x in v], "rule": rule}
    return Instance(name, spec, isect.Polygon(v, rule=rule), inf_norm(v), c, s, points=v)


def polygon_convex(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _polygon("polygon_convex", rng, s, c, star=False)


def polygon_concave(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _polygon("polygon_concave", rng, s, c, star=True)


def convex(rng: Rng, s: float, c: np.ndarray) -> Instance:
    """A rotated box-like polytope with four random extra cuts (10 planes)."""
    R = rotation(rng)
    normals = [sgn * R[k] for k in range(3) for sgn in (-1, 1)] + [unit(rng) for _ in range(4)]
    planes = []
    for n in normals:
        lam = loguniform(rng, 0.1, 10)
        ns = n * lam
        planes.append(as_list(ns) + [-float(ns @ c) - lam * s * rng.uniform(0.6, 1.0)])
    spec = {"type": "convex", "planes": planes}
    return Instance("convex", spec, isect.ConvexPolyhedron(np.array(planes)), max(inf_norm(c), s), c, 1.8 * s)


def _cylinder(name: str, rng: Rng, s: float, c: np.ndarray, capped: bool) -> Instance:
    a = unit(rng) * s * rng.uniform(0.5, 2)
    p0, p1, r = c - a / 2, c + a / 2, s * rng.uniform(0.2, 1)
    spec = {"type": "cylinder", "p0": as_list(p0), "p1": as_list(p1), "radius": r, "capped": capped}
    return Instance(name, spec, isect.Cylinder(p0, p1, r, capped=capped),
                    max(inf_norm(p0), inf_norm(p1), r), c, float(np.linalg.norm(a)) / 2 + r)


def cylinder_capped(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _cylinder("cylinder_capped", rng, s, c, True)


def cylinder_open(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _cylinder("cylinder_open", rng, s, c, False)


def cylinder_inf(rng: Rng, s: float, c: np.ndarray) -> Instance:
    axis = unit(rng) * loguniform(rng, 1e-2, 1e2)
    spec = {"type": "infinite_cylinder", "point": as_list(c), "axis": as_list(axis), "radius": s}
    return Instance("cylinder_inf", spec, isect.InfiniteCylinder(c, axis, s), max(inf_norm(c), s), c, 2 * s, True)


def ellipsoid(rng: Rng, s: float, c: np.ndarray) -> Instance:
    radii = s * rng.uniform(0.2, 1, 3)
    spec = {"type": "ellipsoid", "center": as_list(c), "radii": as_list(radii)}
    return Instance("ellipsoid", spec, isect.Ellipsoid(c, radii), max(inf_norm(c), s), c, s)


def _quadric(name: str, rng: Rng, s: float, c: np.ndarray, diag: tuple[float, float, float],
             lin: float, const: float) -> Instance:
    """lam * (u^T D u + lin * u_z + const), u = R (x - c) / s, expanded to 10 doubles."""
    R = rotation(rng)
    lam = loguniform(rng, 1e-2, 1e2)
    A = R.T @ np.diag(diag) @ R / (s * s)
    g = lin * R[2] / s
    lin_x = -2 * A @ c + g
    k = [A[0, 0], A[1, 1], A[2, 2], 2 * A[0, 1], 2 * A[0, 2], 2 * A[1, 2], lin_x[0], lin_x[1], lin_x[2],
         float(c @ A @ c) - float(g @ c) + const]
    coeffs = [float(lam * x) for x in k]
    spec = {"type": "quadric", "coeffs": coeffs}
    return Instance(name, spec, isect.Quadric(coeffs), max(inf_norm(c), s), c, 1.5 * s, True)


def hyperboloid(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _quadric("hyperboloid", rng, s, c, (1, 1, -1), 0, -1)


def cone(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _quadric("cone", rng, s, c, (1, 1, -1), 0, 0)


def paraboloid(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _quadric("paraboloid", rng, s, c, (1, 1, 0), -1, 0)


def _matrix(rng: Rng, s: float, c: np.ndarray) -> tuple[list[float], float]:
    """Rotation x non-uniform scale x s, then translation c; and the largest scale."""
    sig = s * 10 ** rng.uniform(-0.5, 0.5, 3)
    L = rotation(rng) @ np.diag(sig)
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = L, c
    return [float(x) for x in m.ravel()], float(sig.max())


def _transformed(name: str, obj: Instance, rng: Rng, s: float, c: np.ndarray) -> Instance:
    m, smax = _matrix(rng, s, c)
    spec = dict(obj.spec, transform=m)
    size = smax * (obj.radius + float(np.linalg.norm(obj.center)))
    M = np.array(m).reshape(4, 4)
    pts = None if obj.points is None else obj.points @ M[:3, :3].T + M[:3, 3]
    return Instance(name, spec, obj.shape.transformed(M), max(inf_norm(c), size), c, size, points=pts)


def xf_sphere(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _transformed("xf_sphere", sphere(rng, 1.0, 0.1 * rng.normal(size=3)), rng, s, c)


def xf_box(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _transformed("xf_box", box(rng, 1.0, 0.1 * rng.normal(size=3)), rng, s, c)


def xf_triangle(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _transformed("xf_triangle", triangle(rng, 1.0, np.zeros(3)), rng, s, c)


def xf_cylinder(rng: Rng, s: float, c: np.ndarray) -> Instance:
    return _transformed("xf_cylinder", cylinder_capped(rng, 1.0, np.zeros(3)), rng, s, c)


def _golden_mesh(m: dict) -> tuple[np.ndarray, list[list[int]]]:
    """A golden mesh's vertices centred on their bounding box, largest distance 1."""
    v = np.array(m["vertices"], dtype=float)
    v -= (v.min(axis=0) + v.max(axis=0)) / 2
    return v / float(np.max(np.linalg.norm(v, axis=1))), m["faces"]


def _mesh(name: str, base: np.ndarray, faces: list[list[int]], rng: Rng, s: float, c: np.ndarray) -> Instance:
    v = c + s * base @ rotation(rng).T
    spec = {"type": "mesh", "vertices": [as_list(x) for x in v], "faces": faces}
    return Instance(name, spec, isect.Mesh(v, faces), inf_norm(v), c, 1.1 * s, points=v)


def mesh_tri(rng: Rng, s: float, c: np.ndarray) -> Instance:
    """The golden reference's icosahedron (20 triangle faces, closed, outward)."""
    from .reference import mesh
    return _mesh("mesh_tri", *_golden_mesh(mesh.icosahedron()), rng, s, c)


def mesh_poly(rng: Rng, s: float, c: np.ndarray) -> Instance:
    """The golden reference's L prism (8 polygon faces, two concave hexagons; closed)."""
    from .reference import mesh
    return _mesh("mesh_poly", *_golden_mesh(mesh.l_prism()), rng, s, c)


Maker = Callable[[Rng, float, np.ndarray], Instance]

#: every measured primitive, in table order
PRIMITIVES: dict[str, Maker] = {
    "plane": plane, "sphere": sphere, "box": box, "triangle": triangle,
    "polygon_convex": polygon_convex, "polygon_concave": polygon_concave, "convex": convex,
    "cylinder_capped": cylinder_capped, "cylinder_open": cylinder_open, "cylinder_inf": cylinder_inf,
    "ellipsoid": ellipsoid, "hyperboloid": hyperboloid, "cone": cone, "paraboloid": paraboloid,
    "xf_sphere": xf_sphere, "xf_box": xf_box, "xf_triangle": xf_triangle, "xf_cylinder": xf_cylinder,
    "mesh_tri": mesh_tri, "mesh_poly": mesh_poly,
}

#: primitives whose surface is a general quadric given by 10 coefficients: a
#: small object far from the origin is not representable that way (the
#: constant term swallows it), so they stay within 1e3 sizes of the origin
QUADRICS = frozenset({"hyperboloid", "cone", "paraboloid"})

#: (primitive, prim) pairs that are curved (tangency rather than parallelism)
def curved(inst: Instance, prim: int) -> bool:
    kind = inst.spec["type"]
    if kind == "cylinder":
        return prim == 0
    return kind in ("sphere", "infinite_cylinder", "ellipsoid", "quadric")
