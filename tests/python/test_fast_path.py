# SPDX-License-Identifier: Apache-2.0
"""The one-ray fast path of ``Shape.intersect`` (``isect._shape._closest_one``).

``shape.intersect(origin, direction)`` with one ray given as 3 plain numbers
(a list or tuple of floats / ints / numpy float64, or a float64 array of
shape (3,)) and the default options skips the general path's numpy packing.
These tests show that the fast path is taken for those inputs, and that it
changes nothing: for every shape class, over many inputs of every form (good,
bad, malformed), the call returns the same bytes in the same kind of object,
or raises the same exception with the same message, and warns alike, as the
general path alone.
"""

from __future__ import annotations

import contextlib

import threading
import warnings
from collections.abc import Callable
from functools import partial
from typing import Any
from unittest import mock

import isect
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from isect import _shape
from meshes import CUBE_QUADS, CUBE_VERTICES, icosphere
from strategies import EDGE_INTS, Sample, one_of_each, ray_arguments

TURN = np.array(
    [[0.8, -0.6, 0.0, 1.0], [0.6, 0.8, 0.0, -2.0], [0.0, 0.0, 2.0, 0.5], [0.0, 0.0, 0.0, 1.0]]
)


def every_class() -> list[isect.Shape]:
    """One shape of every class (the cylinder capped and open), meshes of
    triangles and of polygon faces, and transformed shapes."""
    shapes = one_of_each()
    ball = isect.Mesh(*icosphere(1))
    shapes += [
        ball,
        isect.Mesh(CUBE_VERTICES - 0.5, CUBE_QUADS),
        shapes[1].transformed(TURN),
        shapes[2].transformed(TURN),
        shapes[3].transformed(TURN),
        ball.transformed(TURN),
    ]
    return shapes


SHAPES = every_class()
IDS = [f"{type(s).__name__}{'-transformed' if s.matrix is not None else ''}" for s in SHAPES]


def sample_of(shape: isect.Shape) -> Sample:
    """The shape with a point to aim at: its placement's origin."""
    center = np.zeros(3) if shape.matrix is None else shape.matrix[:3, 3].copy()
    return Sample(shape, center, 2.0)


def general_only() -> Any:
    """A context in which intersect always takes the general path."""
    return mock.patch.object(_shape, "_closest_one", lambda *args: None)


def no_general_path() -> Any:
    """A context in which the general path of intersect raises."""

    def refuse(*args: object) -> None:
        raise AssertionError("the general path was taken")

    patches = (mock.patch.object(_shape, "make_rays", refuse),
               mock.patch.object(_shape, "_soa_columns", refuse))
    return _both(*patches)


@contextlib.contextmanager
def _both(first: Any, second: Any) -> Any:
    """Two patches as one context."""
    with first, second:
        yield


#: What a call returned or raised, and the warnings it gave (see outcome()).
Outcome = tuple[tuple[object, ...], tuple[tuple[type[Warning], str], ...]]


def outcome(call: Callable[[], Any]) -> Outcome:
    """Everything observable about a call: what it returned (type, dtype,
    shape, bytes, writability, the record's base array) or raised (type,
    message, args, index), and the warnings it gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            r = call()
        except Exception as exc:  # noqa: BLE001 - comparing whatever is raised
            result: tuple[object, ...] = (
                "raised",
                type(exc),
                str(exc),
                exc.args,
                getattr(exc, "index", None),
            )
        else:
            base = r.base if isinstance(r, np.void) else None
            result = (
                "returned",
                type(r),
                r.dtype,
                np.shape(r),
                r.tobytes(),
                r.flags.writeable,
                None
                if base is None
                else (type(base), base.shape, base.dtype, base.flags.writeable),
            )
    return result, tuple((w.category, str(w.message)) for w in caught)


# ------------------------------------------------------------ taken or not


COMMON = [
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {}),
    ([0, 0, -5], [0, 0, 1], {}),
    ((0.1, 0.2, -5.0), (0, 0, 1.0), {}),
    ([np.float64(0.1), 0.2, -5], (0.0, np.float64(0.0), 1), {}),
    (np.array([0.1, 0.2, -5.0]), np.array([0.0, 0.0, 1.0]), {}),
    (np.array([0.1, 9, 0.2, 9, -5.0, 9])[::2], np.array([0.0, 0.0, 1.0]), {}),  # strided
    (np.array([[0.0, 0, 0], [0.1, 0.2, -5]])[1], np.array([[0.0, 7], [0, 7], [1, 7]])[:, 0], {}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"tmin": 0.5, "tmax": 100.0}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"tmin": 1, "tmax": np.float64(8.0)}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"tmin": 9.0, "tmax": 1.0}),  # empty interval: a miss
    ([0.1, 0.2, -5.0], [0.0, 1.0, 0.0], {}),  # a miss
    (
        [0.1, 0.2, -5.0],
        [0.0, 0.0, 1.0],
        {"eps": None, "cull_back": False, "any_hit": False, "threads": None, "errors": "raise"},
    ),
]


@pytest.mark.parametrize("shape", SHAPES, ids=IDS)
@pytest.mark.parametrize("origin, direction, kwargs", COMMON)
def test_fast_path_is_taken(
    shape: isect.Shape, origin: Any, direction: Any, kwargs: dict[str, Any]
) -> None:
    """One ray of plain numbers with default options never reaches the
    general path, and gives its record."""
    expected = outcome(partial(shape.intersect, origin, direction, **kwargs))
    with general_only():
        assert outcome(partial(shape.intersect, origin, direction, **kwargs)) == expected
    with no_general_path():
        record = shape.intersect(origin, direction, **kwargs)
    assert outcome(lambda: record) == expected
    assert isinstance(record, np.void) and record.dtype == isect.HIT_DTYPE


GENERAL = [
    ([0.1, 0.2, -5.0], [[0.0, 0.0, 1.0]], {}),  # a batch of one
    ([0.1, 0.2, -5.0], np.zeros((0, 3)), {}),
    (np.array([0.1, 0.2, -5.0], dtype=np.float32), [0.0, 0.0, 1.0], {}),
    (np.array([0.1, 0.2, -5.0], dtype=">f8"), [0.0, 0.0, 1.0], {}),
    ([0.1, 0.2, np.float32(-5.0)], [0.0, 0.0, 1.0], {}),
    ([0.1, 0.2, True], [0.0, 0.0, 1.0], {}),
    (["0.1", 0.2, -5.0], [0.0, 0.0, 1.0], {}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"tmin": np.array(0.0)}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"tmax": [1.0, 9.0]}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"eps": 1e-9}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"cull_back": True}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"threads": 1}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"errors": "mark"}),
    ([0.1, 0.2, np.nan], [0.0, 0.0, 1.0], {}),  # bad rays: the general path raises
    ([0.1, 0.2, -5.0], [0.0, 0.0, 0.0], {}),
    ([0.1, 0.2, -5.0], [0.0, 0.0, 1.0], {"tmin": np.nan}),
    ([0.1, 0.2, 10**400], [0.0, 0.0, 1.0], {}),
]


@pytest.mark.parametrize("origin, direction, kwargs", GENERAL)
def test_other_inputs_take_the_general_path(
    origin: Any, direction: Any, kwargs: dict[str, Any]
) -> None:
    """Batches, other number types, options and bad rays go the general way."""
    shape = SHAPES[1]
    expected = outcome(partial(shape.intersect, origin, direction, **kwargs))
    with no_general_path():
        assert outcome(partial(shape.intersect, origin, direction, **kwargs)) != expected
    with general_only():
        assert outcome(partial(shape.intersect, origin, direction, **kwargs)) == expected


# ----------------------------------------------------- the same, bit for bit


@pytest.mark.parametrize("big", EDGE_INTS)
def test_large_ints(big: int) -> None:
    """An int coordinate or bound beyond 2**53 becomes the double numpy makes
    of it (the correctly rounded one) on the fast path too; one beyond the
    doubles takes the general path and raises its OverflowError."""
    try:
        float(big)
    except OverflowError:
        fits = False
    else:
        fits = True
    calls: list[tuple[Any, Any, dict[str, Any]]] = [
        ([big, 0, -5], [0, 0, 1], {}),
        ([0.5, 0.25, -5], (big, 1, 2), {}),
        ([0.5, 0.25, -5], [0, 0, 1], {"tmax": big}),
        ([0.5, 0.25, -5], [0, 0, 1], {"tmin": -big}),
    ]
    for shape in SHAPES:
        for origin, direction, kwargs in calls:
            fast = outcome(partial(shape.intersect, origin, direction, **kwargs))
            with general_only():
                assert outcome(partial(shape.intersect, origin, direction, **kwargs)) == fast
            if fits and fast[0][0] == "returned":
                with no_general_path():
                    assert outcome(partial(shape.intersect, origin, direction, **kwargs)) == fast


@pytest.mark.parametrize("shape", SHAPES, ids=IDS)
@given(data=st.data())
def test_fast_path_changes_nothing(shape: isect.Shape, data: st.DataObject) -> None:
    """Over rays of every form (aimed at the shape, bad, malformed) and tmin /
    tmax of every kind, intersect returns or raises exactly what the general
    path alone returns or raises."""
    origin, direction, kwargs = data.draw(ray_arguments(sample_of(shape)))
    fast = outcome(partial(shape.intersect, origin, direction, **kwargs))
    with general_only():
        general = outcome(partial(shape.intersect, origin, direction, **kwargs))
    assert fast == general


def test_fast_path_across_threads() -> None:
    """Threads calling the fast path at once get each ray's own record."""
    shape = SHAPES[1]
    rng = np.random.default_rng(5)
    origins = rng.normal(size=(400, 3)) * 4
    directions = -origins + rng.normal(size=(400, 3))
    expected = shape.intersect(origins, directions)
    failures: list[int] = []

    def run(offset: int) -> None:
        for _ in range(20):
            for i in range(offset, 400, 4):
                r = shape.intersect(origins[i].tolist(), directions[i].tolist())
                if r.tobytes() != expected[i].tobytes():
                    failures.append(i)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert failures == []
