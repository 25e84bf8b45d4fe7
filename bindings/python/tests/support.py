"""Where the tests find what lies beside the package, and what they do when it is missing."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

# The repository holding these tests (bindings/python/tests/ in it); the package itself is the
# installed wheel, never this tree.
REPOSITORY = Path(__file__).resolve().parents[3]
EXAMPLES = REPOSITORY / "bindings" / "python" / "examples"
# The mesh corpus beside the clone (README: "Test corpus").
CORPUS = REPOSITORY.parent / "shared" / "meshes"


def require(present: bool, what: str) -> None:
    """Skips the test when ``what`` is missing; under CI (``CI`` set), which must provide
    everything, fails it instead."""
    if present:
        return
    if os.environ.get("CI"):
        pytest.fail(f"{what} is missing; CI must provide it")
    pytest.skip(f"needs {what}")


def require_corpus_file(path: Path) -> None:
    """Skips the test (under CI: fails it) when the mesh corpus file ``path`` is absent."""
    require(path.is_file(), f'the mesh corpus file {path} (scripts/fetch-corpus fetches it; README: "Test corpus")')


def same_bits(a: NDArray[Any], b: NDArray[Any]) -> bool:
    """Bitwise equality of two float32 arrays, NaN payloads and signed zeros included."""
    a, b = np.ascontiguousarray(a, dtype=np.float32), np.ascontiguousarray(b, dtype=np.float32)
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))
