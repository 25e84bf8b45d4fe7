"""Tangent-space bases for triangle meshes, on numpy arrays.

A unit tangent and a handedness sign per vertex (or per triangle corner), for normal mapping,
computed by the tbasis library in Rust on the arrays themselves: float32 rows are read and written
in place whatever their stride, so the fields of one structured vertex array serve as inputs and
output without copies; other dtypes and layouts are converted once.

- ``generate``: per vertex; ``generate_corners``: per corner (``method="mikktspace"``: exactly
  mikktspace.c); ``split_corners`` and ``apply_split``: the vertices a per-corner result needs;
- ``to_tangent_space``, ``from_tangent_space``: directions between object and tangent space;
- ``Method``, ``Policy``: the choices, also accepted as their string values;
- ``Error`` and its subclasses: what can go wrong; no output is written then (``InternalError``,
  a bug, excepted: outputs may then be partly written).
"""

from ._errors import (
    DegenerateUvError,
    Error,
    IndexOutOfRangeError,
    InternalError,
    InvalidDtypeError,
    InvalidFrameError,
    InvalidIndexCountError,
    InvalidLayoutError,
    InvalidOptionError,
    MissingTexcoordsError,
    OutOfMemoryError,
    OverlapError,
    TooManyVerticesError,
)
from ._generate import Report, generate, generate_corners
from ._native import __version__
from ._options import Method, MethodName, Policy, PolicyName
from ._split import Split, apply_split, split_corners
from ._transform import from_tangent_space, to_tangent_space

__all__ = [
    "__version__",
    "generate",
    "generate_corners",
    "split_corners",
    "apply_split",
    "to_tangent_space",
    "from_tangent_space",
    "Method",
    "Policy",
    "MethodName",
    "PolicyName",
    "Report",
    "Split",
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

# Shown as tbasis.X (in tracebacks, reprs and pickles), where users import them from.
for _public in (
    Report,
    Split,
    Method,
    Policy,
    Error,
    InvalidDtypeError,
    InvalidLayoutError,
    InvalidOptionError,
    MissingTexcoordsError,
    InvalidIndexCountError,
    IndexOutOfRangeError,
    OverlapError,
    DegenerateUvError,
    InvalidFrameError,
    TooManyVerticesError,
    OutOfMemoryError,
    InternalError,
):
    _public.__module__ = __name__
del _public
