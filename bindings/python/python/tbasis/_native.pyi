# The compiled module (src/ in the binding's crate). Arrays must already be in the layout the
# library reads (see _arrays.py); the public functions in this package make them so.

from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

__version__: str
library_version: int

class LibraryError(Exception):
    """args: (status, message, details)."""

_ReportTuple = tuple[int, Optional[int], int, int, int, int, int, int, int]

def generate(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    texcoords: Optional[NDArray[np.float32]],
    indices: Optional[NDArray[Any]],
    method: int,
    policy: int,
    threshold: Optional[float],
    flip_v: bool,
    threads: int,
    tangents: NDArray[np.float32],
    bitangents: Optional[NDArray[np.float32]],
) -> _ReportTuple: ...
def generate_corners(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    texcoords: Optional[NDArray[np.float32]],
    indices: Optional[NDArray[Any]],
    method: int,
    policy: int,
    threshold: Optional[float],
    flip_v: bool,
    threads: int,
    tangents: NDArray[np.float32],
) -> _ReportTuple: ...
def split_corners(
    indices: Optional[NDArray[Any]], vertex_count: int, corner_tangents: NDArray[np.float32]
) -> tuple[NDArray[np.uint32], NDArray[np.uint32]]: ...
def to_tangent_space(
    normals: NDArray[np.float32],
    tangents: NDArray[np.float32],
    directions: NDArray[np.float32],
    out: NDArray[np.float32],
) -> None: ...
def from_tangent_space(
    normals: NDArray[np.float32],
    tangents: NDArray[np.float32],
    directions: NDArray[np.float32],
    out: NDArray[np.float32],
) -> None: ...
