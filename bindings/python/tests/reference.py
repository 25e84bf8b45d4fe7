"""The reference the package is compared with: the library's C ABI (include/tbasis.h), called
through ctypes on the shared library cargo builds (tests/python.rs passes its path in
TBASIS_REFERENCE_LIBRARY). Only tests use it; the package links the Rust crate itself."""

from __future__ import annotations

import ctypes
import os
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

from support import require

VARIABLE = "TBASIS_REFERENCE_LIBRARY"
SIZE_MAX = 2 ** (8 * ctypes.sizeof(ctypes.c_size_t)) - 1
INDEX_U16, INDEX_U32 = 1, 2
FLAG_FLIP_V = 1
DEGENERATE_UV = 11


class Mesh(ctypes.Structure):
    _fields_ = [
        ("vertex_count", ctypes.c_size_t),
        ("positions", ctypes.c_void_p),
        ("positions_stride", ctypes.c_size_t),
        ("normals", ctypes.c_void_p),
        ("normals_stride", ctypes.c_size_t),
        ("texcoords", ctypes.c_void_p),
        ("texcoords_stride", ctypes.c_size_t),
        ("indices", ctypes.c_void_p),
        ("index_count", ctypes.c_size_t),
        ("index_type", ctypes.c_uint32),
    ]


class Options(ctypes.Structure):
    _fields_ = [
        ("method", ctypes.c_uint32),
        ("degenerate_policy", ctypes.c_uint32),
        ("flags", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("degenerate_threshold", ctypes.c_float),
        ("scratch", ctypes.c_void_p),
        ("scratch_size", ctypes.c_size_t),
    ]


class Output(ctypes.Structure):
    _fields_ = [
        ("tangents", ctypes.c_void_p),
        ("tangents_stride", ctypes.c_size_t),
        ("bitangents", ctypes.c_void_p),
        ("bitangents_stride", ctypes.c_size_t),
    ]


# The report's counts, in the order of the package's Report; the C struct ends with
# `failed_triangle`, which the package gives as the error's triangle instead.
REPORT_COUNTS = (
    "degenerate_triangles",
    "first_degenerate_triangle",
    "fallback_vertices",
    "mirrored_vertices",
    "unreferenced_vertices",
    "inherited_vertices",
    "abnormal_normals",
    "repaired_corners",
    "split_vertices",
)


class CReport(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in REPORT_COUNTS + ("failed_triangle",)]


@dataclass
class Result:
    status: int
    tangents: NDArray[np.float32]
    bitangents: Optional[NDArray[np.float32]]
    report: tuple[Optional[int], ...]  # the fields of tbasis.Report, in order


@lru_cache(maxsize=None)
def library() -> ctypes.CDLL:
    path = os.environ.get(VARIABLE, "")
    require(bool(path) and os.path.isfile(path), f"the C library to compare with, libtbasis.so, in ${VARIABLE}")
    lib = ctypes.CDLL(path)
    for name in ("tbasis_generate", "tbasis_generate_corners", "tbasis_split_corners"):
        getattr(lib, name).restype = ctypes.c_uint32
    return lib


def _rows(array: NDArray[np.float32]) -> tuple[int, int]:
    """(address, byte stride) of float32 rows; the C ABI takes any stride."""
    assert array.dtype == np.float32 and (len(array) == 0 or array.strides[1] == 4)
    return array.ctypes.data, max(array.strides[0], 4 * array.shape[1])


def _mesh(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    texcoords: Optional[NDArray[np.float32]],
    indices: Optional[NDArray[Any]],
) -> tuple[Mesh, Optional[NDArray[Any]]]:
    mesh = Mesh(vertex_count=len(positions))
    mesh.positions, mesh.positions_stride = _rows(positions)
    mesh.normals, mesh.normals_stride = _rows(normals)
    if texcoords is not None:
        mesh.texcoords, mesh.texcoords_stride = _rows(texcoords)
    packed = None
    if indices is not None:
        packed = np.ascontiguousarray(indices.reshape(-1))  # the C ABI reads packed indices
        assert packed.dtype in (np.uint16, np.uint32)
        mesh.indices, mesh.index_count = packed.ctypes.data, packed.size
        mesh.index_type = INDEX_U16 if packed.dtype == np.uint16 else INDEX_U32
    return mesh, packed  # `packed` must stay alive until the call returns


def _options(method: int, policy: int, threshold: Optional[float], flip_v: bool) -> Options:
    return Options(
        method=method,
        degenerate_policy=policy,
        flags=FLAG_FLIP_V if flip_v else 0,
        degenerate_threshold=0.0 if threshold is None else threshold,
    )


def _report(report: CReport) -> tuple[Optional[int], ...]:
    values: list[Optional[int]] = [getattr(report, name) for name in REPORT_COUNTS]
    if values[1] == SIZE_MAX:
        values[1] = None
    return tuple(values)


def generate(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    texcoords: Optional[NDArray[np.float32]],
    indices: Optional[NDArray[Any]],
    method: int,
    policy: int,
    threshold: Optional[float] = None,
    flip_v: bool = False,
) -> Result:
    """``tbasis_generate`` with tangents and bitangents, on one thread."""
    mesh, packed = _mesh(positions, normals, texcoords, indices)
    tangents = np.zeros((len(positions), 4), dtype=np.float32)
    bitangents = np.zeros((len(positions), 3), dtype=np.float32)
    output = Output(
        tangents=tangents.ctypes.data, tangents_stride=16, bitangents=bitangents.ctypes.data, bitangents_stride=12
    )
    report = CReport()
    options = _options(method, policy, threshold, flip_v)
    status = library().tbasis_generate(
        ctypes.byref(mesh), ctypes.byref(options), ctypes.byref(output), ctypes.byref(report)
    )
    del packed
    return Result(status, tangents, bitangents, _report(report))


def generate_corners(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    texcoords: Optional[NDArray[np.float32]],
    indices: Optional[NDArray[Any]],
    method: int,
    policy: int,
    threshold: Optional[float] = None,
    flip_v: bool = False,
) -> Result:
    """``tbasis_generate_corners``, on one thread."""
    mesh, packed = _mesh(positions, normals, texcoords, indices)
    corners = len(positions) if packed is None else packed.size
    tangents = np.zeros((corners, 4), dtype=np.float32)
    report = CReport()
    options = _options(method, policy, threshold, flip_v)
    status = library().tbasis_generate_corners(
        ctypes.byref(mesh),
        ctypes.byref(options),
        ctypes.c_void_p(tangents.ctypes.data),
        ctypes.c_size_t(16),
        ctypes.byref(report),
    )
    del packed
    return Result(status, tangents, None, _report(report))


def split_corners(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    indices: Optional[NDArray[Any]],
    corners: NDArray[np.float32],
) -> tuple[int, NDArray[np.uint32], NDArray[np.uint32]]:
    """``tbasis_split_corners``: (status, new indices, sources)."""
    mesh, packed = _mesh(positions, normals, None, indices)
    count = len(corners)
    assert corners.flags.c_contiguous
    new_indices = np.zeros(count, dtype=np.uint32)
    sources = np.zeros(count, dtype=np.uint32)
    appended = ctypes.c_size_t(0)
    status = library().tbasis_split_corners(
        ctypes.byref(mesh),
        ctypes.c_void_p(corners.ctypes.data),
        ctypes.c_size_t(16),
        ctypes.c_void_p(new_indices.ctypes.data),
        ctypes.c_void_p(sources.ctypes.data),
        ctypes.byref(appended),
    )
    del packed
    return status, new_indices, sources[: appended.value]
