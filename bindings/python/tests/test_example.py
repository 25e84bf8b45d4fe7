"""The README's Python snippet (examples/interleaved.py; tests/readme.rs keeps them equal) does what it says."""

import runpy
from pathlib import Path

import numpy as np

BINDING = Path(__file__).resolve().parents[1]
EXAMPLE = BINDING / "examples" / "interleaved.py"


def test_example_writes_tangents_in_place(capsys):
    names = runpy.run_path(str(EXAMPLE))
    vertices = names["vertices"]
    assert np.array_equal(vertices["tangent"], np.tile(np.float32([1, 0, 0, 1]), (4, 1)))
    assert np.array_equal(vertices["uv"], [[0, 0], [1, 0], [1, 1], [0, 1]])
    assert "[1. 0. 0. 1.]" in capsys.readouterr().out
