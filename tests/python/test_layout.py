# SPDX-License-Identifier: Apache-2.0
"""The numpy dtypes mirror the C structs, and the cffi declarations follow isect.h."""

from __future__ import annotations

import dataclasses
import re

import isect
import numpy as np
import pytest
from conftest import ROOT
from isect._isect import ffi, lib

HEADER = ROOT / "libisect" / "include" / "isect.h"

RAY_FIELDS = [("org", 0, (3,)), ("dir", 24, (3,)), ("tmin", 48, ()), ("tmax", 56, ())]
HIT_FIELDS = [
    ("t", 0, ()),
    ("point", 8, (3,)),
    ("normal", 32, (3,)),
    ("uv", 56, (2,)),
    ("prim", 72, ()),
    ("kind", 76, ()),
]


@pytest.mark.parametrize(
    ("dtype", "ctype", "size", "fields"),
    [
        (isect.RAY_DTYPE, "isect_ray", 64, RAY_FIELDS),
        (isect.HIT_DTYPE, "isect_hit", 80, HIT_FIELDS),
    ],
    ids=["ray", "hit"],
)
def test_dtype_matches_c_struct(
    dtype: np.dtype, ctype: str, size: int, fields: list[tuple[str, int, tuple[int, ...]]]
) -> None:
    """Size, field names, offsets, shapes and types equal the C struct's."""
    assert dtype.itemsize == ffi.sizeof(ctype) == size
    assert dtype.names == tuple(name for name, _, _ in fields)
    assert dtype.fields is not None
    c_fields = dict(ffi.typeof(ctype).fields)
    for name, offset, shape in fields:
        sub, off = dtype.fields[name][:2]
        assert off == ffi.offsetof(ctype, name) == c_fields[name].offset == offset, name
        assert sub.shape == shape, name
        assert sub.itemsize == ffi.sizeof(c_fields[name].type), name
        base = sub.base if sub.shape else sub
        expected = np.int32 if name in ("prim", "kind") else np.float64
        assert base == np.dtype(expected), name


def test_other_struct_sizes() -> None:
    """The documented sizes of the structs the package fills."""
    assert ffi.sizeof("isect_opts") == 16
    assert ffi.sizeof("isect_xform") == 256
    assert ffi.sizeof("isect_mesh_report") == 128
    if ffi.sizeof("void *") == 8:
        assert ffi.sizeof("isect_shape") == 40


def test_records_round_trip_through_c() -> None:
    """Bytes written by C into a HIT_DTYPE array read back field by field."""
    hits = isect.Box([0, 0, 0], [1, 2, 3]).intersect([0.5, 0.5, -1], [0, 0, 2])
    assert hits["t"] == 0.5 and hits["prim"] == 4 and hits["kind"] == isect.HitKind.ENTER
    assert hits["point"].tolist() == [0.5, 0.5, 0.0]
    assert hits["normal"].tolist() == [0.0, 0.0, -1.0]


def test_hit_kinds_are_the_c_constants() -> None:
    """HitKind values are the ISECT_* constants."""
    for kind in isect.HitKind:
        assert int(kind) == getattr(lib, f"ISECT_{kind.name}")
    assert [k.name for k in isect.HitKind] == ["MISS", "ENTER", "EXIT", "TOUCH", "INVALID"]


def test_status_table_is_the_c_constants() -> None:
    """Each exception class carries its C status code."""
    assert isect.InvalidArgumentError.status == lib.ISECT_E_ARG == -1
    assert isect.NonFiniteError.status == lib.ISECT_E_NONFINITE == -2
    assert isect.DegenerateError.status == lib.ISECT_E_DEGENERATE == -3
    assert isect.OutOfMemoryError.status == lib.ISECT_E_NOMEM == -4


#: isect_mesh_report: (field, offset) in declaration order; 128 bytes.
REPORT_FIELDS = [
    ("vertices", 0),
    ("edges", 8),
    ("faces", 16),
    ("boundary_edges", 24),
    ("nonmanifold_edges", 32),
    ("misoriented_edges", 40),
    ("degenerate_faces", 48),
    ("components", 56),
    ("euler_characteristic", 64),
    ("genus", 72),
    ("closed", 80),
    ("oriented", 84),
    ("volume", 88),
    ("area", 96),
    ("reserved", 104),
]


def test_mesh_report_layout() -> None:
    """isect_mesh_report is laid out as isect.h documents, and MeshReport has
    one field per C field but the reserved ones, in the same order."""
    assert ffi.sizeof("isect_mesh_report") == 128
    c_fields = [name for name, _ in ffi.typeof("isect_mesh_report").fields]
    assert c_fields == [name for name, _ in REPORT_FIELDS]
    for name, offset in REPORT_FIELDS:
        assert ffi.offsetof("isect_mesh_report", name) == offset, name
    assert ffi.sizeof("int64_t[3]") == 128 - 104
    py_fields = [f.name for f in dataclasses.fields(isect.MeshReport)]
    assert py_fields == c_fields[:-1]


def _header_functions() -> set[str]:
    text = HEADER.read_text(encoding="utf-8")
    return set(re.findall(r"ISECT_API\b[^;(]*?\b(isect_\w+)\s*\(", text))


def test_cdef_covers_the_header() -> None:
    """Every function of isect.h is bound, and nothing else."""
    declared = _header_functions()
    assert len(declared) > 20
    assert {"isect_mesh_create", "isect_mesh_destroy", "isect_mesh_check"} <= declared
    bound = {name for name in dir(lib) if name.startswith("isect_")}
    assert not (declared - bound), f"isect.h functions missing from the cdef: {sorted(declared - bound)}"
    assert not (bound - declared), f"bound but not in isect.h: {sorted(bound - declared)}"


def test_header_constants_match() -> None:
    """The integer macros of isect.h have the values cffi compiled in."""
    text = HEADER.read_text(encoding="utf-8")
    for name, value in re.findall(r"#define\s+(ISECT_[A-Z_0-9]+)\s+\(?(-?\d+)\)?\s", text):
        if hasattr(lib, name):
            assert getattr(lib, name) == int(value), name
