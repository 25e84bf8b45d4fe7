"""Seam splitting: per-corner tangents as an indexed mesh a GPU can draw."""

from __future__ import annotations

import operator
from typing import Any, NamedTuple, Optional, SupportsIndex

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _native
from ._arrays import indices as index_array
from ._arrays import converted, rows
from ._errors import IndexOutOfRangeError, InvalidDtypeError, InvalidLayoutError, from_library

__all__ = ["Split", "split_corners", "apply_split"]


class Split(NamedTuple):
    """The result of ``split_corners``."""

    indices: NDArray[np.uint32]
    """The new index buffer, one index per corner, in the shape of the given indices (unindexed:
    ``(vertex_count,)``): a corner keeps its vertex where it carries that vertex's first tangent,
    else it is drawn with an appended vertex."""
    sources: NDArray[np.uint32]
    """Appended vertex ``vertex_count + j`` is a copy of vertex ``sources[j]``."""


def split_corners(indices: Optional[ArrayLike], vertex_count: SupportsIndex, corner_tangents: ArrayLike) -> Split:
    """Duplicates exactly the vertices whose corners carry different tangents (mirror seams,
    orientation flips), so that per-corner tangents can be drawn as per-vertex ones.

    indices: as for ``generate`` (None: unindexed). corner_tangents: ``(corners, 4)``, one row per
    corner, as ``generate_corners`` returns them. Two corners of a vertex share an output vertex
    exactly when their tangents have the same bits. Give every vertex attribute the appended
    vertices with ``apply_split(attribute, split.sources)``, and the new vertices their tangents
    with ``tangents[split.indices.ravel()] = corner_tangents``.
    """
    try:
        count = operator.index(vertex_count)
    except TypeError:
        raise InvalidDtypeError(f"vertex_count must be an integer, not {vertex_count!r}") from None
    if not 0 <= count < 1 << 64:
        raise InvalidLayoutError(f"vertex_count must be between 0 and 2**64 - 1, not {count}")
    flat, shape = index_array(indices, count)
    corners = count if flat is None else flat.size
    tangents = rows("corner_tangents", corner_tangents, 4)
    if len(tangents) != corners:
        what = "one per index" if flat is not None else "unindexed: one per vertex"
        raise InvalidLayoutError(f"corner_tangents has {len(tangents)} rows, the mesh has {corners} corners ({what})")
    try:
        new_indices, sources = _native.split_corners(flat, count, tangents)
    except _native.LibraryError as failure:
        raise from_library(failure, count) from None
    return Split(new_indices.reshape(shape) if flat is not None else new_indices, sources)


def apply_split(attribute: ArrayLike, sources: ArrayLike) -> NDArray[Any]:
    """``attribute`` (one row per vertex: positions, normals, UVs, colours, joints, weights...,
    any dtype and row shape) with the vertices a split appended: a new array of
    ``len(attribute) + len(sources)`` rows, row ``len(attribute) + j`` a copy of row
    ``sources[j]``."""
    data = np.asarray(attribute)
    if data.ndim == 0:
        raise InvalidLayoutError("attribute must have one row per vertex, not be a scalar")
    picks = np.asarray(sources)
    if picks.size == 0 and picks.dtype.kind == "f":
        picks = picks.astype(np.intp)  # numpy reads [] as float64
    if picks.dtype.kind not in "iu":
        raise InvalidDtypeError(f"sources must hold integers, not dtype {picks.dtype}")
    if picks.ndim != 1:
        raise InvalidLayoutError(f"sources must have shape (k,), not {picks.shape}")
    outside = np.flatnonzero((picks < 0) | (picks >= len(data)))
    if outside.size:
        position = int(outside[0])
        value = int(picks[position])
        raise IndexOutOfRangeError(
            f"sources[{position}] is {value}, not in range for an attribute of {len(data)} rows", position, value, None
        )
    return converted("attribute", lambda: np.concatenate((data, data[picks])))
