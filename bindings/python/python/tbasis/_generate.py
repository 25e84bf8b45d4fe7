"""``generate`` and ``generate_corners``: tangent frames per vertex and per triangle corner."""

from __future__ import annotations

import dataclasses
from typing import Any, Literal, NamedTuple, Optional, Union, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _native
from ._arrays import indices as index_array
from ._arrays import deliver, output, refuse_overlap, rows
from ._errors import InvalidDtypeError, InvalidLayoutError, InvalidOptionError, from_library
from ._options import Method, MethodName, Policy, PolicyName, method_code, policy_code, threads_value, threshold_value

__all__ = ["Report", "generate", "generate_corners"]

MethodLike = Union[Method, MethodName]
PolicyLike = Union[Policy, PolicyName]


@dataclasses.dataclass(frozen=True)
class Report:
    """What a call found in the mesh and what it did about it: the C ``tbasis_report``.

    ``first_degenerate_triangle`` is None when there is no degenerate triangle (C: ``SIZE_MAX``).
    """

    degenerate_triangles: int
    """Triangles whose UV or position quality is below the threshold, or whose inputs are not
    finite (method ``"lengyel"`` with policy ``"legacy"``: exactly-zero UV determinants). Method
    ``"mikktspace"`` counts the triangles mikktspace.c cannot use: two corners at one position, or
    no texture derivatives (a UV area, |dP/ds| or |dP/dt| that is NaN or not above the smallest
    normal float in magnitude); with ``"reject"``, whose test decides instead, a successful call
    has none."""
    first_degenerate_triangle: Optional[int]
    """The first of them."""
    fallback_vertices: int
    """Vertices given the frame built from their normal alone."""
    mirrored_vertices: int
    """Vertices used by non-degenerate triangles of both UV orientations (mirror folds)."""
    unreferenced_vertices: int
    """Vertices no triangle uses."""
    inherited_vertices: int
    """Vertices that took their tangent from neighbours (policy ``"inherit"``)."""
    abnormal_normals: int
    """Normals zero, not finite or off unit length by more than 1e-3 (not counted by ``"legacy"``)."""
    repaired_corners: int
    """``"mikktspace"`` with ``"skip"`` or ``"inherit"``: corners whose mikktspace.c tangent was replaced."""
    split_vertices: int
    """``"mikktspace"``: vertices whose corners do not all get the same frame."""


class _Mesh(NamedTuple):
    positions: NDArray[np.float32]
    normals: NDArray[np.float32]
    texcoords: Optional[NDArray[np.float32]]
    indices: Optional[NDArray[Any]]
    vertex_count: int
    corner_count: int


def _mesh(
    positions: ArrayLike, normals: ArrayLike, texcoords: Optional[ArrayLike], indices: Optional[ArrayLike]
) -> _Mesh:
    checked_positions = rows("positions", positions, 3)
    count = len(checked_positions)
    checked_normals = rows("normals", normals, 3)
    checked_texcoords = None if texcoords is None else rows("texcoords", texcoords, 2)
    for name, array in (("normals", checked_normals), ("texcoords", checked_texcoords)):
        if array is not None and len(array) != count:
            raise InvalidLayoutError(f"{name} has {len(array)} rows, positions has {count}: one row per vertex")
    flat, _ = index_array(indices, count)
    corners = count if flat is None else flat.size
    return _Mesh(checked_positions, checked_normals, checked_texcoords, flat, count, corners)


def _inputs(positions: Any, normals: Any, texcoords: Any, indices: Any) -> dict[str, Any]:
    """The caller's input arrays by the library's names for them."""
    return {"positions": positions, "normals": normals, "texcoords": texcoords, "indices": indices}


class _Options(NamedTuple):
    method: int
    policy: int
    threshold: Optional[float]
    flip_v: bool
    threads: int


def _options(
    method: MethodLike, policy: PolicyLike, threshold: Optional[float], flip_v: bool, threads: int
) -> _Options:
    if not isinstance(flip_v, (bool, np.bool_)):
        raise InvalidOptionError(f"flip_v must be True or False, not {flip_v!r}")
    return _Options(
        method_code(method), policy_code(policy), threshold_value(threshold), bool(flip_v), threads_value(threads)
    )


@overload
def generate(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    bitangents: Literal[False] = False,
    report: Literal[False] = False,
) -> NDArray[np.float32]: ...
@overload
def generate(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    bitangents: Union[Literal[True], NDArray[Any]],
    report: Literal[False] = False,
) -> tuple[NDArray[np.float32], NDArray[np.float32]]: ...
@overload
def generate(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    bitangents: Literal[False] = False,
    report: Literal[True],
) -> tuple[NDArray[np.float32], Report]: ...
@overload
def generate(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    bitangents: Union[Literal[True], NDArray[Any]],
    report: Literal[True],
) -> tuple[NDArray[np.float32], NDArray[np.float32], Report]: ...
@overload
def generate(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    bitangents: Union[bool, NDArray[Any]] = False,
    report: bool = False,
) -> Union[NDArray[np.float32], tuple[Any, ...]]: ...


def generate(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    bitangents: Union[bool, NDArray[Any]] = False,
    report: bool = False,
) -> Union[NDArray[np.float32], tuple[Any, ...]]:
    """A unit tangent and handedness per vertex: an ``(n, 4)`` float32 array ``x, y, z, w``,
    ``xyz`` orthogonal to the normal, ``w`` +1 or -1, the bitangent being
    ``w * cross(normal, xyz)``.

    positions, normals: ``(n, 3)``; texcoords: ``(n, 2)``, or None (every vertex gets the frame
    built from its normal; methods and policies that need texcoords raise
    ``MissingTexcoordsError``). float32 rows are read in place whatever their stride (the fields
    of a structured vertex array); other arrays are converted to float32 once.
    indices: None (unindexed: triangle ``t`` is vertices ``3t, 3t+1, 3t+2``), or integers of
    shape ``(k,)`` or ``(m, 3)``; uint16 and uint32 are read in place, other integer types are
    converted to uint32 once.

    method, policy: names or ``Method``/``Policy`` members; ``"default"`` is the library's
    default (``"angle"``, or ``"lengyel"`` with policy ``"legacy"``; the policy: ``"legacy"`` for
    ``"mikktspace"``, which is then exactly mikktspace.c, else ``"inherit"``). threshold: the UV quality below which a triangle is
    degenerate (None: 1e-5). flip_v: V points down in texcoords (glTF, Direct3D) as read from
    the file. threads: at most this many threads (0 and 1: the calling thread); any number gives
    the same bits. The GIL is released while the library runs: other threads must not modify
    the arrays meanwhile.

    out: a writable ``(n, 4)`` float32 array (or view) to write, returned instead of a new array.
    bitangents: True for a new ``(n, 3)`` array of bitangents, or such an array to write.
    report: also return the ``Report``.

    Returns ``tangents``; with bitangents ``(tangents, bitangents)``; with report
    ``(tangents, report)``; with both ``(tangents, bitangents, report)``. On any error a
    ``tbasis.Error`` is raised and neither ``out`` nor ``bitangents`` has been written (but for
    ``tbasis.InternalError``, a bug, after which they may be partly written).
    """
    options = _options(method, policy, threshold, flip_v, threads)
    mesh = _mesh(positions, normals, texcoords, indices)
    bitangents_out = bitangents if isinstance(bitangents, np.ndarray) else None
    if bitangents_out is None and not isinstance(bitangents, (bool, np.bool_)):
        raise InvalidDtypeError(f"bitangents must be True, False or a float32 array, not {type(bitangents).__name__}")
    refuse_overlap({"tangents": out, "bitangents": bitangents_out}, _inputs(positions, normals, texcoords, indices))
    tangents, pending = output("out", out, (mesh.vertex_count, 4))
    wanted = bitangents_out is not None or bool(bitangents)
    written, pending_bitangents = (
        output("bitangents", bitangents_out, (mesh.vertex_count, 3)) if wanted else (None, None)
    )
    try:
        counts = _native.generate(
            mesh.positions, mesh.normals, mesh.texcoords, mesh.indices, *options, tangents, written
        )
    except _native.LibraryError as failure:
        raise from_library(failure, mesh.vertex_count) from None
    results: list[Any] = [deliver(tangents, pending, out)]
    if wanted:
        assert written is not None
        results.append(deliver(written, pending_bitangents, bitangents_out))
    if report:
        results.append(Report(*counts))
    return results[0] if len(results) == 1 else tuple(results)


@overload
def generate_corners(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    report: Literal[False] = False,
) -> NDArray[np.float32]: ...
@overload
def generate_corners(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    report: Literal[True],
) -> tuple[NDArray[np.float32], Report]: ...
@overload
def generate_corners(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    report: bool = False,
) -> Union[NDArray[np.float32], tuple[NDArray[np.float32], Report]]: ...


def generate_corners(
    positions: ArrayLike,
    normals: ArrayLike,
    texcoords: Optional[ArrayLike],
    indices: Optional[ArrayLike] = None,
    *,
    method: MethodLike = "default",
    policy: PolicyLike = "default",
    threshold: Optional[float] = None,
    flip_v: bool = False,
    threads: int = 1,
    out: Optional[NDArray[Any]] = None,
    report: bool = False,
) -> Union[NDArray[np.float32], tuple[NDArray[np.float32], Report]]:
    """A unit tangent and handedness per triangle corner: a ``(corners, 4)`` float32 array, row
    ``3t + k`` for corner ``k`` of triangle ``t`` (one row per index; unindexed, per vertex).

    With ``method="mikktspace"`` each row is exactly mikktspace.c's frame for that corner (the
    tangents normal maps are baked against; add ``flip_v=True`` for V pointing down as read from
    a glTF file). The per-vertex methods give each corner its vertex's frame, except on the far
    side of a mirror fold. Arguments as for ``generate``; ``out`` is ``(corners, 4)``.
    ``split_corners`` turns the result into an index buffer a GPU can draw.

    Returns the tangents, or ``(tangents, report)`` with ``report=True``.
    """
    options = _options(method, policy, threshold, flip_v, threads)
    mesh = _mesh(positions, normals, texcoords, indices)
    refuse_overlap({"tangents": out}, _inputs(positions, normals, texcoords, indices))
    tangents, pending = output("out", out, (mesh.corner_count, 4))
    try:
        counts = _native.generate_corners(
            mesh.positions, mesh.normals, mesh.texcoords, mesh.indices, *options, tangents
        )
    except _native.LibraryError as failure:
        raise from_library(failure, mesh.vertex_count) from None
    result = deliver(tangents, pending, out)
    return (result, Report(*counts)) if report else result
