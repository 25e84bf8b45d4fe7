"""The GIL is released while the library runs (every call that computes), and ``threads`` reaches it."""

from __future__ import annotations

import os
import sys
import threading
import time
from typing import Any, Callable, NamedTuple

import numpy as np
import pytest
from numpy.typing import NDArray

import tbasis
from meshes import Mesh, torus
from support import same_bits


@pytest.fixture(scope="module")
def big() -> Mesh:
    return torus(nu=600, nv=300, jitter=0.001, random_diagonals=True)  # 180,901 vertices


class Inputs(NamedTuple):
    """Every call's arguments, made before any call is timed: a timed window then holds the
    package's argument checks and the library's work alone."""

    mesh: Mesh
    split_tangents: NDArray[np.float32]
    """One tangent per corner, each of its own (its corner's number as x): the largest split."""
    frames: tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float32]]
    """Normals, MikkTSpace tangents and unit directions, one per corner of the mesh, four times
    over: long enough that a transform's call can be told from its argument checks."""
    out: NDArray[np.float32]
    """Where the transforms write."""


@pytest.fixture(scope="module")
def inputs(big: Mesh) -> Inputs:
    corners = big.indices.ravel()
    split_tangents = np.zeros((corners.size, 4), dtype=np.float32)
    split_tangents[:, 0] = np.arange(corners.size, dtype=np.float32)
    tangents = tbasis.generate_corners(big.positions, big.normals, big.uvs, big.indices, method="mikktspace")
    normals = np.tile(big.normals[corners], (4, 1))
    directions = np.tile(np.array([0.48, 0.6, 0.64], dtype=np.float32), (len(normals), 1))
    frames = (normals, np.tile(tangents, (4, 1)), directions)
    return Inputs(big, split_tangents, frames, np.empty_like(directions))


def _generate(call: Any) -> Callable[[Inputs], object]:
    return lambda i: call(i.mesh.positions, i.mesh.normals, i.mesh.uvs, i.mesh.indices, method="mikktspace")


def _split(i: Inputs) -> object:
    return tbasis.split_corners(i.mesh.indices, len(i.mesh.positions), i.split_tangents)


def _transform(call: Any) -> Callable[[Inputs], object]:
    return lambda i: call(*i.frames, out=i.out)


@pytest.mark.parametrize(
    "call",
    [
        _generate(tbasis.generate_corners),
        _generate(tbasis.generate),
        _split,
        _transform(tbasis.to_tangent_space),
        _transform(tbasis.from_tangent_space),
    ],
    ids=["generate_corners", "generate", "split_corners", "to_tangent_space", "from_tangent_space"],
)
def test_python_runs_while_the_library_computes(inputs: Inputs, call: Any) -> None:
    window: list[float] = []

    def compute() -> None:
        window.append(time.perf_counter())
        call(inputs)
        window.append(time.perf_counter())

    worker = threading.Thread(target=compute)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    start, end = window
    margin = (end - start) / 10
    inside = [t for t in ticks if start + margin < t < end - margin]
    # Holding the GIL, the call would leave this thread no moment in the middle of its run.
    assert end - start > 0.05, "the call is too short to tell"
    assert len(inside) > 1000, f"{len(inside)} iterations of the main thread during the call's middle"


def test_threads_give_the_same_bits(big: Mesh) -> None:
    args = (big.positions, big.normals, big.uvs, big.indices)
    one = tbasis.generate(*args)
    for threads in (0, 2, 8):
        assert same_bits(tbasis.generate(*args, threads=threads), one)
    corners = tbasis.generate_corners(*args, method="mikktspace")
    assert same_bits(tbasis.generate_corners(*args, method="mikktspace", threads=4), corners)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="counts threads in /proc/self/task, as on Linux")
def test_threads_start_workers(big: Mesh) -> None:
    def count() -> int:
        return len(os.listdir("/proc/self/task"))

    baseline = count()
    seen = baseline
    args = (big.positions, big.normals, big.uvs, big.indices)
    for _ in range(20):
        worker = threading.Thread(target=lambda: tbasis.generate(*args, method="lengyel", threads=4))
        worker.start()
        while worker.is_alive():
            seen = max(seen, count())
        worker.join()
        if seen > baseline + 1:
            break
    # One more thread is the Python worker; more are the library's.
    assert seen > baseline + 1, f"at most {seen} threads, {baseline} before"
    assert np.isfinite(tbasis.generate(*args, threads=4)).all()
