# SPDX-License-Identifier: Apache-2.0
"""Run the library, the textbook code and the exact reference on the same rays.

For every ray of a class the library answers twice -- ``intersect`` (closest
hit, batch) and ``intersect_all_batch`` (every hit) -- and the textbook code
once; the exact reference (``reference.solve``) gives every crossing of the
line.  ``metrics.match`` pairs hits and counts decision errors; every pair is
measured (t, point, normal).

Secondary rays: the library's own first hits of a batch of random rays are the
origins, the directions are the mirror direction d - 2 (d.n) n or a random
direction on the same side, tmin = 0.  A "self hit" is a closest hit at
t |d| < 1e-9 times the object's size (re-hitting the surface the ray leaves);
``exact_self_hits`` counts those the exact geometry really has (the rounded
origin lies on the far side of the surface).  When the shape has ``spawn``
(isect_spawn_ray, SPEC revision 2) the rays come from
``shape.spawn(hits, directions)`` instead, origin and tmin included (a hit it
refuses, e.g. a TOUCH decided by eps off the surface, keeps the plain ray).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from fractions import Fraction

import mpmath
import numpy as np

from . import metrics as M
from . import primitives as P
from . import rays as RY
from . import reference as R
from . import surface, textbook
from .metrics import LibHit, Tally

SELF_HIT = 1e-9
PRIMITIVES = tuple(P.PRIMITIVES)
CLASSES = RY.CLASSES


@dataclass(frozen=True)
class Cell:
    """The result of one (primitive, class): library and textbook summaries."""
    primitive: str
    cls: str
    lib: M.Summary
    textbook: M.Summary
    seconds: float


def seed_of(seed: int, name: str, cls: str) -> list[int]:
    return [seed, PRIMITIVES.index(name), CLASSES.index(cls)]


def secondary(group: RY.Group, rng: np.random.Generator) -> RY.Group | None:
    """Rays leaving the library's first hits of ``group`` (see the module doc)."""
    shape = group.inst.shape
    first = shape.intersect(group.org, group.dir, tmin=group.tmin, tmax=group.tmax, errors="mark")
    hit = (first["kind"] >= 1) & (first["kind"] <= 3)
    if not hit.any():
        return None
    first, d0 = first[hit], group.dir[hit]
    n = first["normal"]
    refl = d0 - 2 * np.einsum("ij,ij->i", d0, n)[:, None] * n
    rnd = rng.normal(size=refl.shape)
    same = np.sign(np.einsum("ij,ij->i", rnd, n)) == np.sign(np.einsum("ij,ij->i", refl, n))
    rnd = np.where(same[:, None], rnd, rnd - 2 * np.einsum("ij,ij->i", rnd, n)[:, None] * n)
    use_refl = rng.random(len(refl)) < 0.5
    dirs = np.where(use_refl[:, None], refl, rnd * np.linalg.norm(d0, axis=1)[:, None])
    if hasattr(shape, "spawn"):
        rays = spawn_all(shape, first, dirs)
        return RY.Group(group.inst, np.array(rays["org"]), np.array(rays["dir"]),
                        np.array(rays["tmin"]), np.array(rays["tmax"]))
    return RY.Group(group.inst, np.array(first["point"]), dirs, np.zeros(len(dirs)),
                    np.full(len(dirs), math.inf))


def spawn_all(shape, first: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """``shape.spawn(first, dirs)``; a hit it refuses (isect_spawn_ray's
    E_DEGENERATE for a point not near the surface, such as a TOUCH decided by
    eps off the surface) keeps the plain ray from the hit point instead."""
    import isect
    rays = np.empty(len(first), dtype=isect.RAY_DTYPE)
    lo = 0
    while lo < len(first):
        try:
            rays[lo:] = shape.spawn(first[lo:], dirs[lo:])
            break
        except isect.IsectError as error:
            bad = lo + int(error.index)
            if bad > lo:
                rays[lo:bad] = shape.spawn(first[lo:bad], dirs[lo:bad])
            rays[bad] = (first[bad]["point"], dirs[bad], 0.0, math.inf)
            lo = bad + 1
    return rays


def point_distance(inst: P.Instance, h: LibHit, r: R.RefHit, org: np.ndarray, d: np.ndarray) -> mpmath.mpf:
    """Distance of the reported point to the exact surface.

    A TOUCH decided by the eps policy need not lie on the surface (the line
    may pass near it, isect.h: org + t dir or snapped): for TOUCH hits the
    smaller of the distances to the surface and to the exact point o + t d
    counts.
    """
    dist = surface.distance(inst.spec, r.prim, h.point)
    if r.kind == "touch":
        p = R.exact.point_on_ray(R.exact.qv(org), R.exact.qv(d), r.t)
        off = mpmath.sqrt(sum((mpmath.mpf(Fraction(a)) - R.exact.mp(b)) ** 2 for a, b in zip(h.point, p)))
        dist = min(dist, off)
    return dist


def measure(tally: Tally, inst: P.Instance, pairs, org: np.ndarray, d: np.ndarray, where: str) -> None:
    """Add the t, point and normal errors of paired hits to ``tally``.

    A pair on different parts (prim) is a decision error already; its point
    and normal are not measured against the other part.
    """
    for h, r in pairs:
        tally.hits += 1
        if r.t == 0:
            tally.t0_bad += h.t != 0
        else:
            tally.add("t", M.t_error_ulps(h.t, r.t), where)
        tally.add("norm", M.length_error_ulps(h.normal), where)
        if h.prim != r.prim:
            continue
        dist = point_distance(inst, h, r, org, d)
        pmax = max(abs(x) for x in h.point)
        tally.add("point", float(dist / mpmath.ldexp(1, M.ulp_exp(pmax))), where)
        scale = max(inst.scale, pmax) if inst.unbounded else inst.scale
        tally.add("point_obj", float(dist / mpmath.ldexp(1, M.ulp_exp(scale))), where)
        tally.add("angle", M.angle_units(h.normal, r.normal), where)


def _closest_wrong(tally: Tally, where: str) -> None:
    tally.decisions["closest"] += 1
    tally.worst.setdefault("closest", (1.0, where))


def _closest(tally: Tally, rec: LibHit | None, ref: R.RefResult, where: str) -> None:
    kept = ref.kept
    if rec is None or not kept:
        if (rec is None) != (not kept):
            _closest_wrong(tally, where)
        return
    nearest = min(ref.hits, key=lambda r: abs(mpmath.mpf(Fraction(rec.t)) - R.exact.mp(r.t)))
    # two crossings whose exact t round to the same double (an entry through
    # a cap 1e-20 before the exit through the side) are told apart by what
    # they are, not by which exact t the rounded one happens to lie nearer
    same = M.KIND_NAMES.get(rec.kind) == kept[0].kind and rec.prim == kept[0].prim
    if nearest is not kept[0] and not (same and M.t_error_ulps(rec.t, kept[0].t) <= 4):
        _closest_wrong(tally, where + f" closest=({rec.t!r}, prim {rec.prim}, kind {rec.kind})")
    elif kept[0].t != 0:
        tally.add("t_closest", M.t_error_ulps(rec.t, kept[0].t), where)


def _self_hit(t: float, d: np.ndarray, size: float) -> bool:
    return math.isfinite(t) and t * float(np.linalg.norm(d)) < SELF_HIT * size


def evaluate(group: RY.Group, lib: Tally, tb: Tally, label: str, is_secondary: bool) -> None:
    """Measure the library and the textbook code on one group of rays."""
    inst = group.inst
    o, d, tmin, tmax = group.org, group.dir, group.tmin, group.tmax
    closest = inst.shape.intersect(o, d, tmin=tmin, tmax=tmax, errors="mark")
    off, hits = inst.shape.intersect_all_batch(o, d, tmin=tmin, tmax=tmax, errors="mark")
    toff, thits = textbook.intersect_all(inst.spec, o, d, tmin, tmax)
    by_prim = inst.spec["type"] == "mesh"
    for i in range(len(o)):
        where = (f"{label} o={o[i].tolist()} d={d[i].tolist()} tmin={tmin[i]!r} tmax={tmax[i]!r} "
                 f"spec={inst.spec}")
        try:
            ref = R.solve(inst.spec, o[i], d[i], float(tmin[i]), float(tmax[i]))
        except R.Undecided:
            lib.undecided += 1
            tb.undecided += 1
            continue
        for tally, recs, first in (
                (lib, hits[off[i]:off[i + 1]], closest[i]),
                (tb, thits[toff[i]:toff[i + 1]], thits[toff[i]] if toff[i + 1] > toff[i] else None)):
            tally.rays += 1
            got = [LibHit.of(x) for x in recs]
            pairs, errs = M.match(got, ref, by_prim)
            for k, v in errs.items():
                tally.decisions[k] += v
                if v and k not in tally.worst:
                    tally.worst[k] = (float(v), where)
            measure(tally, inst, pairs, o[i], d[i], where)
            rec = None if first is None or not 1 <= int(first["kind"]) <= 3 else LibHit.of(first)
            _closest(tally, rec, ref, where)
            if is_secondary:
                tally.self_hits += rec is not None and _self_hit(rec.t, d[i], inst.radius)
        if is_secondary:
            k = ref.kept
            hit0 = k and _self_hit(float(R.exact.mp(k[0].t)), d[i], inst.radius)
            lib.exact_self_hits += bool(hit0)
            tb.exact_self_hits += bool(hit0)


def run_cell(name: str, cls: str, n: int, seed: int = 1) -> Cell:
    """Generate the class's rays for one primitive and measure both implementations."""
    start = time.perf_counter()
    rng = np.random.default_rng(seed_of(seed, name, cls))
    lib, tb = Tally(), Tally()
    for gi, group in enumerate(RY.GENERATORS[cls](name, rng, n)):
        if cls == "secondary":
            group = secondary(group, rng)
            if group is None:
                continue
        evaluate(group, lib, tb, f"{name}/{cls} seed={seed} group={gi}", cls == "secondary")
    return Cell(name, cls, lib.summary(), tb.summary(), time.perf_counter() - start)


def _run_star(args: tuple[str, str, int, int]) -> Cell:
    return run_cell(*args)


def run(primitives: list[str], classes: list[str], n: int, seed: int = 1, jobs: int = 1,
        progress=None) -> list[Cell]:
    """Every applicable (primitive, class) cell, in table order."""
    todo = [(p, c, n, seed) for p in primitives for c in classes if RY.applicable(p, c)]
    if jobs <= 1:
        cells = []
        for t in todo:
            cells.append(run_cell(*t))
            if progress:
                progress(cells[-1])
        return cells
    import multiprocessing as mp_
    with mp_.get_context("fork").Pool(jobs) as pool:
        cells = []
        for cell in pool.imap_unordered(_run_star, todo):
            cells.append(cell)
            if progress:
                progress(cell)
    order = {(p, c): i for i, (p, c, _, _) in enumerate(todo)}
    return sorted(cells, key=lambda c: order[(c.primitive, c.cls)])
