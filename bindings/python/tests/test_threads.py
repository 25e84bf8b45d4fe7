"""The GIL is released while the library runs (every call that computes), and ``threads`` reaches it."""

from __future__ import annotations

import os
import sys
import threading
import time
from typing import Any, Callable

import numpy as np
import pytest
from numpy.typing import NDArray

import tbasis
from meshes import Mesh, torus
from support import same_bits


@pytest.fixture(scope="module")
def big() -> Mesh:
    return torus(nu=600, nv=300, jitter=0.001, random_diagonals=True)  # 180,901 vertices


@pytest.fixture(scope="module")
def frames(big: Mesh) -> tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float32]]:
    """Normals, MikkTSpace tangents and unit directions, one per corner of ``big`` repeated: long
    enough that a transform's call can be told from its argument checks."""
    corners = big.indices.ravel()
    tangents = tbasis.generate_corners(big.positions, big.normals, big.uvs, big.indices, method="mikktspace")
    normals = np.tile(big.normals[corners], (4, 1))
    directions = np.tile(np.array([0.48, 0.6, 0.64], dtype=np.float32), (len(normals), 1))
    return normals, np.tile(tangents, (4, 1)), directions


def _generate(call: Any) -> Callable[[Mesh, Any], object]:
    return lambda big, frames: call(big.positions, big.normals, big.uvs, big.indices, method="mikktspace")


def _split(big: Mesh, frames: Any) -> object:
    # Every corner a tangent of its own (their positions as x): the largest split.
    tangents = np.zeros((big.indices.size, 4), dtype=np.float32)
    tangents[:, 0] = np.arange(big.indices.size, dtype=np.float32)
    return tbasis.split_corners(big.indices, len(big.positions), tangents)


def _transform(call: Any) -> Callable[[Mesh, Any], object]:
    return lambda big, frames: call(*frames, out=frames[2].copy())


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
def test_python_runs_while_the_library_computes(big: Mesh, frames: Any, call: Any) -> None:
    window: list[float] = []

    def compute() -> None:
        window.append(time.perf_counter())
        call(big, frames)
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
