"""The exceptions: ``Error`` and one subclass per kind of failure.

Each subclass also derives from the built-in exception that fits it (``ValueError``,
``TypeError``, ``IndexError``...), so code that catches those keeps working. Whatever is raised,
no output array has been written, except after ``InternalError`` (a bug: the library panicked
while writing), when ``out`` and ``bitangents`` may hold old and new rows mixed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

if TYPE_CHECKING:
    from ._generate import Report

__all__ = [
    "Error",
    "InvalidDtypeError",
    "InvalidLayoutError",
    "InvalidOptionError",
    "MissingTexcoordsError",
    "InvalidIndexCountError",
    "IndexOutOfRangeError",
    "OverlapError",
    "DegenerateUvError",
    "InvalidFrameError",
    "TooManyVerticesError",
    "OutOfMemoryError",
    "InternalError",
]


class Error(Exception):
    """Base class of every tbasis error.

    ``status`` is the library's status value (``tbasis_status`` in C) when the library refused
    the call, ``None`` when the package's own checks did.
    """

    def __init__(self, message: str, status: Optional[int] = None) -> None:
        super().__init__(message)
        self.status = status

    def __reduce__(self) -> tuple[Any, ...]:
        # Subclasses take more than the message; pickle (multiprocessing) rebuilds them from it
        # and their attributes.
        return (_rebuild, (type(self), str(self)), self.__dict__)


class InvalidDtypeError(Error, TypeError):
    """An argument is not an array of numbers (or ``out`` not a float32 array)."""


class InvalidLayoutError(Error, ValueError):
    """An array has the wrong shape or row count, or an output is read-only."""


class InvalidOptionError(Error, ValueError):
    """An unknown method or policy, a negative or non-finite threshold, a bad thread count."""


class MissingTexcoordsError(Error, ValueError):
    """``texcoords`` is None, but the method or policy needs texture coordinates."""


class InvalidIndexCountError(Error, ValueError):
    """The index count (unindexed: the vertex count) is not a multiple of 3."""


class IndexOutOfRangeError(Error, IndexError):
    """An index is negative or not less than the vertex count.

    ``position`` is where it is in the flattened index array (in ``sources`` for
    ``apply_split``), ``value`` the index itself, ``triangle`` the triangle it belongs to
    (``position // 3``; None for ``apply_split``).
    """

    def __init__(
        self, message: str, position: int, value: int, triangle: Optional[int], status: Optional[int] = None
    ) -> None:
        super().__init__(message, status)
        self.position = position
        self.value = value
        self.triangle = triangle


class OverlapError(Error, ValueError):
    """An output array shares memory with an input or with the other output."""


class DegenerateUvError(Error):
    """Policy ``"reject"`` met a triangle with degenerate texture coordinates or non-finite input.

    ``triangle`` is the first such triangle, ``report`` the full ``Report`` of the mesh.
    """

    def __init__(self, message: str, report: Report, status: Optional[int] = None) -> None:
        super().__init__(message, status)
        self.report = report
        self.triangle = report.first_degenerate_triangle


class InvalidFrameError(Error, ValueError):
    """A tangent-space transform met a singular frame, a non-finite input or an overflowing result.

    ``index`` is the position of the first such vector in the broadcast leading shape (a tuple).
    """

    def __init__(self, message: str, index: tuple[int, ...], status: Optional[int] = None) -> None:
        super().__init__(message, status)
        self.index = index


class TooManyVerticesError(Error, OverflowError):
    """The split mesh would need vertex indices beyond 32 bits."""


class OutOfMemoryError(Error, MemoryError):
    """An allocation of the library failed (its working memory, or a smaller one).

    Nothing was written.
    """


class InternalError(Error):
    """A failure the package does not expect: a bug, in the package or the library.

    Unlike the other errors it may come after writing began: ``out`` and ``bitangents`` may hold
    any mix of their old rows and new values, and must not be used.
    """


# The library's status values (include/tbasis.h) and the class each raises.
_BY_STATUS: dict[int, type[Error]] = {
    2: InvalidLayoutError,  # INVALID_STRIDE
    3: InvalidIndexCountError,
    5: InvalidDtypeError,  # INVALID_INDEX_TYPE
    6: InvalidOptionError,  # UNKNOWN_METHOD
    7: InvalidOptionError,  # UNKNOWN_POLICY
    8: InvalidOptionError,  # UNKNOWN_FLAGS
    9: InvalidLayoutError,  # SIZE_OVERFLOW
    10: OverlapError,
    12: OutOfMemoryError,
    14: InvalidOptionError,  # INVALID_THRESHOLD
    15: InvalidLayoutError,  # INVALID_COUNT
    18: TooManyVerticesError,
    19: InvalidOptionError,  # NO_LEGACY_FORM
}
# NULL_POINTER: the C library's status for missing texcoords, which the binding gives too.
_NULL_POINTER = 1
_INDEX_OUT_OF_RANGE = 4
_DEGENERATE_UV = 11
_INVALID_FRAME = 17


def from_library(failure: BaseException, vertex_count: int = 0, leading_shape: tuple[int, ...] = ()) -> Error:
    """The exception for a ``tbasis._native.LibraryError``, naming the culprit where it is known.

    ``vertex_count`` is the mesh's, for an index out of range; ``leading_shape`` the broadcast
    shape of a transform's vectors, to turn the failing row into an index.
    """
    status, message, details = failure.args
    details_map: dict[str, Any] = details
    if status == _INDEX_OUT_OF_RANGE and "position" in details_map:
        return out_of_range(details_map["position"], details_map["value"], vertex_count, status)
    if status == _DEGENERATE_UV and "report" in details_map:
        from ._generate import Report

        report = Report(*details_map["report"])
        return DegenerateUvError(
            f"triangle {report.first_degenerate_triangle} has degenerate texture coordinates, zero area or "
            f"non-finite input (policy 'reject'; {report.degenerate_triangles} degenerate triangles in all)",
            report,
            status,
        )
    if status == _INVALID_FRAME and "row" in details_map:
        index = _unravel(details_map["row"], leading_shape)
        where = "the vector" if not index else f"vector {index[0] if len(index) == 1 else index}"
        return InvalidFrameError(f"{where}: {message}", index, status)
    if status == _NULL_POINTER:
        return MissingTexcoordsError(
            "texcoords is None, but the method or the policy needs texture coordinates (method 'mikktspace' "
            "always does, and so does policy 'legacy', the default of 'mikktspace')",
            status,
        )
    return _BY_STATUS.get(status, InternalError)(f"{message} (status {status})", status)


def out_of_range(position: int, value: int, vertex_count: int, status: Optional[int] = None) -> IndexOutOfRangeError:
    """The error for the index ``value`` at ``position`` of the flattened index array."""
    triangle, corner = divmod(position, 3)
    return IndexOutOfRangeError(
        f"index {position} (triangle {triangle}, corner {corner}) is {value}, not in range for {vertex_count} vertices",
        position,
        value,
        triangle,
        status,
    )


def _rebuild(kind: type[Error], message: str) -> Error:
    error = kind.__new__(kind)
    Exception.__init__(error, message)
    return error


def _unravel(row: int, shape: tuple[int, ...]) -> tuple[int, ...]:
    index = []
    for size in reversed(shape):
        row, rest = divmod(row, size)
        index.append(rest)
    return tuple(reversed(index)) if shape else ()
