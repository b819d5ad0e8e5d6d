# SPDX-License-Identifier: Apache-2.0
"""Secondary rays (isect_spawn_ray, SPEC revision 2, op "spawn"): cases.

A spawn case holds a shape (and optional transform), the primary ray and the
secondary direction ``dir``. The runner intersects the primary ray, spawns a
ray from its first hit in direction ``dir`` and intersects that ray; the
expectation is the status of isect_spawn_ray and the secondary ray's hits.

The reference (reference.evaluate_spawn) follows the *exact* geometry: the
secondary ray starts at the exact first hit point P (every primary ray here
meets its shape at a rational point, so P is known exactly) in direction dir
over [0, inf), and the crossing of the surface it leaves, at t = 0, is not
counted. isect.h places the spawned origin a few ulps from P, strictly on the
side dir points into, so the library must find exactly these hits: none of
the surface left, every other crossing (those lie at least 2^16 spawn offsets
away from P, which the reference checks). The library's origin is a few ulps
off P, so t, point and normal are compared to 1e-9.

Primary rays are built as P - s*d0 with direction d0, so they reach the
chosen surface point P at t = s exactly.
"""
from __future__ import annotations

import math

from box import box
from convex import TETRA
from cylinder import cyl
from ellipsoid import ell
from mesh import cube_tris, l_prism
from model import SPAWN_TOL, case, ray
from plane import plane
from polygon import poly
from sphere import sphere
from transformed import SCALE, world_ray
from triangle import tri

FAMILY = "spawn"


def toward(p, d0, s: float = 1.0) -> dict:
    """The primary ray reaching p at t = s along d0 (origin p - s*d0, exact in doubles here)."""
    return ray([x - s * v for x, v in zip(p, d0)], d0)


def cases() -> list[dict]:
    c = []

    def spawn(name, flags, shape, primary, d, **kw):
        c.append(case(name, ["spawn", *flags], op="spawn", shape=shape, ray=primary,
                      dir=[float(x) for x in d], tol=dict(SPAWN_TOL), **kw))

    # sphere of radius 5: the primary ray from (5, 6, 2) along -(1, 1, 1) enters at (3, 4, 0), t = 2
    s5 = sphere((0, 0, 0), 5)
    at = toward((3, 4, 0), (-1, -1, -1), 2)
    spawn("sphere: reflection (outward): the secondary ray meets nothing", ["miss"], s5, at, (0.68, 1.24, -1))
    spawn("sphere: refraction (inward): the far side only, never the entry point", [], s5, at, (-1, -2, 0.5))
    spawn("sphere: grazing refraction (slightly inward): a short chord", [], s5, at, (-4, 2.875, 0.5))
    spawn("sphere: from the exit point onward (outward): nothing", ["miss"], s5,
          toward((3, 4, 0), (1, 1, 0.25), 2), (1, 1, 0.25))
    spawn("sphere: back from the exit point (inward): the other side", [], s5,
          toward((3, 4, 0), (1, 1, 0.25), 2), (-1, -1, -0.25))

    # planes and triangles: leaving them never finds them again, on either side
    tilt = plane((1, 2, 2), -6)                           # through (2, 1, 1)
    p_at = toward((2, 1, 1), (-1, -2, -2))
    spawn("plane: leaving on the side it came from (reflection): nothing", ["miss"], tilt, p_at, (0.5, 0, 1))
    spawn("plane: going on through it (transmission): nothing", ["miss"], tilt, p_at, (-1, -0.5, -1))
    slant = tri((1, 0, 0), (0, 1, 0), (0, 0, 1))          # through (0.25, 0.25, 0.5)
    t_at = toward((0.25, 0.25, 0.5), (-1, -1, -1))
    spawn("triangle: reflection: nothing", ["miss"], slant, t_at, (0.5, 1, 1.5))
    spawn("triangle: transmission: nothing", ["miss"], slant, t_at, (-1, -2, -3))
    spawn("triangle: hit from behind, transmission to the front: nothing", ["miss"], slant,
          toward((0.25, 0.25, 0.5), (1, 0.5, 0.25)), (1, 0.5, 0.25))

    # a polygon (the U lifted into x + 2y + 4z = 8)
    u_up = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]
    tilted_u = poly([(x, y, (8 - x - 2 * y) / 4) for x, y in u_up])
    u_at = toward((0.5, 2.5, 0.625), (-1, -2, -4), 0.25)
    spawn("polygon: reflection: nothing", ["miss", "concave"], tilted_u, u_at, (1, 2, 1))
    spawn("polygon: transmission: nothing", ["miss", "concave"], tilted_u, u_at, (-1, -2, -1))

    # a box slab 1e-9 thick: refraction must find the second face 1e-9 away
    slab = box((0, 0, 0), (1, 1, 1e-9))
    s_at = ray((0.5, 0.25, 1), (0, 0, -1))                # enters the top face at (0.5, 0.25, 1e-9)
    spawn("box slab 1e-9 thick: refraction finds the bottom face at t = 1e-9", [], slab, s_at, (0, 0, -1))
    spawn("box slab 1e-9 thick: oblique refraction, bottom face at t = 1e-9", [], slab, s_at, (0.125, 0.25, -1))
    spawn("box slab 1e-9 thick: reflection: nothing", ["miss"], slab, s_at, (0.125, 0.25, 1))
    spawn("box slab 1e-9 thick: entering the bottom face, refraction finds the top face", [], slab,
          ray((0.5, 0.25, -1), (0, 0, 1)), (0.25, 0, 1))

    # closed meshes
    ct = cube_tris()
    m_at = toward((0.25, 0.75, 1), (0, 0, -1))            # the top face, inside triangle 11
    spawn("triangle cube: reflection at the top face: nothing", ["miss"], ct, m_at, (0.25, -0.5, 1))
    spawn("triangle cube: into the mesh: the far side", [], ct, m_at, (0.25, -0.5, -1))
    spawn("triangle cube: from inside, at the exit, back inward", ["inside"], ct,
          ray((0.25, 0.75, 0.5), (0, 0, 1)), (0.125, 0.25, -1))
    lp = l_prism()
    n_at = toward((1.5, 1, 0.5), (0, -1, 0), 0.75)       # the notch wall y = 1, from inside the notch
    spawn("L prism: reflection off the notch wall into the other arm", ["concave", "polygon-faces"], lp,
          n_at, (-1, 1, 0.125))
    spawn("L prism: refraction through the notch wall", ["concave", "polygon-faces"], lp, n_at, (-0.25, -1, 0.125))

    # transformed sphere (exact transform: object-space rays are exact)
    w_at = world_ray(SCALE, (5, 6, 2), (-1, -1, -1))     # enters at SCALE (3, 4, 0) = (7, 0, 3), t = 2
    spawn("transformed sphere: refraction: the far side", ["transformed", "scaling", "exact-transform"],
          s5, w_at, (-2, -1, 2), transform=SCALE)
    spawn("transformed sphere: reflection: nothing", ["transformed", "scaling", "exact-transform", "miss"],
          s5, w_at, (2, 0.5, -1), transform=SCALE)

    # other solids
    c5 = cyl((1, 2, 3), (1, 5, 7), 5)
    spawn("capped cylinder: refraction at the side: the far side", [], c5,
          toward((1, 7.5, 2), (0, -4, 3)), (0.5, -1, 0.5))
    spawn("capped cylinder: refraction at cap p1", ["cap"], c5, toward((3, 7, 5.5), (0, -1, -1)), (-0.5, -1, -1))
    spawn("convex tetrahedron: refraction at the slanted face", [], TETRA,
          toward((0.25, 0.25, 0.5), (-1, -1, -1)), (-1, -2, -3))
    e3 = ell((1, 2, 3), (3, 6, 1.5))
    spawn("ellipsoid: refraction: the far side", [], e3, toward((3, 4, 4), (-1, -1, -1)), (-1, -0.5, -2))

    # bad input: the status of isect_spawn_ray (the primary ray is valid)
    spawn("the primary ray misses: the MISS record is not a hit", ["bad-input", "miss"], s5,
          ray((10, 10, -10), (0, 0, 1)), (0, 0, 1))
    spawn("zero direction", ["bad-input"], s5, at, (0, 0, 0))
    spawn("zero direction with -0.0 components", ["bad-input", "neg-zero"], s5, at, (-0.0, 0, -0.0))
    spawn("NaN direction", ["bad-input", "nonfinite"], s5, at, (0, math.nan, 1))
    spawn("infinite direction", ["bad-input", "nonfinite"], s5, at, (-math.inf, 0, 0))
    spawn("mesh: zero direction", ["bad-input"], ct, m_at, (0, 0, 0))
    spawn("mesh: the primary ray misses", ["bad-input", "miss"], ct, ray((3, 3, 3), (1, 0, 0)), (1, 0, 0))
    spawn("transformed sphere: NaN direction", ["bad-input", "nonfinite", "transformed", "scaling"], s5, w_at,
          (math.nan, 0, 0), transform=SCALE)
    return c
