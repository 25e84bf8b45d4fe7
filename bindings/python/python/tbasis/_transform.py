"""Directions moved between object space and the tangent space of vertex frames."""

from __future__ import annotations

from typing import Any, Callable, Optional

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _native
from ._arrays import deliver, output, rows, vectors
from ._errors import InvalidLayoutError, from_library

__all__ = ["to_tangent_space", "from_tangent_space"]


def to_tangent_space(
    normals: ArrayLike, tangents: ArrayLike, directions: ArrayLike, *, out: Optional[NDArray[Any]] = None
) -> NDArray[np.float32]:
    """Object-space ``directions`` in the tangent space of each frame: ``inverse(M) @ d`` with
    ``M = [T B N]`` (columns), ``T = tangent.xyz``, ``B = w * cross(N, T)``.

    normals ``(..., 3)``, tangents ``(..., 4)`` as ``generate`` writes them, directions
    ``(..., 3)``; the leading shapes broadcast (one light direction for every vertex: shape
    ``(3,)``). The inverse is exact, computed in double precision and rounded once, so the frame
    need not be orthonormal. Returns float32 ``(..., 3)``, or writes ``out`` (which may be
    ``directions`` itself). A singular frame (zero or parallel normal and tangent, ``w`` zero),
    a non-finite input or an overflowing result raises ``InvalidFrameError`` naming the first
    such vector, and nothing is written.
    """
    return _transform(_native.to_tangent_space, normals, tangents, directions, out)


def from_tangent_space(
    normals: ArrayLike, tangents: ArrayLike, directions: ArrayLike, *, out: Optional[NDArray[Any]] = None
) -> NDArray[np.float32]:
    """Tangent-space ``directions`` (x along the tangent, y along the bitangent, z along the normal,
    e.g. decoded normal-map samples) in object space: ``x T + y B + z N``, nothing normalized.
    Arguments, frames and errors as for ``to_tangent_space``, of which it is the inverse."""
    return _transform(_native.from_tangent_space, normals, tangents, directions, out)


def _transform(
    native: Callable[[NDArray[np.float32], NDArray[np.float32], NDArray[np.float32], NDArray[np.float32]], None],
    normals: ArrayLike,
    tangents: ArrayLike,
    directions: ArrayLike,
    out: Optional[NDArray[Any]],
) -> NDArray[np.float32]:
    arrays = [vectors("normals", normals, 3), vectors("tangents", tangents, 4), vectors("directions", directions, 3)]
    try:
        leading = np.broadcast_shapes(*(array.shape[:-1] for array in arrays))
    except ValueError:
        shapes = ", ".join(str(array.shape) for array in arrays)
        raise InvalidLayoutError(f"normals, tangents and directions do not broadcast: {shapes}") from None
    flat = [
        rows(name, np.broadcast_to(array, leading + array.shape[-1:]).reshape(-1, array.shape[-1]), array.shape[-1])
        for name, array in zip(("normals", "tangents", "directions"), arrays)
    ]
    written, pending = output("out", out, leading + (3,))
    try:
        native(flat[0], flat[1], flat[2], written)
    except _native.LibraryError as failure:
        raise from_library(failure, leading_shape=leading) from None
    result = deliver(written, pending, out)
    return result if out is not None else result.reshape(leading + (3,))
