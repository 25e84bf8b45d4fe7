"""Arrays as the library reads and writes them, in place whenever numpy's layout allows it.

The library takes float32 rows any positive number of bytes apart (each row's floats contiguous)
and uint16/uint32 indices any positive number of bytes apart. An array in that form is handed
over as it is: the fields of a structured vertex array are strided views of one buffer, read and
written where they are. Any other array is converted once into a packed copy: another dtype
(float64, int32, ...), another byte order, columns not contiguous, reversed or broadcast rows.
"""

from __future__ import annotations

from typing import Any, Callable, Optional

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._errors import IndexOutOfRangeError, InvalidDtypeError, InvalidLayoutError, OutOfMemoryError, OverlapError
from ._errors import out_of_range

_FLOAT32 = np.dtype(np.float32)
# One past the largest index the library reads (uint32).
_INDEX_END = 1 << 32
_INDEX_TYPES = (np.dtype(np.uint16), np.dtype(np.uint32))
# TBASIS_ERROR_OVERLAP, the status the library gives the same refusal.
_OVERLAP = 10


def rows(name: str, array: ArrayLike, width: int) -> NDArray[np.float32]:
    """``array`` as ``(n, width)`` float32 rows the library can read in place."""
    data = converted(name, lambda: np.asarray(array))
    if data.dtype.kind not in "fiu":
        raise InvalidDtypeError(f"{name} must hold real numbers (float32 is read in place), not dtype {data.dtype}")
    if data.ndim != 2 or data.shape[1] != width:
        raise InvalidLayoutError(f"{name} must have shape (n, {width}), not {data.shape}")
    if data.dtype == _FLOAT32 and _rows_in_place(data, width):
        return data
    return converted(name, lambda: np.array(data, dtype=np.float32, order="C"))


def converted(name: str, make: Callable[[], NDArray[Any]]) -> NDArray[Any]:
    """The array ``make`` returns, numpy's failure to allocate it as ``OutOfMemoryError``."""
    try:
        return make()
    except MemoryError:
        raise OutOfMemoryError(f"no memory for a copy of {name}") from None


def vectors(name: str, array: ArrayLike, width: int) -> NDArray[Any]:
    """``array`` as numbers whose last axis has ``width`` entries (any leading shape)."""
    data = np.asarray(array)
    if data.dtype.kind not in "fiu":
        raise InvalidDtypeError(f"{name} must hold real numbers, not dtype {data.dtype}")
    if data.ndim == 0 or data.shape[-1] != width:
        raise InvalidLayoutError(f"{name} must have shape (..., {width}), not {data.shape}")
    return data


def output(
    name: str, out: Optional[NDArray[Any]], shape: tuple[int, ...]
) -> tuple[NDArray[np.float32], Optional[NDArray[Any]]]:
    """Where the library writes an output of ``shape`` (its last axis a row), as ``(rows, width)``,
    and the caller's array to copy the result into after a successful call when the library
    cannot write that one itself.

    ``out`` None: a new array. Otherwise ``out`` must be a writable float32 array of ``shape``.
    """
    width = shape[-1]
    count = int(np.prod(shape[:-1], dtype=np.int64))
    if out is None:
        return converted(name, lambda: np.empty((count, width), dtype=np.float32)), None
    if not isinstance(out, np.ndarray):
        raise InvalidDtypeError(f"{name} must be a numpy array of dtype float32, not {type(out).__name__}")
    if out.dtype.kind != "f" or out.dtype.itemsize != 4:
        raise InvalidDtypeError(f"{name} must have dtype float32, not {out.dtype}")
    if out.shape != shape:
        raise InvalidLayoutError(f"{name} must have shape {shape}, not {out.shape}")
    if not out.flags.writeable:
        raise InvalidLayoutError(f"{name} is read-only")
    flat = out.reshape(count, width)
    # reshape copies when no view has that shape; the library must write the caller's memory.
    in_place = count == 0 or np.may_share_memory(flat, out)
    if in_place and flat.dtype == _FLOAT32 and _rows_in_place(flat, width):
        return flat, None
    return converted(name, lambda: np.empty((count, width), dtype=np.float32)), out


def refuse_overlap(outputs: dict[str, Any], inputs: dict[str, Any]) -> None:
    """``OverlapError`` when an output array shares a byte with an input or with another output.

    Judged on the caller's arrays, before any conversion: where the library cannot write ``out``
    in place it writes a copy, which shares nothing, and the result copied back would overwrite
    an input. An input that is not a numpy array is judged by the array numpy reads it as (a
    view of its memory where it exposes one); ``None`` shares nothing.
    """
    given = [(name, array) for name, array in outputs.items() if isinstance(array, np.ndarray)]
    read = [(name, np.asarray(array)) for name, array in inputs.items() if array is not None]
    for k, (written, out) in enumerate(given):
        for other, array in read + given[k + 1 :]:
            # The bounds test first: exact answers on interleaved views cost more.
            if np.may_share_memory(out, array) and np.shares_memory(out, array):
                raise OverlapError(f"the {written} output shares bytes with the {other} buffer", _OVERLAP)


def deliver(written: NDArray[np.float32], pending: Optional[NDArray[Any]], out: Optional[NDArray[Any]]) -> NDArray[Any]:
    """The array to return: ``out`` when the caller gave one (after copying ``written`` into
    ``pending``, the same array, when the library could not write it in place), else ``written``."""
    if pending is not None:
        pending[...] = written.reshape(pending.shape)
    return written if out is None else out


def indices(array: Optional[ArrayLike], vertex_count: int) -> tuple[Optional[NDArray[Any]], tuple[int, ...]]:
    """The flat uint16/uint32 index array the library reads (None: unindexed), and the shape the
    caller gave, ``(k,)`` or ``(m, 3)``.

    Other integer types are converted once to uint32, after checking that every index is one
    (a negative one or one of 2**32 or more would not survive the conversion); the library checks
    them against the vertex count, as it checks uint16 and uint32 indices. An empty list is an
    empty index array.
    """
    if array is None:
        return None, ()
    data = converted("indices", lambda: np.asarray(array))
    if data.size == 0 and data.dtype.kind == "f":
        data = data.astype(np.uint32)  # numpy reads [] as float64
    if data.dtype.kind not in "iu":
        raise InvalidDtypeError(
            f"indices must be integers (uint16 and uint32 are read in place), not dtype {data.dtype}"
        )
    if not (data.ndim == 1 or (data.ndim == 2 and data.shape[1] == 3)):
        raise InvalidLayoutError(f"indices must have shape (k,) or (m, 3), not {data.shape}")
    flat = converted("indices", lambda: data.reshape(-1))  # a view where the layout allows one
    if flat.dtype in _INDEX_TYPES:
        if flat.size > 1 and flat.strides[0] < flat.itemsize:
            flat = converted("indices", lambda: np.ascontiguousarray(flat))
        return flat, data.shape
    if np.any((flat < 0) | (flat >= _INDEX_END)):
        # The first index out of range, as the library would name it.
        position = int(np.flatnonzero((flat < 0) | (flat >= min(vertex_count, _INDEX_END)))[0])
        value = int(flat[position])
        if value < _INDEX_END:
            raise out_of_range(position, value, vertex_count)
        triangle = position // 3
        raise IndexOutOfRangeError(
            f"index {position} (triangle {triangle}, corner {position % 3}) is {value}: indices are 32-bit",
            position,
            value,
            triangle,
        )
    return converted("indices", lambda: flat.astype(np.uint32)), data.shape


def _rows_in_place(data: NDArray[Any], width: int) -> bool:
    """Whether the library can read or write the rows of this ``(n, width)`` float32 array as they are."""
    count = data.shape[0]
    if count == 0:
        return True
    # numpy may report any stride along an axis of length 1, where it is never applied.
    return data.strides[1] == 4 and (count == 1 or data.strides[0] >= 4 * width)
