"""The README's Python snippet is examples/interleaved.py, and it does what it says."""

import re
import runpy
from pathlib import Path

import numpy as np
import pytest

BINDING = Path(__file__).resolve().parents[1]
EXAMPLE = BINDING / "examples" / "interleaved.py"
README = BINDING.parents[1] / "README.md"


def test_example_writes_tangents_in_place(capsys):
    names = runpy.run_path(str(EXAMPLE))
    vertices = names["vertices"]
    assert np.array_equal(vertices["tangent"], np.tile(np.float32([1, 0, 0, 1]), (4, 1)))
    assert np.array_equal(vertices["uv"], [[0, 0], [1, 0], [1, 1], [0, 1]])
    assert "[1. 0. 0. 1.]" in capsys.readouterr().out


def test_readme_python_snippet_is_the_example():
    section = re.search(r"^## Python\n(.*?)(?=^## |\Z)", README.read_text(), flags=re.M | re.S)
    if section is None:
        pytest.skip("README.md has no '## Python' section")
    snippets = re.findall(r"```python\n(.*?)```", section.group(1), flags=re.S)
    assert snippets, "the README's Python section has no ```python block"
    example = EXAMPLE.read_text()
    for snippet in snippets:
        assert snippet in example, f"README snippet not in {EXAMPLE.name}:\n{snippet}"
