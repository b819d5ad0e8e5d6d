# SPDX-License-Identifier: Apache-2.0
"""Meshes (isect_mesh_create + ISECT_MESH): reference solver, containment, report, cases.

Hits.  A mesh is its faces, each a thin surface with the semantics of the
single primitive (isect.h, "Meshes"): a 3-index face is the triangle of its
vertices (module triangle: normal unit((b - a) x (c - a)), uv the barycentric
weights of b and c), a longer face the polygon of its vertices under the
even-odd rule (module polygon: Newell normal, uv 0).  prim = face index.  The
exactly-once guarantee is not assumed here: every face is solved on its own
with the exact perturbed winding number, and the generator checks, for each
case flagged "parity", that the count is odd exactly when the origin is
inside (by the containment below, which shares nothing with the ray tests).

Containment (independent of the tie-breaking rule).  p is inside when it
lies on a face (exact point-in-planar-polygon with boundary); otherwise the
crossing parity of a ray from p in a "generic" rational direction, taken from
a fixed list, the first one that meets no edge or vertex and lies in no face
plane it could touch (all decided exactly with rationals).

Report.  Edges are the undirected vertex pairs of consecutive face corners
(a pair a -> a is no edge); uses 1 = boundary, >= 3 = non-manifold, 2 in the
same direction = misoriented.  Components connect faces sharing an edge;
genus = sum over components of (2 - chi_c) / 2 for closed oriented meshes,
else -1.  Volume: divergence theorem over each face's fan from its first
vertex, relative to the centre of the vertices' bounding box; area: half the
length of each face's summed fan cross products (exact rationals, one mpmath
square root per face at 80 digits, one rounding at the end).
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Sequence

import mpmath

from exact import DesignError, cross, dot, is_zero, qv, sub, to_double
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, origin_tol as _origin_tol, ray, surface_case
import polygon
import transformed
import triangle

FAMILY = "mesh"

V3 = tuple[Fraction, Fraction, Fraction]


# ------------------------------------------------------------------ status
def status(shape: dict) -> set[str]:
    """Statuses isect_mesh_create gives (E_ARG before E_NONFINITE in isect.h)."""
    nv = len(shape["vertices"])
    out: set[str] = set()
    for f in shape["faces"]:
        if len(f) < 3 or not all(isinstance(i, int) and 0 <= i < nv for i in f):
            out.add("E_ARG")
    if not out and not all(math.isfinite(x) for v in shape["vertices"] for x in v):
        out.add("E_NONFINITE")
    return out


# -------------------------------------------------------------------- hits
def face_shape(shape: dict, f: Sequence[int]) -> dict:
    vs = [shape["vertices"][i] for i in f]
    if len(vs) == 3:
        return {"type": "triangle", "a": vs[0], "b": vs[1], "c": vs[2]}
    return {"type": "polygon", "vertices": vs, "rule": "evenodd"}


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    hits = []
    for i, f in enumerate(shape["faces"]):
        fs = face_shape(shape, f)
        solver = triangle.solve if fs["type"] == "triangle" else polygon.solve
        for h in solver(fs, r, ctx):
            h.prim = i
            hits.append(h)
    return hits


# ------------------------------------------------------------- topology
def edge_uses(shape: dict) -> dict[tuple[int, int], list[tuple[int, bool]]]:
    """Undirected edge -> [(face, reversed)], reversed when the face runs hi -> lo."""
    uses: dict[tuple[int, int], list[tuple[int, bool]]] = {}
    for fi, f in enumerate(shape["faces"]):
        for k in range(len(f)):
            a, b = f[k], f[(k + 1) % len(f)]
            if a != b:
                uses.setdefault((min(a, b), max(a, b)), []).append((fi, a > b))
    return uses


def is_closed(shape: dict) -> bool:
    return all(len(u) == 2 for u in edge_uses(shape).values())


def newell(vs: Sequence[V3]) -> V3:
    """Twice the vector area (sum of the fan's cross products; the same for any fan apex)."""
    acc = (Fraction(0),) * 3
    for k in range(1, len(vs) - 1):
        c = cross(sub(vs[k], vs[0]), sub(vs[k + 1], vs[0]))
        acc = tuple(x + y for x, y in zip(acc, c))
    return acc


def report(shape: dict) -> dict:
    faces = shape["faces"]
    verts = [qv(v) for v in shape["vertices"]]
    uses = edge_uses(shape)
    parent = list(range(len(faces)))

    def find(x: int) -> int:
        while parent[x] != x:
            x = parent[x]
        return x
    for u in uses.values():
        for fi, _ in u[1:]:
            a, b = find(u[0][0]), find(fi)
            parent[max(a, b)] = min(a, b)
    comp_of = [find(i) for i in range(len(faces))]
    comps = sorted(set(comp_of))
    boundary = sum(1 for u in uses.values() if len(u) == 1)
    nonmanifold = sum(1 for u in uses.values() if len(u) >= 3)
    misoriented = sum(1 for u in uses.values() if len(u) == 2 and u[0][1] == u[1][1])
    referenced = {i for f in faces for i in f}
    closed = boundary == 0 and nonmanifold == 0
    oriented = misoriented == 0
    genus = -1
    if closed and oriented:
        genus = 0
        for c in comps:
            vc = len({i for fi, f in enumerate(faces) if comp_of[fi] == c for i in f})
            ec = sum(1 for u in uses.values() if comp_of[u[0][0]] == c)
            fc = sum(1 for x in comp_of if x == c)
            chi = vc - ec + fc
            if chi % 2:
                raise DesignError("odd Euler characteristic of a closed oriented component")
            genus += (2 - chi) // 2
    degenerate = sum(1 for f in faces if is_zero(newell([verts[i] for i in f])))

    if verts:
        centre = tuple((min(v[k] for v in verts) + max(v[k] for v in verts)) / 2 for k in range(3))
    else:
        centre = (Fraction(0),) * 3
    volume = Fraction(0)
    area = mpmath.mpf(0)
    for f in faces:
        vs = [sub(verts[i], centre) for i in f]
        for k in range(1, len(vs) - 1):
            volume += dot(vs[0], cross(vs[k], vs[k + 1])) / 6
        n = newell(vs)
        area += mpmath.sqrt(mpmath.mpf(dot(n, n))) / 2
    return {"vertices": len(referenced), "edges": len(uses), "faces": len(faces),
            "boundary_edges": boundary, "nonmanifold_edges": nonmanifold,
            "misoriented_edges": misoriented, "degenerate_faces": degenerate,
            "components": len(comps), "euler_characteristic": len(referenced) - len(uses) + len(faces),
            "genus": genus, "closed": int(closed), "oriented": int(oriented),
            "volume": to_double(volume), "area": to_double(area)}


# ---------------------------------------------------------- containment
def on_segment(p, a, b) -> bool:
    return is_zero(cross(sub(b, a), sub(p, a))) and all(
        min(a[k], b[k]) <= p[k] <= max(a[k], b[k]) for k in range(3))


def locate(vs: Sequence[V3], n: V3, p: V3) -> str:
    """Where p (in the face's plane) lies: "boundary", "inside" or "outside" (even-odd)."""
    if any(on_segment(p, vs[k], vs[(k + 1) % len(vs)]) for k in range(len(vs))):
        return "boundary"
    drop = max(range(3), key=lambda k: abs(n[k]))
    i, j = [k for k in range(3) if k != drop]
    inside = False
    for k in range(len(vs)):
        a, b = vs[k], vs[(k + 1) % len(vs)]
        if (a[j] > p[j]) != (b[j] > p[j]):
            x = a[i] + (p[j] - a[j]) * (b[i] - a[i]) / (b[j] - a[j])
            if x > p[i]:
                inside = not inside
    return "inside" if inside else "outside"


#: generic directions for the parity ray (tried in order)
DIRECTIONS = [qv(d) for d in ((1, 0.3671875, 0.2109375), (-0.4453125, 1, 0.1796875),
                              (0.2890625, -0.6484375, 1), (-1, -0.1328125, 0.5546875))]


def planar_faces(shape: dict) -> list[tuple[list[V3], V3]]:
    """(vertices, Newell normal) of the faces with nonzero area."""
    out = []
    for f in shape["faces"]:
        vs = [qv(shape["vertices"][i]) for i in f]
        n = newell(vs)
        if not is_zero(n):
            out.append((vs, n))
    return out


def on_surface(shape: dict, p: V3) -> bool:
    return any(dot(n, sub(p, vs[0])) == 0 and locate(vs, n, p) != "outside"
               for vs, n in planar_faces(shape))


def contains(shape: dict, p: V3) -> bool:
    if on_surface(shape, p):
        return True
    faces = planar_faces(shape)
    for d in DIRECTIONS:
        crossings = 0
        for vs, n in faces:
            den, num = dot(n, d), dot(n, sub(vs[0], p))
            if den == 0:
                if num == 0:
                    break           # the ray lies in this face's plane: try another direction
                continue
            t = num / den
            if t <= 0:
                continue
            where = locate(vs, n, tuple(p[k] + t * d[k] for k in range(3)))
            if where == "boundary":
                break               # through an edge or vertex: try another direction
            crossings += where == "inside"
        else:
            return crossings % 2 == 1
    raise DesignError("no generic direction for the containment reference")


# ---------------------------------------------------------------- meshes
def mesh(vertices, faces) -> dict:
    return {"type": "mesh", "vertices": [[float(x) for x in v] for v in vertices],
            "faces": [[int(i) for i in f] for f in faces]}


CUBE_V = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
_i = {v: k for k, v in enumerate(CUBE_V)}
CUBE_QUADS = [[_i[v] for v in vs] for vs in polygon.CUBE_FACES.values()]
CUBE_TRIS = [t for f in CUBE_QUADS for t in ([f[0], f[1], f[2]], [f[0], f[2], f[3]])]


def cube_quads(lo=(0, 0, 0), size=1) -> dict:
    return mesh([[lo[k] + size * v[k] for k in range(3)] for v in CUBE_V], CUBE_QUADS)


def cube_tris() -> dict:
    return mesh(CUBE_V, CUBE_TRIS)


def octahedron() -> dict:
    vs = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    fs = []
    for sx in (0, 1):
        for sy in (2, 3):
            for sz in (4, 5):
                sign = (1 if sx == 0 else -1) * (1 if sy == 2 else -1) * (1 if sz == 4 else -1)
                fs.append([sx, sy, sz] if sign > 0 else [sx, sz, sy])
    return mesh(vs, fs)


def icosahedron() -> dict:
    """Vertices (0, +-1, +-phi) and cyclic permutations, phi rounded to a double."""
    phi = (1 + 5 ** 0.5) / 2
    vs = []
    for a in (1, -1):
        for b in (phi, -phi):
            vs += [(0, a, b), (a, b, 0), (b, 0, a)]
    # Faces: the 20 triples of mutually adjacent vertices (edge length 2), outward.
    q = [qv(v) for v in vs]
    e2 = min(sum((x - y) ** 2 for x, y in zip(q[i], q[j])) for i in range(12) for j in range(i))
    # phi is rounded, so the 30 edges are only nearly equal in length
    adj = [[abs(sum((x - y) ** 2 for x, y in zip(q[i], q[j])) - e2) < Fraction(1, 10**9) for j in range(12)]
           for i in range(12)]
    fs = []
    for i in range(12):
        for j in range(i + 1, 12):
            for k in range(j + 1, 12):
                if adj[i][j] and adj[j][k] and adj[i][k]:
                    out = dot(cross(sub(q[j], q[i]), sub(q[k], q[i])), q[i]) > 0
                    fs.append([i, j, k] if out else [i, k, j])
    assert len(fs) == 20
    return mesh(vs, fs)


def l_prism() -> dict:
    """An L (concave hexagon) extruded over z in [0, 1]: top and bottom are concave faces."""
    l2 = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    vs = [(x, y, 0) for x, y in l2] + [(x, y, 1) for x, y in l2]
    n = len(l2)
    fs = [list(range(n - 1, -1, -1)), list(range(n, 2 * n))]
    fs += [[k, (k + 1) % n, n + (k + 1) % n, n + k] for k in range(n)]
    return mesh(vs, fs)


def grid_solid(w: int, h: int, holes: Sequence[tuple[int, int]]) -> dict:
    """Unit cells of a w x h grid minus holes, extruded over z in [0, 1], quad faces.

    One hole makes a torus (genus 1), two a genus-2 solid. Top and bottom are
    coplanar quads sharing edges and vertices.
    """
    cells = [(x, y) for y in range(h) for x in range(w) if (x, y) not in holes]
    index: dict[tuple[int, int, int], int] = {}

    def v(x: int, y: int, z: int) -> int:
        return index.setdefault((x, y, z), len(index))
    fs = []
    for x, y in cells:
        fs.append([v(x, y, 1), v(x + 1, y, 1), v(x + 1, y + 1, 1), v(x, y + 1, 1)])
        fs.append([v(x, y, 0), v(x, y + 1, 0), v(x + 1, y + 1, 0), v(x + 1, y, 0)])
    solid = set(cells)
    for x, y in cells:        # side walls where a neighbour cell is missing, outward
        if (x, y - 1) not in solid:
            fs.append([v(x, y, 0), v(x + 1, y, 0), v(x + 1, y, 1), v(x, y, 1)])
        if (x, y + 1) not in solid:
            fs.append([v(x + 1, y + 1, 0), v(x, y + 1, 0), v(x, y + 1, 1), v(x + 1, y + 1, 1)])
        if (x - 1, y) not in solid:
            fs.append([v(x, y + 1, 0), v(x, y, 0), v(x, y, 1), v(x, y + 1, 1)])
        if (x + 1, y) not in solid:
            fs.append([v(x + 1, y, 0), v(x + 1, y + 1, 0), v(x + 1, y + 1, 1), v(x + 1, y, 1)])
    vs = [None] * len(index)
    for p, k in index.items():
        vs[k] = p
    return mesh(vs, fs)


def torus() -> dict:
    return grid_solid(3, 3, [(1, 1)])


def genus2() -> dict:
    return grid_solid(5, 3, [(1, 1), (3, 1)])


def with_faces(m: dict, faces) -> dict:
    return {"type": "mesh", "vertices": m["vertices"], "faces": [list(f) for f in faces]}


def two_cubes() -> dict:
    """The triangle cube and a quad cube at x in [2, 3]: mixed face sizes, two components."""
    a, b = cube_tris(), cube_quads((2, 0, 0))
    off = len(a["vertices"])
    return {"type": "mesh", "vertices": a["vertices"] + b["vertices"],
            "faces": a["faces"] + [[i + off for i in f] for f in b["faces"]]}


def book() -> dict:
    """Three triangles hinged on the edge (0,0,0)-(0,0,1): one non-manifold edge."""
    return mesh([(0, 0, 0), (0, 0, 1), (1, 0, 0.5), (-1, 1, 0.5), (-1, -1, 0.5)],
                [[0, 1, 2], [1, 0, 3], [0, 1, 4]])


def with_degenerate() -> dict:
    """The triangle cube and, apart, a zero-area triangle of three collinear points."""
    m = cube_tris()
    return {"type": "mesh", "vertices": m["vertices"] + [[2.0, 0.5, 0.5], [3.0, 0.5, 0.5], [4.0, 0.5, 0.5]],
            "faces": m["faces"] + [[8, 9, 10]]}


def cube_zero_area_face(polygons: bool = False, quarters: bool = False) -> dict:
    """Issue 13's closed cube with a zero-area face: v3 = (0, 0, 1/2) is the
    midpoint of the cube edge v0-v4, the x = 0 side uses the run 0 -> 3 -> 4,
    the y = 0 side the edge 4 -> 0, and the face (3, 0, 4) of three collinear
    vertices closes the T-junction (edges 3 -> 0, 0 -> 4, 4 -> 3 pair with
    their reverses: closed and oriented).  Triangles, or (polygons) quads and
    the x = 0 side as a pentagon with the collinear run; quarters: the run
    also through q1 = (0, 0, 1/4) and q3 = (0, 0, 3/4) (vertices 9, 10) and
    the zero-area face the collinear pentagon (0, 4, 10, 3, 9)."""
    vs = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 0, 0.5), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 1, 0),
          (0, 0, 0.25), (0, 0, 0.75)]
    quads = [[1, 2, 6, 5],   # x = 1
             [0, 1, 5, 4],   # y = 0 (edge 4 -> 0)
             [8, 7, 6, 2],   # y = 1
             [0, 8, 2, 1],   # z = 0
             [4, 5, 6, 7]]   # z = 1
    run = [0, 9, 3, 10, 4] if quarters else [0, 3, 4]
    if polygons:
        faces = quads + [run + [7, 8]]
    else:
        faces = [t for f in quads for t in ([f[0], f[1], f[2]], [f[0], f[2], f[3]])]
        faces += [[run[i], run[i + 1], 7 if i + 1 >= len(run) // 2 + 1 else 8] for i in range(len(run) - 1)]
        faces += [[run[len(run) // 2], 7, 8]]
    faces.append([0, 4, 10, 3, 9] if quarters else [3, 0, 4])
    return mesh(vs, faces)


# ------------------------------------------------------------------ cases
def up(x: float, y: float, z0: float = -1) -> dict:
    return ray((x, y, z0), (0, 0, 1))


def down(x: float, y: float, z0: float = 2) -> dict:
    return ray((x, y, z0), (0, 0, -1))


def cases() -> list[dict]:
    cq, ct, oc, ico = cube_quads(), cube_tris(), octahedron(), icosahedron()
    lp, tor, g2 = l_prism(), torus(), genus2()
    c = []

    def hit(name, flags, shape, r, **kw):
        c.append(case(name, flags, shape=shape, ray=r, **kw))

    # --- cube of quads (polygon faces through CSR offsets)
    hit("quad cube: straight through", ["basic", "polygon-faces", "parity"], cq, up(0.5, 0.25))
    hit("quad cube: oblique, non-unit direction", ["basic", "polygon-faces", "non-unit-dir", "parity"], cq,
        ray((-1, 0.25, 0.5), (3, 0.5, 0.25)))
    hit("quad cube: from inside", ["inside", "polygon-faces", "parity"], cq, ray((0.5, 0.5, 0.5), (0.25, -1, 0.5)))
    hit("quad cube: from inside, tmin = -inf", ["inside", "negative-t", "polygon-faces"], cq,
        ray((0.5, 0.5, 0.5), (0.25, -1, 0.5), tmin=-INF))
    hit("quad cube: corner to corner (vertices)", ["vertex", "polygon-faces", "frame-tie", "parity"], cq,
        ray((-1, -1, -1), (1, 1, 1)))
    hit("quad cube: through the edges x=y=0 and x=y=1", ["edge", "polygon-faces", "frame-tie", "parity"], cq,
        ray((-1, -1, 0.5), (1, 1, 0)))
    hit("quad cube: grazing the edge x=0, y=1", ["edge", "edge-graze", "polygon-faces", "frame-tie", "parity"], cq,
        ray((-1, 0, 0.5), (1, 1, 0)))
    hit("quad cube: through edge x=0,z=1 and corner (1,1,0)", ["edge", "vertex", "polygon-faces", "parity"], cq,
        ray((-0.5, 0.25, 1.5), (1, 0.5, -1)))
    hit("quad cube: along a face (in its plane)", ["in-plane", "polygon-faces", "parity"], cq,
        ray((-1, 0, 0.5), (1, 0, 0)))
    hit("quad cube: miss", ["miss", "polygon-faces", "parity"], cq, up(1.5, 0.5))
    hit("quad cube: cull_back keeps the entry", ["cull-back", "polygon-faces"], cq, up(0.5, 0.25),
        opts=opts(flags=["cull_back"]))
    hit("quad cube: tmax between entry and exit", ["clip", "polygon-faces"], cq,
        ray((0.5, 0.25, -1), (0, 0, 1), tmax=1.5))
    hit("quad cube: exit exactly at tmax", ["clip-exact", "polygon-faces"], cq,
        ray((0.5, 0.25, -1), (0, 0, 1), tmax=2.0))
    hit("quad cube: origin on the bottom face, exit through an edge", ["on-surface", "edge", "polygon-faces"], cq,
        ray((0.5, 0.25, 0), (0.5, 0.25, 1)))
    hit("quad cube: eps = 0", ["eps", "vertex", "polygon-faces", "parity"], cq, ray((-1, -1, -1), (1, 1, 1)),
        opts=opts(eps=0.0))

    # --- cube of triangles
    hit("triangle cube: straight through (uv)", ["basic", "parity"], ct, up(0.75, 0.25))
    hit("triangle cube: through both face diagonals", ["edge", "parity"], ct, up(0.5, 0.5))
    hit("triangle cube: through the diagonal, ray down", ["edge", "frame-swap", "parity"], ct, down(0.25, 0.75))
    hit("triangle cube: corner to corner", ["vertex", "frame-tie", "parity"], ct, ray((2, 2, 2), (-1, -1, -1)))
    hit("triangle cube: from the centre through corner (1,1,1)", ["vertex", "inside", "frame-tie", "parity"], ct,
        ray((0.5, 0.5, 0.5), (1, 1, 1)))
    hit("triangle cube: from the centre through the edge x=1,y=0", ["edge", "inside", "frame-tie", "parity"], ct,
        ray((0.5, 0.5, 0.5), (1, -1, 0)))
    hit("triangle cube: grazing the edge y=0, z=0", ["edge", "edge-graze", "parity"], ct, ray((0.5, -1, 1), (0, 1, -1)))
    hit("triangle cube: cull_back from inside drops the exit", ["cull-back", "inside"], ct, up(0.75, 0.25, 0.5),
        opts=opts(flags=["cull_back"]))

    # --- octahedron |x|+|y|+|z| = 1
    hit("octahedron: along x through two vertices", ["vertex", "parity"], oc, ray((-2, 0, 0), (1, 0, 0)))
    hit("octahedron: from the centre through an edge midpoint", ["edge", "inside", "frame-tie", "parity"], oc,
        ray((0, 0, 0), (1, 1, 0)))
    hit("octahedron: from the centre through a face centre", ["inside", "frame-tie", "parity"], oc,
        ray((0, 0, 0), (1, 1, 1)))
    hit("octahedron: touching an edge from below", ["edge", "edge-graze", "parity"], oc, up(0.5, 0.5, -2))
    hit("octahedron: line through a vertex and a face", ["vertex", "negative-t", "frame-tie"], oc,
        ray((0, 0, 1), (0.25, 0.5, -1), tmin=-INF))

    # --- icosahedron (phi rounded to a double; axis rays keep the projection exact)
    hit("icosahedron: from the centre through an edge midpoint", ["edge", "inside", "parity"], ico,
        ray((0, 0, 0), (0, 0, 1)))
    hit("icosahedron: along z through two edge midpoints", ["edge", "parity"], ico, up(0, 0, -3))
    hit("icosahedron: along z through two vertices", ["vertex", "parity"], ico, up(0, 1, -3))
    hit("icosahedron: oblique", ["basic", "parity"], ico, ray((3, -2, 1), (-1, 0.75, -0.125)))

    # --- L prism: concave faces
    hit("L prism: down through the arm", ["concave", "polygon-faces", "frame-swap", "parity"], lp, down(0.5, 1.5))
    hit("L prism: down through the notch", ["concave", "miss", "polygon-faces", "parity"], lp, down(1.5, 1.5))
    hit("L prism: down the reflex edge (1,1)", ["reflex", "vertex", "polygon-faces", "frame-swap", "parity"],
        lp, down(1, 1))
    hit("L prism: across the notch wall", ["concave", "polygon-faces", "parity"], lp, ray((-1, 1.5, 0.5), (1, 0, 0)))
    hit("L prism: along y = 1 through the reflex edge", ["reflex", "edge", "polygon-faces", "parity"], lp,
        ray((-1, 1, 0.5), (1, 0, 0)))
    hit("L prism: diagonal through the reflex edge", ["reflex", "edge", "polygon-faces", "frame-tie", "parity"],
        lp, ray((2.5, 2.5, 0.5), (-1, -1, 0)))

    # --- torus and genus 2 (grid of coplanar quads)
    hit("torus: down through the hole", ["genus", "miss", "polygon-faces", "frame-swap", "parity"], tor,
        down(1.5, 1.5))
    hit("torus: down through the ring", ["genus", "polygon-faces", "frame-swap", "parity"], tor, down(0.5, 0.5))
    hit("torus: across both walls of the hole", ["genus", "polygon-faces", "parity"], tor,
        ray((-1, 1.5, 0.5), (1, 0, 0)))
    hit("torus: down a shared edge of coplanar quads", ["genus", "edge", "polygon-faces", "frame-swap", "parity"],
        tor, down(1, 0.5))
    hit("torus: down a vertex shared by three quads and the hole", ["genus", "vertex", "polygon-faces",
                                                                  "frame-swap", "parity"], tor, down(1, 1))
    hit("2x2 block: down a vertex shared by four coplanar quads", ["vertex", "polygon-faces", "frame-swap",
                                                                  "parity"], grid_solid(2, 2, []), down(1, 1))
    hit("genus 2: across both holes", ["genus", "polygon-faces", "parity"], g2, ray((-1, 1.5, 0.5), (1, 0, 0)))
    hit("genus 2: diagonal through grid vertices", ["genus", "vertex", "polygon-faces", "frame-tie", "parity"], g2,
        ray((-1, -1, 0.5), (1, 1, 0)))
    hit("genus 2: oblique from inside", ["genus", "inside", "polygon-faces", "parity"], g2,
        ray((0.5, 0.5, 0.5), (1, 0.25, 0.125)))

    # --- transformed meshes
    scale2 = transformed.affine([[2, 0, 0], [0, 2, 0], [0, 0, 2]], (1, -1, 0.5))
    hit("quad cube scaled 2 and moved: through", ["transformed", "scaling", "translation", "exact-transform",
                                                  "polygon-faces"], cq, up(2, 0, -1), transform=scale2)
    hit("triangle cube scaled 2 and moved: through the diagonal", ["transformed", "scaling", "translation",
                                                                   "exact-transform", "edge"], ct,
        up(2, 0, -1), transform=scale2)
    mirror = transformed.affine([[-1, 0, 0], [0, 1, 0], [0, 0, 1]])
    hit("triangle cube mirrored in x: normals stay outward", ["transformed", "mirror", "exact-transform"], ct,
        ray((-0.25, 0.5, -1), (0, 0.125, 1)), transform=mirror)
    rot = transformed.affine(transformed.rotation((1, 2, 2), 30.0), (0.5, 0, 0))
    hit("L prism rotated: oblique", ["transformed", "rotation", "polygon-faces"], lp,
        ray((-3, 0.5, 0.25), (1, 0.125, 0.0625)), transform=rot)

    # --- open, misoriented, mixed, non-manifold, degenerate, empty
    open_cube = with_faces(cq, CUBE_QUADS[:5])     # the z = 1 face removed
    hit("open cube: up through the missing face", ["open-mesh", "polygon-faces"], open_cube, up(0.5, 0.5))
    hit("open cube: any_hit, one possible hit", ["open-mesh", "any-hit", "polygon-faces"], open_cube,
        up(0.5, 0.5), opts=opts(flags=["any_hit"]))
    hit("triangle cube: any_hit on a miss", ["any-hit", "miss"], ct, up(1.5, 0.5), opts=opts(flags=["any_hit"]))
    hit("triangle cube: any_hit, one hit in [tmin, tmax]", ["any-hit", "clip"], ct,
        ray((0.25, 0.5, -1), (0, 0, 1), tmax=1.5), opts=opts(flags=["any_hit"]))
    flipped = with_faces(cq, CUBE_QUADS[:4] + [CUBE_QUADS[4][::-1]] + CUBE_QUADS[5:])
    hit("cube with the z = 0 face flipped: both hits exit", ["misoriented", "polygon-faces"], flipped,
        up(0.25, 0.5))
    tc = two_cubes()
    hit("two cubes (triangles, quads): through both", ["components", "mixed-faces", "parity"], tc,
        ray((-1, 0.5, 0.25), (1, 0, 0)))
    hit("book: a line through two of the three pages", ["nonmanifold", "negative-t"], book(),
        ray((-0.5, 0, 0.5), (0, 1, 0), tmin=-INF))
    hit("degenerate face is never hit", ["degenerate", "miss"], with_degenerate(), ray((3, 0.5, -1), (0, 0, 1)))
    # Issue 13: a zero-area face closing a T-junction in a closed cube; rays through the collinear
    # run (its midpoint vertex, points of its two halves), from outside and inside, along it.
    zc, zp, zq = cube_zero_area_face(), cube_zero_area_face(polygons=True), cube_zero_area_face(True, True)
    for zname, zm, zflags in (("zero-area face cube", zc, []), ("zero-area face cube (pentagon)", zp,
                                                                  ["polygon-faces"]),
                              ("zero-area face cube (collinear pentagon)", zq, ["polygon-faces"])):
        f = ["degenerate", "parity"] + zflags
        hit(f"{zname}: from outside through the midpoint vertex", f + ["vertex"], zm,
            ray((-1, -0.5, 0.25), (1, 0.5, 0.25)))
        hit(f"{zname}: from outside through the edge below it", f + ["edge"], zm,
            ray((-1, -0.5, 0.125), (1, 0.5, 0.125)))
        hit(f"{zname}: from outside through the edge above it", f + ["edge"], zm,
            ray((-0.5, -1, 0.5), (0.5, 1, 0.25)))
        hit(f"{zname}: from inside out through the midpoint vertex", f + ["vertex", "inside"], zm,
            ray((0.5, 0.25, 0.5), (-1, -0.5, 0)))
        hit(f"{zname}: along the collinear edge", f + ["edge", "in-plane"], zm, ray((0, 0, -1), (0, 0, 1)))
        hit(f"{zname}: eps = 0, through the edge", f + ["edge", "eps"], zm,
            ray((-1, -0.5, 0.125), (1, 0.5, 0.125)), opts=opts(eps=0.0))
    # The reported ray: with the shear rounded, it got one EXIT hit from outside (parity "inside").
    for zname, zm in (("zero-area face cube", zc), ("zero-area face cube (pentagon)", zp)):
        for dz in (1.013, 1.002):
            hit(f"{zname}: the audit's ray (dir z {dz}) past the run", ["degenerate", "rounded-frame", "parity"],
                zm, ray((-1, -0.7, -0.3), (1, 0.7, dz)), opts=opts(eps=0.0))
            c[-1]["_exact"] = True
    hit("empty mesh (no faces) is never hit", ["empty-mesh", "miss"], mesh(CUBE_V, []), up(0.5, 0.5))

    # --- containment
    def inside(name, flags, shape, p):
        c.append(case(name, ["contains"] + flags, op="contains", shape=shape, point=[float(x) for x in p]))
    inside("quad cube: centre", ["polygon-faces"], cq, (0.5, 0.5, 0.5))
    inside("quad cube: outside", ["polygon-faces"], cq, (1.5, 0.5, 0.5))
    inside("quad cube: on a face", ["boundary", "polygon-faces"], cq, (1, 0.25, 0.5))
    inside("quad cube: on an edge", ["boundary", "edge", "polygon-faces"], cq, (1, 0.25, 1))
    inside("quad cube: on a vertex", ["boundary", "vertex", "polygon-faces"], cq, (1, 1, 0))
    inside("quad cube: 2^-40 outside a face", ["polygon-faces"], cq, (1 + 2 ** -40, 0.5, 0.5))
    inside("quad cube: 2^-40 inside a face", ["polygon-faces"], cq, (1 - 2 ** -40, 0.5, 0.5))
    inside("quad cube: outside, +x ray along an edge", ["edge", "in-plane", "polygon-faces"], cq, (-1, 1, 1))
    inside("quad cube: beside, +x ray along a face plane", ["in-plane", "polygon-faces"], cq, (-1, 0, 0.5))
    inside("triangle cube: on a face diagonal", ["boundary", "edge"], ct, (0.5, 0.5, 0))
    inside("triangle cube: centre, +x ray through the face diagonal", ["edge"], ct, (0.5, 0.5, 0.5))
    inside("octahedron: +x ray through an edge", ["edge"], oc, (0.5, 0.25, 0))
    inside("octahedron: +x ray through a vertex", ["vertex"], oc, (-0.5, 0, 0))
    inside("octahedron: outside, +x ray through a vertex", ["vertex"], oc, (-1.5, 0, 0))
    inside("icosahedron: centre", [], ico, (0, 0, 0))
    inside("icosahedron: just inside a vertex", [], ico, (0, 1, 1.6))
    inside("icosahedron: just outside a vertex", [], ico, (0, 1, 1.62))
    inside("L prism: in the notch", ["concave", "polygon-faces"], lp, (1.5, 1.5, 0.5))
    inside("L prism: in the arm", ["concave", "polygon-faces"], lp, (0.5, 1.5, 0.5))
    inside("L prism: on the reflex edge", ["boundary", "reflex", "polygon-faces"], lp, (1, 1, 0.5))
    inside("L prism: +x ray through the reflex edge", ["reflex", "polygon-faces"], lp, (0.5, 1, 0.5))
    inside("L prism: notch, +x ray along the wall y = 1", ["reflex", "in-plane", "polygon-faces"], lp,
           (-0.5, 1, 0.5))
    inside("torus: in the hole", ["genus", "polygon-faces"], tor, (1.5, 1.5, 0.5))
    inside("torus: in the ring, +x ray along hole corners", ["genus", "vertex", "polygon-faces"], tor, (0.5, 1, 0.5))
    inside("torus: on the top, at a shared vertex", ["genus", "boundary", "vertex", "polygon-faces"], tor,
           (2, 1, 1))
    inside("genus 2: between the holes", ["genus", "polygon-faces"], g2, (2.5, 1.5, 0.5))
    inside("genus 2: in the second hole", ["genus", "polygon-faces"], g2, (3.5, 1.5, 0.5))
    inside("two cubes: in the quad cube", ["components", "mixed-faces"], tc, (2.5, 0.5, 0.5))
    inside("two cubes: between them", ["components", "mixed-faces"], tc, (1.5, 0.5, 0.5))
    inside("cube with a flipped face: parity still decides", ["misoriented", "polygon-faces"], flipped,
           (0.5, 0.5, 0.5))
    inside("zero-area face cube: centre", ["degenerate"], zc, (0.5, 0.5, 0.5))
    inside("zero-area face cube: outside, +x ray through the midpoint vertex", ["degenerate", "vertex"], zc,
           (-0.5, 0, 0.5))
    inside("zero-area face cube: inside, +x ray along y = 0 past the run", ["degenerate", "in-plane"], zc,
           (0.5, 0, 0.25))
    inside("zero-area face cube (collinear pentagon): on the run", ["degenerate", "boundary", "polygon-faces"],
           zq, (0, 0, 0.375))

    # --- report
    def check(name, flags, shape):
        c.append(case(name, ["report"] + flags, op="mesh_check", shape=shape))
    check("quad cube: chi 2, volume 1, area 6", ["polygon-faces"], cq)
    check("triangle cube", [], ct)
    check("octahedron", [], oc)
    check("icosahedron", [], ico)
    check("L prism (concave faces): volume 3", ["concave", "polygon-faces"], lp)
    check("torus: chi 0, genus 1", ["genus", "polygon-faces"], tor)
    check("genus 2: chi -2", ["genus", "polygon-faces"], g2)
    check("open cube: 4 boundary edges", ["open-mesh", "polygon-faces"], open_cube)
    check("flipped face: 4 misoriented edges", ["misoriented", "polygon-faces"], flipped)
    check("two cubes: 2 components", ["components", "mixed-faces"], tc)
    check("book: 1 non-manifold edge", ["nonmanifold"], book())
    check("a degenerate face", ["degenerate"], with_degenerate())
    check("zero-area face cube: closed, 1 degenerate face", ["degenerate"], zc)
    check("zero-area face cube (collinear pentagon)", ["degenerate", "polygon-faces"], zq)
    check("empty mesh", ["empty-mesh"], mesh(CUBE_V, []))
    check("quad cube scaled by 1e3 far from the origin", ["far", "polygon-faces"],
          cube_quads((1e6, -2e6, 3e6), 1e3))

    # --- bad input
    bad_r = up(0.25, 0.25)
    hit("index out of range", ["bad-input"], mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 3]]), bad_r)
    hit("negative index", ["bad-input"], mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, -1, 2]]), bad_r)
    hit("a face of two vertices", ["bad-input"], with_faces(cq, CUBE_QUADS[:5] + [[1, 2]]), bad_r)
    hit("NaN vertex", ["bad-input", "nonfinite"], mesh([(0, 0, 0), (1, math.nan, 0), (0, 1, 0)], [[0, 1, 2]]),
        bad_r)
    hit("infinite vertex (unused by any face)", ["bad-input", "nonfinite"],
        mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0), (math.inf, 0, 0)], [[0, 1, 2]]), bad_r)
    hit("zero direction", ["bad-input"], cq, ray((0.5, 0.5, -1), (0, 0, 0)))
    inside("contains on an open mesh", ["bad-input", "open-mesh", "polygon-faces"], open_cube, (0.5, 0.5, 0.5))
    inside("contains on a non-manifold mesh", ["bad-input", "nonmanifold"], book(), (0, 0, 0.5))
    inside("contains, NaN point", ["bad-input", "nonfinite"], cq, (math.nan, 0.5, 0.5))
    check("report of a mesh with a bad index", ["bad-input"], mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 7]]))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0)
    top = (0.25, 0.75, 1.0)                  # on the top face, inside one triangle of it
    into, out = (0.25, -0.5, -1), (-0.125, 0.25, 1)
    for nm, sh, extra in (("triangle cube", ct, []), ("quad cube", cq, ["polygon-faces"])):
        hit(f"{nm}: on the top face, inward: enter at t = 0, exit", ["origin-on-surface"] + extra, sh,
            ray(top, into))
        c[-1]["_tol"] = _origin_tol
        for name, o, d, more in (("on the top face, outward: exit at t = 0 only", top, out, []),
                                 ("1 ulp above the top face, inward", nudged(top, 2, 1), into, []),
                                 ("1 ulp above the top face, outward: no hit", nudged(top, 2, 1), out, ["miss"]),
                                 ("1 ulp below the top face, outward: t ~ +1e-16", nudged(top, 2, -1), out, []),
                                 ("2 ulps below the top face, inward: exit only", nudged(top, 2, -2), into, [])):
            c.append(surface_case(f"{nm}: {name}", extra + more, shape=sh, ray=ray(o, d)))
    c.append(surface_case("triangle cube: on the top face's diagonal, inward (one face claims t = 0)", ["edge"],
                          shape=ct, ray=ray((0.5, 0.5, 1.0), (0.25, -0.5, -1))))
    c.append(surface_case("triangle cube: on the edge x = 1, z = 1, inward (one face claims t = 0)", ["edge"],
                          shape=ct, ray=ray((1.0, 0.5, 1.0), (-1, 0.25, -0.5))))
    c.append(surface_case("triangle cube: on the edge x = 1, z = 1, outward (one face claims t = 0)", ["edge"],
                          shape=ct, ray=ray((1.0, 0.5, 1.0), (1, 0.25, 0.5))))
    c.append(surface_case("octahedron: 1 ulp outside a face, inward", [], shape=oc,
                          ray=ray(nudged((0.25, 0.25, 0.5), 0, 1), (-1, -0.5, -0.75))))
    c.append(surface_case("octahedron: 1 ulp inside a face, outward", [], shape=oc,
                          ray=ray(nudged((0.25, 0.25, 0.5), 0, -1), (1, 0.5, 0.75))))
    c.append(surface_case("L prism: on the concave top face, outward", ["concave", "polygon-faces"], shape=lp,
                          ray=ray((0.5, 1.5, 1.0), (0.25, 0.125, 1))))
    c.append(surface_case("L prism: 1 ulp below the concave top face, outward", ["concave", "polygon-faces"],
                          shape=lp, ray=ray(nudged((0.5, 1.5, 1.0), 2, -1), (0.25, 0.125, 1))))
    c.append(surface_case("triangle cube scaled 2 and moved: 1 ulp outside, inward", ["transformed", "scaling",
                          "translation", "exact-transform"], shape=ct, transform=scale2,
                          ray=ray(nudged((1.5, 0.5, 2.5), 2, 1), (0.25, -0.5, -1))))

    # --- revision 2: grazing (a face nearly parallel to the ray). Triangles and polygons use no
    # eps, so the top face is crossed at a slope of 2^-44 (far below the default eps) and the
    # count keeps the parity of the origin, at every eps
    s44 = 2.0 ** -44
    for nm, sh, extra in (("triangle cube", ct, []), ("quad cube", cq, ["polygon-faces"])):
        hit(f"{nm}: grazing into the top face at slope 2^-44, out through x = 1", ["grazing", "near-parallel",
            "parity"] + extra, sh, ray((-0.25, 0.375, 1 + s44 / 2), (1, 0.125, -s44)), tol=TIGHT)
        hit(f"{nm}: the same with eps 1e-3: still two hits", ["grazing", "near-parallel", "eps"] + extra, sh,
            ray((-0.25, 0.375, 1 + s44 / 2), (1, 0.125, -s44)), opts=opts(eps=1e-3), tol=TIGHT)
        hit(f"{nm}: 2^-45 below the top face, rising at 2^-44: exits through it", ["grazing", "near-parallel",
            "inside", "parity"] + extra, sh, ray((0.25, 0.375, 1 - s44 / 2), (1, 0.125, s44)), tol=TIGHT)
        hit(f"{nm}: 2^-45 above the top face, rising: miss", ["grazing", "near-parallel", "miss", "parity"]
            + extra, sh, ray((0.25, 0.375, 1 + s44 / 2), (1, 0.125, s44)))

    # --- revision 2: far and small (t to about 4 ulp)
    far_cube = cube_quads((1e7, 0, 0), 2.0 ** -10)
    hit("far: quad cube of side 2^-10 at x = 1e7, oblique ray from the origin", ["far", "polygon-faces"], far_cube,
        ray((0, 3e-4, 5e-4), (1, 2e-11, -1e-11)), tol=TIGHT)
    far_ico = mesh([[6e6 + 1e-3 * x, 8e6 + 1e-3 * y, 1e-3 * z] for x, y, z in icosahedron()["vertices"]],
                   icosahedron()["faces"])
    hit("far: icosahedron of radius ~2e-3 at (6e6, 8e6, 0)", ["far", "loose-point"], far_ico,
        ray((0, 2e-4, 3e-4), (3, 4, 0)), tol={"t": 1e-15, "point": 1e-8, "uv": 1e-6})
    return c


def check_case(c: dict) -> None:
    """Exactly-once, checked on the reference itself: cases flagged "parity" hit a
    closed mesh an odd number of times exactly when the origin is inside."""
    if "parity" not in c["flags"]:
        return
    r, shape, e = c["ray"], c["shape"], c["expect"]
    if not (is_closed(shape) and r["tmin"] == 0 and r["tmax"] == INF and "transform" not in c
            and not (c.get("opts") or {}).get("flags")):
        raise DesignError("a parity case needs a closed mesh, [0, inf), no transform, no flags")
    org = qv(r["org"])
    if on_surface(shape, org):
        raise DesignError("a parity case's origin lies on the surface")
    if e["count"] % 2 != int(contains(shape, org)):
        raise AssertionError(f"exactly-once violated by the reference: {e['count']} hits, "
                             f"origin inside = {contains(shape, org)}")
