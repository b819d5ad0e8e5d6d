# SPDX-License-Identifier: Apache-2.0
"""Bad input (every error class of SPEC.md / isect.h) and degenerate geometry that
is *not* an error (status ok, never hit).

Each error case has exactly one defect, so the expected status does not
depend on the order in which an implementation validates its arguments
(the reference refuses a case that would have two different statuses).
NULL pointers and the hit buffer capacity are not expressible in the schema;
an empty vertex or plane list stands for the "bad count" class.
"""
from __future__ import annotations

import math

from box import box
from convex import convex
from cylinder import cyl, icyl
from ellipsoid import ell
from model import case, opts, ray
from plane import plane
from polygon import poly
from quadric import quad
from sphere import sphere
from transformed import affine
from triangle import tri

FAMILY = "bad_input"

NAN, INF = math.nan, math.inf


def cases() -> list[dict]:
    S = sphere((0, 0, 0), 1)
    R = ray((0, 0, -5), (0, 0, 1))
    c = []

    def bad(name, flags, **kw):
        c.append(case(name, ["bad-input"] + flags, **kw))

    def deg(name, shape, r=R, flags=()):
        c.append(case(name, ["degenerate", "miss", *flags], shape=shape, ray=r))

    # the ray
    bad("ray origin NaN", ["nonfinite"], shape=S, ray=ray((NAN, 0, -5), (0, 0, 1)))
    bad("ray origin +Inf", ["nonfinite"], shape=S, ray=ray((0, INF, -5), (0, 0, 1)))
    bad("ray direction NaN", ["nonfinite"], shape=S, ray=ray((0, 0, -5), (0, 0, NAN)))
    bad("ray direction -Inf", ["nonfinite"], shape=S, ray=ray((0, 0, -5), (-INF, 0, 1)))
    bad("tmin NaN", ["nonfinite"], shape=S, ray=ray((0, 0, -5), (0, 0, 1), tmin=NAN))
    bad("tmax NaN", ["nonfinite"], shape=S, ray=ray((0, 0, -5), (0, 0, 1), tmax=NAN))
    bad("zero direction", [], shape=S, ray=ray((0, 0, -5), (0, 0, 0)))
    bad("zero direction with -0.0 components", ["neg-zero"], shape=S, ray=ray((0, 0, -5), (-0.0, 0, -0.0)))
    bad("zero direction on a plane", [], shape=plane((0, 0, 1), -1), ray=ray((0, 0, 5), (0, 0, 0)))
    c.append(case("tmin = +inf is allowed: no hits", ["empty-interval", "miss"], shape=S,
                  ray=ray((0, 0, -5), (0, 0, 1), tmin=INF)))
    c.append(case("tmax = -inf is allowed: no hits", ["empty-interval", "miss"], shape=S,
                  ray=ray((0, 0, -5), (0, 0, 1), tmax=-INF)))
    c.append(case("tiny direction 1e-300 is not zero", ["non-unit-dir"], shape=S,
                  ray=ray((0, 0, -5), (0, 0, 1e-300))))
    # options
    bad("eps negative", [], shape=S, ray=R, opts=opts(eps=-1e-12))
    bad("eps NaN", ["nonfinite"], shape=S, ray=R, opts=opts(eps=NAN))
    bad("eps +Inf", ["nonfinite"], shape=S, ray=R, opts=opts(eps=INF))
    c.append(case("eps = -0.0 is allowed (not < 0)", ["eps", "neg-zero", "tangent"], shape=S,
                  ray=ray((1, 0, -5), (0, 0, 1)), opts=opts(eps=-0.0)))
    # plane
    bad("plane normal NaN", ["nonfinite"], shape=plane((0, NAN, 1), -1), ray=R)
    bad("plane d +Inf", ["nonfinite"], shape=plane((0, 0, 1), INF), ray=R)
    deg("plane with zero normal", plane((0, 0, 0), 0))
    # sphere
    bad("sphere centre NaN", ["nonfinite"], shape=sphere((0, NAN, 0), 1), ray=R)
    bad("sphere radius +Inf", ["nonfinite"], shape=sphere((0, 0, 0), INF), ray=R)
    bad("sphere radius NaN", ["nonfinite"], shape=sphere((0, 0, 0), NAN), ray=R)
    bad("sphere radius negative", [], shape=sphere((0, 0, 0), -1), ray=R)
    bad("sphere radius -1e-300", [], shape=sphere((0, 0, 0), -1e-300), ray=R)
    deg("sphere radius 0", sphere((0, 0, 0), 0))
    deg("sphere radius -0.0 (equal to 0: degenerate, not negative)", sphere((0, 0, 0), -0.0), flags=("neg-zero",))
    # box
    bad("box lo NaN", ["nonfinite"], shape=box((NAN, -1, -1), (1, 1, 1)), ray=R)
    bad("box hi +Inf", ["nonfinite"], shape=box((-1, -1, -1), (1, INF, 1)), ray=R)
    bad("box lo > hi in y", [], shape=box((-1, 1, -1), (1, -1, 1)), ray=R)
    deg("flat box (lo.x == hi.x)", box((0, -1, -1), (0, 1, 1)), ray((-5, 0, 0), (1, 0, 0)))
    deg("box collapsed to a point", box((0, 0, 0), (0, 0, 0)))
    # triangle
    bad("triangle vertex +Inf", ["nonfinite"], shape=tri((0, 0, 0), (INF, 0, 0), (0, 1, 0)), ray=R)
    bad("triangle vertex NaN", ["nonfinite"], shape=tri((0, 0, 0), (1, 0, 0), (0, NAN, 0)), ray=R)
    deg("zero-area triangle (collinear)", tri((-1, -1, 0), (0, 0, 0), (1, 1, 0)))
    deg("zero-area triangle (repeated vertex)", tri((0, 0, 0), (1, 0, 0), (1, 0, 0)), ray((0.5, 0, -5), (0, 0, 1)))
    # polygon
    bad("polygon with 2 vertices", [], shape=poly([(0, 0), (1, 0)]), ray=R)
    bad("polygon with 0 vertices", [], shape={"type": "polygon", "vertices": [], "rule": "evenodd"}, ray=R)
    bad("polygon rule 2", [], shape=poly([(-1, -1), (1, -1), (0, 1)], 2), ray=R)
    bad("polygon rule -1", [], shape=poly([(-1, -1), (1, -1), (0, 1)], -1), ray=R)
    bad("polygon vertex NaN", ["nonfinite"], shape=poly([(-1, -1), (1, NAN), (0, 1)]), ray=R)
    deg("collinear polygon", poly([(-1, 0), (0, 0), (1, 0), (2, 0)]), ray((0.5, 0, -5), (0, 0, 1)))
    deg("polygon of one repeated point", poly([(0, 0), (0, 0), (0, 0)]))
    deg("bowtie with cancelling areas", poly([(-1, -1), (1, 1), (1, -1), (-1, 1)]), ray((0.5, 0.25, -5), (0, 0, 1)),
        flags=("self-intersecting",))
    # convex
    bad("convex with 0 planes", [], shape=convex([]), ray=R)
    bad("convex plane NaN", ["nonfinite"], shape=convex([(1, 0, 0, -1), (NAN, 0, 0, -1)]), ray=R)
    bad("convex plane d -Inf", ["nonfinite"], shape=convex([(1, 0, 0, -INF)]), ray=R)
    # cylinders
    bad("cylinder radius negative", [], shape=cyl((0, 0, 0), (0, 0, 1), -1), ray=ray((-5, 0, 0.5), (1, 0, 0)))
    bad("cylinder capped = 2", ["c-only"], shape=cyl((0, 0, 0), (0, 0, 1), 1, 2), ray=ray((-5, 0, 0.5), (1, 0, 0)))
    bad("cylinder capped = -1", ["c-only"], shape=cyl((0, 0, 0), (0, 0, 1), 1, -1), ray=ray((-5, 0, 0.5), (1, 0, 0)))
    bad("cylinder p1 NaN", ["nonfinite"], shape=cyl((0, 0, 0), (0, 0, NAN), 1), ray=ray((-5, 0, 0.5), (1, 0, 0)))
    bad("cylinder radius +Inf", ["nonfinite"], shape=cyl((0, 0, 0), (0, 0, 1), INF), ray=ray((-5, 0, 0.5), (1, 0, 0)))
    deg("capped cylinder with zero radius", cyl((0, 0, 0), (0, 0, 1), 0), ray((-5, 0, 0.5), (1, 0, 0)))
    deg("capped cylinder with zero-length axis", cyl((0, 0, 0.5), (0, 0, 0.5), 1), ray((0, 0, -5), (0, 0, 1)))
    deg("open cylinder with zero-length axis", cyl((0, 0, 0.5), (0, 0, 0.5), 1, False), ray((-5, 0, 0.5), (1, 0, 0)),
        flags=("open",))
    bad("infinite cylinder radius negative", [], shape=icyl((0, 0, 0), (0, 0, 1), -0.5), ray=ray((-5, 0, 0), (1, 0, 0)))
    bad("infinite cylinder axis NaN", ["nonfinite"], shape=icyl((0, 0, 0), (0, NAN, 1), 1),
        ray=ray((-5, 0, 0), (1, 0, 0)))
    deg("infinite cylinder with zero axis", icyl((0, 0, 0), (0, 0, 0), 1), ray((-5, 0, 0), (1, 0, 0)))
    deg("infinite cylinder with zero radius", icyl((0, 0, 0), (0, 0, 1), 0), ray((-5, 0, 0), (1, 0, 0)))
    # ellipsoid, quadric
    bad("ellipsoid semi-axis negative", [], shape=ell((0, 0, 0), (1, -1, 1)), ray=R)
    bad("ellipsoid semi-axis +Inf", ["nonfinite"], shape=ell((0, 0, 0), (1, 1, INF)), ray=R)
    deg("ellipsoid with a zero semi-axis", ell((0, 0, 0), (1, 1, 0)))
    bad("quadric coefficient NaN", ["nonfinite"], shape=quad(1, 1, 1, 0, 0, 0, 0, 0, NAN, -1), ray=R)
    bad("quadric coefficient -Inf", ["nonfinite"], shape=quad(1, 1, 1, 0, 0, 0, 0, 0, 0, -INF), ray=R)
    deg("quadric with all coefficients zero", quad(*[0] * 10))
    # unknown shape types (raw isect_shape.type)
    for t in (0, 12, -1, 11):
        what = "ISECT_MESH without a mesh" if t == 11 else "unknown shape type"
        bad(f"{what}: type {t}", ["c-only"], shape={"type": t, "center": [0.0, 0.0, 0.0], "radius": 1.0}, ray=R)
    # transforms
    bad("singular transform", ["transformed", "singular"], shape=S,
        transform=affine([[1, 0, 0], [0, 1, 0], [2, 0, 0]]), ray=R)
    bad("non-affine transform", ["transformed", "non-affine"], shape=S,
        transform=affine([[1, 0, 0], [0, 1, 0], [0, 0, 1]])[:12] + [0.0, 0.5, 0.0, 1.0], ray=R)
    bad("transform with NaN", ["transformed", "nonfinite"], shape=S,
        transform=affine([[1, 0, 0], [0, 1, 0], [0, 0, NAN]]), ray=R)
    # contains
    for nm, sh in (("plane", plane((0, 0, 1), 0)), ("triangle", tri((0, 0, 0), (1, 0, 0), (0, 1, 0))),
                   ("polygon", poly([(0, 0), (1, 0), (0, 1)])),
                   ("open cylinder", cyl((0, 0, 0), (0, 0, 1), 1, False))):
        bad(f"contains on a thin surface: {nm}", ["contains"], op="contains", shape=sh, point=[0.0, 0.0, 0.0])
    bad("contains with a NaN point", ["contains", "nonfinite"], op="contains", shape=S, point=[0.0, NAN, 0.0])
    bad("contains on a box with lo > hi", ["contains"], op="contains", shape=box((1, 0, 0), (0, 1, 1)),
        point=[0.5, 0.5, 0.5])
    c.append(case("contains on a degenerate (zero-radius) sphere: outside", ["contains", "degenerate"],
                  op="contains", shape=sphere((0, 0, 0), 0), point=[0.0, 0.0, 0.0]))
    # 2D helpers
    sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    bad("point_in_polygon2 with 2 vertices", [], op="point_in_polygon2", polygon=sq[:2], point=[0.5, 0.5],
        rule="evenodd")
    bad("point_in_polygon2 rule 7", [], op="point_in_polygon2", polygon=sq, point=[0.5, 0.5], rule=7)
    bad("point_in_polygon2 point NaN", ["nonfinite"], op="point_in_polygon2", polygon=sq, point=[NAN, 0.5],
        rule="evenodd")
    bad("point_in_polygon2 vertex Inf", ["nonfinite"], op="point_in_polygon2",
        polygon=[[0.0, 0.0], [INF, 0.0], [1.0, 1.0]], point=[0.5, 0.25], rule="nonzero")
    bad("winding_number2 with 0 vertices", ["winding"], op="winding_number2", polygon=[], point=[0.5, 0.5])
    bad("winding_number2 point Inf", ["winding", "nonfinite"], op="winding_number2", polygon=sq, point=[0.5, INF])
    bad("polygon_normal with 2 vertices", ["normal-op"], op="polygon_normal", vertices=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    bad("polygon_normal vertex NaN", ["normal-op", "nonfinite"], op="polygon_normal",
        vertices=[[0.0, 0.0, 0.0], [1.0, NAN, 0.0], [0.0, 1.0, 0.0]])
    bad("plane_from_points with 1 point", ["normal-op"], op="plane_from_points", vertices=[[0.0, 0.0, 0.0]])
    bad("polygon_normal of collinear points", ["normal-op", "degenerate"], op="polygon_normal",
        vertices=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]])
    return c
