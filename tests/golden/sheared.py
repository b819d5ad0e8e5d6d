# SPDX-License-Identifier: Apache-2.0
"""The exact inside test of triangles and polygons (isect.h, "Tie-breaking").

1. The ray's sheared frame (Woop, Benthin & Wald 2013), as isect.h defines it:
   kz = index of the largest |dir[k]| (lowest index on ties),
   kx = (kz+1) mod 3, ky = (kz+2) mod 3, kx and ky swapped when dir[kz] < 0;
   a point p maps to  x = (p-org)[kx] - (dir[kx]/dir[kz]) (p-org)[kz],
                      y = (p-org)[ky] - (dir[ky]/dir[kz]) (p-org)[kz].
   The ray becomes the +z axis through the 2D origin.  Here the map is
   evaluated exactly (rationals).

2. The winding number of the projected polygon around the query point q = 0,
   moved symbolically to q = (-e^2, -e) for an infinitesimal e > 0.
   For an edge P -> Q (coordinates relative to the unperturbed query point)
        det(P - q, Q - q) = det(P, Q) + e (Px - Qx) + e^2 (Qy - Py),
   so its sign is the sign of det(P, Q) if nonzero, else of Px - Qx if
   nonzero, else of Qy - Py.  A vertex is "above" the test line when its y
   >= 0 (since y > -e); an upward edge (P below, Q above) with q on its left
   adds +1, a downward edge with q on its right adds -1.  A horizontal edge
   on the line has both ends above and counts for neither side.

Because the library evaluates the projection in doubles, an exact decision
(a zero determinant or a vertex on the test line) only carries over when the
projection is exact in doubles; ``Frame.project`` emulates it and
``winding_sheared`` refuses cases where it would not be.
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

from exact import U, q, refuse

P2 = tuple[Fraction, Fraction]


# ------------------------------------------------------- perturbed 2D tests
def orient_perturbed(p: P2, r: P2) -> int:
    """Sign of det(p - q, r - q) with q = (-e^2, -e); p, r relative to q's base point."""
    d = p[0] * r[1] - p[1] * r[0]
    if d != 0:
        return 1 if d > 0 else -1
    if p[0] != r[0]:
        return 1 if p[0] > r[0] else -1
    if r[1] != p[1]:
        return 1 if r[1] > p[1] else -1
    return 0  # a zero-length edge


def winding_perturbed(poly: Sequence[P2]) -> tuple[int, list[int]]:
    """Winding number of poly around the perturbed origin.

    Also returns the indices of the edges whose orientation sign was used,
    for the robustness checks of the sheared frame.
    """
    w = 0
    used: list[int] = []
    n = len(poly)
    for i in range(n):
        p, r = poly[i], poly[(i + 1) % n]
        p_above, r_above = p[1] >= 0, r[1] >= 0
        if not p_above and r_above:          # upward crossing
            used.append(i)
            if orient_perturbed(p, r) > 0:
                w += 1
        elif p_above and not r_above:        # downward crossing
            used.append(i)
            if orient_perturbed(p, r) < 0:
                w -= 1
    return w, used


def winding_at(poly: Sequence[Sequence[Fraction]], pt: Sequence[Fraction]) -> int:
    """2D helper semantics: winding number of poly around pt (perturbed)."""
    rel = [(v[0] - pt[0], v[1] - pt[1]) for v in poly]
    return winding_perturbed(rel)[0]


# ----------------------------------------------------------- sheared frame
@dataclass(frozen=True)
class Frame:
    kz: int
    kx: int
    ky: int
    sx: Fraction      # dir[kx] / dir[kz], exact
    sy: Fraction      # dir[ky] / dir[kz], exact
    org: tuple[Fraction, ...]
    dir: tuple[Fraction, ...]

    @staticmethod
    def of(org: Sequence[Fraction], d: Sequence[Fraction]) -> "Frame":
        mags = [abs(x) for x in d]
        kz = max(range(3), key=lambda k: (mags[k], -k))  # largest, lowest index on ties
        kx, ky = (kz + 1) % 3, (kz + 2) % 3
        if d[kz] < 0:
            kx, ky = ky, kx
        return Frame(kz, kx, ky, d[kx] / d[kz], d[ky] / d[kz], tuple(org), tuple(d))

    def project(self, p: Sequence[Fraction]) -> tuple[P2, bool, Fraction]:
        """Exact 2D image of p, whether doubles compute it exactly, and an error bound.

        The double emulation is a = fl(p - org), s = fl(dir[kx]/dir[kz]),
        x = fl(a[kx] - fl(s*a[kz])); when every intermediate is exact, any
        evaluation order (or an FMA) gives the exact value.
        """
        a = [p[k] - self.org[k] for k in range(3)]
        exact = True
        bound = Fraction(0)
        out = []
        for k, s in ((self.kx, self.sx), (self.ky, self.sy)):
            val = a[k] - s * a[self.kz]
            af = [float(p[j]) - float(self.org[j]) for j in (k, self.kz)]
            sf = float(self.dir[k]) / float(self.dir[self.kz])
            prod = sf * af[1]
            vf = af[0] - prod
            ok = (Fraction(af[0]) == a[k] and Fraction(af[1]) == a[self.kz]
                  and Fraction(sf) == s and Fraction(prod) == s * a[self.kz]
                  and Fraction(vf) == val)
            exact = exact and ok
            if not ok:
                bound = max(bound, 8 * U * (abs(a[k]) + abs(s) * abs(a[self.kz])))
            out.append(val)
        return (out[0], out[1]), exact, bound


def winding_sheared(verts: Sequence[Sequence[Fraction]], org: Sequence[Fraction],
                    d: Sequence[Fraction], ray_exact: bool = True) -> int:
    """Winding number of the sheared projection of verts around the ray.

    Raises DesignError when the answer could depend on how the library rounds
    the projection: an exact tie (vertex on the test line, zero determinant)
    needs an exact projection; otherwise every sign must clear the rounding
    bound by a factor 1000 (or a relative 1e-6 when the library sees an
    inexact object-space ray through a transform).
    """
    frame = Frame.of(org, d)
    proj = [frame.project(v) for v in verts]
    pts = [p for p, _, _ in proj]
    all_exact = ray_exact and all(e for _, e, _ in proj)
    w, used = winding_perturbed(pts)

    def bound(i: int) -> Fraction:
        if ray_exact:
            return proj[i][2]
        mag = max(abs(x) for x in pts[i]) + max(abs(x - o) for x, o in zip(verts[i], org))
        return mag * Fraction(1, 10**9)

    ties = any(p[1] == 0 for p in pts)
    n = len(pts)
    for i in used:
        p, r = pts[i], pts[(i + 1) % n]
        det = p[0] * r[1] - p[1] * r[0]
        if det == 0:
            ties = True
        elif not all_exact:
            err = bound(i) * (abs(r[0]) + abs(r[1])) + bound((i + 1) % n) * (abs(p[0]) + abs(p[1]))
            if abs(det) <= 1000 * err:
                refuse("edge determinant too close to 0 for an inexact projection")
    if ties and not all_exact:
        refuse("exact tie in the sheared frame but the projection is inexact in doubles")
    if not all_exact:
        for i, p in enumerate(pts):
            if p[1] != 0 and abs(p[1]) <= 1000 * bound(i):
                refuse("vertex too close to the test line for an inexact projection")
    return w


def frame_info(d: Sequence[float]) -> tuple[int, bool, bool]:
    """(kz, swapped, tie) of a direction, for flagging cases."""
    dq = [q(x) for x in d]
    f = Frame.of([Fraction(0)] * 3, dq)
    mags = sorted((abs(x) for x in dq), reverse=True)
    return f.kz, dq[f.kz] < 0, mags[0] == mags[1]
