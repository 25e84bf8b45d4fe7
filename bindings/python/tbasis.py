"""Per-vertex tangents for triangle meshes: a ctypes binding of the tbasis C library.

Inputs are float32 numpy arrays read in place with their byte strides, so fields of one
structured (interleaved) vertex array work without copies, and tangents can be written back into
that array. See ``generate``. The library is loaded on first use (see ``find_library``).
"""

from __future__ import annotations

import ctypes
import dataclasses
import enum
import functools
import operator
import os
import sys
from pathlib import Path

import numpy as np

__all__ = [
    "Method",
    "Policy",
    "Status",
    "Report",
    "TbasisError",
    "generate",
    "generate_with_report",
    "find_library",
    "status_string",
    "version",
    "VERSION",
    "INDEX_U16",
    "INDEX_U32",
    "FLAG_FLIP_V",
]

# The header's constants (include/tbasis.h).
VERSION_MAJOR = 0
VERSION_MINOR = 2
VERSION_PATCH = 0
VERSION = VERSION_MAJOR * 1000000 + VERSION_MINOR * 1000 + VERSION_PATCH

INDEX_U16 = 1
INDEX_U32 = 2
FLAG_FLIP_V = 1


class Method(enum.IntEnum):
    """``tbasis_options.method``; DEFAULT is ANGLE.

    MIKKTSPACE is mikktspace.c's frame per corner; ``generate`` gives each vertex the frame of
    its first corner (per-corner output is not in this binding yet).
    """

    DEFAULT = 0
    LENGYEL = 1
    ANGLE = 2
    AREA = 3
    UNIFORM = 4
    MIKKTSPACE = 5


class Policy(enum.IntEnum):
    """``tbasis_options.degenerate_policy``; DEFAULT is the method's default: LEGACY for
    MIKKTSPACE, INHERIT for the others."""

    DEFAULT = 0
    LEGACY = 1
    SKIP = 2
    INHERIT = 3
    REJECT = 4


class Status(enum.IntEnum):
    """``tbasis_status`` values (``TBASIS_OK``, ``TBASIS_ERROR_*``)."""

    OK = 0
    NULL_POINTER = 1
    INVALID_STRIDE = 2
    INVALID_INDEX_COUNT = 3
    INDEX_OUT_OF_RANGE = 4
    INVALID_INDEX_TYPE = 5
    UNKNOWN_METHOD = 6
    UNKNOWN_POLICY = 7
    UNKNOWN_FLAGS = 8
    SIZE_OVERFLOW = 9
    OVERLAP = 10
    DEGENERATE_UV = 11
    OUT_OF_MEMORY = 12
    SCRATCH_TOO_SMALL = 13
    INVALID_THRESHOLD = 14
    INVALID_COUNT = 15
    INTERNAL = 16
    INVALID_FRAME = 17


# The header's structs, field for field.


class tbasis_mesh(ctypes.Structure):
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


class tbasis_options(ctypes.Structure):
    _fields_ = [
        ("method", ctypes.c_uint32),
        ("degenerate_policy", ctypes.c_uint32),
        ("flags", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("degenerate_threshold", ctypes.c_float),
        ("scratch", ctypes.c_void_p),
        ("scratch_size", ctypes.c_size_t),
    ]


class tbasis_output(ctypes.Structure):
    _fields_ = [
        ("tangents", ctypes.c_void_p),
        ("tangents_stride", ctypes.c_size_t),
        ("bitangents", ctypes.c_void_p),
        ("bitangents_stride", ctypes.c_size_t),
    ]


class tbasis_report(ctypes.Structure):
    _fields_ = [
        ("degenerate_triangles", ctypes.c_size_t),
        ("first_degenerate_triangle", ctypes.c_size_t),
        ("fallback_vertices", ctypes.c_size_t),
        ("mirrored_vertices", ctypes.c_size_t),
        ("unreferenced_vertices", ctypes.c_size_t),
        ("inherited_vertices", ctypes.c_size_t),
        ("abnormal_normals", ctypes.c_size_t),
        ("repaired_corners", ctypes.c_size_t),
        ("split_vertices", ctypes.c_size_t),
    ]


SIZE_MAX = 2 ** (8 * ctypes.sizeof(ctypes.c_size_t)) - 1
_U32_MAX = 2**32 - 1


@dataclasses.dataclass(frozen=True)
class Report:
    """What a call found (``tbasis_report``); ``first_degenerate_triangle`` is None when none."""

    degenerate_triangles: int
    first_degenerate_triangle: int | None
    fallback_vertices: int
    mirrored_vertices: int
    unreferenced_vertices: int
    inherited_vertices: int
    abnormal_normals: int
    repaired_corners: int
    split_vertices: int

    @classmethod
    def _from_c(cls, report: tbasis_report) -> Report:
        values = {name: getattr(report, name) for name, _ in tbasis_report._fields_}
        if values["first_degenerate_triangle"] == SIZE_MAX:
            values["first_degenerate_triangle"] = None
        return cls(**values)


class TbasisError(Exception):
    """A call returned an error status; nothing was written to the outputs.

    ``status`` is the ``Status`` (an int), ``message`` the library's ``tbasis_status_string``,
    ``report`` the ``Report`` for ``Status.DEGENERATE_UV`` (it names the triangle), else None.
    """

    def __init__(self, status: int, report: Report | None = None):
        try:
            status = Status(status)
        except ValueError:
            pass
        self.status = status
        self.message = status_string(status)
        self.report = report
        name = status.name if isinstance(status, Status) else "unknown status"
        detail = ""
        if report is not None and report.first_degenerate_triangle is not None:
            detail = f" (first degenerate triangle: {report.first_degenerate_triangle})"
        super().__init__(f"tbasis: {self.message} [{name} = {int(status)}]{detail}")


def _library_name() -> str:
    if sys.platform == "win32":
        return "tbasis.dll"
    if sys.platform == "darwin":
        return "libtbasis.dylib"
    return "libtbasis.so"


def find_library() -> Path:
    """The shared library to load: ``$TBASIS_LIBRARY`` if set, else the repository's
    ``target/release``, then ``target/debug``. Raises FileNotFoundError naming what it tried.
    """
    override = os.environ.get("TBASIS_LIBRARY")
    if override:
        path = Path(override)
        if path.is_file():
            return path
        # An explicit choice that is wrong must not fall back to some other build.
        raise FileNotFoundError(f"TBASIS_LIBRARY={override!r} is not a file")
    target = Path(__file__).resolve().parent.parent.parent / "target"
    tried = [target / profile / _library_name() for profile in ("release", "debug")]
    for path in tried:
        if path.is_file():
            return path
    raise FileNotFoundError(
        "tbasis shared library not found; tried TBASIS_LIBRARY (not set), "
        + ", ".join(str(p) for p in tried)
        + ". Build it with `cargo build --release` or set TBASIS_LIBRARY to its path."
    )


@functools.lru_cache(maxsize=None)
def _lib() -> ctypes.CDLL:
    path = find_library()
    lib = ctypes.CDLL(str(path))
    lib.tbasis_generate.argtypes = [
        ctypes.POINTER(tbasis_mesh),
        ctypes.POINTER(tbasis_options),
        ctypes.POINTER(tbasis_output),
        ctypes.POINTER(tbasis_report),
    ]
    lib.tbasis_generate.restype = ctypes.c_uint32
    lib.tbasis_scratch_size.argtypes = [ctypes.POINTER(tbasis_mesh), ctypes.POINTER(tbasis_options)]
    lib.tbasis_scratch_size.restype = ctypes.c_size_t
    lib.tbasis_status_string.argtypes = [ctypes.c_uint32]
    lib.tbasis_status_string.restype = ctypes.c_char_p
    lib.tbasis_version.argtypes = []
    lib.tbasis_version.restype = ctypes.c_uint32
    found = lib.tbasis_version()
    # Structs and constants here are those of this version; another minor (0.x) may differ.
    if found // 1000 != VERSION // 1000:
        raise OSError(f"{path} is tbasis version {found}, this binding is for {VERSION}")
    return lib


def version() -> int:
    """The loaded library's ``tbasis_version()``."""
    return _lib().tbasis_version()


def status_string(status: int) -> str:
    """The library's description of a status value."""
    return _lib().tbasis_status_string(int(status)).decode()


def _invoke(mesh, options, output, report) -> int:
    # The one place the library is called (tests wrap it to see the descriptors).
    return _lib().tbasis_generate(
        ctypes.byref(mesh), ctypes.byref(options), ctypes.byref(output), ctypes.byref(report)
    )


def _rows(name: str, array, width: int, count: int | None, writable: bool = False) -> tuple[int, int, int]:
    """(address, byte stride, rows) of a float32 (n, width) array whose rows may be strided."""
    if not isinstance(array, np.ndarray):
        raise TypeError(
            f"{name} must be a numpy float32 array of shape (n, {width}), not {type(array).__name__} "
            f"(no implicit copies; use np.asarray({name}, dtype=np.float32))"
        )
    if array.dtype != np.float32:
        raise TypeError(f"{name} must have dtype float32 (native byte order), not {array.dtype}")
    if array.ndim != 2 or array.shape[1] != width:
        raise ValueError(f"{name} must have shape (n, {width}), not {array.shape}")
    rows = array.shape[0]
    # numpy reports arbitrary strides for empty arrays; their memory is never read.
    if rows > 0 and array.strides[1] != 4:
        raise ValueError(
            f"{name}: the {width} floats of a row must be contiguous (strides[1] == 4), not strides {array.strides}"
        )
    if count is not None and rows != count:
        raise ValueError(f"{name} has {rows} rows, positions has {count}")
    if writable and not array.flags.writeable:
        raise ValueError(f"{name} is read-only")
    stride = array.strides[0]
    if rows <= 1:
        # One row: the stride is never applied, and numpy may report anything for it.
        stride = max(stride, 4 * width)
    elif stride < 0:
        raise ValueError(f"{name}: negative row stride {stride} (reversed views are not supported)")
    return array.ctypes.data, stride, rows


def _indices(indices) -> tuple[np.ndarray | None, int]:
    """The packed index array to pass (the C API reads indices without a stride) and its type."""
    if indices is None:
        return None, 0
    if not isinstance(indices, np.ndarray):
        raise TypeError(f"indices must be a numpy uint16 or uint32 array or None, not {type(indices).__name__}")
    if indices.dtype == np.uint16:
        index_type = INDEX_U16
    elif indices.dtype == np.uint32:
        index_type = INDEX_U32
    else:
        raise TypeError(
            f"indices must have dtype uint16 or uint32 (native byte order), not {indices.dtype}; "
            "convert with indices.astype(np.uint32)"
        )
    if not (indices.ndim == 1 or (indices.ndim == 2 and indices.shape[1] == 3)):
        raise ValueError(f"indices must have shape (k,) or (m, 3), not {indices.shape}")
    # Strided indices are the one input that has to be packed first.
    return np.ascontiguousarray(indices), index_type


def _u32(name: str, value) -> int:
    value = operator.index(value)  # ints and enum members; not floats or strings
    if not 0 <= value <= _U32_MAX:
        raise ValueError(f"{name} must fit in an unsigned 32-bit integer, not {value}")
    return value


def generate_with_report(
    positions,
    normals,
    texcoords,
    indices=None,
    *,
    method=Method.DEFAULT,
    policy=Policy.DEFAULT,
    threshold=None,
    flip_v=False,
    threads=1,
    out=None,
    bitangents=None,
) -> tuple[np.ndarray, Report]:
    """Like ``generate``, returning ``(tangents, Report)``."""
    address, positions_stride, count = _rows("positions", positions, 3, None)
    mesh = tbasis_mesh(vertex_count=count, positions=address, positions_stride=positions_stride)
    mesh.normals, mesh.normals_stride, _ = _rows("normals", normals, 3, count)
    if texcoords is not None:
        mesh.texcoords, mesh.texcoords_stride, _ = _rows("texcoords", texcoords, 2, count)
    packed, index_type = _indices(indices)
    if packed is not None:
        mesh.indices = packed.ctypes.data
        mesh.index_count = packed.size
        mesh.index_type = index_type

    options = tbasis_options(
        method=_u32("method", method),
        degenerate_policy=_u32("policy", policy),
        flags=FLAG_FLIP_V if flip_v else 0,
        threads=_u32("threads", threads),
        degenerate_threshold=0.0 if threshold is None else float(threshold),
    )

    if out is None:
        out = np.empty((count, 4), dtype=np.float32)
    output = tbasis_output()
    output.tangents, output.tangents_stride, _ = _rows("out", out, 4, count, writable=True)
    if bitangents is not None:
        output.bitangents, output.bitangents_stride, _ = _rows("bitangents", bitangents, 3, count, writable=True)

    report = tbasis_report()
    # The arrays stay referenced by this frame's locals (positions, packed, out, ...) until the
    # call returns, so the addresses in the descriptors stay valid.
    status = _invoke(mesh, options, output, report)
    if status == Status.DEGENERATE_UV:
        raise TbasisError(status, Report._from_c(report))
    if status != Status.OK:
        raise TbasisError(status)
    return out, Report._from_c(report)


def generate(
    positions,
    normals,
    texcoords,
    indices=None,
    *,
    method=Method.DEFAULT,
    policy=Policy.DEFAULT,
    threshold=None,
    flip_v=False,
    threads=1,
    out=None,
    bitangents=None,
) -> np.ndarray:
    """Per-vertex tangents ``(n, 4)`` float32: unit ``xyz`` orthogonal to the normal, ``w = ±1``.

    positions, normals: float32 ``(n, 3)``; texcoords: float32 ``(n, 2)`` or None (fallback
    frames). Rows may be any byte stride apart (e.g. ``vertices['position']`` of a structured
    array) but each row's floats must be contiguous; they are read in place, never copied.
    indices: None (unindexed: triangle i is vertices 3i..3i+2), or uint16/uint32 of shape
    ``(k,)`` or ``(m, 3)``; the C API takes packed indices, so strided ones are packed first.

    method, policy: ``Method``/``Policy`` values (defaults ANGLE, and the method's default policy:
    INHERIT, or LEGACY for MIKKTSPACE). threshold: degenerate
    shape quality (None or 0: 1e-5). flip_v: V points down (glTF, Direct3D). threads: upper bound.

    out: an ``(n, 4)`` float32 array or view to write (e.g. ``vertices['tangent']``), returned;
    a new array when None. bitangents: optional ``(n, 3)`` float32 view, also written.
    Raises TbasisError (outputs untouched), TypeError or ValueError (bad arrays).
    """
    tangents, _ = generate_with_report(
        positions,
        normals,
        texcoords,
        indices,
        method=method,
        policy=policy,
        threshold=threshold,
        flip_v=flip_v,
        threads=threads,
        out=out,
        bitangents=bitangents,
    )
    return tangents
